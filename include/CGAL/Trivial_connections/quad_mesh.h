// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_QUAD_MESH_H
#define CGAL_TRIVIAL_CONNECTIONS_QUAD_MESH_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/quad_size.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/quad/quad_mesh_measures.h>
#include <CGAL/Trivial_connections/internal/quad/quad_mesh_pipeline.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cmath>
#include <cstddef>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
How `compute_quad_mesh()` rounds the integer unknowns of its parametrisation (the (u, v) of the singular
vertices and the translations across the cut).
*/
enum class Quad_rounding {
  /// the unknown closest to an integer first, fixed, then a new solve, and so on (each solve an update of a kept
  /// factorization: a back-substitution per fixed unknown, a new factorization every few hundred). When its
  /// integers contradict each other (an unknown that a singular vertex's closure ties to them implied at a half),
  /// the naive rounding makes the map (`Quad_mesh_report::naive_rounding_fallback`)
  greedy,
  naive   ///< all rounded at once from the continuous solution, then one more solve (fast, more distortion)
};

/*!
\ingroup PkgTrivialConnectionsRef
What `compute_quad_mesh()` made and measured. The counts of the map (folded, degenerate triangles) are those of
the integer-grid map; the others are measured on the quads themselves.
*/
struct Quad_mesh_report
{
  double quad_size = 0;                    ///< H, the quad size used (given, or from `target_faces`)
  std::size_t number_of_quads = 0;         ///< the quads written to the output mesh
  std::size_t number_of_vertices = 0;      ///< the vertices written (the integer points of the map in some quad)
  std::size_t integer_points = 0;          ///< all integer points of the map, in a quad or not
  /// per valence (the iso-line pieces leaving an integer point): how many integer points have it
  std::map<int, std::size_t> valence_histogram;
  /// the integer points whose valence is not 4 - 4k, k the index of the singularity at the mesh vertex they are
  /// on (0 off the singular vertices); on the border: not 3, 2 (a convex corner) or 4 (a concave one)
  std::size_t valence_errors = 0;
  std::size_t border_corners = 0;          ///< integer points on the border of valence 2 or 4: corners of quads
  std::size_t feature_edges = 0;           ///< input edges put on integer iso-lines (`edge_is_constrained_map`)
  std::size_t folded_triangles = 0;        ///< input triangles whose (u, v) image is inverted (skipped)
  std::size_t degenerate_triangles = 0;    ///< input triangles whose (u, v) image has zero area (skipped)
  std::size_t rejected_polygons = 0;       ///< cells of the iso-lines that are not quads (left out: holes)
  std::size_t open_edges = 0;              ///< quad edges in fewer than two quads (0 on a closed output)
  std::size_t dangling_edges = 0;          ///< iso-line chains from an integer point that end at a fold
  /// quads whose vector area (half the sum of the cross products of consecutive vertices) points against the sum
  /// of the input's normals at their four vertices
  std::size_t flipped_quads = 0;
  /// quads with a corner (the triangle of a vertex and its two neighbours) pointing against that sum: valid cells
  /// of the map, but not convex
  std::size_t concave_quads = 0;
  /// the largest distance from a point of the quads (each split into two triangles) to the input surface
  double hausdorff_quads_to_input = 0;
  /// the largest distance from a point of the input to the quads (infinity when there is no quad)
  double hausdorff_input_to_quads = 0;
  std::size_t split_vertices = 0;          ///< vertices duplicated to make the output a manifold (around holes)
  double continuous_energy = 0;            ///< the parametrisation's energy before rounding
  double rounded_energy = 0;               ///< and after
  std::size_t solves = 0;                  ///< the least-squares minimisers of the rounding (one per greedy step)
  /// the sparse factorizations behind them: the greedy steps update a kept factor and factor again only every
  /// few hundred fixed integers
  std::size_t factorizations = 0;
  double rounding_seconds = 0;             ///< the rounding's wall time (seconds)
  /// the greedy rounding's integers contradicted each other (an unknown implied at a half) and the naive rounding
  /// made the map (see `Quad_rounding`); false with `Quad_rounding::naive` asked
  bool naive_rounding_fallback = false;
  /// folded and degenerate triangles of the rounded map, before the untangling (`quad_untangling`): those of
  /// the map the quads come from are `folded_triangles` and `degenerate_triangles`
  std::size_t inverted_before_untangling = 0;
  bool untangled = false;                  ///< the quads come from the untangled map (fewer inverted triangles)
  double untangled_energy = 0;             ///< the parametrisation's energy of that map (`rounded_energy` if not)
  double untangling_seconds = 0;           ///< the untangling's wall time (seconds)
  /// the map comes from the two stages of `quad_cone_mode_weight` (its untangling of the continuous map included
  /// in `untangling_seconds`)
  bool cone_modes = false;
  /// interior singular vertices, with no folded or degenerate triangle around them, that the map winds around
  /// the wrong number of times: the (u, v) angles of their corners sum to 2 pi (1 - k), k their index, plus or
  /// minus whole turns (fandisk: a quarter turn instead of five around some -1/4 vertices). The least squares
  /// already wind so there, before any rounding (`quad_cone_mode_weight` changes that); the untangling winds some of
  /// them right, not all. Each is a valence error (manual, \ref TCQuadUntangling)
  std::size_t wrongly_wound_singularities = 0;
  /// interior regular vertices, with no folded or degenerate triangle around them, that the map winds around more
  /// than once (their angles sum to 4 pi or more): where the missing turn of a wrongly wound singular vertex went.
  /// The cells around them are not quads
  std::size_t branch_points = 0;

