// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_PARAMETERS_H
#define CGAL_TRIVIAL_CONNECTIONS_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The weights `w_e` of the energy `sum_e w_e x_e^2`.
*/
enum class Weighting {
  hodge_star, ///< `w_e = |e| / |e*|`, with the barycentric dual length `|e*|` (see the user manual)
  unit        ///< `w_e = 1`
};

// Tags of our own named parameters. Not called `internal_np`: that would hide CGAL::internal_np.
namespace tc_np {
enum weighting_t { weighting };
enum symmetry_order_t { symmetry_order };
enum loop_periods_t { loop_periods };
enum seed_face_t { seed_face };
enum seed_angle_t { seed_angle };
enum progress_t { progress };
enum constrained_faces_t { constrained_faces };
enum align_with_boundary_t { align_with_boundary };
enum face_directions_t { face_directions };
enum guided_faces_t { guided_faces };
enum guidance_weight_t { guidance_weight };
enum maximum_faces_per_ray_t { maximum_faces_per_ray };
enum triangulate_t { triangulate };
enum energy_gradient_t { energy_gradient };
enum alignment_guide_t { alignment_guide };
enum alignment_strength_t { alignment_strength };
enum fixed_singularities_t { fixed_singularities };
enum fixed_vertices_t { fixed_vertices };
enum cancel_pairs_t { cancel_pairs };
enum maximum_trials_t { maximum_trials };
enum quad_size_t { quad_size };
enum target_faces_t { target_faces };
enum quad_rounding_t { quad_rounding };
enum max_quads_t { max_quads };
enum quad_scale_smoothness_t { quad_scale_smoothness };
enum quad_untangling_t { quad_untangling };
enum quad_cone_mode_weight_t { quad_cone_mode_weight };
} // namespace tc_np

