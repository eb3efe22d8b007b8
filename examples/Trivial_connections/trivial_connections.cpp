// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The command-line program: computes the trivial connection closest to Levi-Civita with prescribed
// singularities on a triangle mesh, and the n-direction field it defines, and writes both to files.
//
//   trivial_connections MESH [options]   (the options: trivial_connections_command_line.h, or --help)
//
// Exit status: 0 on success, 1 on an input error (mesh, singularities, solver, output files), 2 on a usage
// error. On any error one line `trivial_connections: error: <message>` goes to stderr and no output file is
// written (both files are committed together, only after everything succeeded).
// Progress (one line per phase with the elapsed time) goes to stderr when stderr is a terminal or with
// --progress, never otherwise.
//
// The steps of a run are in the headers beside this file (one translation unit): the command line
// (trivial_connections_command_line.h), the inputs (_inputs.h), the design modes (_design.h, _features.h), the
// output files (_outputs.h) and the report (_report.h); run() below gives their order.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/IO/atomic_file.h>
#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/field_file.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/quad_mesh.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>

#include "trivial_connections_command_line.h"
#include "trivial_connections_design.h"
#include "trivial_connections_features.h"
#include "trivial_connections_inputs.h"
#include "trivial_connections_outputs.h"
#include "trivial_connections_process.h"
#include "trivial_connections_repair.h"
#include "trivial_connections_report.h"
#include "trivial_connections_state.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>
#include <optional>
#include <string>

