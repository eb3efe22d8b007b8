// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_FEATURE_ALIGNMENT_H
#define CGAL_TRIVIAL_CONNECTIONS_FEATURE_ALIGNMENT_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/features/feature_curves.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/parameters.h>

#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/number_type_config.h>

#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The default threshold of `feature_curves()` and `feature_aligned_faces()`, in degrees: an interior edge is sharp
when the normals of its two faces make an angle over it (a dihedral angle of 180 minus it or less). On CGAL's
CAD-like meshes (fandisk, fandisk_large, blade, anchor) every edge of a designed crease exceeds it while smooth
patches and fillets stay under it; 20 degrees already picks up the curvature of coarse fillets (see the user
manual, "Feature-aligned fields").
*/
constexpr double default_feature_angle_degrees = 30;

/*!
\ingroup PkgTrivialConnectionsRef
The default of the named parameter `feature_smoothing`: the tangent of a feature curve at a sharp edge is the
least-squares line through the vertices of the curve within this many sharp edges of the edge's ends. On
fandisk_large (n = 4, threshold 30 degrees) the pairs of neighbouring pinned faces that differ by more than 5
degrees are 1,713 of 2,674 with 0 (each edge its own direction), 1,158 with 1, 787 with 2, 721 with 3 and 693
with 4; on fandisk, whose creases are chains of edges, 11, 22, 26, 28 and 28 of 858 (the window reaches around
the ends of curved creases).
*/
constexpr int default_feature_smoothing = 3;

/*!
\ingroup PkgTrivialConnectionsRef
An isolated curve (both ends free: no other sharp edge at either end, and not closed) is dropped when it has
fewer edges than this and is shorter than `feature_minimum_length_factor` times the mean edge length of the mesh:
a lone sharp edge is noise (a flipped sliver on a scan, a crease the mesher left) rather than a feature.
*/
constexpr int feature_minimum_edges = 2;
/*!
\ingroup PkgTrivialConnectionsRef
See `feature_minimum_edges`.
*/
constexpr double feature_minimum_length_factor = 3;

namespace tc_np {
enum feature_smoothing_t { feature_smoothing };
} // namespace tc_np

namespace parameters {
#ifdef DOXYGEN_RUNNING
/// `int` >= 0, default `default_feature_smoothing` (3): the reach, in sharp edges, of the line fitted to a feature
/// curve around each of its edges; 0 gives every edge its own direction (the jagged, naive pins); read by
/// `feature_aligned_faces()`
/// \param value the half-width
/// \returns a sequence of named parameters holding `value`
template <class T>
unspecified_type feature_smoothing(const T& value);
#else
template <class T>
CGAL::Named_function_parameters<T, tc_np::feature_smoothing_t> feature_smoothing(const T& v)
{
  return CGAL::Named_function_parameters<T, tc_np::feature_smoothing_t>(v);
}
template <class T, class NP_T, class NP_Tag, class NP_Base>
CGAL::Named_function_parameters<T, tc_np::feature_smoothing_t, CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>>
feature_smoothing(const T& v, const CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>& np)
{
  return CGAL::Named_function_parameters<T, tc_np::feature_smoothing_t,
                                         CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>>(v, np);
}
#endif
} // namespace parameters

/*!
\ingroup PkgTrivialConnectionsRef
One feature curve: sharp edges connected through vertices that are not corners (see `feature_curves()`). On a mesh
whose creases follow its edges it is a chain; where a crease crosses triangles it is a band of sharp edges.
*/
template <class TriangleMesh>
struct Feature_curve
{
  /// one halfedge per sharp edge of the curve, in breadth-first order from one of them (which one, and which of
  /// the two halfedges, depends on the numbering of the mesh)
  std::vector<typename boost::graph_traits<TriangleMesh>::halfedge_descriptor> halfedges;
  double length = 0; ///< the sum of its edges' lengths
};

