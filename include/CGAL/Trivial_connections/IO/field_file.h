// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_FIELD_FILE_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_FIELD_FILE_H

#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/number_utils.h>

#include <array>
#include <cstddef>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsIO
Writes a field file (CONVENTIONS.md): `#` header lines stating the format, then one line `x y z` per face
in the order of `faces(tm)` (the input face order for a mesh read by `read_triangle_mesh()`), the
coordinates of `get(field, f)`. Numbers are written with the shortest representation that reads back
exactly (`std::to_chars`), as precise as 17 significant digits.
\tparam FaceVectorMap a readable property map `face_descriptor -> Vector_3` (any type with `x()`, `y()`, `z()`
        convertible by `CGAL::to_double`)
\param os the output stream
\param tm the triangle mesh
\param field the field, e.g. from `Trivial_connection_solver::compute_field()`
*/
template <class TriangleMesh, class FaceVectorMap>
void write_field(std::ostream& os, const TriangleMesh& tm, FaceVectorMap field)
{
  os << "# direction field: one line 'x y z' per face, in input face order: a unit tangent vector of the face\n"
        "# (for an n-direction field, n > 1, one of its n directions)\n";
  internal::io::Number_writer out(os);
  for(auto f : faces(tm)) {
    const auto v = get(field, f);
    out.number(CGAL::to_double(v.x()));
    out.character(' ');
    out.number(CGAL::to_double(v.y()));
    out.character(' ');
    out.number(CGAL::to_double(v.z()));
    out.character('\n');
  }
  out.flush();
}

/*!
\ingroup PkgTrivialConnectionsIO
Reads a field file written by `write_field()`: one vector per non-comment, non-blank line, in file order.
\throws Invalid_input `parse_error` (message `source_name:line: ...`) for a line without exactly three numbers;
        `io_error` if the stream cannot be read
\param is the stream to read
\param source_name the name used in error messages (e.g. the file name)
\returns the vectors `(x, y, z)` of the lines, in file order (face order for a file of `write_field()`)
*/
inline std::vector<std::array<double, 3>> read_field(std::istream& is, const std::string& source_name)
{
  std::vector<std::array<double, 3>> result;
  internal::io::for_each_record(is, source_name, [&](const std::string& where, const std::vector<std::string>& f,
                                                     std::size_t) {
    if(f.size() != 3)
      throw Invalid_input(Error_code::parse_error, where + "expected 'x y z', found " + std::to_string(f.size()) +
                                                     (f.size() == 1 ? " field" : " fields"));
    result.push_back({internal::io::parse_double(f[0], where, "coordinate"),
                      internal::io::parse_double(f[1], where, "coordinate"),
                      internal::io::parse_double(f[2], where, "coordinate")});
  });
  return result;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_FIELD_FILE_H
