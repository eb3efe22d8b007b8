// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// A smooth unit vector field on an icosahedron (a closed genus-0 surface, Euler characteristic 2) with two
// +1 singularities at opposite vertices, computed with the one-shot function compute_direction_field().
// Prints the energy and the holonomy residuals; exits 0 iff the residuals are below 1e-9.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <CGAL/Trivial_connections/trivial_connection.h>

#include <iostream>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;
using vertex_descriptor = Mesh::Vertex_index;
using halfedge_descriptor = Mesh::Halfedge_index;
using face_descriptor = Mesh::Face_index;

int main()
{
  Mesh mesh;
  CGAL::make_icosahedron<Mesh, Point>(mesh, Point(0, 0, 0), 1.0);

  // two +1 singularities at opposite vertices: their indices sum to the Euler characteristic 2
  const vertex_descriptor north = *vertices(mesh).begin();
  vertex_descriptor south = north;
  for(vertex_descriptor v : vertices(mesh))
    if(CGAL::squared_distance(mesh.point(v), mesh.point(north)) >
       CGAL::squared_distance(mesh.point(south), mesh.point(north)))
      south = v;
  const std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> singularities = {
    {north, TC::Singularity_index(1)}, {south, TC::Singularity_index(1)}};

  // outputs: one angle per halfedge (the connection), one unit tangent vector per face (the field)
  auto x = mesh.add_property_map<halfedge_descriptor, double>("h:connection", 0.).first;
  auto field = mesh.add_property_map<face_descriptor, Vector>("f:field", CGAL::NULL_VECTOR).first;

  const TC::Solve_report report =
    TC::compute_direction_field(mesh, singularities, x, field, TC::parameters::symmetry_order(1));

  std::cout << "icosahedron: " << num_vertices(mesh) << " vertices, " << num_faces(mesh) << " faces\n"
            << "singularities: +1 at vertices " << north << " and " << south << "\n"
            << "energy: " << report.energy << "\n"
            << "max holonomy residual: vertices " << report.max_vertex_residual << ", loops "
            << report.max_loop_residual << "\n"
            << "field in face " << *faces(mesh).begin() << ": " << field[*faces(mesh).begin()] << "\n";

  const bool ok = report.max_vertex_residual < 1e-9 && report.max_loop_residual < 1e-9;
  std::cout << (ok ? "OK" : "FAILED: residual too large") << std::endl;
  return ok ? 0 : 1;
}
