// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/IO/internal/build_mesh.h>
#include <CGAL/Trivial_connections/IO/internal/file_contents.h>
#include <CGAL/Trivial_connections/IO/internal/read_obj.h>
#include <CGAL/Trivial_connections/IO/internal/read_off.h>
#include <CGAL/Trivial_connections/IO/internal/read_ply.h>
#include <CGAL/Trivial_connections/IO/internal/text_parsing.h>
#include <CGAL/Trivial_connections/IO/internal/triangle_soup.h>
#include <CGAL/Trivial_connections/IO/internal/triangulate_polygons.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/properties.h>

#include <boost/container/small_vector.hpp>
#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

namespace internal {
namespace io {

// Reads any supported mesh file (extension `ext`, lower case, already checked) as a polygon soup. OFF and PLY
// are read by our own readers (see read_off_soup() and Ply_reader for what CGAL's do with malformed files);
// OBJ is diagnosed by ours first, then read by CGAL's, like STL and GOCAD. Throws Invalid_input (io_error,
// parse_error).
template <class Point, class PolygonRange>
void read_polygon_soup_file(const std::string& path, const std::string& ext, std::vector<Point>& points,
                            PolygonRange& polygons)
{
  bool read = true;
  if(ext == "off") {
    read_off_soup(path, points, polygons);
  } else if(ext == "ply") {
    const File_contents data(path);
    if(!data.ok())
      throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "'");
    Ply_reader(data.begin(), data.end(), path).read(points, polygons);
  } else {
    if(ext == "obj")
      diagnose_obj(path);
    try {
      read = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
    } catch(const std::length_error&) {
      read = false; // a count too large for a vector
    }
  }
  if(!read)
    throw Invalid_input(Error_code::parse_error, "cannot parse '" + path + "' as a " + ext + " mesh file");
}

// Checks that `path` is a readable file with a supported extension; returns the extension in lower case.
inline std::string check_mesh_path(const std::string& path)
{
  std::error_code ec;
  if(!std::filesystem::exists(path, ec))
    throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "': no such file");
  if(std::filesystem::is_directory(path, ec))
    throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "': it is a directory");
  {
    errno = 0;
    std::ifstream probe(path);
    if(!probe) {
      const int err = errno;
      throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "'" +
                                                  (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
    }
  }
  const std::string ext = lower_extension(path);
  if(ext != "off" && ext != "obj" && ext != "ply" && ext != "stl" && ext != "ts")
    throw Invalid_input(Error_code::parse_error,
                        "cannot read mesh file '" + path + "': " +
                          (ext.empty() ? std::string("no file extension") : "unknown file extension '." + ext + "'") +
                          " (supported: .off, .obj, .ply, .stl, .ts)");
  return ext;
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
The elements of a mesh built by `read_triangle_mesh()` or `triangle_soup_to_mesh()`, by input index:
`vertices[i]` is vertex `i` of the file (also the `i`-th vertex of `vertices(tm)`), `faces[f]` is face `f`
(also the `f`-th face of `faces(tm)`). When `read_triangle_mesh()` triangulated faces of the file
(`parameters::triangulate(true)`), `faces[t]` is the `t`-th triangle and `source_faces[t]` the face of the
file it comes from (the triangles of a face are consecutive, faces in file order); otherwise `source_faces`
is empty and triangles and faces of the file are the same.
*/
template <class TriangleMesh>
struct Mesh_input_order
{
  /// the mesh's vertex type
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  /// the mesh's face type
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  std::vector<vertex_descriptor> vertices; ///< vertex `i` of the file
  std::vector<face_descriptor> faces;      ///< face (or triangle) `f`
  std::vector<std::size_t> source_faces;   ///< the face of the file each triangle comes from, when triangulated
};

/*!
\ingroup PkgTrivialConnectionsIO
Validates a polygon soup as an oriented 2-manifold triangle mesh (possibly with boundary) and builds it in
`tm` such that point `i` becomes the `i`-th vertex and polygon `f` the `f`-th face of `tm` in iteration
order. Points used by no polygon are kept as isolated vertices, so indices never shift. Checks, in this
order: at least one face; every index in range (before anything else uses them); triangles only; three
different vertices per face; no edge in more than two faces; no two faces traversing the same directed edge;
the faces around every vertex form one fan. Runs in linear time (plus small per-vertex sorts).

\tparam TriangleMesh a model of `MutableFaceGraph` with an internal vertex point map (e.g.
        `CGAL::Surface_mesh<Point_3>`, `CGAL::Polyhedron_3<K>`); \pre `tm` is empty
\tparam PointRange a range of values assignable to the mesh's points
\tparam PolygonRange a random-access range of ranges of integer indices (0-based)

\param points the points of the soup
\param polygons the faces of the soup, each the 0-based indices in `points` of its vertices, in order
\param tm the empty mesh that receives the result
\returns the vertices and faces of `tm` by input index (`source_faces` is empty)

\throws Invalid_input `empty_mesh`, `invalid_vertex`, `not_triangle_mesh`, `degenerate_face`, `non_manifold`,
        `inconsistent_orientation`; `where()` is the face (vertex for a non-manifold vertex) concerned
*/
template <class TriangleMesh, class PointRange, class PolygonRange>
Mesh_input_order<TriangleMesh> triangle_soup_to_mesh(const PointRange& points, const PolygonRange& polygons,
                                                     TriangleMesh& tm)
{
  const internal::io::Triangle_soup_connectivity soup =
    internal::io::validate_triangle_soup(std::size_t(std::distance(points.begin(), points.end())), polygons);
  return internal::io::build_mesh(points, soup, tm);
}

/*!
\ingroup PkgTrivialConnectionsIO
Reads a triangle mesh from an OFF, OBJ, PLY, STL or GOCAD (`.ts`) file (by extension, any letter case: the
formats `CGAL::IO::read_polygon_mesh()` reads without VTK), validates it and builds it in `tm` with
`triangle_soup_to_mesh()`: vertex `i` of the file is the `i`-th vertex of `tm` and face `f` its `f`-th face,
unused vertices included. Every message starts with `path: `.

OFF and PLY are read by the package's own readers, which check every count against the size of the file
before using it (CGAL 5.5's readers trust them: a file of a few bytes can ask for gigabytes or crash them).
OFF: ASCII, keyword `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF`, ... (normals, colours and texture coordinates
are read past); binary, homogeneous (`4OFF`) and n-dimensional (`nOFF`) OFF files are refused. PLY: ASCII
and binary of either endianness; the `x`, `y`, `z` properties of the `vertex` element, of any numeric type,
and the `vertex_indices` (or `vertex_index`) list of the `face` element, of any integer type; other elements
and properties are read past. OBJ is checked by the package and then read, like STL and GOCAD, with
`CGAL::IO::read_polygon_soup()`.

\tparam TriangleMesh as for `triangle_soup_to_mesh()`
\tparam NamedParameters a sequence of named parameters
\param path the file to read; its extension gives the format
\param tm the empty mesh that receives the result
\param np an optional sequence of named parameters among the ones listed below
\returns the vertices and faces of `tm` by index in the file, and the face of the file each triangle comes from
         when faces were triangulated

\cgalNamedParamsBegin
  \cgalParamNBegin{triangulate}
    \cgalParamDescription{whether faces of more than three vertices are split into triangles (a quad along
      its better diagonal with `CGAL::Polygon_mesh_processing::triangulate_face()`, a larger face by a
      constrained Delaunay triangulation of its corners in the plane of its normal, without new vertices; a
      larger face more than 5% of its size from planar, or whose boundary crosses itself in that plane, is a
      `degenerate_face` error), keeping their orientation and the vertex numbering.
      Triangle `t` of `tm` then comes from face `source_faces[t]` of the file; see `Mesh_input_order`.}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`: such a face is a `not_triangle_mesh` error}
  \cgalParamNEnd
\cgalNamedParamsEnd

\pre `tm` is empty
\throws Invalid_input
  - `io_error`: the file does not exist, is a directory or cannot be read;
  - `parse_error`: unknown or missing extension, or the file cannot be parsed (the message names the line
    for OFF, OBJ and a PLY header, the element and item in a PLY body), or is a refused OFF variant;
  - `invalid_vertex`: a face uses a vertex index out of range (`where()`: the face);
  - `not_triangle_mesh`: a face of more than three vertices without `triangulate(true)`, or of fewer than
    three; `degenerate_face`: also a face that `triangulate(true)` cannot split (a zero normal) or that uses
    a vertex twice;
  - `empty_mesh`, `non_manifold`, `inconsistent_orientation`: as `triangle_soup_to_mesh()`, on the triangles
    (faces are then numbered as the triangles of `tm`).
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Mesh_input_order<TriangleMesh> read_triangle_mesh(const std::string& path, TriangleMesh& tm,
                                                  const NamedParameters& np = parameters::default_values())
{
  using Point = typename boost::property_traits<
    typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>::value_type;

  const std::string ext = internal::io::check_mesh_path(path);
  const bool triangulate =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::triangulate), false);

  if(ext == "off" || ext == "obj") {
    std::vector<Point> points;
    std::vector<std::array<int, 3>> triangles;
    bool parsed = false;
    {
      const internal::io::File_contents data(path);
      if(data.ok())
        parsed = ext == "off" ? internal::io::fast_parse_off(data.begin(), data.end(), points, triangles)
                              : internal::io::fast_parse_obj(data.begin(), data.end(), points, triangles);
    }
    if(parsed) {
      try {
        const internal::io::Triangle_soup_connectivity soup =
          internal::io::validate_triangles(points.size(), std::move(triangles));
        return internal::io::build_mesh(points, soup, tm);
      } catch(const Invalid_input& e) {
        throw Invalid_input(e.code(), path + ": " + e.what(), e.where());
      }
    }
  }

  std::vector<Point> points;
  std::vector<boost::container::small_vector<std::size_t, 3>> polygons;
  internal::io::read_polygon_soup_file(path, ext, points, polygons);
  try {
    const bool has_polygons = std::any_of(polygons.begin(), polygons.end(),
                                          [](const auto& polygon) { return polygon.size() > 3; });
    if(!triangulate || !has_polygons)
      return triangle_soup_to_mesh(points, polygons, tm);
    std::vector<std::array<int, 3>> triangles;
    std::vector<std::size_t> source_faces;
    internal::io::triangulate_polygons(points, polygons, triangles, source_faces);
    const internal::io::Triangle_soup_connectivity soup =
      internal::io::validate_triangles(points.size(), std::move(triangles));
    Mesh_input_order<TriangleMesh> order = internal::io::build_mesh(points, soup, tm);
    order.source_faces = std::move(source_faces);
    return order;
  } catch(const Invalid_input& e) {
    throw Invalid_input(e.code(), path + ": " + e.what(), e.where());
  }
}

} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_READ_TRIANGLE_MESH_H
