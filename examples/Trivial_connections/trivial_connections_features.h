// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// --align-features of the program trivial_connections (trivial_connections.cpp): the faces beside the mesh's
// feature curves pinned to the curves' directions (feature_alignment.h), merged with the pins of --constraints, and
// the curves written for viewers (--feature-lines). Included by that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_FEATURES_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_FEATURES_H

#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <CGAL/Trivial_connections/feature_alignment.h>

#include "trivial_connections_command_line.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <iostream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace trivial_connections_program {

// What --align-features did
struct Feature_pins
{
  CGAL::Trivial_connections::Feature_alignment_report report;
  std::size_t pinned = 0;           // feature pins given to the solver
  std::size_t named_by_user = 0;    // left to the constraint file, which names those faces
  std::size_t on_guided_faces = 0;  // left to the guidance file
  std::size_t on_aligned_boundary = 0; // left out: the field follows the boundary there
  std::vector<std::array<std::size_t, 2>> lines; // the sharp edges of the kept curves (vertices in file order)
  std::vector<char> sharp_edges; // by edge: on a kept curve (--quad-mesh puts them on iso-lines)
};

/*
  The feature pins, added to the constrained faces of `in` (an `Inputs` of trivial_connections.cpp): the user's
  constraint file wins on the faces it names, a guided face stays guided, and with --align-boundary the boundary
  faces are left to the alignment (the solver refuses targets there).
*/
template <class Inputs>
Feature_pins add_feature_pins(const Options& o, Inputs& in)
{
  namespace TC = CGAL::Trivial_connections;
  using Mesh = std::decay_t<decltype(in.mesh)>;
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  Feature_pins out;
  using Vector = typename std::decay_t<decltype(in.directions)>::value_type;
  auto map = in.mesh.template add_property_map<face_descriptor, Vector>("f:tc_feature_directions").first;
  std::vector<face_descriptor> faces;
  out.report = TC::feature_aligned_faces(in.mesh, o.feature_angle, std::back_inserter(faces), map,
                                         TC::parameters::symmetry_order(o.n));
  std::vector<char> taken(num_faces(in.mesh), 0); // by descriptor index: constrained or guided already
  for(face_descriptor f : in.constrained_faces)
    taken[std::size_t(f)] = 1;
  for(face_descriptor f : in.guided_faces)
    taken[std::size_t(f)] = 2;
  for(face_descriptor f : faces) {
    if(taken[std::size_t(f)]) {
      ++(taken[std::size_t(f)] == 1 ? out.named_by_user : out.on_guided_faces);
      continue;
    }
    bool on_boundary = false;
    for(auto h : CGAL::halfedges_around_face(halfedge(f, in.mesh), in.mesh))
      on_boundary = on_boundary || CGAL::is_border(opposite(h, in.mesh), in.mesh);
    if(o.align_boundary && on_boundary) {
      ++out.on_aligned_boundary;
      continue;
    }
    in.constrained_faces.push_back(f);
    in.directions[f] = map[f];
    ++out.pinned;
  }
  in.mesh.remove_property_map(map);
  // the curves once, for --feature-lines, the quads' iso-lines and the singularities kept off them
  const auto curves = TC::feature_curves(in.mesh, o.feature_angle).curves;
  out.sharp_edges.assign(num_edges(in.mesh), 0);
  for(const auto& curve : curves)
    for(auto h : curve.halfedges)
      out.sharp_edges[std::size_t(edge(h, in.mesh))] = 1;
  if(!o.feature_lines.empty()) {
    std::vector<std::size_t> file_index(num_vertices(in.mesh));
    for(std::size_t v = 0; v < in.order.vertices.size(); ++v)
      file_index[std::size_t(in.order.vertices[v])] = v;
    for(const auto& curve : curves)
      for(auto h : curve.halfedges)
        out.lines.push_back({{file_index[std::size_t(source(h, in.mesh))], file_index[std::size_t(target(h, in.mesh))]}});
  }
  return out;
}

