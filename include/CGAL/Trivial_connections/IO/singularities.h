// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_SINGULARITIES_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_SINGULARITIES_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

namespace internal {
namespace io {

// Splits a line into whitespace-separated fields, ignoring everything from the first '#'.
inline std::vector<std::string> fields_of(const std::string& line)
{
  std::vector<std::string> out;
  const std::string::size_type end = (std::min)(line.find('#'), line.size());
  std::string::size_type i = 0;
  while(i < end) {
    while(i < end && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::string::size_type start = i;
    while(i < end && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if(i > start)
      out.push_back(line.substr(start, i - start));
  }
  return out;
}

inline std::string location(const std::string& source, std::size_t line)
{
  return source + ":" + std::to_string(line) + ": ";
}

// A non-negative decimal integer that fits in std::size_t, or throws parse_error.
inline std::size_t parse_vertex_index(const std::string& text, const std::string& where)
{
  if(!text.empty() && text[0] == '-' && text.size() > 1 &&
     text.find_first_not_of("0123456789", 1) == std::string::npos)
    throw Invalid_input(Error_code::parse_error, where + "negative vertex index '" + text + "'");
  std::size_t i = (!text.empty() && text[0] == '+') ? 1 : 0;
  if(i == text.size() || text.find_first_not_of("0123456789", i) != std::string::npos)
    throw Invalid_input(Error_code::parse_error,
                        where + "the vertex index '" + text + "' is not a non-negative integer");
  std::size_t v = 0;
  for(; i < text.size(); ++i) {
    const std::size_t d = std::size_t(text[i] - '0');
    if(v > ((std::numeric_limits<std::size_t>::max)() - d) / 10)
      throw Invalid_input(Error_code::parse_error, where + "the vertex index '" + text + "' is too large");
    v = 10 * v + d;
  }
  return v;
}

// Calls record(where, fields, line_number) for every line that has fields (blank and '#' lines are
// skipped); `where` is the "source:line: " prefix of messages. Throws io_error if the stream fails.
template <class Record>
void for_each_record(std::istream& is, const std::string& source_name, Record record)
{
  std::string line;
  std::size_t line_number = 0;
  while(std::getline(is, line)) {
    ++line_number;
    const std::vector<std::string> f = fields_of(line);
    if(!f.empty())
      record(location(source_name, line_number), f, line_number);
  }
  if(is.bad())
    throw Invalid_input(Error_code::io_error, source_name + ": read error after line " + std::to_string(line_number));
}

// The text file `path` open for reading, or Invalid_input(io_error) "cannot read <what> 'path': <reason>" (a
// directory, or the system's reason)
inline std::ifstream open_input_file(const std::string& path, const std::string& what)
{
  std::error_code ec;
  if(std::filesystem::is_directory(path, ec))
    throw Invalid_input(Error_code::io_error, "cannot read " + what + " '" + path + "': it is a directory");
  errno = 0;
  std::ifstream is(path);
  if(!is) {
    const int err = errno;
    throw Invalid_input(Error_code::io_error, "cannot read " + what + " '" + path + "'" +
                                                (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
  }
  return is;
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
Value passed as `number_of_vertices` to `read_singularities()` to skip the range check.
*/
constexpr std::size_t unchecked_vertex_count = (std::numeric_limits<std::size_t>::max)();

/*!
\ingroup PkgTrivialConnectionsIO
Reads a singularity file: one line `v k` per singular vertex, `v` a 0-based vertex index (input order) and
`k` its index, an integer or a fraction `p/q` (`1`, `-1`, `1/4`, `-1/2`). Everything from a `#` to the end
of a line is a comment; blank lines are ignored. The pairs are returned in file order.

\param is the stream to read
\param source_name the name used in error messages (e.g. the file name)
\param number_of_vertices when given, a vertex index `>= number_of_vertices` is rejected
\returns the pairs (vertex index, index) of the lines, in file order

\throws Invalid_input with a message `source_name:line: ...`:
  - `parse_error`: a line without exactly two fields, a vertex index that is not a non-negative integer,
    a malformed index or a zero denominator;
  - `invalid_index`: an index too large to represent;
  - `duplicate_singularity`: a vertex listed twice (the message names the vertex and both lines;
    `where()` is the vertex);
  - `invalid_vertex`: a vertex index out of range (`where()` is the vertex);
  - `io_error`: the stream could not be read.
*/
inline std::vector<std::pair<std::size_t, Singularity_index>>
read_singularities(std::istream& is, const std::string& source_name,
                   std::size_t number_of_vertices = unchecked_vertex_count)
{
  std::vector<std::pair<std::size_t, Singularity_index>> result;
  std::unordered_map<std::size_t, std::size_t> line_of_vertex;
  internal::io::for_each_record(is, source_name, [&](const std::string& where, const std::vector<std::string>& f,
                                                     std::size_t line_number) {
    if(f.size() != 2)
      throw Invalid_input(Error_code::parse_error,
                          where + "expected 'vertex index' (two fields), found " + std::to_string(f.size()) +
                            (f.size() == 1 ? " field" : " fields"));
    const std::size_t v = internal::io::parse_vertex_index(f[0], where);
    Singularity_index k;
    try {
      k = Singularity_index::parse(f[1]);
    } catch(const Invalid_input& e) {
      throw Invalid_input(e.code(), where + "vertex " + std::to_string(v) + ": " + e.what(), v);
    }
    if(number_of_vertices != unchecked_vertex_count && v >= number_of_vertices)
      throw Invalid_input(Error_code::invalid_vertex,
                          where + "vertex " + std::to_string(v) + " does not exist: the mesh has " +
                            std::to_string(number_of_vertices) + " vertices (0 to " +
                            (number_of_vertices == 0 ? std::string("none")
                                                     : std::to_string(number_of_vertices - 1)) + ")",
                          v);
    const auto inserted = line_of_vertex.emplace(v, line_number);
    if(!inserted.second)
      throw Invalid_input(Error_code::duplicate_singularity,
                          where + "vertex " + std::to_string(v) + " is listed twice (lines " +
                            std::to_string(inserted.first->second) + " and " + std::to_string(line_number) + ")",
                          v);
    result.emplace_back(v, k);
  });
  return result;
}

/*!
\ingroup PkgTrivialConnectionsIO
Reads the singularity file `path` (see the stream overload; messages start with `path:line:`).
\param path the file to read
\param number_of_vertices when given, a vertex index `>= number_of_vertices` is rejected
\returns the pairs (vertex index, index) of the lines, in file order
\throws Invalid_input `io_error` if the file cannot be opened or read, and the errors of the stream overload
*/
inline std::vector<std::pair<std::size_t, Singularity_index>>
read_singularities(const std::string& path, std::size_t number_of_vertices = unchecked_vertex_count)
{
  std::ifstream is = internal::io::open_input_file(path, "singularity file");
  return read_singularities(is, path, number_of_vertices);
}

/*!
\ingroup PkgTrivialConnectionsIO
Writes singularities in the format read by `read_singularities()`: a `#` header line, then one line `v k`
per element of `singularities`, a range of pairs (`first`: vertex index, `second`: `Singularity_index`).
\param os the output stream
\param singularities a range of pairs whose `first` is a 0-based vertex index (written with `operator<<`) and
       whose `second` is a `Singularity_index`; written in the order of the range
*/
template <class SingularityRange>
void write_singularities(std::ostream& os, const SingularityRange& singularities)
{
  os << "# singularities: one line 'v k' per singular vertex (0-based vertex index, index k = p or p/q)\n";
  for(const auto& s : singularities)
    os << s.first << ' ' << s.second.to_string() << '\n';
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_SINGULARITIES_H
