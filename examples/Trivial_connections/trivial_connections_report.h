// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The report of the program trivial_connections (trivial_connections.cpp) on stdout: the mesh, the design, the
// energy, the design controls, the loops, the files and the times. Included by that file only: the program is one
// translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_REPORT_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_REPORT_H

#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/solver_traits.h>

#include "trivial_connections_command_line.h"
#include "trivial_connections_design.h"
#include "trivial_connections_features.h"
#include "trivial_connections_repair.h"
#include "trivial_connections_state.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace trivial_connections_program {

inline std::size_t number_of_interior_edges(const Mesh& mesh)
{
  std::size_t interior_edges = 0;
  for(auto e : edges(mesh))
    if(!CGAL::is_border(e, mesh))
      ++interior_edges;
  return interior_edges;
}

inline void print_mesh(std::ostream& out, const Options& o, const Inputs& in, const TC::Solve_report& report,
                std::size_t interior_edges)
{
  out << "mesh: " << o.mesh << ": " << num_vertices(in.mesh) << " vertices, " << num_faces(in.mesh) << " faces, "
      << num_edges(in.mesh) << " edges (" << interior_edges << " interior), " << report.components.size()
      << (report.components.size() == 1 ? " component\n" : " components\n");
  if(in.repair)
    out << repair_report_line(*in.repair);
  const std::vector<std::size_t>& source_faces = in.order.source_faces;
  if(!source_faces.empty()) {
    std::size_t split = 0; // faces of the file that gave more than one triangle
    for(std::size_t t = 0; t < source_faces.size(); ++t)
      split += (t == 0 || source_faces[t] != source_faces[t - 1]) && t + 1 < source_faces.size() &&
               source_faces[t + 1] == source_faces[t];
    out << "triangulated: " << split << " of the file's " << source_faces.back() + 1
        << " faces had more than three vertices, " << source_faces.size() << " triangles\n";
  }
  const std::size_t max_lines = 10;
  for(std::size_t c = 0; c < report.components.size() && c < max_lines; ++c) {
    const TC::Component_report& r = report.components[c];
    out << "  component " << c << ": " << r.number_of_faces << " faces, chi = " << r.euler_characteristic
        << ", genus " << r.genus << ", " << r.number_of_boundary_loops << " boundary loop"
        << (r.number_of_boundary_loops == 1 ? "" : "s") << ", vertex index sum " << r.vertex_index_sum << "\n";
  }
  if(report.components.size() > max_lines)
    out << "  ... and " << report.components.size() - max_lines << " more components\n";
}

inline void print_energy(std::ostream& out, const Options& o, const Inputs& in, const TC::Solve_report& report)
{
  out << "singularities: " << in.singularities.size()
      << (o.singularities.empty() ? std::string() : " (from " + o.singularities + ")")
      << (o.boundary_indices.empty() ? std::string() : "; boundary indices from " + o.boundary_indices)
      << "; n = " << o.n << "; weights " << o.weights_name << "\n";
  out << "energy: " << std::setprecision(10) << report.energy;
  if(!in.guided_faces.empty())
    out << " + guidance " << report.guidance_energy << " = " << report.energy + report.guidance_energy;
  if(!report.loops.empty() || !report.constraints.empty())
    out << " (with the integers rounded one by one: " << report.rounding_energy << ")";
  out << "\n";
  out << "max residual: vertices " << scientific(report.max_vertex_residual) << ", loops "
      << scientific(report.max_loop_residual);
  if(!report.constraints.empty())
    out << ", constraints " << scientific(report.max_constraint_residual);
  out << "\n";
}


// whether the integers (loops, links) are proven optimal, else how far below the optimum may be
inline std::string integers_verdict(const TC::Solve_report& report)
{
  if(report.integers_proven_optimal)
    return "proven optimal";
  const double minimised = report.energy + report.guidance_energy;
  std::ostringstream text;
  text << "not proven optimal (no choice gives less than " << std::setprecision(10) << report.energy_lower_bound
       << ": the optimum is at most " << std::setprecision(3)
       << 100 * (minimised - report.energy_lower_bound) / minimised << " % below this energy)";
  return text.str();
}

