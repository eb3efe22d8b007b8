// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The input files of the program trivial_connections (trivial_connections.cpp), read onto the mesh, and the file
// named in the solver's errors about them. Included by that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_INPUTS_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_INPUTS_H

#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/repair_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/Progress.h>

#include "trivial_connections_command_line.h"
#include "trivial_connections_features.h"
#include "trivial_connections_state.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace trivial_connections_program {

inline void read_mesh(const Options& o, Progress_printer& progress, Inputs& in)
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

inline void read_face_directions(const Options& o, Inputs& in)
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
inline void read_inputs(const Options& o, Progress_printer& progress, Inputs& in, Timings& time)
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

using Loop_periods = std::vector<std::optional<std::int64_t>>;

// The periods of the boundary loops named by one of their vertices; the generators are left to the solver.
inline Loop_periods boundary_loop_periods(const Options& o, const Inputs& in, const Solver& solver)
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

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_INPUTS_H
