// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TEXT_PARSING_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TEXT_PARSING_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/exceptions.h>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

// Character ranges [p, end): the fast OFF and OBJ parsers and the PLY reader work on the file's bytes.

// the characters std::isspace accepts in the "C" locale (what the iostreams of CGAL's readers skip)
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }

inline const char* skip_blanks(const char* p, const char* end)
{
  while(p != end && is_blank(*p))
    ++p;
  return p;
}

inline const char* token_end(const char* p, const char* end)
{
  while(p != end && !is_blank(*p))
    ++p;
  return p;
}

inline const char* end_of_line(const char* p, const char* end)
{
  const void* eol = std::memchr(p, '\n', std::size_t(end - p));
  return eol != nullptr ? static_cast<const char*>(eol) : end;
}

// The finite double written in [first, last) (an optional '+' first, as `operator>>` allows).
inline bool parse_finite_double(const char* first, const char* last, double& d)
{
  if(first != last && *first == '+') {
    ++first;
    if(first != last && (*first == '+' || *first == '-'))
      return false;
  }
  const std::from_chars_result r = std::from_chars(first, last, d, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == last && std::isfinite(d);
}

// The unsigned integer written with decimal digits only in [first, last), at most `max`.
inline bool parse_plain_index(const char* first, const char* last, std::uint64_t max, std::uint64_t& i)
{
  if(first == last || *first < '0' || *first > '9')
    return false;
  const std::from_chars_result r = std::from_chars(first, last, i, 10);
  return r.ec == std::errc() && r.ptr == last && i <= max;
}

// Reads exactly three finite numbers in [p, last), separated and surrounded by blanks, nothing else.
inline bool parse_three_doubles(const char* p, const char* last, double (&xyz)[3])
{
  for(int k = 0; k < 3; ++k) {
    p = skip_blanks(p, last);
    const char* e = token_end(p, last);
    if(!parse_finite_double(p, e, xyz[k]))
      return false;
    p = e;
  }
  return skip_blanks(p, last) == last;
}

// std::string tokens: the line-by-line OFF reader and the OBJ diagnosis, where speed does not matter.

inline std::string lower_extension(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  if(!ext.empty() && ext[0] == '.')
    ext.erase(0, 1);
  for(char& ch : ext)
    ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

inline bool parse_integer(const std::string& s, long long& value)
{
  if(s.empty())
    return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(s.c_str(), &end, 10);
  return errno == 0 && end == s.c_str() + s.size();
}

inline bool parse_number(const std::string& s)
{
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

// Throws parse_error if one of the first three tokens of a vertex line is not a finite number.
inline void check_coordinates(const std::vector<std::string>& t, std::size_t first, const std::string& where,
                              std::size_t v)
{
  if(t.size() < first + 3)
    throw Invalid_input(Error_code::parse_error, where + ": expected three coordinates", v);
  for(std::size_t k = first; k < first + 3; ++k) {
    if(!parse_number(t[k]))
      throw Invalid_input(Error_code::parse_error, where + ": expected three coordinates, '" + t[k] +
                                                     "' is not a number", v);
    if(!std::isfinite(std::strtod(t[k].c_str(), nullptr)))
      throw Invalid_input(Error_code::parse_error, where + ": the coordinate '" + t[k] +
                                                     "' is not a finite number", v);
  }
}

inline std::vector<std::string> tokens_of(const std::string& line)
{
  std::vector<std::string> out;
  std::istringstream ss(line.substr(0, line.find('#')));
  std::string t;
  while(ss >> t)
    out.push_back(t);
  return out;
}

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TEXT_PARSING_H
