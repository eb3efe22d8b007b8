// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The program's --repair and --write-mesh (trivial_connections.cpp): the report line of what the repair
// changed, and the mesh the field is on as an OFF file. The repair itself is the library's
// read_and_repair_triangle_mesh() (CGAL/Trivial_connections/IO/repair_triangle_mesh.h).
// Included by that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_REPAIR_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_REPAIR_H

#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/repair_triangle_mesh.h>

#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace trivial_connections_program {

// "repaired: 2 points merged or removed, ..." (only the steps that changed something), or "repaired: nothing
// to repair"; then the size of the repaired mesh.
inline std::string repair_report_line(const CGAL::Trivial_connections::Repair_report& r)
{
  std::ostringstream out;
  out << "repaired:";
  const std::pair<std::size_t, const char*> steps[] = {
    {r.points_removed, "points merged or removed"},
    {r.polygons_removed, "degenerate or duplicate faces removed"},
    {r.polygons_reoriented, "faces reoriented"},
    {r.points_duplicated, "points duplicated (orientation)"},
    {r.polygons_triangulated, "polygons triangulated"},
    {r.edges_stitched, "edges stitched"},
    {r.degenerate_faces_removed, "zero-area faces removed"},
    {r.non_manifold_vertices_split, "non-manifold vertices split"}};
  const char* separator = " ";
  for(const auto& [count, what] : steps)
    if(count != 0) {
      out << separator << count << " " << what;
      separator = ", ";
    }
  if(!r.changed())
    out << " nothing to repair";
  out << " (" << r.input_points << " points, " << r.input_polygons << " faces in the file; " << r.output_vertices
      << " vertices, " << r.output_faces << " triangles after)\n";
  return out.str();
}

// The mesh as an ASCII OFF file, vertices and faces in input order (`order`), with full precision.
template <class Mesh>
void write_mesh_off(std::ostream& os, const Mesh& mesh, const CGAL::Trivial_connections::Mesh_input_order<Mesh>& order)
{
  std::vector<std::size_t> file_index(num_vertices(mesh));
  for(std::size_t v = 0; v < order.vertices.size(); ++v)
    file_index[std::size_t(order.vertices[v])] = v;
  os << "OFF\n" << order.vertices.size() << " " << order.faces.size() << " 0\n";
  os << std::setprecision(std::numeric_limits<double>::max_digits10);
  for(auto v : order.vertices) {
    const auto& p = get(CGAL::vertex_point, mesh, v);
    os << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  for(auto f : order.faces) {
    os << "3";
    for(auto v : vertices_around_face(halfedge(f, mesh), mesh))
      os << " " << file_index[std::size_t(v)];
    os << "\n";
  }
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_REPAIR_H
