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
#include <CGAL/Trivial_connections/singularities_off_features.h>

#include "trivial_connections_command_line.h"
#include "trivial_connections_inputs.h"
#include "trivial_connections_state.h"

#include <iterator>
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
  --auto --align-features --quad-mesh: the placed singularities closer than H to a sharp edge (but not on one) are
  moved to the nearest vertex at least H from every sharp edge, before the final solve
  (TC::move_singularities_off_features(), with the same H as the quad step: --quad-size, or --target-faces read by
  the same rule). Fandisk at H = diagonal / 40: 6 moved, folded triangles 55 + 8 degenerate -> 40 + 1, valence
  errors 22 -> 12. The singularities of --singularities stay (fixed_vertices). Returns how many moved.
*/
inline std::size_t move_singularities_off_features(const Options& o, Inputs& in)
{
  if(!o.automatic || !o.align_features || o.quad_mesh.empty())
    return 0;
  namespace P = TC::parameters;
  std::vector<char> sharp = in.features.sharp_edges;
  sharp.resize(num_edges(in.mesh), 0);
  const auto features = boost::make_iterator_property_map(sharp.begin(), get(boost::edge_index, in.mesh));
  std::vector<vertex_descriptor> fixed;
  for(const auto& s : in.fixed) // --singularities with --auto: the file's stay where they are
    fixed.push_back(s.first);
  // the quad step's H: --quad-size, or --target-faces by compute_quad_mesh()'s rule
  const double H = o.quad_size > 0 ? o.quad_size : TC::quad_size_for_target_faces(in.mesh, o.target_faces);
  const auto report =
    TC::move_singularities_off_features(in.mesh, in.singularities, features, P::quad_size(H, P::fixed_vertices(fixed)));
  in.singularities.assign(report.singularities.begin(), report.singularities.end());
  return report.moves.size();
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_DESIGN_H
