// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SINGULARITIES_OFF_FEATURES_H
#define CGAL_TRIVIAL_CONNECTIONS_SINGULARITIES_OFF_FEATURES_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/quad_size.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/mesh/off_features_search.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>

#include <boost/graph/graph_traits.hpp>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
One singularity moved by `move_singularities_off_features()`. Distances are graph distances: the length of the
shortest path along mesh edges.
*/
template <class VertexDescriptor>
struct Feature_move
{
  VertexDescriptor from;          ///< where the singularity was
  VertexDescriptor to;            ///< where it went
  double distance_before = 0;     ///< from `from` to the nearest vertex of a feature edge (less than H)
  double distance_after = 0;      ///< from `to` to the nearest vertex of a feature edge (at least H)
  double path_length = 0;         ///< from `from` to `to`, through vertices of no feature edge
};

/*!
\ingroup PkgTrivialConnectionsRef
What `move_singularities_off_features()` did.
*/
template <class TriangleMesh>
struct Off_features_report
{
  /// the vertex type of `TriangleMesh`
  using vertex_descriptor = typename boost::graph_traits<TriangleMesh>::vertex_descriptor;
  double quad_size = 0; ///< H, the distance kept from the feature edges (given, or from `target_faces`)
  /// the singularities after the move: the input's, in its order and with its indices, each vertex replaced by
  /// the one it moved to
  std::vector<std::pair<vertex_descriptor, Singularity_index>> singularities;
  /// the moves, in the order of the input
  std::vector<Feature_move<vertex_descriptor>> moves;
  /// singularities closer than H to a feature edge that stayed: no free vertex at least H from every feature edge
  /// is reachable from them without crossing a feature edge's vertex
  std::vector<vertex_descriptor> stuck;
  std::size_t on_features = 0; ///< singularities on a vertex of a feature edge (they stay)
  std::size_t fixed = 0;       ///< singularities closer than H kept where they are by `fixed_vertices`
};

/*!
\ingroup PkgTrivialConnectionsRef
Moves the singularities placed closer than H to a feature edge to the nearest vertex at least H from every
feature edge, the step before `compute_quad_mesh()` with `edge_is_constrained_map` (issue 43). A singular vertex
is an integer point of the quads' map and a feature edge lies on an integer iso-line: a distance below H between
them rounds to 0 (the quads between them collapse) or to 1 (they stretch), and the map folds there. Moving the
singularities onto the feature lines instead would cost the field a quarter turn between its pins.

The singularities are solved again after the move (`Trivial_connection_solver::solve()` with
`report.singularities`, on the same solver and factor): this function only chooses the vertices.

Definitions. The distance d(v) of a vertex v to the feature edges is the length of the shortest path along mesh
edges from v to a vertex of a feature edge (infinite in a component without one). A singularity at v with
0 < d(v) < H moves to the vertex w that minimises the length of a path from v through vertices of no feature edge,
among the vertices with d(w) >= H that are not on the border and not listed among the singularities (after the
moves of those before it in `singularities`). Equal path lengths are decided by the smallest point (x, then y, then
z), so that the result does not depend on the numbering of the vertices. The singularities are taken in the order
of the range. Left where they are:
- the singularities on a vertex of a feature edge (d(v) = 0: on the iso-line, an integer point of it);
- those at d(v) >= H, those with index 0, and those of `fixed_vertices`;
- those from which no such w can be reached (a component thinner than 2 H, or a region walled in by feature
  lines): listed in `stuck`, the quads may fold near them.
The indices are kept and a singularity moves within its connected component, so the index sum of every component
(Poincare-Hopf) is unchanged; no two singularities end on the same vertex.

The searches are Boost.Graph's Dijkstra (`boost::dijkstra_shortest_paths()`) on `tm`: one from all the feature
edges' vertices at once, then one per singularity to move, stopped at the first vertex found (they cost O(V) each
for the heap's index even when they stop early).

\param tm the triangle mesh
\param singularities a range of pairs (`vertex_descriptor`, index convertible to `Singularity_index`), e.g. those of
                     `place_singularities()`
\param feature_edges a readable property map `edge_descriptor -> bool`: the feature edges, e.g. the sharp edges
                     of `feature_curves()`; the same map as `compute_quad_mesh()`'s `edge_is_constrained_map`
\param np a sequence of named parameters among the ones listed below; exactly one of `quad_size` and `target_faces`
\returns the singularities after the move and what moved where
\throws Invalid_input `invalid_argument` when neither or both of `quad_size` and `target_faces` are given, or H is not
        positive and finite; `invalid_vertex` for a singular vertex in no face; `duplicate_singularity` for a vertex
        listed twice; `singularity_on_boundary` for a nonzero index on a border vertex; the mesh errors of the solver
        (`empty_mesh`, `not_triangle_mesh`, `non_manifold`, `non_finite_point`, `degenerate_face`, ...). The
        input is never modified.
\cgalNamedParamsBegin
  \cgalParamNBegin{quad_size} \cgalParamType{`double`} \cgalParamDescription{H, the quads' edge length: the distance
    kept from the feature edges} \cgalParamNEnd
  \cgalParamNBegin{target_faces} \cgalParamType{`std::size_t`} \cgalParamDescription{instead of `quad_size`: H =
    sqrt(area / N) (`quad_size_for_target_faces()`), as `compute_quad_mesh()` reads it} \cgalParamNEnd
  \cgalParamNBegin{fixed_vertices} \cgalParamType{a range of `vertex_descriptor`} \cgalParamDescription{singular
    vertices that stay (e.g. the user's singularities among placed ones)} \cgalParamDefault{none} \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{geom_traits} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
\cgalNamedParamsEnd
\sa `compute_quad_mesh()`, `feature_curves()`
*/
template <class TriangleMesh, class SingularityRange, class EdgeIsConstrainedMap,
          class NamedParameters = parameters::Default_named_parameters>