/*!
\ingroup PkgTrivialConnectionsRef
Named parameters of this package. It also re-exports CGAL's own (`vertex_point_map`, `geom_traits`,
`default_values()`, ...), so `CGAL::Trivial_connections::parameters::` is the only prefix users need.
Each of our parameters comes as a starter, `symmetry_order(4)`, and as an appender that takes any pack,
`symmetry_order(4, CGAL::parameters::vertex_point_map(vpm))`; CGAL's own parameters chain after ours as
members: `symmetry_order(4).vertex_point_map(vpm)`.
*/
namespace parameters {
using namespace CGAL::parameters;

#ifdef DOXYGEN_RUNNING
// what the reference manual shows for each named parameter
#define CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(NAME) template <class T> unspecified_type NAME(const T& value);
#else
#define CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(NAME)                                           \
  template <class T>                                                                             \
  CGAL::Named_function_parameters<T, tc_np::NAME##_t> NAME(const T& v)                           \
  {                                                                                              \
    return CGAL::Named_function_parameters<T, tc_np::NAME##_t>(v);                               \
  }                                                                                              \
  template <class T, class NP_T, class NP_Tag, class NP_Base>                                    \
  CGAL::Named_function_parameters<T, tc_np::NAME##_t,                                            \
                                  CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>>        \
  NAME(const T& v, const CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>& np)             \
  {                                                                                              \
    return CGAL::Named_function_parameters<T, tc_np::NAME##_t,                                   \
                                           CGAL::Named_function_parameters<NP_T, NP_Tag, NP_Base>>(v, np); \
  }
#endif

/// `Weighting::hodge_star` (default) or `Weighting::unit`; read by the solver's constructor
/// \param value the `Weighting` of the energy
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(weighting)
/// n of the n-direction field (`int`, default 1); read by `solve()`
/// \param value n, an `int` (`solve()` requires `n >= 1`)
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(symmetry_order)
/// prescribed integers of the loops (`std::vector<long long>`, one per loop of `loops()`); read by `solve()`
/// \param value one integer per loop, in the order of `Trivial_connection_solver::loops()`: a
///        `std::vector<std::int64_t>`, or a `std::vector<std::optional<std::int64_t>>` whose empty entries
///        are chosen by the solver
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(loop_periods)
/// the face the field is seeded from (a `face_descriptor`); read by `compute_field()`
/// \param value a `face_descriptor` of the mesh
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(seed_face)
/// angle of the field in the seed face, counter-clockwise from `halfedge(seed_face)` (`double`, default 0)
/// \param value the angle, in radians
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(seed_angle)
/// a `Progress_callback` (or any callable `void(Phase, double)`); read by the constructor, `solve()` and
/// `compute_field()`
/// \param value the callback, called as `value(phase, fraction)`
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(progress)

/// faces whose field direction is prescribed (a range of `face_descriptor`); read by the solver's constructor
/// \param value a range of `face_descriptor` of the mesh, each listed once
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(constrained_faces)
/// `bool`, default `false`: the field follows the boundary on every boundary face; read by the constructor
/// \param value `true` to align the field with the boundary
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(align_with_boundary)
/// a readable property map `face_descriptor -> Vector_3`: the target direction of every constrained face and
/// the guide of every guided face; read by `solve()` and `compute_field()`
/// \param value a readable property map with `face_descriptor` as key type and the kernel's `Vector_3` as
///        value type
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(face_directions)

/// faces on which the field is drawn towards a direction given to each `solve()` (a range of
/// `face_descriptor`, soft guidance); read by the solver's constructor
/// \param value a range of `face_descriptor` of the mesh, each listed once and none of them constrained
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(guided_faces)
/// `double` mu > 0, default 1: the weight of the guidance term mu sum_g d_g^2; read by the constructor
/// \param value mu, a positive and finite `double`
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(guidance_weight)

/// `std::size_t`: the faces a streamline ray may cross at most; read by `trace_streamlines()`
/// \param value the maximum number of faces of one ray
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(maximum_faces_per_ray)
/// whether `read_triangle_mesh()` triangulates the faces of more than three vertices (`bool`, default `false`:
/// such faces are an error)
/// \param value `true` to triangulate such faces
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(triangulate)

/// a writable property map `vertex_descriptor -> double`; read by `solve()`, which writes there the derivative of
/// the minimised energy with respect to the index of every interior vertex (0 at the others), the integers fixed
/// (see `Trivial_connection_solver::solve()`)
/// \param value the map
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(energy_gradient)
/// a readable property map `face_descriptor -> Vector_3`: per face a guide direction whose length is its weight
/// (0: no guide there); read by `place_singularities()`, which then places the singularities of the field
/// aligned with it (for example `principal_curvature_guide()`)
/// \param value the map
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(alignment_guide)
/// `double` > 0, default 100: how closely the aligned field of `place_singularities()` follows its guide (see the
/// user manual)
/// \param value the strength, positive and finite
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(alignment_strength)
/// a range of singularities (pairs of a `vertex_descriptor` and a `Singularity_index`) that
/// `place_singularities()` keeps, placing the others around them
/// \param value the range
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(fixed_singularities)
/// a range of `vertex_descriptor` whose singularities `refine_singularities()` does not move (and onto which it
/// moves none); `move_singularities_off_features()` leaves them where they are too
/// \param value the range
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(fixed_vertices)
/// `bool`, default `false`: `refine_singularities()` may also cancel opposite singularities of a component, at
/// any distance, one unit of 1/n of each at a time
/// \param value whether pairs may cancel
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(cancel_pairs)
/// `std::size_t`, default none: a budget of the solves `refine_singularities()` may try (without one it runs to a
/// local minimum)
/// \param value the budget of trial solves
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(maximum_trials)

/// `double` H > 0: the edge length of the quads of `compute_quad_mesh()`, in the mesh's length unit (one unit
/// of the parametrisation is H long); the distance `move_singularities_off_features()` keeps from feature edges
/// \param value H, positive and finite
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(quad_size)
/// `std::size_t` N > 0: the number of quads `compute_quad_mesh()` aims at, instead of `quad_size`: H is then
/// sqrt(area / N), the area of the mesh (`quad_size_for_target_faces()`; `move_singularities_off_features()`
/// reads it the same way)
/// \param value N, positive
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(target_faces)
/// a `Quad_rounding`, default `Quad_rounding::greedy`: how `compute_quad_mesh()` makes its parametrisation an
/// integer-grid map
/// \param value the rounding scheme
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(quad_rounding)
/// `double`, default 1e7: the largest number of quads `compute_quad_mesh()` may make (more is refused: the quad
/// size is too small)
/// \param value the bound, positive
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(max_quads)
/// `double` S >= 0, default 0 (off): `compute_quad_mesh()` first scales the field per face, with a scale whose
/// logarithm varies over about sqrt(S) H, so that it is closer to a gradient (fewer folds near singularities on
/// fine meshes; 0.1 is a good value there)
/// \param value S, non-negative and finite
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(quad_scale_smoothness)
/// `bool`, default true: `compute_quad_mesh()` moves a rounded map that has folded or degenerate triangles out of
/// them where its integers allow it (a barrier energy minimised over the maps with the same integers)
/// \param value false keeps the rounded map as it is
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(quad_untangling)
/// `double` W >= 0, default 0 (off): `compute_quad_mesh()` makes the map wind around every singular vertex as its
/// index asks, in two stages: the least squares penalise with weight W the harmonics of the singular vertices'
/// one-rings that wind wrongly, the continuous map is untangled with its rightly wound one-rings held, and the
/// rounding fits that map (manual, Cone modes; 30 removes most valence errors on fandisk, at two to three times
/// the quad step's time)
/// \param value W, non-negative and finite
/// \returns a sequence of named parameters holding `value`
CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER(quad_cone_mode_weight)

#undef CGAL_TRIVIAL_CONNECTIONS_NAMED_PARAMETER
} // namespace parameters

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_PARAMETERS_H