namespace {

using namespace trivial_connections_program;

Solver build_solver(const Options& o, const Inputs& in, const TC::Progress_callback& progress, Timings& time)
{
  Stopwatch stopwatch{time.setup};
  namespace P = TC::parameters;
  // the targets are known already: touching pins that disagree are left to the lattice (not rounded)
  const auto guides = P::guided_faces(in.guided_faces, P::guidance_weight(o.guidance_weight,
                                                                           P::face_directions(in.directions,
                                                                                              P::symmetry_order(o.n))));
  const auto np = P::progress(progress, P::weighting(o.weighting, P::constrained_faces(in.constrained_faces,
                                                       P::align_with_boundary(o.align_boundary, guides))));
  return naming_the_direction_file(o, in, [&] { return Solver(in.mesh, np); });
}

Solution solve(const Options& o, Inputs& in, Solver& solver, const TC::Progress_callback& progress,
               Timings& time)
{
  const Loop_periods loop_periods = boundary_loop_periods(o, in, solver);
  Stopwatch stopwatch{time.solve};
  Solution s;
  s.x = in.mesh.add_property_map<halfedge_descriptor, double>("h:tc_connection", 0.).first;
  s.field = in.mesh.add_property_map<face_descriptor, Kernel::Vector_3>("f:tc_field", CGAL::NULL_VECTOR).first;
  const auto np = TC::parameters::progress(progress, TC::parameters::face_directions(
                                                       in.directions, TC::parameters::symmetry_order(o.n)));
  if(in.boundary_indices.empty()) {
    s.report = naming_the_direction_file(o, in, [&] { return solver.solve(in.singularities, s.x, np); });
  } else {
    // the solver checks the loops (every hole of a component or none, Poincare-Hopf): name the file
    try {
      s.report = naming_the_direction_file(
        o, in, [&] { return solver.solve(in.singularities, s.x, TC::parameters::loop_periods(loop_periods, np)); });
    } catch(const TC::Invalid_input& e) {
      if(e.code() != TC::Error_code::invalid_loop_periods)
        throw;
      throw TC::Invalid_input(e.code(), o.boundary_indices + ": " + e.what(), e.where());
    }
  }
  solver.compute_field(s.x, s.field, np);
  return s;
}

// The quads of a solution; when --quad-cone-modes is not given and they have singular vertices wound the wrong
// number of times (valence errors that the map's least squares already make: manual, Untangling), made again
// with the map made to wind as the indices ask, and those kept when they have fewer flaws (elephant has more)
Quads make_quads_trying_cone_modes(const Options& o, const Inputs& in, const Solution& s, Progress_printer& progress,
                                   Timings& time)
{
  Quads quads = make_quad_mesh(o, in, s, progress, time);
  if(o.quad_cone_modes < 0 && quads.report && quads.report->wrongly_wound_singularities > 0) {
    std::optional<Quads> wound;
    try {
      wound = make_quad_mesh(o, in, s, progress, time, -1, automatic_quad_cone_mode_weight);
    } catch(const TC::Invalid_input&) {
      // a rounding fitted to another map can be infeasible where the first was not: the first quads stay
    }
    if(wound && quad_flaws(*wound) < quad_flaws(quads)) {
      wound->flaws_without_cone_modes = quad_flaws(quads);
      quads = std::move(*wound);
    }
  }
  return quads;
}

int run(const Options& o, Progress_printer& progress)
{
  const TC::Progress_callback solver_progress = progress.callback();
  Timings time;
  Inputs in;
  read_inputs(o, progress, in, time);
  Solver solver = build_solver(o, in, solver_progress, time);
  Design design;
  design_singularities(o, in, solver, design, progress, time);
  const Singularities placed = in.singularities;
  design.moved_off_features = move_singularities_off_features(o, in);
  Solution solution = solve(o, in, solver, solver_progress, time);
  Quads quads = make_quads_trying_cone_modes(o, in, solution, progress, time);
  if(design.moved_off_features > 0 && quad_flaws(quads) > 0) {
    // the move folds less at most sizes, not all (fandisk at the diagonal / 54: 54 folded triangles moved, 29 + 2
    // degenerate not): the quads without it, kept when they have fewer flaws (the solves reuse the factor)
    const Singularities moved = in.singularities;
    in.singularities = placed;
    solution = solve(o, in, solver, solver_progress, time);
    std::optional<Quads> unmoved;
    try {
      unmoved = make_quads_trying_cone_modes(o, in, solution, progress, time);
    } catch(const TC::Invalid_input&) {
      // without the move the rounding can be infeasible (fandisk at the diagonal / 25): the moved quads stay
    }
    if(unmoved && quad_flaws(*unmoved) < quad_flaws(quads)) {
      design.moves_not_kept = design.moved_off_features;
      design.flaws_moved = quad_flaws(quads);
      design.flaws_kept = quad_flaws(*unmoved);
      design.moved_off_features = 0;
      quads = std::move(*unmoved);
    } else {
      in.singularities = moved; // the connection and field of the moved set again (x and field are shared maps)
      solution = solve(o, in, solver, solver_progress, time);
    }
  }
  if(o.quad_scale_smoothness < 0 && quad_flaws(quads) > 0) {
    // The folds around the singularities of fine organic meshes go with the field scaled per face (bunny00 at
    // 3,000 quads: 29 folded triangles -> 0), which elsewhere only makes the quads' sizes uneven (fandisk: the
    // Hausdorff distance 0.60 -> 0.75 H): tried when the quads have flaws, kept when it has fewer (the same field)
    std::optional<Quads> scaled;
    try {
      scaled = make_quad_mesh(o, in, solution, progress, time, automatic_quad_scale_smoothness,
                              quads.cone_mode_weight);
    } catch(const TC::Invalid_input&) {
      // the rounding of the scaled map can be infeasible (fandisk with its feature lines at 6,000 quads)
    }
    if(scaled && quad_flaws(*scaled) < quad_flaws(quads)) {
      scaled->flaws_unscaled = quad_flaws(quads);
      scaled->flaws_without_cone_modes = quads.flaws_without_cone_modes;
      quads = std::move(*scaled);
    }
  }
  write_outputs(o, in, solver, solution, quads, progress, time);
  print_report(std::cout, o, in, solution, design, quads, time, solver);
#ifndef __SANITIZE_ADDRESS__
  // Done: the files are complete. Freeing the mesh, the solver and its factor piece by piece would take about 3 %
  // of the run for memory that the kernel takes back at once (the sanitizer builds still destroy everything).
  std::cout.flush();
  std::cerr.flush();
  std::_Exit(0);
#endif
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  Options options;
  try {
    options = parse_arguments(argc, argv);
  } catch(const std::exception& e) { // a Usage_error, or anything else out of the command line: status 2
    return fail(e.what(), 2, std::find(argv + 1, argv + argc, std::string("--error-codes")) != argv + argc
                                 ? "usage_error" : nullptr);
  }
  if(options.help) {
    std::cout << usage_text;
    return 0;
  }
  if(options.version) {
    print_version(std::cout);
    return 0;
  }
  one_blas_thread_under_address_limit(argv);
  use_huge_pages(argv, options.mesh);
  stop_idle_blas_threads();
  Progress_printer progress(options.progress || stderr_is_terminal());
  try {
    return run(options, progress);
  } catch(const TC::Invalid_input& e) {
    progress.end_line();
    return fail(e.what(), 1, options.error_codes ? TC::error_code_name(e.code()) : nullptr);
  } catch(const std::bad_alloc&) {
    progress.end_line();
    return fail("out of memory", 1, options.error_codes ? "out_of_memory" : nullptr);
  } catch(const std::exception& e) {
    progress.end_line();
    return fail(e.what(), 1, options.error_codes ? "internal_error" : nullptr);
  } catch(...) {
    progress.end_line();
    return fail("unexpected error", 1, options.error_codes ? "internal_error" : nullptr);
  }
}
