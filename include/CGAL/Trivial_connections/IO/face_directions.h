// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_FACE_DIRECTIONS_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_FACE_DIRECTIONS_H

#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <ostream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsIO
One line of a directional constraint file: a face (0-based, input order) and the direction the field must
have there (not necessarily tangent: the solver projects it onto the face).
*/
struct Face_direction
{
  std::size_t face = 0;                           ///< 0-based face index, in file order
  std::array<double, 3> direction = {{0, 0, 0}};  ///< the direction `x y z` as written (not yet projected)
};

/*!
\ingroup PkgTrivialConnectionsIO
Reads a directional constraint file: one line `f x y z` per constrained face, `f` a 0-based face index
(input order) and `(x, y, z)` a direction. Everything from a `#` to the end of a line is a comment; blank
lines are ignored. Returned in file order.

\param is the stream to read
\param source_name the name used in error messages (e.g. the file name)
\param number_of_faces when given, a face index `>= number_of_faces` is rejected
\returns the face and direction of every line, in file order

\throws Invalid_input with a message `source_name:line: ...`:
  - `parse_error`: a line without exactly four fields, a face index that is not a non-negative integer, a
    coordinate that is not a finite number;
  - `invalid_constraint`: a face out of range, a face listed twice (both lines named), a zero vector
    (`where()` is the face);
  - `io_error`: the stream could not be read.
*/
inline std::vector<Face_direction> read_face_directions(std::istream& is, const std::string& source_name,
                                                        std::size_t number_of_faces = unchecked_vertex_count)
{
  std::vector<Face_direction> result;
  std::unordered_map<std::size_t, std::size_t> line_of_face;
  internal::io::for_each_record(is, source_name, [&](const std::string& where, const std::vector<std::string>& f,
                                                     std::size_t line_number) {
    if(f.size() != 4)
      throw Invalid_input(Error_code::parse_error,
                          where + "expected 'face x y z' (four fields), found " + std::to_string(f.size()) +
                            (f.size() == 1 ? " field" : " fields"));
    Face_direction d;
    try {
      d.face = internal::io::parse_vertex_index(f[0], where);
    } catch(const Invalid_input&) {
      throw Invalid_input(Error_code::parse_error,
                          where + "the face index '" + f[0] + "' is not a non-negative integer that fits");
    }
    for(int c = 0; c < 3; ++c) {
      const std::string& text = f[std::size_t(c) + 1];
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if(end != text.c_str() + text.size() || !std::isfinite(value)) // an overflow gives infinity
        throw Invalid_input(Error_code::parse_error, where + "face " + std::to_string(d.face) + ": the coordinate '" +
                                                       text + "' is not a finite number");
      d.direction[std::size_t(c)] = value;
    }
    if(number_of_faces != unchecked_vertex_count && d.face >= number_of_faces)
      throw Invalid_input(Error_code::invalid_constraint,
                          where + "face " + std::to_string(d.face) + " does not exist: the mesh has " +
                            std::to_string(number_of_faces) + " faces (0 to " +
                            (number_of_faces == 0 ? std::string("none") : std::to_string(number_of_faces - 1)) + ")",
                          d.face);
    if(d.direction[0] == 0 && d.direction[1] == 0 && d.direction[2] == 0)
      throw Invalid_input(Error_code::invalid_constraint,
                          where + "face " + std::to_string(d.face) + ": the direction is the zero vector", d.face);
    const auto inserted = line_of_face.emplace(d.face, line_number);
    if(!inserted.second)
      throw Invalid_input(Error_code::invalid_constraint,
                          where + "face " + std::to_string(d.face) + " is listed twice (lines " +
                            std::to_string(inserted.first->second) + " and " + std::to_string(line_number) + ")",
                          d.face);
    result.push_back(d);
  });
  return result;
}

/*!
\ingroup PkgTrivialConnectionsIO
Reads the directional constraint file `path` (see the stream overload; messages start with `path:line:`).
\param path the file to read
\param number_of_faces when given, a face index `>= number_of_faces` is rejected
\returns the face and direction of every line, in file order
\throws Invalid_input `io_error` if the file cannot be opened or read, and the errors of the stream overload
*/
inline std::vector<Face_direction> read_face_directions(const std::string& path,
                                                        std::size_t number_of_faces = unchecked_vertex_count)
{
  std::ifstream is = internal::io::open_input_file(path, "direction file");
  return read_face_directions(is, path, number_of_faces);
}

/*!
\ingroup PkgTrivialConnectionsIO
Writes a directional constraint file in the format read by `read_face_directions()`: a `#` header line, then one
line `f x y z` per element of `directions`, in the order of the range. Numbers are written with the shortest
representation that reads back exactly (`std::to_chars`), so `read_face_directions()` gives back the same faces, in
the same order, and the same bits of every coordinate.

The elements are checked before anything is written: nothing is written for a range that
`read_face_directions()` would not read back.
\tparam FaceDirectionRange a range of `Face_direction` (or of any type with a member `face` convertible to
        `std::size_t` and a member `direction` whose elements 0, 1 and 2 convert to `double`)
\param os the output stream
\param directions the faces and their directions, written in the order of the range
\throws Invalid_input `invalid_constraint` (`where()` is the face) for a direction that is the zero vector or has a
        coordinate that is not finite, and for a face listed twice
*/
template <class FaceDirectionRange>
void write_face_directions(std::ostream& os, const FaceDirectionRange& directions)
{
  std::unordered_map<std::size_t, std::size_t> entry_of_face;
  std::size_t entry = 0;
  for(const auto& d : directions) {
    const std::size_t face = std::size_t(d.face);
    const double x = double(d.direction[0]), y = double(d.direction[1]), z = double(d.direction[2]);
    if(!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      throw Invalid_input(Error_code::invalid_constraint,
                          "face " + std::to_string(face) + ": the direction has a coordinate that is not finite", face);
    if(x == 0 && y == 0 && z == 0)
      throw Invalid_input(Error_code::invalid_constraint,
                          "face " + std::to_string(face) + ": the direction is the zero vector", face);
    const auto inserted = entry_of_face.emplace(face, entry);
    if(!inserted.second)
      throw Invalid_input(Error_code::invalid_constraint,
                          "face " + std::to_string(face) + " is listed twice (entries " +
                            std::to_string(inserted.first->second) + " and " + std::to_string(entry) + ")",
                          face);
    ++entry;
  }
  os << "# face directions: one line 'f x y z' per face (0-based face index, a direction, projected onto the face)\n";
  internal::io::Number_writer out(os);
  for(const auto& d : directions) {
    out.index(std::size_t(d.face));
    for(std::size_t c = 0; c < 3; ++c) {
      out.character(' ');
      out.number(double(d.direction[c]));
    }
    out.character('\n');
  }
  out.flush();
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_FACE_DIRECTIONS_H
