// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The design modes of the program trivial_connections (trivial_connections.cpp): --align-curvature, --auto and
// --refine choose the guides and the singularities before the final solve. Included by that file only: the program
// is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_DESIGN_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_DESIGN_H

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>

#include "trivial_connections_command_line.h"
#include "trivial_connections_inputs.h"
#include "trivial_connections_state.h"

#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

namespace trivial_connections_program {

// --align-curvature: the guide (principal directions times anisotropy) on every face, and the faces guided towards
// it in the trivial connection (the user's guided faces are none: the options exclude each other)
inline void align_with_curvature(const Options& o, Inputs& in, Solver& solver, Design& design)
{
  in.curvature = in.mesh.add_property_map<face_descriptor, Kernel::Vector_3>("f:tc_curvature", CGAL::NULL_VECTOR).first;
  TC::principal_curvature_guide(solver, in.curvature);
  // no guide where the field is constrained: on the constrained faces, and on the boundary faces when aligned
  for(face_descriptor f : in.constrained_faces)
    in.curvature[f] = CGAL::NULL_VECTOR;
  if(o.align_boundary)
    for(face_descriptor f : in.order.faces)
      for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, in.mesh), in.mesh))
        if(CGAL::is_border(opposite(h, in.mesh), in.mesh))
          in.curvature[f] = CGAL::NULL_VECTOR;
  const std::vector<face_descriptor> guided = TC::spread_guided_faces(solver, in.curvature, 64);
  design.curvature_guides = guided.size();
  in.guided_faces = guided;
  for(face_descriptor f : guided)
    in.directions[f] = in.curvature[f];
  naming_the_direction_file(o, in, [&] {
    return solver.set_constraints(TC::parameters::guided_faces(in.guided_faces,
                                                               TC::parameters::constrained_faces(in.constrained_faces)));
  });
}

inline std::string refinement_stop(TC::Refinement_stop stop)
{
  switch(stop) {
  case TC::Refinement_stop::local_minimum:
    return "a local minimum of the energy";
  case TC::Refinement_stop::maximum_trials:
    return "the budget of trials ran out";
  default:
    return "its best moves did not lower the energy once the integers were chosen again";
  }
}

// --auto (which refines unless --no-refine) and --refine: the singularities the trivial connection gets
inline void design_singularities(const Options& o, Inputs& in, Solver& solver, Design& design, Progress_printer& progress,
                          Timings& time)
{
  Stopwatch stopwatch{time.placement};
  namespace P = TC::parameters;
  if(o.align_curvature) {
    progress.begin("curvature guide");
    align_with_curvature(o, in, solver, design);
    progress.end("curvature guide", std::to_string(design.curvature_guides) + " guided faces");
  }
  if(o.automatic) {
    progress.begin("placement");
    in.fixed = in.singularities;
    Singularities placed;
    // the holes' indices of --boundary-indices fix the index sums of their components; the constrained faces are
    // held at their directions in the smooth field
    const auto base = P::loop_periods(boundary_loop_periods(o, in, solver),
                                      P::align_with_boundary(o.align_boundary, P::face_directions(in.directions,
                                                                                                  P::symmetry_order(o.n))));
    auto place = [&](const auto& np) {
      if(o.align_curvature)
        design.placement = TC::place_singularities(solver, std::back_inserter(placed),
                                                   P::alignment_strength(o.alignment_strength,
                                                                         P::alignment_guide(in.curvature, np)));
      else
        design.placement = TC::place_singularities(solver, std::back_inserter(placed), np);
    };
    if(in.fixed.empty())
      place(base);
    else
      place(P::fixed_singularities(in.fixed, base));
    in.singularities = placed;
    const TC::Placement_report& p = *design.placement;
    progress.end("placement", std::string(p.aligned ? "curvature-aligned" : "smoothest") + " field" +
                                (p.iterations > 0 ? ", " + std::to_string(p.iterations) + " iterations" : "") + ", " +
                                std::to_string(p.number_of_singularities) + " singularities");
  }
  if(o.refine) {
    progress.begin("refinement");
    std::vector<vertex_descriptor> fixed_vertices;
    for(const auto& s : in.fixed)
      fixed_vertices.push_back(s.first);
    auto x = in.mesh.add_property_map<halfedge_descriptor, double>("h:tc_refinement", 0.).first;
    // with the holes' indices of --boundary-indices, as the final solve has them
    const Loop_periods loop_periods = boundary_loop_periods(o, in, solver);
    design.refinement = naming_the_direction_file(o, in, [&] {
      return TC::refine_singularities(
        solver, in.singularities, x,
        P::loop_periods(loop_periods,
                        P::cancel_pairs(o.cancel_pairs,
                                        P::fixed_vertices(fixed_vertices, P::face_directions(in.directions,
                                                                                             P::symmetry_order(o.n))))));
    });
    in.mesh.remove_property_map(x);
    in.singularities.assign(design.refinement->singularities.begin(), design.refinement->singularities.end());
    const auto& r = *design.refinement;
    progress.end("refinement", std::to_string(r.moves.size()) + " moves in " + std::to_string(r.trials) + " trial solves, " +
                                 refinement_stop(r.stop));
  }
}

