// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// From a mesh file to pictures: reads a polygon mesh (faces of more than three vertices are triangulated),
// computes a cross field (n = 4) with singularities read from a file, traces streamlines from every tenth
// face, and writes the files a viewer opens (ParaView: the mesh with the four directions per face and the
// singularity index per vertex; the streamlines as polylines), all or nothing.
// Usage: streamlines_example [MESH [SINGULARITIES [OUT_DIR]]]
//   default: examples/data/sphere.off with eight +1/4 singularities at vertices 0..7 (sum 2, the Euler
//   characteristic of a sphere), output in the current directory.
// Then, for a PNG: /usr/bin/python3 scripts/render_field.py OUT_DIR/field.vtk --streamlines
//   OUT_DIR/streamlines.vtk -o field.png
// Exits 0 iff the holonomy residuals are below 1e-9 and every streamline segment follows the field.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>

#include <CGAL/Trivial_connections/IO/atomic_file.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/streamlines.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vector = Kernel::Vector_3;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using vertex_descriptor = Mesh::Vertex_index;
using face_descriptor = Mesh::Face_index;

#ifndef TC_EXAMPLE_DATA_DIR
#define TC_EXAMPLE_DATA_DIR "examples/data"
#endif

int main(int argc, char* argv[])
{
  const std::string mesh_file = argc > 1 ? argv[1] : TC_EXAMPLE_DATA_DIR "/sphere.off";
  const std::filesystem::path out_dir = argc > 3 ? argv[3] : ".";
  const int n = 4;
  try {
    Mesh mesh;
    const TC::Mesh_input_order<Mesh> order =
      TC::read_triangle_mesh(mesh_file, mesh, TC::parameters::triangulate(true));

    std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> singularities;
    if(argc > 2) {
      for(const auto& s : TC::read_singularities(argv[2], order.vertices.size()))
        singularities.emplace_back(order.vertices[s.first], s.second);
    } else {
      for(std::size_t v = 0; v < 8; ++v)
        singularities.emplace_back(order.vertices[v], TC::Singularity_index(1, n));
    }

    auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
    auto field = mesh.add_property_map<face_descriptor, Vector>("f:field", CGAL::NULL_VECTOR).first;
    TC::Trivial_connection_solver<Mesh> solver(mesh);
    const TC::Solve_report report = solver.solve(singularities, x, TC::parameters::symmetry_order(n));
    solver.compute_field(x, field);

    std::vector<face_descriptor> seeds;
    for(std::size_t f = 0; f < order.faces.size(); f += 10)
      seeds.push_back(order.faces[f]);
    const auto lines = TC::trace_streamlines(mesh, x, field, singularities, seeds, TC::parameters::symmetry_order(n));

    // every segment of a streamline lies along one of the n directions of its face
    double worst = 0;
    std::size_t segments = 0;
    for(const auto& line : lines)
      for(std::size_t i = 0; i + 1 < line.points.size(); ++i, ++segments) {
        const Vector s(line.points[i + 1][0] - line.points[i][0], line.points[i + 1][1] - line.points[i][1],
                       line.points[i + 1][2] - line.points[i][2]);
        const Vector u = field[line.faces[i]];
        const Vector normal = CGAL::Polygon_mesh_processing::compute_face_normal(line.faces[i], mesh);
        const double angle = std::atan2(CGAL::cross_product(u, s) * normal, u * s);
        const double step = 2 * CGAL_PI / n;
        worst = (std::max)(worst, std::abs(angle - step * std::round(angle / step)));
      }

    const std::string vtk = (out_dir / "field.vtk").string(), polylines = (out_dir / "streamlines.vtk").string();
    TC::write_files_atomically(
      {{vtk, [&](std::ostream& os) { TC::write_field_vtk(os, mesh, field, singularities, TC::parameters::symmetry_order(n)); }},
       {polylines, [&](std::ostream& os) { TC::write_streamlines_vtk(os, lines); }}});

    std::cout << mesh_file << ": " << num_faces(mesh) << " triangles"
              << (order.source_faces.empty() ? std::string() : " (triangulated)") << ", " << singularities.size()
              << " singularities, n = " << n << "\n"
              << "max holonomy residual: " << (std::max)(report.max_vertex_residual, report.max_loop_residual) << "\n"
              << lines.size() << " streamlines, " << segments << " segments, largest angle to the field "
              << worst << " rad\n"
              << "wrote " << vtk << " and " << polylines << "\n";
    const bool ok = report.max_vertex_residual < 1e-9 && report.max_loop_residual < 1e-9 && worst < 1e-6 &&
                    segments > 0;
    std::cout << (ok ? "OK" : "FAILED") << std::endl;
    return ok ? 0 : 1;
  } catch(const TC::Invalid_input& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return 1;
  }
}