  /// the Hausdorff distance: the larger of the two one-sided distances
  /// \returns `max(hausdorff_quads_to_input, hausdorff_input_to_quads)`
  double hausdorff_distance() const
  {
    return hausdorff_quads_to_input > hausdorff_input_to_quads ? hausdorff_quads_to_input : hausdorff_input_to_quads;
  }
};

/*!
\ingroup PkgTrivialConnectionsRef
The quad mesh of a cross field: the integer iso-lines of a seamless integer-grid map whose gradients follow the
field, scaled so that a unit of the map is `H` long (the quad size). The steps (cut graph through the
singularities, seamless parametrisation, integer rounding, extraction of the quads), in words:
- the field's matching across each edge (the quarter turns that bring one face's directions onto the next
  ones' under the connection) and a cut graph that makes every component a disk through all the singular
  vertices;
- a map (u, v) per corner minimising the squared difference of its gradients with the field over `H` (and its
  quarter turn), with transitions across the cut that are quarter turns plus translations;
- the (u, v) of the singular vertices and the translations made integers (`quad_rounding`), so that the integer
  iso-lines are continuous across the cut;
- where that map has folded or degenerate triangles, the map moved out of them with the same integers
  (`quad_untangling`): a map whose gradients are the field's exactly has none, but a singular vertex moved to an
  integer point by up to 0.7 H drags only its nearest triangles along;
- the quads: the cells those iso-lines cut the surface into. Triangles whose map is folded or degenerate are
  skipped and counted; the cells that are not quads around them are left out (holes in the output) and counted.

A vertex of the quad mesh at a singular vertex of index k has valence 4 - 4k (+1/4 gives 3, -1/4 gives 5); every
other one valence 4, where the map has no fold. The quads are added to `quad_mesh` only when everything
succeeded, as a polygon soup made a mesh by `CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh()`
(after `orient_polygon_soup()`, which splits the vertices where holes meet, when needed).

The Hausdorff distances of the report are sampled: on every triangle of each side (the quads split into two) the
points of a barycentric grid of spacing at most H/4 (at most 33 points per edge), each at its exact distance to
the other side's triangles (CGAL's AABB tree): a lower bound of each one-sided distance, within about H/4 of it.

\param tm the triangle mesh the connection and the field were computed on. Its border edges are put on integer
          iso-lines (the quads end there): the field must be aligned with them (`boundary_alignment`), otherwise
          the call is refused
\param x the connection (from `solve()` with `symmetry_order(4)`): a readable property map `halfedge_descriptor
         -> double`
\param field the cross field (from `compute_field()` with the same connection): a readable property map
             `face_descriptor -> Vector_3`, parallel for `x` up to quarter turns
\param singularities a range of pairs (`vertex_descriptor`, `Singularity_index`): the singularities given to
                     `solve()`
\param quad_mesh a model of `MutableFaceGraph` the quads are added to, counter-clockwise like `tm`
\param np a sequence of named parameters among the ones listed below; exactly one of `quad_size` and `target_faces`
\returns the counts and measures of the quads
\throws Invalid_input `invalid_symmetry_order` when `symmetry_order` is not 4 (not a cross field);
        `index_not_multiple` for an index that is not a multiple of 1/4; `duplicate_singularity`,
        `invalid_vertex`, `singularity_on_boundary` for such singularities; `invalid_argument` when neither or
        both of `quad_size` and `target_faces` are given, when H is not positive and finite, when the quad mesh
        would have more than `max_quads` quads (estimated by area / H^2 first, then by the map's area: "the quad
        size is too small"), when the field is not parallel for the connection up to quarter turns or turns around
        a vertex that is not singular, when the field is not aligned with a border or feature edge (it names
        the edge), and when the integer rounding is infeasible
        (it says which unknown); `solver_failure` when a sparse solve fails; and the mesh errors of the solver.
\cgalNamedParamsBegin
  \cgalParamNBegin{quad_size} \cgalParamType{`double`} \cgalParamDescription{H, the quads' edge length, in the
    mesh's unit} \cgalParamNEnd
  \cgalParamNBegin{target_faces} \cgalParamType{`std::size_t`} \cgalParamDescription{instead of `quad_size`:
    about that many quads, H = sqrt(area / N) (`quad_size_for_target_faces()`)} \cgalParamNEnd
  \cgalParamNBegin{quad_rounding} \cgalParamType{`Quad_rounding`} \cgalParamDefault{`Quad_rounding::greedy`} \cgalParamNEnd
  \cgalParamNBegin{max_quads} \cgalParamType{`double`} \cgalParamDefault{1e7} \cgalParamNEnd
  \cgalParamNBegin{quad_scale_smoothness} \cgalParamType{`double`} \cgalParamDescription{S > 0: the field's
    length is first scaled per face to make it closer to a gradient (the least squares of the map and of a smooth
    log-scale together, whose variation costs S times its Dirichlet energy: it varies over about sqrt(S) H), the
    mean quad size staying H; 0.1 removes the folds near singularities on bunny00 (see the manual)}
    \cgalParamDefault{0: off} \cgalParamNEnd
  \cgalParamNBegin{quad_untangling} \cgalParamType{`bool`} \cgalParamDescription{a rounded map with folded or
    degenerate triangles is moved, keeping its integers, to a minimiser of its least squares plus a barrier energy
    (Garanzha et al. 2021) on the triangles that are or were close to inverted, and kept when it has fewer of them;
    the report gives both counts (see the manual, Untangling)}
    \cgalParamDefault{true} \cgalParamNEnd
  \cgalParamNBegin{quad_cone_mode_weight} \cgalParamType{`double`} \cgalParamDescription{W > 0: the map is made
    to wind around every singular vertex as its index asks (the valence errors of `wrongly_wound_singularities`),
    in two stages: the least squares penalise, with weight W, the harmonics of the singular vertices' one-rings
    that wind a turn less or fold; the continuous map is untangled with the one-rings it winds right held by a
    strict barrier; the integers are rounded against that map's gradients; the rounded map is untangled against
    the field with its rightly wound one-rings held. Measured in the manual (\ref TCQuadConeModes): 30 removes
    most of fandisk's valence errors and can add flaws elsewhere (elephant), so the program tries it only when
    the quads have wrongly wound singular vertices; the reported energies include the penalty} \cgalParamDefault{0: off} \cgalParamNEnd
  \cgalParamNBegin{edge_is_constrained_map} \cgalParamType{a readable property map `edge_descriptor -> bool`}
    \cgalParamDescription{the feature edges (e.g. the sharp edges of `feature_curves()`): each is put on an integer
    iso-line, so that quad edges follow it. The field must be aligned with them (as `feature_aligned_faces()`
    pins it), within 20 degrees on both faces, but for a face inside a sector of less than 45 degrees between two
    consecutive feature edges around a vertex (a cusp: the field turns across it, see `feature_aligned_faces()`),
    checked on its other face only; a feature curve keeps one iso-value along it}
    \cgalParamDefault{no feature edge} \cgalParamNEnd
  \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{4, the only value accepted} \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{geom_traits} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
\cgalNamedParamsEnd
\sa `trace_streamlines()`, which follows the same field's lines one by one
*/
template <class TriangleMesh, class HalfedgeAngleMap, class FaceVectorMap, class SingularityRange, class PolygonMesh,
          class NamedParameters = parameters::Default_named_parameters>