inline void print_design_controls(std::ostream& out, const Options& o, const Inputs& in, const TC::Solve_report& report)
{
  if(!in.guides.empty()) {
    double worst = 0;
    for(const TC::Guidance_report& g : report.guidance)
      worst = (std::max)(worst, std::abs(g.mismatch));
    out << "guidance: " << in.guides.size() << " face" << (in.guides.size() == 1 ? "" : "s") << " from "
        << o.guidance << ", weight " << o.guidance_weight << "; guidance energy " << report.guidance_energy
        << ", largest angle to a guide " << fixed(worst, 6) << " rad\n";
  }
  if(in.constraints.empty() && !o.align_boundary && in.guides.empty() && in.features.pinned == 0)
    return;
  std::string parts;
  auto part = [&](const std::string& p) { parts += (parts.empty() ? "" : "; ") + p; };
  if(!in.constraints.empty())
    part(std::to_string(in.constraints.size()) + (in.constraints.size() == 1 ? " face" : " faces") + " from " +
         o.constraints);
  if(in.features.pinned > 0)
    part(std::to_string(in.features.pinned) + " beside feature curves");
  if(o.align_boundary)
    part("aligned with the boundary");
  if(!in.guides.empty())
    part(std::to_string(in.guides.size()) + " guided");
  std::size_t decided = 0;
  for(const TC::Constraint_report& c : report.constraints)
    decided += c.decided ? 1 : 0;
  const std::size_t chosen = report.constraints.size() - decided;
  out << "constraints: " << parts << "; " << report.constraints.size()
      << (report.constraints.size() == 1 ? " link" : " links") << " between constrained or guided faces: " << decided
      << " between touching faces (the short way), " << chosen << " with integers chosen with the loops'";
  if(report.loops.empty())
    out << "; integers " << integers_verdict(report);
  out << "\n";
}

inline void print_loops(std::ostream& out, const Options& o, const TC::Solve_report& report)
{
  if(report.loops.empty()) {
    out << "loops: none (no generator, no boundary loop)\n";
    return;
  }
  std::size_t boundary = 0, generators = 0;
  for(const TC::Loop_report& l : report.loops)
    (l.kind == TC::Loop_kind::boundary ? boundary : generators) += 1;
  out << "loops: " << boundary << " boundary, " << generators << " generators; integers " << integers_verdict(report)
      << "\n";
  const std::size_t max_loops = 20;
  for(std::size_t l = 0; l < report.loops.size() && l < max_loops; ++l) {
    const TC::Loop_report& r = report.loops[l];
    out << "  loop " << l << " (component " << r.component << "): ";
    if(r.kind == TC::Loop_kind::boundary)
      out << "boundary, index " << r.index;
    else
      out << "generator, period " << r.period << " (holonomy 2pi*" << r.period << "/" << o.n << ")";
    out << (r.prescribed ? " (prescribed)" : "") << ", residual " << scientific(r.residual) << "\n";
  }
  if(report.loops.size() > max_loops)
    out << "  ... and " << report.loops.size() - max_loops << " more loops\n";
}

inline void print_design(std::ostream& out, const Options& o, const Design& d)
{
  if(d.placement) {
    const TC::Placement_report& p = *d.placement;
    out << "placement: " << (p.aligned ? "curvature-aligned field" : "smoothest field") << " (n = " << o.n;
    if(p.iterations > 0)
      out << ", " << p.iterations << " iterations";
    out << "), its connection energy " << std::setprecision(10) << p.field_energy << "; " << p.number_of_singularities
        << " singularities:";
    for(const auto& [index, count] : p.singularities_per_index)
      out << " " << count << " x " << index;
    if(p.fixed > 0)
      out << "; " << p.fixed << " kept from " << o.singularities;
    if(p.fixed > 0 || p.units_removed > 0 || p.units_added > 0)
      out << "; " << p.units_removed << " units of 1/" << o.n << " given way, " << p.units_added << " added";
    out << "\n";
  }
  if(d.curvature_guides > 0)
    out << "curvature guidance: " << d.curvature_guides << " faces, weight " << o.guidance_weight << "\n";
  if(d.placement) {
    // which field this is, in words: --auto refines unless --no-refine, and users of the old default should see it
    const std::string field = d.placement->aligned ? "curvature-aligned field" : "smoothest field";
    out << "design: the singularities of the " << field
        << (d.placement->fixed > 0 ? " (those of " + o.singularities + " kept)" : std::string()) << ", ";
    if(!d.refinement)
      out << "not refined (--no-refine)\n";
    else if(d.refinement->stop == TC::Refinement_stop::local_minimum)
      out << "refined to a local minimum of the energy (--no-refine keeps those of the " << field << ")\n";
    else
      out << "refined, stopped before a local minimum: " << refinement_stop(d.refinement->stop) << "\n";
  }
  if(d.refinement) {
    const auto& r = *d.refinement;
    out << "refinement: energy " << std::setprecision(10) << r.energy_before << " -> " << r.energy_after << ", "
        << r.singularities_before << " -> " << r.singularities.size() << " singularities, " << r.moves.size()
        << " moves (" << r.cancellations << " cancellations) in " << r.trials << " trial solves ("
        << refinement_stop(r.stop) << ")\n";
  }
  if(o.automatic && o.align_features && !o.quad_mesh.empty()) {
    out << "singularities moved off feature lines: " << d.moved_off_features;
    if(d.moves_not_kept > 0)
      out << " (the " << d.moves_not_kept << " closer than H to a sharp edge stay where they were placed: with them "
          << "moved the quads had more flaws, " << d.flaws_moved << " folded or degenerate triangles and valence "
          << "errors against " << d.flaws_kept << ")\n";
    else
      out << " (closer than H to a sharp edge, now at least H from every one, before the final solve)\n";
  }
}