/*
  --auto --align-features --quad-mesh: the singular vertices placed closer than H to a sharp edge (but not on
  one) are moved to the nearest vertex at least H from every sharp edge, before the final solve. Such a vertex
  is an integer point of the map and the sharp edge an integer iso-line: a distance below H rounds to 0 (the
  quads between them collapse) or to 1 (they stretch), and the map folds there (issue 43, fandisk: 6 moved,
  folded triangles 55 + 8 degenerate -> 40 + 1, valence errors 22 -> 12). Moving them onto the sharp edges
  instead costs the field a quarter turn between its pins (fandisk: energy 18 -> 119, a thousand folds).
  This is the program's design step, not compute_quad_mesh()'s: that call takes a solved field, and moving a
  singularity needs the trivial connection solved again (here, the final solve). Distances along mesh edges;
  the nearest vertex by that distance from the singularity, away from the sharp edges, not singular, not on
  the border; none: the singularity stays. Returns how many moved.
*/
inline std::size_t move_singularities_off_features(const Options& o, Inputs& in)
{
  if(!o.automatic || !o.align_features || o.quad_mesh.empty())
    return 0;
  const Mesh& mesh = in.mesh;
  double H = o.quad_size;
  if(!(H > 0)) { // --target-faces, as compute_quad_mesh() reads it
    double area = 0;
    for(face_descriptor f : faces(mesh)) {
      const auto h = halfedge(f, mesh);
      area += std::sqrt(CGAL::to_double(CGAL::squared_area(mesh.point(source(h, mesh)), mesh.point(target(h, mesh)),
                                                           mesh.point(target(next(h, mesh), mesh)))));
    }
    H = std::sqrt(area / double(o.target_faces));
  }
  const std::size_t nv = mesh.number_of_vertices() + mesh.number_of_removed_vertices();
  std::vector<char> on_line(nv, 0);
  for(auto e : edges(mesh))
    if(in.features.sharp_edges[std::size_t(e)])
      on_line[std::size_t(source(e, mesh))] = on_line[std::size_t(target(e, mesh))] = 1;
  using Item = std::pair<double, vertex_descriptor>;
  auto length = [&](halfedge_descriptor h) {
    return std::sqrt(CGAL::to_double(CGAL::squared_distance(mesh.point(source(h, mesh)), mesh.point(target(h, mesh)))));
  };
  // distance to the sharp edges' vertices (Dijkstra from all of them)
  std::vector<double> to_line(nv, std::numeric_limits<double>::infinity());
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for(vertex_descriptor v : vertices(mesh))
    if(on_line[std::size_t(v)]) {
      to_line[std::size_t(v)] = 0;
      queue.push({0., v});
    }
  while(!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if(d > to_line[std::size_t(v)])
      continue;
    for(halfedge_descriptor h : CGAL::halfedges_around_source(v, mesh))
      if(d + length(h) < to_line[std::size_t(target(h, mesh))]) {
        to_line[std::size_t(target(h, mesh))] = d + length(h);
        queue.push({d + length(h), target(h, mesh)});
      }
  }
  std::vector<char> singular(nv, 0), kept(nv, 0);
  for(const auto& s : in.singularities)
    singular[std::size_t(s.first)] = 1;
  for(const auto& s : in.fixed) // --singularities with --auto: the file's stay where they are
    kept[std::size_t(s.first)] = 1;
  std::size_t moved = 0;
  std::vector<double> from(nv, std::numeric_limits<double>::infinity());
  std::vector<vertex_descriptor> touched;
  for(auto& s : in.singularities) {
    const vertex_descriptor v = s.first;
    if(on_line[std::size_t(v)] || kept[std::size_t(v)] || !(to_line[std::size_t(v)] < H))
      continue;
    // the nearest vertex at least H from the lines, through vertices off them
    for(vertex_descriptor w : touched)
      from[std::size_t(w)] = std::numeric_limits<double>::infinity();
    touched.assign(1, v);
    from[std::size_t(v)] = 0;
    queue.push({0., v});
    vertex_descriptor found = Mesh::null_vertex();
    while(!queue.empty()) {
      const auto [d, u] = queue.top();
      queue.pop();
      if(d > from[std::size_t(u)])
        continue;
      if(to_line[std::size_t(u)] >= H && !singular[std::size_t(u)] && !mesh.is_border(u)) {
        found = u;
        break;
      }
      for(halfedge_descriptor h : CGAL::halfedges_around_source(u, mesh)) {
        const vertex_descriptor w = target(h, mesh);
        if(!on_line[std::size_t(w)] && d + length(h) < from[std::size_t(w)]) {
          from[std::size_t(w)] = d + length(h);
          touched.push_back(w);
          queue.push({d + length(h), w});
        }
      }
    }
    queue = decltype(queue)();
    if(found == Mesh::null_vertex())
      continue;
    singular[std::size_t(v)] = 0;
    singular[std::size_t(found)] = 1;
    s.first = found;
    ++moved;
  }
  return moved;
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_DESIGN_H
