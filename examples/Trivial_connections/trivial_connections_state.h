// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// What one run of the program trivial_connections (trivial_connections.cpp) reads, decides, computes and times, the
// types it names, and the number formats of its report. Included by that file only: the program is one translation
// unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_STATE_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_STATE_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/quad_mesh.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>

#include "trivial_connections_features.h"
#include "trivial_connections_repair.h"

#include <chrono>
#include <cstddef>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Solver = TC::Trivial_connection_solver<Mesh, CGAL::Default, TC::Recommended_solver_traits>;
using vertex_descriptor = boost::graph_traits<Mesh>::vertex_descriptor;
using halfedge_descriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
using face_descriptor = boost::graph_traits<Mesh>::face_descriptor;

namespace trivial_connections_program {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

inline std::string fixed(double x, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

inline std::string scientific(double x)
{
  std::ostringstream s;
  s << std::scientific << std::setprecision(2) << x;
  return s.str();
}

using Singularities = std::vector<std::pair<vertex_descriptor, TC::Singularity_index>>;
using Face_vectors = Mesh::Property_map<face_descriptor, Kernel::Vector_3>;

// What the input files say, on the mesh. The solver refers to the mesh, so this is never moved.
struct Inputs
{
  Mesh mesh;
  TC::Mesh_input_order<Mesh> order;
  std::optional<TC::Repair_report> repair; // --repair: what it changed
  Singularities singularities;
  std::vector<std::pair<std::size_t, TC::Singularity_index>> boundary_indices; // (vertex of the file, index)
  std::vector<TC::Face_direction> constraints, guides;
  std::vector<face_descriptor> constrained_faces, guided_faces;
  Face_vectors directions;          // of the constrained and guided faces
  std::vector<char> in_constraints; // by face of the file
  Singularities fixed;              // --auto with --singularities: the file's, kept
  Face_vectors curvature;           // --align-curvature: the guide on every face
  Feature_pins features;            // --align-features: its pins are among the constrained faces
};

// What --auto, --align-curvature and --refine did
struct Design
{
  std::optional<TC::Placement_report> placement;
  std::optional<TC::Refinement_report<vertex_descriptor>> refinement;
  std::size_t curvature_guides = 0;
  std::size_t moved_off_features = 0; // --auto --align-features --quad-mesh: see move_singularities_off_features()
  // when the quads with them moved had more flaws than without, and were not kept: how many would have moved, and
  // the flaws (folded and degenerate triangles, valence errors) both ways
  std::size_t moves_not_kept = 0, flaws_moved = 0, flaws_kept = 0;
};

struct Solution
{
  TC::Solve_report report;
  Mesh::Property_map<halfedge_descriptor, double> x;
  Face_vectors field;
};

// --quad-mesh: the quads and what compute_quad_mesh() reports
struct Quads
{
  std::optional<TC::Quad_mesh_report> report;
  Mesh mesh;
  double scale_smoothness = 0;     // the quad_scale_smoothness they were made with
  std::size_t flaws_unscaled = 0;  // when tried automatically: the flaws of the quads without the scale
  double cone_mode_weight = 0;     // the quad_cone_mode_weight they were made with
  std::size_t flaws_without_cone_modes = 0; // when tried automatically: the flaws of the quads without them
};

struct Timings
{
  double read = 0, setup = 0, placement = 0, solve = 0, quads = 0, write = 0;
};

// Adds its lifetime to `seconds` when it goes (a step done twice counts twice): it also times a step that returns
// the solver, which can be neither copied nor moved.
struct Stopwatch
{
  double& seconds;
  Clock::time_point start = Clock::now();
  ~Stopwatch() { seconds += seconds_since(start); }
};

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_STATE_H