// --align-features: the pins added to `in`, a note on stderr when the mesh has no sharp edge
template <class Inputs>
void align_with_features(const Options& o, Progress_printer& progress, Inputs& in)
{
  progress.begin("feature curves");
  in.features = add_feature_pins(o, in);
  progress.end("feature curves", std::to_string(in.features.report.number_of_curves) + " curves, " +
                                   std::to_string(in.features.pinned) + " pinned faces");
  if(in.features.report.number_of_sharp_edges == 0) {
    progress.end_line();
    std::cerr << program << ": note: no edge is sharper than " << o.feature_angle
              << " degrees: --align-features pins no face\n";
  }
}

// The constraints the solver got (the file's and the features'), as a --constraints file: faces in file order
template <class Inputs>
void write_constraints_used(std::ostream& os, const Inputs& in)
{
  std::vector<std::size_t> file_index(num_faces(in.mesh));
  for(std::size_t f = 0; f < in.order.faces.size(); ++f)
    file_index[std::size_t(in.order.faces[f])] = f;
  std::vector<CGAL::Trivial_connections::Face_direction> lines;
  for(auto f : in.constrained_faces) {
    const auto& d = in.directions[f];
    lines.push_back({file_index[std::size_t(f)], {{CGAL::to_double(d.x()), CGAL::to_double(d.y()), CGAL::to_double(d.z())}}});
  }
  std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.face < b.face; });
  CGAL::Trivial_connections::write_face_directions(os, lines);
}

// The sharp edges of the feature curves as legacy VTK lines (the mesh's points, one 2-point line per edge)
template <class Inputs>
void write_feature_lines_vtk(std::ostream& os, const Inputs& in, const Feature_pins& features)
{
  namespace io = CGAL::Trivial_connections::internal::io;
  io::Number_writer out(os);
  io::write_text(out, "# vtk DataFile Version 3.0\nfeature curves (CGAL Trivial Connections)\nASCII\nDATASET POLYDATA\n"
                      "POINTS " + std::to_string(in.order.vertices.size()) + " double\n");
  for(auto v : in.order.vertices) {
    const auto& p = in.mesh.point(v);
    io::write_triple(out, {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
  }
  io::write_text(out, "LINES " + std::to_string(features.lines.size()) + " " + std::to_string(3 * features.lines.size()) +
                        "\n");
  for(const auto& l : features.lines) {
    io::write_text(out, "2 ");
    out.index(l[0]);
    out.character(' ');
    out.index(l[1]);
    out.character('\n');
  }
  out.flush();
}

inline std::string feature_report_line(const Options& o, const Feature_pins& f)
{
  const auto& r = f.report;
  std::ostringstream s;
  s << "features: threshold " << o.feature_angle << " degrees: ";
  if(r.number_of_sharp_edges == 0) {
    s << "no sharp edge, no face pinned\n";
    return s.str();
  }
  s << r.number_of_sharp_edges << " sharp edges, " << r.number_of_curves << " curves";
  if(r.dropped_curves > 0)
    s << " (" << r.dropped_curves << " isolated short ones dropped, " << r.dropped_edges << " edges)";
  s << "; " << r.number_of_pinned_faces << " faces beside them (" << r.faces_with_several_edges
    << " beside several), " << f.pinned << " pinned";
  if(r.number_of_cusps > 0)
    s << " (" << r.number_of_cusps << (r.number_of_cusps == 1 ? " cusp" : " cusps") << ": " << r.sector_rule_faces
      << " faces by the sector rule)";
  if(f.named_by_user > 0)
    s << ", " << f.named_by_user << " left to " << o.constraints;
  if(f.on_guided_faces > 0)
    s << ", " << f.on_guided_faces << " left to " << o.guidance;
  if(f.on_aligned_boundary > 0)
    s << ", " << f.on_aligned_boundary << " left to the boundary alignment";
  s << "; disagreement: " << r.disagreeing_pairs << " of " << r.neighbouring_pairs
    << " neighbouring pairs over 5 degrees (mod 360/" << o.n << "), max " << std::fixed << std::setprecision(2)
    << r.max_disagreement_degrees << " degrees\n";
  return s.str();
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_FEATURES_H