/*!
\ingroup PkgTrivialConnectionsRef
What `feature_curves()` found.
*/
template <class TriangleMesh>
struct Feature_curves
{
  std::vector<Feature_curve<TriangleMesh>> curves; ///< the kept curves
  std::size_t number_of_sharp_edges = 0;           ///< all the sharp edges, of kept and dropped curves
  std::size_t dropped_curves = 0;                  ///< isolated short curves dropped (see `feature_minimum_edges`)
  std::size_t dropped_edges = 0;                   ///< their edges
};

/*!
\ingroup PkgTrivialConnectionsRef
What `feature_aligned_faces()` did, and how well its pins agree.
*/
struct Feature_alignment_report
{
  double threshold_degrees = default_feature_angle_degrees; ///< the threshold used
  std::size_t number_of_sharp_edges = 0;     ///< interior edges whose faces' normals differ by more than the threshold
  std::size_t number_of_curves = 0;          ///< feature curves kept
  std::size_t dropped_curves = 0;            ///< isolated short curves dropped
  std::size_t dropped_edges = 0;             ///< the sharp edges of the dropped curves
  std::size_t number_of_pinned_faces = 0;    ///< faces written: those beside an edge of a kept curve
  std::size_t faces_with_several_edges = 0;  ///< pinned faces beside two or three curve edges
  std::size_t number_of_cusps = 0;           ///< cusps whose sector got the sector rule (n = 4; see below)
  std::size_t sector_rule_faces = 0;         ///< the faces pinned by it (in the cusps' sectors and tongues)
  std::size_t neighbouring_pairs = 0;        ///< pairs of pinned faces that share an interior edge
  std::size_t disagreeing_pairs = 0;         ///< those whose directions differ by more than 5 degrees (see below)
  double max_disagreement_degrees = 0;       ///< the largest difference over the pairs, in [0, 180 / n]
};

namespace internal {
namespace features {

inline void check_threshold(double threshold_degrees)
{
  if(!(threshold_degrees >= 0 && threshold_degrees <= 180)) {
    std::ostringstream s;
    s << "the feature angle threshold must be a number of degrees in [0, 180] (got " << threshold_degrees << ")";
    throw Invalid_input(Error_code::invalid_argument, s.str());
  }
}

template <class TriangleMesh, class NamedParameters>
internal::Mesh_arrays<TriangleMesh> arrays(const TriangleMesh& tm, const NamedParameters& np)
{
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  return internal::Mesh_arrays<TriangleMesh>(
    tm,
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                       get_const_property_map(CGAL::vertex_point, tm)),
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits),
                                       Geom_traits()));
}

