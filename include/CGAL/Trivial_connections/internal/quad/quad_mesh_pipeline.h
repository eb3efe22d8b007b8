// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_MESH_PIPELINE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_MESH_PIPELINE_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/quad/cut_graph.h>
#include <CGAL/Trivial_connections/internal/quad/integer_rounding.h>
#include <CGAL/Trivial_connections/internal/quad/map_untangling.h>
#include <CGAL/Trivial_connections/internal/quad/quad_extraction.h>
#include <CGAL/Trivial_connections/internal/quad/seamless_parametrization.h>

#include <CGAL/number_utils.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The four layers of quad meshing (issue 43) in a row, from a solved cross field to the quad mesh: the only place
  that calls them, so that new options of a layer (feature curves and borders as iso-lines) are wired here once.
  The public call is compute_quad_mesh() (quad_mesh.h); the measures of its result are in quad_mesh_measures.h.
*/

// The cross field as the layers read it: per face its angle in the face's frame, per interior edge the connection
// of its canonical corner halfedge (Mesh_geometry numbering). `g` has its angles computed.
struct Quad_field
{
  std::vector<double> angle;      // per face
  std::vector<double> connection; // per interior edge
};

template <class TriangleMesh, class HalfedgeAngleMap, class FaceVectorMap>
Quad_field quad_field(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g, HalfedgeAngleMap x,
                      FaceVectorMap field)
{
  Quad_field q;
  q.angle.resize(m.nf);
  for(int f = 0; f < m.nf; ++f) {
    const auto v = get(field, m.face_descriptors[f]);
    const Vec3 d = {{CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z())}};
    // the field's component in the face's plane must not vanish: its angle would be noise
    Vec3 ex, ey;
    Mesh_geometry::frame(m, f, ex, ey);
    const double in_plane = std::hypot(dot(d, ex), dot(d, ey));
    if(!(in_plane > 1e-12 * std::sqrt(dot(d, d))) || !std::isfinite(in_plane))
      throw Invalid_input(Error_code::invalid_argument,
                          "the field of face " + std::to_string(f) + " is zero, not finite or normal to the face",
                          std::size_t(f));
    q.angle[f] = angle_in_frame(m, f, d);
  }
  q.connection.resize(g.number_of_interior_edges());
  for(int e = 0; e < g.number_of_interior_edges(); ++e) {
    q.connection[e] = double(get(x, m.halfedges[g.edge_corner[e]]));
    if(!std::isfinite(q.connection[e]))
      throw Invalid_input(Error_code::invalid_argument,
                          "the connection is not finite across interior edge " + std::to_string(e), std::size_t(e));
  }
  return q;
}

// The faces around the singular vertices that `map` winds around as their index asks (the (u, v) angles sum to
// 2 pi (1 - k)) with no folded or degenerate triangle beside them: for Map_untangling::hold()
template <class TriangleMesh>
std::vector<int> rightly_wound_one_rings(const Mesh_arrays<TriangleMesh>& m, const std::vector<int>& singular,
                                         const std::vector<long long>& k4, const Seamless_parametrization::Map& map)
{
  const Uv_windings w = uv_windings(m, map);
  std::vector<char> right(std::size_t(m.nv), 0);
  for(int v : singular)
    right[std::size_t(v)] = !w.beside_inverted[std::size_t(v)] && w.turns_off(std::size_t(v), k4[std::size_t(v)]) == 0;
  std::vector<int> faces;
  for(int c = 0; c < 3 * m.nf; ++c)
    if(right[std::size_t(m.source_of(c))])
      faces.push_back(c / 3);
  return faces;
}

struct Quad_pipeline_result
{
  Quad_mesh mesh;
  double continuous_energy = 0, rounded_energy = 0;
  int integer_unknowns = 0, solves = 0, factorizations = 0, arcs = 0;
  double rounding_seconds = 0;
  bool naive_fallback = false; // the greedy rounding was infeasible and the naive one made the map
  bool cone_modes = false;      // the map of the cone-mode stages (cone_mode_weight > 0)
  Untangling_result continuous_untangling; // with cone_mode_weight > 0: the continuous map's
  Untangling_result untangling; // the map the quads come from: the rounded one, or moved out of its folds
};