Quad_mesh_report compute_quad_mesh(const TriangleMesh& tm, HalfedgeAngleMap x, FaceVectorMap field,
                                   const SingularityRange& singularities, PolygonMesh& quad_mesh,
                                   const NamedParameters& np = parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;

  const int n = choose_parameter(get_parameter(np, tc_np::symmetry_order), 4);
  if(n != 4)
    throw Invalid_input(Error_code::invalid_symmetry_order,
                        "a quad mesh needs a cross field (n = 4), not an n-direction field with n = " + std::to_string(n));
  const double max_quads = double(choose_parameter(get_parameter(np, tc_np::max_quads), 1e7));
  const double scale_smoothness = double(choose_parameter(get_parameter(np, tc_np::quad_scale_smoothness), 0.));
  const bool untangle = choose_parameter(get_parameter(np, tc_np::quad_untangling), true);
  const double cone_mode_weight = double(choose_parameter(get_parameter(np, tc_np::quad_cone_mode_weight), 0.));
  if(!(cone_mode_weight >= 0) || !std::isfinite(cone_mode_weight))
    throw Invalid_input(Error_code::invalid_argument, "quad_cone_mode_weight must be a non-negative finite number");
  if(!(scale_smoothness >= 0) || !std::isfinite(scale_smoothness))
    throw Invalid_input(Error_code::invalid_argument, "quad_scale_smoothness must be a non-negative finite number");
  if(!(max_quads >= 1) || !std::isfinite(max_quads))
    throw Invalid_input(Error_code::invalid_argument, "max_quads must be a finite number of at least 1");

  const internal::Mesh_arrays<TriangleMesh> m(
    tm, choose_parameter(get_parameter(np, CGAL::internal_np::vertex_point), get_const_property_map(CGAL::vertex_point, tm)),
    choose_parameter(get_parameter(np, CGAL::internal_np::geom_traits), Geom_traits()));
  internal::Mesh_geometry g(m, Weighting::hodge_star);
  g.compute_angles(m);

  // the one rule for H (quad_size.h), shared with move_singularities_off_features()
  const double area = internal::surface_area(m);
  const double H = internal::quad_size_from_parameters(area, np);
  if(!(area / (H * H) <= max_quads)) {
    std::ostringstream s;
    s << "the quad size is too small: H = " << H << " would give about " << area / (H * H)
      << " quads on this mesh (area " << area << "), more than the " << max_quads << " allowed (max_quads)";
    throw Invalid_input(Error_code::invalid_argument, s.str());
  }

  // the singular vertices (array numbering) and their indices times 4
  std::vector<long long> k4(m.nv, 0);
  std::vector<char> listed(m.nv, 0);
  std::vector<int> singular;
  for(const auto& s : singularities) {
    const std::size_t v = internal::checked_singular_vertex(m, s.first, listed);
    const Singularity_index k(s.second);
    if((4 * k.numerator()) % k.denominator() != 0)
      throw Invalid_input(Error_code::index_not_multiple, "the index of vertex " + std::to_string(v) +
                                                            " is not a multiple of 1/4", v);
    k4[v] = 4 * k.numerator() / k.denominator();
    if(k4[v] == 0)
      continue;
    if(g.on_boundary[v])
      throw Invalid_input(Error_code::singularity_on_boundary, "singular vertex " + std::to_string(v) + " is on the boundary", v);
    singular.push_back(int(v));
  }

  const internal::Quad_field q = internal::quad_field(m, g, x, field);
  const internal::Rounding_scheme scheme =
    choose_parameter(get_parameter(np, tc_np::quad_rounding), Quad_rounding::greedy) == Quad_rounding::naive
      ? internal::Rounding_scheme::naive : internal::Rounding_scheme::greedy;
  // the feature edges, per corner halfedge
  std::vector<char> feature_corners;
  std::size_t feature_edges = 0;
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, CGAL::internal_np::edge_is_constrained_t>::value) {
    const auto constrained = get_parameter(np, CGAL::internal_np::edge_is_constrained);
    feature_corners.assign(std::size_t(3 * m.nf), 0);
    for(int i = 0; i < 3 * m.nf; ++i)
      if(get(constrained, edge(m.halfedges[std::size_t(i)], tm))) {
        feature_corners[std::size_t(i)] = 1;
        feature_edges += m.opposite_corner[i] < 0 || i < m.opposite_corner[i];
      }
  }
  const internal::Quad_pipeline_result made =
    internal::quad_mesh_pipeline(m, g, q, singular, k4, H, scheme, max_quads, feature_corners, scale_smoothness,
                                 untangle, cone_mode_weight);
  const internal::Quad_mesh& quads = made.mesh;
  const internal::Quad_measures measures = internal::measure_quad_mesh(m, quads, H / 4);

  Quad_mesh_report report;
  report.quad_size = H;
  report.integer_points = quads.points.size();
  for(std::size_t p = 0; p < quads.points.size(); ++p) {
    const int valence = quads.valence[p];
    ++report.valence_histogram[valence];
    if(quads.on_border[p]) {
      report.border_corners += valence == 2 || valence == 4;
      report.valence_errors += valence < 2 || valence > 4;
      continue;
    }
    const int v = quads.locations[p].mesh_vertex;
    report.valence_errors += valence != 4 - (v >= 0 ? k4[v] : 0);
  }
  report.folded_triangles = std::size_t(quads.folded_triangles);
  report.degenerate_triangles = std::size_t(quads.degenerate_triangles);
  report.rejected_polygons = std::size_t(quads.non_quads);
  report.open_edges = std::size_t(quads.open_edges);
  report.dangling_edges = std::size_t(quads.dangling_edges);
  report.flipped_quads = std::size_t(measures.flipped_quads);
  report.concave_quads = std::size_t(measures.concave_quads);
  report.hausdorff_quads_to_input = measures.hausdorff_quads_to_input;
  report.hausdorff_input_to_quads = measures.hausdorff_input_to_quads;
  report.continuous_energy = made.continuous_energy;
  report.rounded_energy = made.rounded_energy;
  report.solves = std::size_t(made.solves);
  report.factorizations = std::size_t(made.factorizations);
  report.rounding_seconds = made.rounding_seconds;
  report.naive_rounding_fallback = made.naive_fallback;
  report.inverted_before_untangling = std::size_t(made.untangling.inverted_before);
  report.untangled = made.untangling.applied;
  report.untangled_energy = made.untangling.map.energy;
  report.untangling_seconds = made.untangling.seconds + made.continuous_untangling.seconds;
  report.cone_modes = made.cone_modes;
  {
    const internal::Uv_windings winding = internal::uv_windings(m, made.untangling.map);
    for(int v = 0; v < m.nv; ++v) {
      if(g.on_boundary[std::size_t(v)] || winding.beside_inverted[std::size_t(v)])
        continue;
      if(winding.turns_off(std::size_t(v), k4[std::size_t(v)]) != 0)
        ++(k4[std::size_t(v)] != 0 ? report.wrongly_wound_singularities : report.branch_points);
    }
  }
  report.feature_edges = feature_edges;

  // the soup: the integer points in some quad, in the extraction's order
  using Out_point = typename boost::property_traits<typename CGAL::GetVertexPointMap<PolygonMesh>::type>::value_type;
  std::vector<int> new_index(quads.points.size(), -1);
  std::vector<Out_point> points;
  std::vector<std::vector<std::size_t>> polygons;
  for(const std::array<int, 4>& quad : quads.faces) {
    std::vector<std::size_t> polygon;
    for(int p : quad) {
      if(new_index[p] < 0) {
        new_index[p] = int(points.size());
        points.emplace_back(quads.points[p][0], quads.points[p][1], quads.points[p][2]);
      }
      polygon.push_back(std::size_t(new_index[p]));
    }
    polygons.push_back(std::move(polygon));
  }
  if(!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons)) {
    const std::size_t before = points.size();
    CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons);
    report.split_vertices = points.size() - before;
  }
  report.number_of_quads = polygons.size();
  report.number_of_vertices = points.size();
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, quad_mesh);
  return report;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_QUAD_MESH_H