template <class Mesh>
Curve_set curves_of(const Mesh& m, const std::vector<Vec3>& N, double threshold_degrees)
{
  return detect_curves(m, N, threshold_degrees * CGAL_PI / 180, feature_minimum_edges, feature_minimum_length_factor);
}

} // namespace features
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsRef
The feature curves of a triangle mesh. An interior edge is sharp when the normals of its two faces make an angle
greater than `threshold_degrees` (border edges never are). A curve is a set of sharp edges connected through
vertices that are not corners. A corner is a vertex around which the sharp edges do not lie along one line: the
vertices on the sharp edges within 3 sharp edges of it have a covariance whose second eigenvalue exceeds 0.3 times
the first, the largest such ratio among those vertices (one corner where three creases meet, or where a crease
turns by more than about 60 degrees). A crease that turns back at a vertex (a cusp: two sharp edges whose arms,
each a smooth chain of at least 3 sharp edges, leave the vertex less than 60 degrees apart) lies along one line to
that covariance, and is a corner too. Chains through the vertices with exactly two sharp edges, broken at the
others, would cut a crease that crosses triangles into single edges: the band of sharp edges along it (zigzags
and the rungs between them) stays one curve this way. An isolated short curve is dropped: one that touches no
corner, with fewer than `feature_minimum_edges` edges and shorter than `feature_minimum_length_factor` mean edge
lengths. The curves, and which are dropped, do not depend on how the mesh is numbered (up to exact ties). Linear
time.
\tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph` with triangle faces
\tparam NamedParameters a sequence of named parameters
\param tm the triangle mesh
\param threshold_degrees the threshold, in [0, 180] (default `default_feature_angle_degrees`)
\param np an optional sequence of named parameters among the ones listed below
\returns the kept curves and the counts
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{geom_traits} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
\cgalNamedParamsEnd
\throws Invalid_input `invalid_argument` for a threshold that is negative, over 180 or not a number; the mesh's
        errors as the solver's constructor (`empty_mesh`, `not_triangle_mesh`, `non_manifold`, `degenerate_face`,
        `non_finite_point`)
*/
template <class TriangleMesh, class NamedParameters = parameters::Default_named_parameters>
Feature_curves<TriangleMesh> feature_curves(const TriangleMesh& tm,
                                            double threshold_degrees = default_feature_angle_degrees,
                                            const NamedParameters& np = parameters::default_values())
{
  internal::features::check_threshold(threshold_degrees);
  const internal::Mesh_arrays<TriangleMesh> m = internal::features::arrays(tm, np);
  const std::vector<internal::Vec3> N = internal::features::face_normals(m);
  internal::features::Curve_set set = internal::features::curves_of(m, N, threshold_degrees);
  Feature_curves<TriangleMesh> out;
  out.number_of_sharp_edges = set.graph.edges.size();
  out.dropped_curves = set.dropped_curves;
  out.dropped_edges = set.dropped_edges;
  for(const internal::features::Curve& c : set.kept) {
    out.curves.emplace_back();
    out.curves.back().length = c.length;
    for(int e : c.edges)
      out.curves.back().halfedges.push_back(m.halfedges[set.graph.edges[e]]);
  }
  return out;
}

/*!
\ingroup PkgTrivialConnectionsRef
The faces beside the feature curves and the direction of the curve there: pins for a feature-aligned field (give
the faces as `constrained_faces` to the solver and the map as `face_directions` to `solve()`).

Every face that has an edge on a kept curve of `feature_curves()` is written to `faces`. Its direction is the
curve's direction there, not its own edge's: the tangent of the curve at an edge is the principal axis (the
least-squares line) of the curve's vertices within `k` sharp edges of the edge's ends, `k` = `feature_smoothing`,
not reaching past corners, so that a jagged crease gives directions that follow the crease rather than each
sawtooth.
Both faces of the edge get the vector that makes with the edge the angle the tangent makes with it (the circular
mean of its angles in the two faces' planes), in their own planes: Levi-Civita transport across the edge maps one
onto the other exactly. A face beside two or three curve edges takes the mean of `exp(i n theta)` of their
directions weighted by the edges' lengths (for n = 4, perpendicular edges agree), nearest to the direction of its
longest such edge, or that direction itself when they cancel. Faces on the boundary are written like the others
(drop them when the solver aligns the field with the boundary: it refuses targets there).

For n = 4 a cusp (see `feature_curves()`) whose sector between the arms is narrower than 45 degrees gets the
sector rule of quad meshing: a sector of angle theta between two features holds k = max(1, round(theta / 90
degrees)) quad corners, so the cross field turns by theta - k 90 degrees across it, not by theta (the short way,
which would give both arms one iso-line and fold the quads between them). The faces of that sector take that turn
linearly in the angle about the cusp (one face: half of it on either side), and so do the faces between the arms
(the tongue) up to where they are 50 degrees apart, with the turn taken linearly in the distances to the two arms;
their vertex then gets index -1/4 from the solve (one corner inside, four outside). The report counts the cusps and
these faces, which are written with the others (a tongue's inner faces are not beside a sharp edge).

The report also says how well the pins agree: for each interior edge between two pinned faces, the angle between
the direction of one moved across the edge by Levi-Civita transport and the other's, modulo `2 pi / n` (how far
the pinned field must turn across that edge). A mesh without a sharp edge gives no face and a report of zeros.
\tparam TriangleMesh a model of `FaceListGraph` and `HalfedgeListGraph` with triangle faces
\tparam FaceOutputIterator an output iterator accepting `face_descriptor`
\tparam FaceVectorMap a writable property map `face_descriptor -> Vector_3` of the geometric traits
\tparam NamedParameters a sequence of named parameters
\param tm the triangle mesh
\param threshold_degrees the feature angle threshold, in [0, 180] (see `feature_curves()`)
\param faces receives the pinned faces, in increasing face index (the order of `faces(tm)` for a `Surface_mesh`)
\param directions receives the unit direction of every pinned face, tangent to it (the map is written for the
       pinned faces only)
\param np an optional sequence of named parameters among the ones listed below
\returns the report
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{geom_traits} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
  \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{1}
    \cgalParamExtra{n: the faces beside several edges and the disagreement are taken modulo `2 pi / n`; for n = 1
    the directions follow each curve's orientation, which depends on the numbering of the mesh} \cgalParamNEnd
  \cgalParamNBegin{feature_smoothing} \cgalParamType{`int`} \cgalParamDefault{`default_feature_smoothing`} \cgalParamNEnd
\cgalNamedParamsEnd
\throws Invalid_input as `feature_curves()`, and `invalid_argument` for `symmetry_order` < 1 or a negative
        `feature_smoothing`
*/
template <class TriangleMesh, class FaceOutputIterator, class FaceVectorMap,
          class NamedParameters = parameters::Default_named_parameters>
Feature_alignment_report feature_aligned_faces(const TriangleMesh& tm, double threshold_degrees, FaceOutputIterator faces,
                                               FaceVectorMap directions,
                                               const NamedParameters& np = parameters::default_values())
{
  using Geom_traits = typename CGAL::GetGeomTraits<TriangleMesh, NamedParameters>::type;
  using FT = typename Geom_traits::FT;
  internal::features::check_threshold(threshold_degrees);
  const int n = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1);
  const int window = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::feature_smoothing),
                                                        default_feature_smoothing);
  if(n < 1)
    throw Invalid_input(Error_code::invalid_argument, "the symmetry order must be at least 1 (got " +
                                                        std::to_string(n) + ")");
  if(window < 0)
    throw Invalid_input(Error_code::invalid_argument, "the feature smoothing must be at least 0 (got " +
                                                        std::to_string(window) + ")");
  const Geom_traits traits =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits), Geom_traits());
  const internal::Mesh_arrays<TriangleMesh> m = internal::features::arrays(tm, np);
  const std::vector<internal::Vec3> N = internal::features::face_normals(m);
  const internal::features::Curve_set set = internal::features::curves_of(m, N, threshold_degrees);
  const internal::features::Face_pins pins = internal::features::pin_faces(m, N, set.graph, set.kept, window, n);
  const internal::features::Disagreement d =
    internal::features::disagreement(m, N, pins.faces, pins.directions, n, 5 * CGAL_PI / 180);

  typename Geom_traits::Construct_vector_3 vector = traits.construct_vector_3_object();
  for(std::size_t i = 0; i < pins.faces.size(); ++i) {
    const auto& v = pins.directions[i];
    put(directions, m.face_descriptors[pins.faces[i]], vector(FT(v[0]), FT(v[1]), FT(v[2])));
    *faces++ = m.face_descriptors[pins.faces[i]];
  }
  Feature_alignment_report r;
  r.threshold_degrees = threshold_degrees;
  r.number_of_sharp_edges = set.graph.edges.size();
  r.number_of_curves = set.kept.size();
  r.dropped_curves = set.dropped_curves;
  r.dropped_edges = set.dropped_edges;
  r.number_of_pinned_faces = pins.faces.size();
  r.faces_with_several_edges = pins.faces_with_several_edges;
  r.number_of_cusps = pins.cusps;
  r.sector_rule_faces = pins.sector_faces;
  r.neighbouring_pairs = d.pairs;
  r.disagreeing_pairs = d.over;
  r.max_disagreement_degrees = d.max_radians * 180 / CGAL_PI;
  return r;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_FEATURE_ALIGNMENT_H