// singular: the singular vertices (array numbering), each once, and k4 their indices times 4 (per vertex, 0
// elsewhere); H > 0 the quad size; max_quads the bound of
// the extraction; feature_corners: empty, or per corner halfedge whether its edge is a feature edge, put on an
// integer iso-line like every border edge; scale_smoothness > 0: the target scaled per face first
// (Seamless_parametrization::reduce_curl()); untangle: a rounded map with folded or degenerate triangles is moved
// out of them where the integers allow it (Map_untangling); cone_mode_weight > 0: the map made to wind around every
// singular vertex as its index asks, in two stages (manual: Cone modes). The least squares penalise the one-rings'
// harmonics that wind wrongly (Seamless_parametrization::penalise_cone_modes()); the continuous map is untangled,
// its rightly wound singular one-rings held; the rounding fits that map's gradients, so that its integers are those
// near a fold-free map; and the rounded map is untangled against the field again with its rightly wound one-rings
// held. Throws Invalid_input as the layers do.
template <class TriangleMesh>
Quad_pipeline_result quad_mesh_pipeline(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                                        const Quad_field& field, const std::vector<int>& singular,
                                        const std::vector<long long>& k4, double H, Rounding_scheme scheme,
                                        double max_quads, const std::vector<char>& feature_corners = {},
                                        double scale_smoothness = 0, bool untangle = true,
                                        double cone_mode_weight = 0)
{
  const std::vector<int> matching = cross_field_matching(m, g, field.angle, field.connection);
  const Cut_graph cut = build_cut_graph(m, g, matching, singular);
  // per edge of the cut graph's numbering: on an iso-line (borders always: the quads end there)
  std::vector<char> on_iso_line(cut.edge_corner.size(), 0);
  bool any = false;
  for(std::size_t e = 0; e < cut.edge_corner.size(); ++e) {
    const int i = cut.edge_corner[e], o = m.opposite_corner[i];
    on_iso_line[e] = o < 0 || (!feature_corners.empty() && (feature_corners[std::size_t(i)] || feature_corners[std::size_t(o)]));
    any = any || on_iso_line[e];
  }
  Seamless_parametrization parametrization(m, cut, field.angle, H, any ? on_iso_line : std::vector<char>());
  if(scale_smoothness > 0)
    parametrization.reduce_curl(scale_smoothness);
  Quad_pipeline_result result;
  Eigen::VectorXd field_target; // the field's target and the cone modes' zeros
  double continuous_energy = 0;
  if(cone_mode_weight > 0) {
    std::vector<std::pair<int, int>> cones;
    for(int v : singular)
      cones.emplace_back(v, int(k4[std::size_t(v)]));
    parametrization.penalise_cone_modes(m, cones, cone_mode_weight);
    field_target = parametrization.gradient_target();
    parametrization.clear_fixed();
    const Seamless_parametrization::Map continuous = parametrization.solve();
    continuous_energy = continuous.energy;
    Map_untangling stage(parametrization);
    stage.hold(rightly_wound_one_rings(m, singular, k4, continuous));
    result.continuous_untangling = stage.untangle(continuous);
    Eigen::VectorXd corners(6 * std::size_t(m.nf));
    for(int c = 0; c < 3 * m.nf; ++c)
      for(int k = 0; k < 2; ++k)
        corners[2 * c + k] = result.continuous_untangling.map.corner_uv[std::size_t(c)][std::size_t(k)];
    parametrization.set_gradient_target(parametrization.gradients() * corners);
    result.cone_modes = true;
  }
  Integer_rounding rounding(parametrization, cut);
  Integer_rounding_result rounded = rounding.round(scheme);
  if(cone_mode_weight > 0) {
    // back to the field: the energies, and the untangling's, are the field's (with the cone modes') again
    parametrization.set_gradient_target(field_target);
    rounded.map.energy = parametrization.map_of(parametrization.reduced_solution()).energy;
    rounded.continuous_energy = continuous_energy;
  }
  if(untangle) {
    Map_untangling untangling(parametrization);
    if(cone_mode_weight > 0)
      untangling.hold(rightly_wound_one_rings(m, singular, k4, rounded.map));
    result.untangling = untangling.untangle(rounded.map);
  } else {
    result.untangling.map = rounded.map;
    result.untangling.inverted_before = result.untangling.inverted_after = inverted_triangles(rounded.map);
  }
  result.mesh = extract_quad_mesh(m, cut, result.untangling.map, max_quads);
  result.continuous_energy = rounded.continuous_energy;
  result.rounded_energy = rounded.map.energy;
  result.integer_unknowns = rounded.integer_unknowns;
  result.solves = rounded.solves;
  result.factorizations = rounded.factorizations;
  result.rounding_seconds = rounded.seconds;
  result.naive_fallback = rounded.naive_fallback;
  result.arcs = int(cut.arcs.size());
  return result;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_MESH_PIPELINE_H
