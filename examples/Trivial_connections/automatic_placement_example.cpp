// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Direction fields without a singularity file: on an ellipsoid with three distinct axes, the singularities of a
// cross field are placed automatically (the globally smoothest field's), then those of a line field aligned with
// the principal curvature directions (its four +1/2 singularities are the umbilics), and the trivial connection
// with exactly them is solved, guided towards the curvature; finally the cross field's singularities are refined
// by moves on the prefactored solver. Exits 0 iff every step's invariants hold.
// Usage: automatic_placement_example [MESH]   (default examples/data/sphere.off, scaled into an ellipsoid)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>

#include <iostream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
namespace P = CGAL::Trivial_connections::parameters;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Solver = TC::Trivial_connection_solver<Mesh>;
using Singularities = std::vector<std::pair<Solver::vertex_descriptor, TC::Singularity_index>>;

void print(const char* what, const TC::Placement_report& r)
{
  std::cout << what << ": " << r.number_of_singularities << " singularities (";
  for(const auto& [index, count] : r.singularities_per_index)
    std::cout << " " << count << " x " << index;
  std::cout << " ), field energy " << r.field_energy << ", " << r.iterations << " iterations\n";
}

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : std::string(TC_EXAMPLE_DATA_DIR) + "/sphere.off";
  Mesh mesh;
  TC::read_triangle_mesh(path, mesh);
  if(argc <= 1)
    for(auto v : vertices(mesh)) {
      const Point& p = mesh.point(v);
      mesh.point(v) = Point(1.6 * p.x(), 1.2 * p.y(), 0.8 * p.z());
    }
  Solver solver(mesh);
  auto x = mesh.add_property_map<Solver::halfedge_descriptor, double>("h:x", 0.).first;
  bool ok = true;

  // 1. a cross field from the mesh alone
  Singularities cross;
  const TC::Placement_report smooth = TC::place_singularities(solver, std::back_inserter(cross), P::symmetry_order(4));
  print("smoothest cross field", smooth);
  const TC::Solve_report r4 = solver.solve(cross, x, P::symmetry_order(4));
  std::cout << "  trivial connection with them: energy " << r4.energy << " (at most the field energy when its "
            << "integers are optimal), residual " << r4.max_vertex_residual << "\n";
  ok = ok && r4.max_vertex_residual < 1e-9 && (!r4.integers_proven_optimal || r4.energy <= smooth.field_energy * (1 + 1e-9));

  // 2. a line field aligned with the curvature: placement from the aligned field, then guidance towards it
  auto guide = mesh.add_property_map<Solver::face_descriptor, Vector>("f:guide", CGAL::NULL_VECTOR).first;
  TC::principal_curvature_guide(solver, guide);
  Singularities lines;
  const TC::Placement_report aligned =
    TC::place_singularities(solver, std::back_inserter(lines), P::alignment_guide(guide, P::symmetry_order(2)));
  print("curvature-aligned line field", aligned);
  solver.set_constraints(P::guided_faces(TC::spread_guided_faces(solver, guide, 64)));
  const TC::Solve_report r2 = solver.solve(lines, x, P::face_directions(guide, P::symmetry_order(2)));
  std::cout << "  trivial connection guided on " << r2.guidance.size() << " faces: energy " << r2.energy
            << " + guidance " << r2.guidance_energy << "\n";
  ok = ok && r2.max_vertex_residual < 1e-9;

  // 3. the cross field's singularities moved to where they cost least (no guides for this one)
  solver.set_constraints();
  const auto refined = TC::refine_singularities(solver, cross, x, P::cancel_pairs(true, P::symmetry_order(4)));
  std::cout << "refinement: energy " << refined.energy_before << " -> " << refined.energy_after << ", "
            << refined.moves.size() << " moves in " << refined.trials << " trial solves"
            << (refined.local_minimum ? " (a local minimum)" : " (stopped before a local minimum)") << "\n";
  ok = ok && refined.energy_after <= refined.energy_before && refined.report.max_vertex_residual < 1e-9;

  std::cout << (ok ? "OK" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}
