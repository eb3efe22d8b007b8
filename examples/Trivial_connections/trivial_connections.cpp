// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The command-line program: computes the trivial connection closest to Levi-Civita with prescribed
// singularities on a triangle mesh, and the n-direction field it defines, and writes both to files.
//
//   trivial_connections MESH [--singularities FILE] [--boundary-indices FILE] [--constraints FILE]
//                            [--triangulate] [--align-boundary] [--guidance FILE] [--guidance-weight MU] [--n N] [--weights hodge|unit]
//                            [--connection OUT] [--field OUT] [--vtk OUT] [--ply OUT] [--singularity-points OUT]
//                            [--streamlines OUT] [--streamline-seeds K] [--progress] [--help] [--version]
//
// Exit status: 0 on success, 1 on an input error (mesh, singularities, solver, output files), 2 on a usage
// error. On any error one line `trivial_connections: error: <message>` goes to stderr and no output file is
// written (both files are committed together, only after everything succeeded).
// Progress (one line per phase with the elapsed time) goes to stderr when stderr is a terminal or with
// --progress, never otherwise.

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
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>

#include "trivial_connections_command_line.h"
#include "trivial_connections_features.h"
#include "trivial_connections_process.h"
#include "trivial_connections_repair.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <new>
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

namespace {

using namespace trivial_connections_program;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string fixed(double x, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

std::string scientific(double x)
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
};

struct Solution
{
  TC::Solve_report report;
  Mesh::Property_map<halfedge_descriptor, double> x;
  Face_vectors field;
};

struct Timings
{
  double read = 0, setup = 0, placement = 0, solve = 0, write = 0;
};

// Sets `seconds` to its lifetime when it goes: it also times a step that returns the solver, which can
// be neither copied nor moved.
struct Stopwatch
{
  double& seconds;
  Clock::time_point start = Clock::now();
  ~Stopwatch() { seconds = seconds_since(start); }
};

void read_mesh(const Options& o, Progress_printer& progress, Inputs& in)
{
  progress.begin("reading mesh");
  try {
    if(o.repair)
      in.order = TC::read_and_repair_triangle_mesh(o.mesh, in.mesh, in.repair.emplace());
    else
      in.order = TC::read_triangle_mesh(o.mesh, in.mesh, TC::parameters::triangulate(o.triangulate));
  } catch(const TC::Invalid_input& e) {
    if(e.code() != TC::Error_code::not_triangle_mesh || o.triangulate)
      throw;
    throw TC::Invalid_input(e.code(), std::string(e.what()) + " (--triangulate splits such faces, --repair too)",
                            e.where());
  }
  progress.end("reading mesh");
}

void read_face_directions(const Options& o, Inputs& in)
{
  if(!o.constraints.empty())
    in.constraints = TC::read_face_directions(o.constraints, in.order.faces.size());
  if(!o.guidance.empty())
    in.guides = TC::read_face_directions(o.guidance, in.order.faces.size());
  in.directions =
    in.mesh.add_property_map<face_descriptor, Kernel::Vector_3>("f:tc_directions", CGAL::NULL_VECTOR).first;
  auto set_direction = [&](const TC::Face_direction& d) {
    in.directions[in.order.faces[d.face]] = Kernel::Vector_3(d.direction[0], d.direction[1], d.direction[2]);
  };
  in.in_constraints.assign(in.order.faces.size(), 0);
  for(const TC::Face_direction& d : in.constraints) {
    in.constrained_faces.push_back(in.order.faces[d.face]);
    in.in_constraints[d.face] = 1;
    set_direction(d);
  }
  for(const TC::Face_direction& d : in.guides) {
    if(in.in_constraints[d.face])
      throw TC::Invalid_input(TC::Error_code::invalid_constraint,
                              "face " + std::to_string(d.face) + " is in both " + o.constraints + " and " + o.guidance,
                              d.face);
    in.guided_faces.push_back(in.order.faces[d.face]);
    set_direction(d);
  }
}

// The files are read in the order of their options, so that the first error reported stays the same.
void read_inputs(const Options& o, Progress_printer& progress, Inputs& in, Timings& time)
{
  {
    Stopwatch stopwatch{time.read};
    read_mesh(o, progress, in);
  }
  if(!o.singularities.empty())
    for(const auto& s : TC::read_singularities(o.singularities, in.order.vertices.size()))
      in.singularities.emplace_back(in.order.vertices[s.first], s.second);
  if(!o.boundary_indices.empty())
    in.boundary_indices = TC::read_singularities(o.boundary_indices, in.order.vertices.size());
  read_face_directions(o, in);
  if(o.align_features)
    align_with_features(o, progress, in);
}

// The solver's errors about the constraints and guides name faces: name the file that has the face too.
template <class Call>
auto naming_the_direction_file(const Options& o, const Inputs& in, Call&& call)
{
  try {
    return call();
  } catch(const TC::Invalid_input& e) {
    if(e.code() != TC::Error_code::invalid_constraint || (o.constraints.empty() && o.guidance.empty()))
      throw;
    std::string file = o.constraints.empty() ? o.guidance : o.constraints;
    if(!o.guidance.empty() && e.where() < in.in_constraints.size() && !in.in_constraints[e.where()])
      file = o.guidance;
    throw TC::Invalid_input(e.code(), file + ": " + e.what(), e.where());
  }
}

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

using Loop_periods = std::vector<std::optional<std::int64_t>>;

// The periods of the boundary loops named by one of their vertices; the generators are left to the solver.
Loop_periods boundary_loop_periods(const Options& o, const Inputs& in, const Solver& solver)
{
  Loop_periods loop_periods(solver.loops().size());
  std::vector<std::size_t> named_by(solver.loops().size());
  for(const auto& [v, index] : in.boundary_indices) {
    const std::optional<std::size_t> l = solver.boundary_loop_of(in.order.vertices[v]);
    if(!l)
      throw TC::Invalid_input(TC::Error_code::invalid_loop_periods,
                              o.boundary_indices + ": vertex " + std::to_string(v) + " is not on a boundary", v);
    if(loop_periods[*l])
      throw TC::Invalid_input(TC::Error_code::invalid_loop_periods,
                              o.boundary_indices + ": vertices " + std::to_string(named_by[*l]) + " and " +
                                std::to_string(v) + " are on the same boundary loop",
                              v);
    const std::string the_index =
      o.boundary_indices + ": the index " + index.to_string() + " of the boundary loop of vertex " + std::to_string(v);
    if(!index.is_multiple_of_one_over(o.n))
      throw TC::Invalid_input(TC::Error_code::index_not_multiple,
                              the_index + " is not a multiple of 1/" + std::to_string(o.n), v);
    // bounded like the vertex indices
    if(!TC::internal::index_in_range(index, o.n))
      throw TC::Invalid_input(TC::Error_code::invalid_index, the_index + " is too large (at most " +
                                                               TC::internal::max_index_text(o.n) + " in absolute value)",
                              v);
    loop_periods[*l] = index.times(o.n);
    named_by[*l] = v;
  }
  return loop_periods;
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

// --align-curvature: the guide (principal directions times anisotropy) on every face, and the faces guided towards
// it in the trivial connection (the user's guided faces are none: the options exclude each other)
void align_with_curvature(const Options& o, Inputs& in, Solver& solver, Design& design)
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

std::string refinement_stop(TC::Refinement_stop stop)
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
void design_singularities(const Options& o, Inputs& in, Solver& solver, Design& design, Progress_printer& progress,
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

std::string provenance(const Options& o)
{
  return "# computed by trivial_connections from '" + o.mesh + "'" +
         (o.automatic ? std::string(", singularities placed automatically") +
                          (o.singularities.empty() ? "" : " around those of '" + o.singularities + "'")
          : o.singularities.empty() ? std::string(", no singularity")
                                    : ", singularities '" + o.singularities + "'") +
         (o.align_curvature ? ", aligned with the curvature" : "") + (o.refine ? ", refined" : "") +
         (o.constraints.empty() ? std::string() : ", constraints '" + o.constraints + "'") +
         (o.align_boundary ? ", aligned with the boundary" : "") +
         (o.align_features ? ", aligned with the features over " + fixed(o.feature_angle, 1) + " degrees" : "") +
         (o.guidance.empty() ? std::string()
                             : ", guidance '" + o.guidance + "' with weight " + std::to_string(o.guidance_weight)) +
         ", n = " + std::to_string(o.n) + ", weights " + o.weights_name + "\n";
}

// K faces spread over those without a singular vertex (a seed there would give no line)
std::vector<face_descriptor> streamline_seeds(const Inputs& in, std::size_t k)
{
  std::vector<char> singular(num_vertices(in.mesh), 0);
  for(const auto& sv : in.singularities)
    singular[std::size_t(sv.first)] = 1;
  std::vector<face_descriptor> candidates, seeds;
  for(face_descriptor f : in.order.faces) {
    bool touches = false;
    for(auto v : CGAL::vertices_around_face(halfedge(f, in.mesh), in.mesh))
      touches = touches || singular[std::size_t(v)];
    if(!touches)
      candidates.push_back(f);
  }
  const std::size_t count = (std::min)(k, candidates.size());
  for(std::size_t i = 0; i < count; ++i)
    seeds.push_back(candidates[i * candidates.size() / count]);
  return seeds;
}

void write_outputs(const Options& o, const Inputs& in, const Solver& solver, const Solution& s,
                   Progress_printer& progress, Timings& time)
{
  Stopwatch stopwatch{time.write};
  progress.begin("writing files");
  const std::string header = provenance(o);
  const auto n = TC::parameters::symmetry_order(o.n);
  const auto vertex_index = get(boost::vertex_index, in.mesh);
  std::vector<std::pair<std::string, TC::File_writer>> files = {
    {o.connection, [&](std::ostream& os) { TC::write_connection(os << header, in.mesh, s.x, vertex_index, solver); }},
    {o.field, [&](std::ostream& os) { TC::write_field(os << header, in.mesh, s.field); }}};
  if(!o.vtk.empty())
    files.push_back(
      {o.vtk, [&](std::ostream& os) { TC::write_field_vtk(os, in.mesh, s.field, in.singularities, n); }});
  if(!o.ply.empty())
    files.push_back(
      {o.ply, [&](std::ostream& os) { TC::write_field_ply(os, in.mesh, s.field, in.singularities, n); }});
  if(!o.write_mesh.empty())
    files.push_back({o.write_mesh, [&](std::ostream& os) { write_mesh_off(os, in.mesh, in.order); }});
  if(!o.singularity_points.empty())
    files.push_back({o.singularity_points, [&](std::ostream& os) {
                       TC::write_singularity_points(os << header, in.mesh, in.singularities);
                     }});
  if(!o.write_singularities.empty()) {
    // the vertices as numbered in the file
    files.push_back({o.write_singularities, [&](std::ostream& os) {
                       std::vector<std::size_t> file_index(num_vertices(in.mesh));
                       for(std::size_t v = 0; v < in.order.vertices.size(); ++v)
                         file_index[std::size_t(in.order.vertices[v])] = v;
                       std::vector<std::pair<std::size_t, TC::Singularity_index>> lines;
                       for(const auto& sv : in.singularities)
                         lines.emplace_back(file_index[std::size_t(sv.first)], sv.second);
                       std::sort(lines.begin(), lines.end(),
                                 [](const auto& a, const auto& b) { return a.first < b.first; });
                       os << header;
                       TC::write_singularities(os, lines);
                     }});
  }
  if(!o.write_constraints.empty())
    files.push_back({o.write_constraints, [&](std::ostream& os) { write_constraints_used(os << header, in); }});
  if(!o.feature_lines.empty())
    files.push_back({o.feature_lines, [&](std::ostream& os) { write_feature_lines_vtk(os, in, in.features); }});
  std::vector<TC::Streamline<Mesh>> streamlines;
  if(!o.streamlines.empty()) {
    // a line across the mesh crosses about sqrt(faces) faces: 50 times that bounds recurrent ones
    const std::size_t bound = 50 * std::size_t(std::sqrt(double(in.order.faces.size()))) + 1000;
    streamlines = TC::trace_streamlines(in.mesh, s.x, s.field, in.singularities,
                                        streamline_seeds(in, o.streamline_seeds),
                                        TC::parameters::maximum_faces_per_ray(bound, n));
    files.push_back({o.streamlines, [&](std::ostream& os) { TC::write_streamlines_vtk(os, streamlines); }});
  }
  // all written or none; the writers only read the mesh, the maps and the solver
  TC::write_files_atomically(files, /* concurrently = */ true);
  progress.end("writing files");
}

std::size_t number_of_interior_edges(const Mesh& mesh)
{
  std::size_t interior_edges = 0;
  for(auto e : edges(mesh))
    if(!CGAL::is_border(e, mesh))
      ++interior_edges;
  return interior_edges;
}

void print_mesh(std::ostream& out, const Options& o, const Inputs& in, const TC::Solve_report& report,
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

void print_energy(std::ostream& out, const Options& o, const Inputs& in, const TC::Solve_report& report)
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
std::string integers_verdict(const TC::Solve_report& report)
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

void print_design_controls(std::ostream& out, const Options& o, const Inputs& in, const TC::Solve_report& report)
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

void print_loops(std::ostream& out, const Options& o, const TC::Solve_report& report)
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

void print_design(std::ostream& out, const Options& o, const Design& d)
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

void print_report(std::ostream& out, const Options& o, const Inputs& in, const Solution& s, const Design& design,
                  const Timings& time, const Solver& solver)
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
  out << "time: read " << fixed(time.read, 3) << " s, set-up " << fixed(time.setup, 3) << " s, ";
  if(o.automatic || o.refine || o.align_curvature)
    out << "placement " << fixed(time.placement, 3) << " s, ";
  out << "solve "
      << fixed(time.solve, 3) << " s, write " << fixed(time.write, 3) << " s\n";
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
  const Solution solution = solve(o, in, solver, solver_progress, time);
  write_outputs(o, in, solver, solution, progress, time);
  print_report(std::cout, o, in, solution, design, time, solver);
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
