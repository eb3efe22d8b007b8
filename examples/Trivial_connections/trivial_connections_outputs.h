// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The output files of the program trivial_connections (trivial_connections.cpp), written all or none. Included by
// that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_OUTPUTS_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_OUTPUTS_H

#include <CGAL/Trivial_connections/IO/atomic_file.h>
#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/IO/field_file.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <boost/property_map/property_map.hpp>

#include "trivial_connections_command_line.h"
#include "trivial_connections_features.h"
#include "trivial_connections_repair.h"
#include "trivial_connections_state.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace trivial_connections_program {

inline std::string provenance(const Options& o)
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
inline std::vector<face_descriptor> streamline_seeds(const Inputs& in, std::size_t k)
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

// --quad-mesh: the quads of the cross field, computed before any file is written (an error leaves no file)
// scale_smoothness: quad_scale_smoothness, cone_mode_weight: quad_cone_mode_weight (negative: the option's, off
// when not given)
inline Quads make_quad_mesh(const Options& o, const Inputs& in, const Solution& s, Progress_printer& progress,
                            Timings& time, double scale_smoothness = -1, double cone_mode_weight = -1)
{
  Quads q;
  if(o.quad_mesh.empty())
    return q;
  Stopwatch stopwatch{time.quads};
  progress.begin("quad mesh");
  namespace P = TC::parameters;
  // with --align-features, the sharp edges the field was pinned along: on iso-lines
  std::vector<char> sharp = in.features.sharp_edges;
  sharp.resize(num_edges(in.mesh), 0); // none without --align-features
  const auto features = boost::make_iterator_property_map(sharp.begin(), get(boost::edge_index, in.mesh));
  const double scaling = (std::max)(scale_smoothness >= 0 ? scale_smoothness : o.quad_scale_smoothness, 0.);
  q.scale_smoothness = scaling;
  const double cone_modes = (std::max)(cone_mode_weight >= 0 ? cone_mode_weight : o.quad_cone_modes, 0.);
  q.cone_mode_weight = cone_modes;
  q.report = o.quad_size > 0
               ? TC::compute_quad_mesh(in.mesh, s.x, s.field, in.singularities, q.mesh,
                                       P::quad_cone_mode_weight(cone_modes, P::quad_untangling(!o.no_untangle, P::quad_scale_smoothness(scaling, P::quad_size(o.quad_size).edge_is_constrained_map(features)))))
               : TC::compute_quad_mesh(in.mesh, s.x, s.field, in.singularities, q.mesh,
                                       P::quad_cone_mode_weight(cone_modes, P::quad_untangling(!o.no_untangle, P::quad_scale_smoothness(scaling, P::target_faces(o.target_faces).edge_is_constrained_map(features)))));
  {
    std::ostringstream rounding;
    rounding << std::fixed << std::setprecision(2) << "rounding " << q.report->rounding_seconds << " s, "
             << q.report->solves << " solves on " << q.report->factorizations << " factorizations";
    if(q.report->inverted_before_untangling > 0)
      rounding << "; untangling " << q.report->untangling_seconds << " s, " << q.report->inverted_before_untangling
               << " -> " << q.report->folded_triangles + q.report->degenerate_triangles << " folded and degenerate";
    progress.end("quad mesh", rounding.str());
  }
  return q;
}

// the quad_scale_smoothness tried when the quads made without it have flaws and --quad-scale-smoothness is not given
// (bunny00: 0.03 to 0.3 remove its 29 folded triangles at 3,000 quads, 1 leaves one, 3 six)
inline constexpr double automatic_quad_scale_smoothness = 0.1;

// the quad_cone_mode_weight tried when the quads made without it have wrongly wound singular vertices and
// --quad-cone-modes is not given (fandisk with its feature lines: kept at six of eight quad sizes, where its 2 or 3
// valence errors become 0 or 1)
inline constexpr double automatic_quad_cone_mode_weight = 30;

// what the program counts against a quad mesh: folded and degenerate triangles of the map, valence errors
inline std::size_t quad_flaws(const Quads& q)
{
  return q.report ? q.report->folded_triangles + q.report->degenerate_triangles + q.report->valence_errors : 0;
}

// The quads as an OBJ file: 'v x y z' per vertex, 'f a b c d' (1-based) per quad, counter-clockwise seen from outside
inline void write_quads_obj(std::ostream& os, const Mesh& quads)
{
  os << std::setprecision(17);
  std::vector<std::size_t> number(quads.number_of_vertices() + quads.number_of_removed_vertices(), 0);
  std::size_t next = 0;
  for(auto v : quads.vertices()) {
    number[std::size_t(v)] = ++next;
    const auto& p = quads.point(v);
    os << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  for(auto f : quads.faces()) {
    os << "f";
    for(auto v : CGAL::vertices_around_face(quads.halfedge(f), quads))
      os << " " << number[std::size_t(v)];
    os << "\n";
  }
}

inline void write_outputs(const Options& o, const Inputs& in, const Solver& solver, const Solution& s,
                          const Quads& quads, Progress_printer& progress, Timings& time)
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
  if(quads.report)
    files.push_back({o.quad_mesh, [&](std::ostream& os) { write_quads_obj(os << header, quads.mesh); }});
  // all written or none; the writers only read the mesh, the maps and the solver
  TC::write_files_atomically(files, /* concurrently = */ true);
  progress.end("writing files");
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_OUTPUTS_H
