// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_CONNECTION_FILE_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_CONNECTION_FILE_H

#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>

#include <charconv>
#include <cstddef>
#include <istream>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

namespace internal {
namespace io {

// An output buffer for numbers: formats with std::to_chars straight into a large block of memory and writes
// it to the stream in big pieces (no iostream formatting, no per-number allocation). Call flush() at the end.
class Number_writer
{
public:
  explicit Number_writer(std::ostream& os) : m_os(os), m_buffer(new char[capacity]), m_ptr(m_buffer.get()) {}
  Number_writer(const Number_writer&) = delete;
  Number_writer& operator=(const Number_writer&) = delete;

  // The shortest decimal representation of `d` that reads back exactly (std::to_chars): as precise as "%.17g",
  // shorter and much faster.
  void number(double d)
  {
    reserve_line();
    m_ptr = std::to_chars(m_ptr, m_buffer.get() + capacity, d).ptr;
  }
  void index(std::size_t i)
  {
    reserve_line();
    m_ptr = std::to_chars(m_ptr, m_buffer.get() + capacity, i).ptr;
  }
  void character(char c)
  {
    reserve_line();
    *m_ptr++ = c;
  }
  // writes what is buffered to the stream
  void flush()
  {
    const std::size_t n = std::size_t(m_ptr - m_buffer.get());
    m_ptr = m_buffer.get();
    if(n > 0)
      m_os.write(m_buffer.get(), std::streamsize(n));
  }

private:
  static constexpr std::size_t capacity = std::size_t(1) << 20;
  static constexpr std::size_t margin = 64; // more than one number (at most 24 characters) or character