// The backend that factored the constraint system: the program's traits choose it by predicted cost
template <class SolverTraits>
std::string factorization_backend(const SolverTraits&)
{
  return "Eigen SimplicialLDLT";
}

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
template <class Crossover>
std::string factorization_backend(const TC::Cost_based_solver_traits<Crossover>& traits)
{
  std::ostringstream s;
  switch(traits.backend()) {
  case TC::Factorization_backend::simplicial_ldlt: s << "Eigen SimplicialLDLT"; break;
  case TC::Factorization_backend::cholmod_supernodal: s << "CHOLMOD supernodal"; break;
  case TC::Factorization_backend::none: return "none (no constraint row)";
  }
  s << ", chosen by predicted cost (factor: " << std::setprecision(3) << traits.factor_nonzeros()
    << " nonzeros, " << traits.factor_flops() / 1e9 << " GFlop)";
  return s.str();
}
#endif

// --quad-mesh: one line, the quads and their defects; the Hausdorff distance in units of H
inline void print_quads(std::ostream& out, const Options& o, const Quads& quads)
{
  if(!quads.report)
    return;
  const TC::Quad_mesh_report& r = *quads.report;
  std::error_code ec;
  out << "quad mesh: " << std::filesystem::absolute(o.quad_mesh, ec).string() << ": " << r.number_of_quads
      << " quads, " << r.number_of_vertices << " vertices, H = " << std::setprecision(6) << r.quad_size
      << "; valence errors " << r.valence_errors << ", folded triangles " << r.folded_triangles << " (degenerate "
      << r.degenerate_triangles << "), rejected polygons " << r.rejected_polygons << ", open edges " << r.open_edges
      << ", flipped quads " << r.flipped_quads << " (concave " << r.concave_quads << "); Hausdorff distance " << fixed(r.hausdorff_distance() / r.quad_size, 3)
      << " H (quads to input " << fixed(r.hausdorff_quads_to_input / r.quad_size, 3) << " H, input to quads "
      << fixed(r.hausdorff_input_to_quads / r.quad_size, 3) << " H); on iso-lines: " << r.feature_edges
      << " feature edges, border corners " << r.border_corners;
  if(r.wrongly_wound_singularities + r.branch_points > 0)
    out << "; wound the wrong number of times: " << r.wrongly_wound_singularities << " singular vertices, "
        << r.branch_points << " branch points";
  if(r.cone_modes)
    out << "; cone modes (weight " << quads.cone_mode_weight << "): the continuous map untangled first";
  if(quads.flaws_without_cone_modes > 0)
    out << "; without them " << quads.flaws_without_cone_modes
        << " folded and degenerate triangles and valence errors";
  if(r.naive_rounding_fallback)
    out << "; rounding: naive (the greedy rounding's integers contradicted each other)";
  if(r.inverted_before_untangling > 0 && !o.no_untangle)
    out << "; untangling: " << r.inverted_before_untangling << " folded and degenerate triangles in the rounded map"
        << (r.untangled ? ", " + std::to_string(r.folded_triangles + r.degenerate_triangles) + " after it"
                        : std::string(", kept (no fewer after it)"));
  if(quads.flaws_unscaled > 0)
    out << "; the field scaled per face (quad scale smoothness " << quads.scale_smoothness << "): without it "
        << quads.flaws_unscaled << " folded and degenerate triangles and valence errors";
  else if(quads.scale_smoothness > 0)
    out << "; the field scaled per face (quad scale smoothness " << quads.scale_smoothness << ")";
  out << "\n";
}

inline void print_report(std::ostream& out, const Options& o, const Inputs& in, const Solution& s, const Design& design,
                         const Quads& quads, const Timings& time, const Solver& solver)
{
  const std::size_t interior_edges = number_of_interior_edges(in.mesh);
  print_mesh(out, o, in, s.report, interior_edges);
  out << "factorization: " << factorization_backend(solver.solver_traits()) << "\n";
  print_design(out, o, design);
  if(o.align_features)
    out << feature_report_line(o, in.features);
  print_energy(out, o, in, s.report);
  print_design_controls(out, o, in, s.report);
  print_loops(out, o, s.report);
  std::error_code ec;
  out << "connection: " << std::filesystem::absolute(o.connection, ec).string() << " (" << interior_edges
      << " interior edges)\n";
  out << "field: " << std::filesystem::absolute(o.field, ec).string() << " (" << num_faces(in.mesh) << " faces)\n";
  print_quads(out, o, quads);
  out << "time: read " << fixed(time.read, 3) << " s, set-up " << fixed(time.setup, 3) << " s, ";
  if(o.automatic || o.refine || o.align_curvature)
    out << "placement " << fixed(time.placement, 3) << " s, ";
  out << "solve " << fixed(time.solve, 3) << " s, ";
  if(quads.report)
    out << "quad mesh " << fixed(time.quads, 3) << " s, ";
  out << "write " << fixed(time.write, 3) << " s\n";
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_REPORT_H