Off_features_report<TriangleMesh>
move_singularities_off_features(const TriangleMesh& tm, const SingularityRange& singularities,
                                EdgeIsConstrainedMap feature_edges,
                                const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;

  const internal::Mesh_arrays<TriangleMesh> m(
    tm, choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm)),
    choose_parameter(get_parameter(np, CGAL::internal_np::geom_traits), Geom_traits()));
  Off_features_report<TriangleMesh> report;
  report.quad_size = internal::quad_size_from_parameters(internal::surface_area(m), np);
  const double H = report.quad_size;

  // the singularities, checked as the solver checks them, before anything moves
  std::vector<char> on_border(m.nv, 0), listed(m.nv, 0), fixed(m.nv, 0);
  for(int i = 0; i < 3 * m.nf; ++i)
    if(m.opposite_corner[i] < 0)
      on_border[m.source_of(i)] = on_border[m.target_of(i)] = 1;
  for(const auto& s : singularities) {
    const std::size_t v = internal::checked_singular_vertex(m, s.first, listed);
    const Singularity_index k(s.second);
    if(k.numerator() != 0 && on_border[v])
      throw Invalid_input(Error_code::singularity_on_boundary, "singular vertex " + std::to_string(v) + " is on the boundary", v);
    report.singularities.emplace_back(s.first, k);
  }
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::fixed_vertices_t>::value)
    for(const vertex_descriptor v : get_parameter(np, tc_np::fixed_vertices)) {
      const std::size_t i = std::size_t(get(m.vertex_index, v));
      if(i >= std::size_t(m.nv))
        throw Invalid_input(Error_code::invalid_vertex, "fixed vertex " + std::to_string(i) + " does not exist", i);
      fixed[i] = 1;
    }

  internal::Off_features_search<TriangleMesh> search(tm, m);
  for(auto e : edges(tm))
    if(get(feature_edges, e))
      search.mark_feature_edge(e);
  search.distances_to_features();

  for(auto& s : report.singularities) {
    const int v = int(get(m.vertex_index, s.first));
    const double d = search.to_features[v];
    if(s.second.numerator() == 0 || !(d < H))
      continue;
    if(search.on_feature[v]) {
      ++report.on_features;
      continue;
    }
    if(fixed[v]) {
      ++report.fixed;
      continue;
    }
    // a free vertex: at least H away, off the border, not listed (no two singularities on one vertex)
    const auto found = search.nearest(v, [&](int w) { return search.to_features[w] >= H && !on_border[w] && !listed[w]; });
    if(found.first < 0) {
      report.stuck.push_back(s.first);
      continue;
    }
    const int w = found.first;
    listed[v] = 0;
    listed[w] = 1;
    report.moves.push_back({s.first, m.vertex_descriptors[w], d, search.to_features[w], found.second});
    s.first = m.vertex_descriptors[w];
  }
  return report;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SINGULARITIES_OFF_FEATURES_H