  void reserve_line()
  {
    if(std::size_t(m_buffer.get() + capacity - m_ptr) < margin)
      flush();
  }
  std::ostream& m_os;
  std::unique_ptr<char[]> m_buffer;
  char* m_ptr;
};

inline double parse_double(const std::string& text, const std::string& where, const char* what)
{
  double d = 0;
  const char* first = text.data();
  if(!text.empty() && text[0] == '+') ++first;
  const std::from_chars_result r = std::from_chars(first, text.data() + text.size(), d);
  if(r.ec != std::errc() || r.ptr != text.data() + text.size())
    throw Invalid_input(Error_code::parse_error, where + "the " + std::string(what) + " '" + text +
                                                   "' is not a number");
  return d;
}

// weight(e) if `weight` is callable with an edge, else weight.weight(e) (e.g. a Trivial_connection_solver)
template <class W, class E>
auto edge_weight(const W& weight, const E& e, int) -> decltype(double(weight(e)))
{
  return double(weight(e));
}
template <class W, class E>
auto edge_weight(const W& weight, const E& e, long) -> decltype(double(weight.weight(e)))
{
  return double(weight.weight(e));
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
Writes a connection file (CONVENTIONS.md): `#` header lines stating the format, then one line `i j x w`
per interior edge, in the order of `edges(tm)`: `i` and `j` are the indices of its vertices with `i < j`,
`x` is `x(h)` for the halfedge `h` from `i` to `j` (so `x(j -> i) = -x`), and `w` the weight `w_e` of the
energy. Numbers are written with the shortest representation that reads back exactly (`std::to_chars`),
which is as precise as 17 significant digits. Border edges are not written.

\tparam TriangleMesh a model of `HalfedgeListGraph` (`EdgeListGraph`)
\tparam HalfedgeAngleMap a readable property map `halfedge_descriptor -> double` (the connection)
\tparam VertexIndexMap a readable property map `vertex_descriptor -> std::size_t` (the file's vertex indices)
\tparam EdgeWeight either callable as `double(edge_descriptor)` or an object with a member
        `double weight(edge_descriptor)`, such as a `Trivial_connection_solver`
\param os the output stream
\param tm the triangle mesh
\param x the connection, e.g. from `Trivial_connection_solver::solve()`
\param vertex_index the 0-based index written for each vertex
\param weight gives the weight `w_e` of each interior edge `e`
*/
template <class TriangleMesh, class HalfedgeAngleMap, class VertexIndexMap, class EdgeWeight>
void write_connection(std::ostream& os, const TriangleMesh& tm, HalfedgeAngleMap x, VertexIndexMap vertex_index,
                      const EdgeWeight& weight)
{
  os << "# trivial connection: one line 'i j x w' per interior edge\n"
        "# i, j: 0-based vertex indices (input order), i < j\n"
        "# x: connection angle in radians of the halfedge i->j (x of j->i is -x): a vector moved from the face\n"
        "#    of i->j to the face of j->i is unfolded about the edge, then turned by x counter-clockwise\n"
        "# w: weight of the edge in the energy sum_e w_e x_e^2\n";
  internal::io::Number_writer out(os);
  for(auto e : edges(tm)) {
    if(CGAL::is_border(e, tm))
      continue;
    auto h = halfedge(e, tm);
    std::size_t i = std::size_t(get(vertex_index, source(h, tm)));
    std::size_t j = std::size_t(get(vertex_index, target(h, tm)));
    if(j < i) {
      h = opposite(h, tm);
      std::swap(i, j);
    }
    out.index(i);
    out.character(' ');
    out.index(j);
    out.character(' ');
    out.number(double(get(x, h)));
    out.character(' ');
    out.number(internal::io::edge_weight(weight, e, 0));
    out.character('\n');
  }
  out.flush();
}

/*!
\ingroup PkgTrivialConnectionsIO
One line of a connection file: the angle `x` of the halfedge `i -> j` and the weight `w` of its edge.
*/
struct Connection_entry
{
  double x = 0; ///< `x(h)` of the halfedge `i -> j`, in radians
  double w = 0; ///< the energy weight `w_e` of its edge
};

/*!
\ingroup PkgTrivialConnectionsIO
Reads a connection file written by `write_connection()`: lines `i j x w` (`w` optional, then 0), `#`
comments and blank lines ignored. Returns the map `(i, j) -> (x, w)` as written in the file.
\param is the stream to read
\param source_name the name used in error messages (e.g. the file name)
\returns the entry of every line, keyed by its vertex indices `(i, j)` in the order of the line (not sorted)
\throws Invalid_input `parse_error` (message `source_name:line: ...`) for a malformed line or an edge listed
        twice (in either direction); `io_error` if the stream cannot be read
*/
inline std::map<std::pair<std::size_t, std::size_t>, Connection_entry>
read_connection(std::istream& is, const std::string& source_name)
{
  std::map<std::pair<std::size_t, std::size_t>, Connection_entry> result;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> line_of_edge;
  internal::io::for_each_record(is, source_name, [&](const std::string& where, const std::vector<std::string>& f,
                                                     std::size_t line_number) {
    if(f.size() != 3 && f.size() != 4)
      throw Invalid_input(Error_code::parse_error, where + "expected 'i j x w', found " +
                                                     std::to_string(f.size()) + " fields");
    const std::size_t i = internal::io::parse_vertex_index(f[0], where);
    const std::size_t j = internal::io::parse_vertex_index(f[1], where);
    if(i == j)
      throw Invalid_input(Error_code::parse_error, where + "an edge from vertex " + std::to_string(i) + " to itself");
    Connection_entry entry;
    entry.x = internal::io::parse_double(f[2], where, "angle");
    if(f.size() == 4)
      entry.w = internal::io::parse_double(f[3], where, "weight");
    const auto key = std::make_pair((std::min)(i, j), (std::max)(i, j));
    const auto inserted = line_of_edge.emplace(key, line_number);
    if(!inserted.second)
      throw Invalid_input(Error_code::parse_error,
                          where + "the edge " + std::to_string(key.first) + "-" + std::to_string(key.second) +
                            " is listed twice (lines " + std::to_string(inserted.first->second) + " and " +
                            std::to_string(line_number) + ")");
    result.emplace(std::make_pair(i, j), entry);
  });
  return result;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_CONNECTION_FILE_H
