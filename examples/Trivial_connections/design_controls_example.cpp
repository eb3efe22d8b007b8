// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Design controls on a cross field (n = 4) over the package's example sphere (examples/data/sphere.off, or
// the mesh given as argument): eight +1/4 singularities; two faces whose direction is pinned (hard
// constraints); three faces drawn towards a guide (soft guidance, weight 2); then one more pinned face on the
// same prefactored solver. Checks that the field meets every pinned direction and prints the angle to each
// guide; exits 0 iff every residual is below 1e-9.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;
using vertex_descriptor = Mesh::Vertex_index;
using face_descriptor = Mesh::Face_index;

// the angle from u to the field vector v in the plane of face f, modulo 2 pi / 4
double angle_mod_quarter(const Mesh& mesh, face_descriptor f, const Vector& u, const Vector& v)
{
  const auto h = halfedge(f, mesh);
  const Point& a = mesh.point(source(h, mesh));
  const Point& b = mesh.point(target(h, mesh));
  const Point& c = mesh.point(target(next(h, mesh), mesh));
  Vector normal = CGAL::cross_product(b - a, c - a);
  normal = normal / std::sqrt(normal.squared_length());
  const Vector t = u - (u * normal) * normal; // the direction as the solver sees it: projected
  const double angle = std::atan2(CGAL::cross_product(t, v) * normal, t * v);
  const double quarter = CGAL_PI / 2;
  return angle - quarter * std::round(angle / quarter);
}

int run(int argc, char** argv)
{
  const std::string file = argc > 1 ? argv[1] : "examples/data/sphere.off";
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(file, mesh) || is_empty(mesh)) {
    std::cerr << "cannot read " << file << "\n";
    return 1;
  }
  // eight +1/4 singularities at vertices spread over the sphere (their indices sum to 2)
  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> singularities;
  const std::size_t nv = num_vertices(mesh);
  for(std::size_t i = 0; i < 8; ++i)
    singularities.push_back({vertex_descriptor(Mesh::size_type(i * nv / 8)), TC::Singularity_index(1, 4)});

  std::vector<face_descriptor> all(faces(mesh).begin(), faces(mesh).end());
  std::vector<face_descriptor> pinned = {all[0], all[all.size() / 2]};
  const std::vector<face_descriptor> guided = {all[all.size() / 5], all[2 * all.size() / 5], all[4 * all.size() / 5]};
  // the directions of the pinned and guided faces (a property map read by solve() and compute_field())
  auto directions = mesh.add_property_map<face_descriptor, Vector>("f:directions", Vector(1, 0, 0)).first;
  directions[all[all.size() / 5]] = Vector(0, 1, 0);
  directions[all[3 * all.size() / 4]] = Vector(0, 0, 1);

  TC::Trivial_connection_solver<Mesh> solver(
    mesh, TC::parameters::constrained_faces(pinned, TC::parameters::guided_faces(guided, TC::parameters::guidance_weight(2.))));
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:connection", 0.).first;
  auto field = mesh.add_property_map<face_descriptor, Vector>("f:field", CGAL::NULL_VECTOR).first;

  bool ok = true;
  for(int round = 0; round < 2; ++round) {
    if(round == 1) {
      // one more pinned face: the solver keeps its factorization and adds one forward substitution per new link
      pinned.push_back(all[3 * all.size() / 4]);
      const TC::Constraint_update update = solver.set_constraints(
        TC::parameters::constrained_faces(pinned, TC::parameters::guided_faces(guided)));
      std::cout << "set_constraints: " << (update.refactored ? "refactored" : "factorization kept") << ", "
                << update.new_forward_substitutions << " new forward substitutions\n";
    }
    const TC::Solve_report report = solver.solve(
      singularities, x, TC::parameters::symmetry_order(4, TC::parameters::face_directions(directions)));
    solver.compute_field(x, field, TC::parameters::symmetry_order(4, TC::parameters::face_directions(directions)));
    double worst = 0;
    for(face_descriptor f : pinned)
      worst = (std::max)(worst, std::abs(angle_mod_quarter(mesh, f, directions[f], field[f])));
    std::cout << pinned.size() << " pinned faces, " << guided.size() << " guided: energy " << report.energy
              << " + guidance " << report.guidance_energy << "; largest angle to a pinned direction " << worst
              << "; angles to the guides:";
    for(const TC::Guidance_report& g : report.guidance)
      std::cout << " " << g.mismatch;
    std::cout << "\n";
    ok = ok && worst < 1e-9 && report.max_vertex_residual < 1e-9 && report.max_constraint_residual < 1e-9;
  }
  std::cout << (ok ? "OK" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}

int main(int argc, char** argv)
{
  try {
    return run(argc, argv);
  } catch(const TC::Invalid_input& e) { // for example a direction normal to its face on another mesh
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
