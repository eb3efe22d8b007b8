// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_REPAIR_TRIANGLE_MESH_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_REPAIR_TRIANGLE_MESH_H

#include <CGAL/disable_warnings.h>

// First: boost's disjoint sets, before the PMP headers declare boost::detail::get() (compressed sparse row graph),
// which would hide from them the global get() for raw pointers that the solver's tree-cotree uses
// (boost::disjoint_sets<int*, int*>): the solver would no longer compile after this header.
#include <boost/pending/disjoint_sets.hpp>

#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>

#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

// Whether a face of `tm` is degenerate for the package (exactly collinear, or too flat: see Mesh_arrays).
template <class TriangleMesh>
bool has_degenerate_face(const TriangleMesh& tm)
{
  const auto vpm = get(CGAL::vertex_point, tm);
  for(auto f : faces(tm)) {
    std::array<std::array<double, 3>, 3> p;
    std::array<typename boost::property_traits<decltype(vpm)>::value_type, 3> q;
    int k = 0;
    for(auto v : vertices_around_face(halfedge(f, tm), tm)) {
      q[k] = get(vpm, v);
      p[k] = {CGAL::to_double(q[k].x()), CGAL::to_double(q[k].y()), CGAL::to_double(q[k].z())};
      ++k;
    }
    if(CGAL::collinear(q[0], q[1], q[2]) || !(largest_corner_sine(p[0], p[1], p[2]) >= minimum_corner_sine))
      return true;
  }
  return false;
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
What `read_and_repair_triangle_mesh()` changed, step by step (every count is zero for a file that needed no
repair, and then the mesh is the one `read_triangle_mesh()` builds).
*/
struct Repair_report
{
  std::size_t input_points = 0;              ///< points in the file
  std::size_t input_polygons = 0;            ///< faces in the file
  std::size_t points_removed = 0;            ///< duplicate points merged and unused points removed (soup repair)
  std::size_t polygons_removed = 0;          ///< degenerate and duplicate faces removed (soup repair)
  std::size_t polygons_reoriented = 0;       ///< faces reversed or re-attached by the orientation of the soup
  std::size_t points_duplicated = 0;         ///< points duplicated by the orientation to separate non-manifold parts
  std::size_t polygons_triangulated = 0;     ///< faces of more than three vertices split into triangles
  std::size_t edges_stitched = 0;            ///< pairs of border halfedges stitched into interior edges
  std::size_t degenerate_faces_removed = 0;  ///< faces of zero area removed (the mesh's face count decreased by)
  std::size_t non_manifold_vertices_split = 0; ///< non-manifold vertices split into one vertex per fan
  std::size_t output_vertices = 0;           ///< vertices of the repaired mesh
  std::size_t output_faces = 0;              ///< triangles of the repaired mesh

  /*!
  \returns whether the repaired mesh differs from the file's (whether any count above but the sizes is not zero)
  */
  bool changed() const
  {
    return points_removed + polygons_removed + polygons_reoriented + points_duplicated + polygons_triangulated +
             edges_stitched + degenerate_faces_removed + non_manifold_vertices_split !=
           0;
  }
};

/*!
\ingroup PkgTrivialConnectionsIO
Reads a mesh file as `read_triangle_mesh()` does; a mesh that it accepts is returned as it is (nothing is
merged, even points at the same place: the file's topology is kept). A mesh that it refuses for its
connectivity or geometry (`not_triangle_mesh`, `non_manifold`, `inconsistent_orientation`, `empty_mesh`, or a face that the
solver would refuse as `degenerate_face`) is repaired with CGAL's Polygon Mesh Processing, then validated and built in `tm` with
`triangle_soup_to_mesh()`. The steps, in this order:
`repair_polygon_soup()` (duplicate points merged, unused points, degenerate and duplicate faces removed),
`orient_polygon_soup()` (faces reversed to one orientation per component; points duplicated where that cannot be
done around a vertex), `polygon_soup_to_polygon_mesh()`, `triangulate_faces()` (faces of more than three
vertices), `stitch_borders()` (border edges with the same end points joined), `remove_degenerate_faces()` (faces
of zero area, tested exactly) and `duplicate_non_manifold_vertices()`.

Vertex and face indices (files of singularities, constraints, the output field) then refer to the repaired
mesh, in the order of `vertices(tm)` and `faces(tm)` (the order of the returned `Mesh_input_order`), not to the
file: write the repaired mesh to use them. When the file was accepted as it is (`Repair_report::changed()` is
false), the mesh is the file's and the indices are the same.

\tparam TriangleMesh as for `triangle_soup_to_mesh()`
\param path the file to read (formats as for `read_triangle_mesh()`); it is not modified
\param tm the empty mesh that receives the result
\param report receives what was changed
\returns the vertices and faces of `tm` in order

\throws Invalid_input as `read_triangle_mesh()` for a file that cannot be read; what the repair cannot mend
        (a face too flat for the package that is not exactly degenerate, a soup that cannot be made a manifold,
        a mesh with no face left) keeps its error code, with the message saying that it was after the repair.
*/
template <class TriangleMesh>
Mesh_input_order<TriangleMesh> read_and_repair_triangle_mesh(const std::string& path, TriangleMesh& tm,
                                                             Repair_report& report)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  using Point = typename boost::property_traits<
    typename boost::property_map<TriangleMesh, CGAL::vertex_point_t>::type>::value_type;

  report = Repair_report();
  const std::string ext = internal::io::check_mesh_path(path);
  try { // a mesh the package accepts as it is is not changed
    Mesh_input_order<TriangleMesh> order = read_triangle_mesh(path, tm);
    if(!internal::io::has_degenerate_face(tm)) {
      report.input_points = report.output_vertices = num_vertices(tm);
      report.input_polygons = report.output_faces = num_faces(tm);
      return order;
    }
    CGAL::clear(tm);
  } catch(const Invalid_input& e) {
    if(e.code() == Error_code::io_error || e.code() == Error_code::parse_error ||
       e.code() == Error_code::invalid_vertex)
      throw;
    CGAL::clear(tm);
  }
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  internal::io::read_polygon_soup_file(path, ext, points, polygons);
  report.input_points = points.size();
  report.input_polygons = polygons.size();
  const auto after_repair = [&path](const Invalid_input& e) {
    return Invalid_input(e.code(), path + ": after --repair: " + e.what(), e.where());
  };
  for(const std::vector<std::size_t>& polygon : polygons)
    for(std::size_t i : polygon)
      if(i >= points.size())
        throw Invalid_input(Error_code::invalid_vertex,
                            path + ": a face uses vertex " + std::to_string(i) + ", which does not exist");

  PMP::repair_polygon_soup(points, polygons);
  report.points_removed = report.input_points - points.size();
  report.polygons_removed = report.input_polygons - polygons.size();

  const std::size_t points_before = points.size();
  const std::vector<std::vector<std::size_t>> before = polygons;
  PMP::orient_polygon_soup(points, polygons);
  report.points_duplicated = points.size() - points_before;
  for(std::size_t f = 0; f < polygons.size() && f < before.size(); ++f)
    report.polygons_reoriented += polygons[f] != before[f];

  if(polygons.empty())
    throw Invalid_input(Error_code::empty_mesh, path + ": after --repair: no face is left");
  if(!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw Invalid_input(Error_code::non_manifold,
                        path + ": after --repair: the faces cannot be oriented into a manifold mesh");
  CGAL::Surface_mesh<Point> sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  for(auto f : faces(sm))
    report.polygons_triangulated += degree(f, sm) > 3;
  if(report.polygons_triangulated != 0 && !PMP::triangulate_faces(sm))
    throw Invalid_input(Error_code::degenerate_face, path + ": after --repair: a face cannot be triangulated");
  report.edges_stitched = PMP::stitch_borders(sm);
  const std::size_t faces_before = num_faces(sm);
  PMP::remove_degenerate_faces(sm);
  sm.collect_garbage();
  report.degenerate_faces_removed = faces_before - num_faces(sm);
  report.non_manifold_vertices_split = PMP::duplicate_non_manifold_vertices(sm);

  std::vector<Point> out_points;
  std::vector<std::array<std::size_t, 3>> triangles;
  PMP::polygon_mesh_to_polygon_soup(sm, out_points, triangles);
  try {
    Mesh_input_order<TriangleMesh> order = triangle_soup_to_mesh(out_points, triangles, tm);
    report.output_vertices = num_vertices(tm);
    report.output_faces = num_faces(tm);
    return order;
  } catch(const Invalid_input& e) {
    throw after_repair(e);
  }
}

} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_REPAIR_TRIANGLE_MESH_H
