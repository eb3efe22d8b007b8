// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SOLVE_REPORT_H
#define CGAL_TRIVIAL_CONNECTIONS_SOLVE_REPORT_H

#include <CGAL/Trivial_connections/Singularity_index.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
The two kinds of non-contractible dual loops whose holonomy carries a free integer.
*/
enum class Loop_kind {
  boundary, ///< goes once counter-clockwise around a boundary loop (as if the hole were a vertex)
  generator ///< one of the 2g homology generators of a component (tree-cotree)
};

/*!
\ingroup PkgTrivialConnectionsRef
What a solve did on one loop. For a loop `L` with Levi-Civita holonomy `H_L` and connection sum
`X_L = sum_L x`, the connection satisfies `H_L + X_L = 2 pi period / n`:
for a boundary loop `H_L` is its geodesic curvature `kappa_B` (exact, not wrapped) and
`period / n` is its index `k_B`; for a generator `H_L` is the Levi-Civita holonomy wrapped to `(-pi, pi]`.
*/
struct Loop_report
{
  Loop_kind kind = Loop_kind::generator; ///< boundary loop or homology generator
  std::size_t component = 0;             ///< index of the loop's component
  std::int64_t period = 0;          ///< the integer (n times the index, for a boundary loop)
  Singularity_index index;          ///< `period / n`: the index of a boundary loop (also filled for generators)
  bool prescribed = false;          ///< given by the user rather than chosen by the solver
  double residual = 0;              ///< `|H_L + X_L - 2 pi period / n|`
};

/*!
\ingroup PkgTrivialConnectionsRef
What a solve did on one row of the directional constraints: a dual path from the constrained face
`from_face` to `to_face` (face indices). With `theta_f` the target angle in face f and `T` the Levi-Civita
transport along the path, the connection satisfies `T + theta_from - theta_to + X = 2 pi period / n`
(`T + theta_from - theta_to` wrapped to `(-pi, pi]`), which is what makes the field meet both targets.
*/
struct Constraint_report
{
  std::size_t component = 0;   ///< index of the component (in `Solve_report::components`) that has the path
  std::size_t from_face = 0;   ///< face index (`faces(tm)` order) where the path starts
  std::size_t to_face = 0;     ///< face index where it ends
  std::size_t length = 0;   ///< number of edges the path crosses
  std::int64_t period = 0;  ///< chosen by the solver, minimising the energy with the loop integers (or `decided`)
  /// `|T + theta_from - theta_to + X - 2 pi period / n - (d_to - d_from)|`, with `d` the mismatch of a guided
  /// end (0 for a constrained one)
  double residual = 0;
  /// `true` for a link between two faces that touch (an edge or a vertex): its period is the rounding, the short
  /// way from one target to the other, not a free integer (see the user manual)
  bool decided = false;
};

/*!
\ingroup PkgTrivialConnectionsRef
The angle between the field and the guide on a guided face: the field's angle minus the guide's, in the
representative chosen with the integers (multiples of `2 pi / n` apart, in `(-pi/n, pi/n]` for optimal
integers), measured counter-clockwise about the face normal.
*/
struct Guidance_report
{
  std::size_t face = 0;   ///< face index (`faces(tm)` order) of the guided face
  double mismatch = 0;    ///< `d_g`: the field's angle minus the guide's, in radians
};

/*!
\ingroup PkgTrivialConnectionsRef
What `Trivial_connection_solver::set_constraints()` did.
*/
struct Constraint_update
{
  bool refactored = false;                    ///< the constraint system was assembled and factored again
  std::size_t links = 0;                      ///< links between constrained or guided faces now
  std::size_t links_outside_the_factor = 0;   ///< of which solved through the dense block (not refactored)
  std::size_t new_forward_substitutions = 0;  ///< made by this call (one per new link; links met before are kept)
};

/*!
\ingroup PkgTrivialConnectionsRef
Topology of one connected component (faces connected through edges).
*/
struct Component_report
{
  std::size_t number_of_faces = 0;          ///< faces of the component
  std::int64_t euler_characteristic = 0;   ///< `V - E + F` of the component
  std::int64_t genus = 0;                  ///< `(2 - chi - b) / 2`
  std::size_t number_of_boundary_loops = 0; ///< `b`, the boundary loops of the component
  Singularity_index vertex_index_sum;      ///< sum of the prescribed interior-vertex indices
};

/*!
\ingroup PkgTrivialConnectionsRef
What `Trivial_connection_solver::solve()` returns.
*/
struct Solve_report
{
  int symmetry_order = 1;              ///< `n` of the solve
  double energy = 0;                    ///< `sum_e w_e x_e^2` over interior edges
  /// with guided faces: `mu sum_g d_g^2` (`guidance_weight` mu, `Guidance_report::mismatch` d_g); the solve
  /// minimises `energy + guidance_energy`
  double guidance_energy = 0;
  double max_vertex_residual = 0;       ///< max over interior vertices of `|K_v + sum x - 2 pi k_v|`
  double max_loop_residual = 0;         ///< max of the `Loop_report::residual`
  /// energy (plus guidance energy) the same solve would have with the integers rounded one by one (for comparison)
  double rounding_energy = 0;
  /// `true` when the integer choice was proven optimal by exhaustive enumeration (or prescribed, or empty)
  bool integers_proven_optimal = true;
  /// a certificate for the integer choice: no choice of the free integers (the prescribed ones fixed) gives
  /// a smaller `energy + guidance_energy` than this (up to rounding). It equals `energy + guidance_energy` when
  /// `integers_proven_optimal`; otherwise the gap between the two bounds how far from optimal the answer can be
  /// (see the user manual: it comes from the radius the enumeration proved empty)
  double energy_lower_bound = 0;
  std::vector<Loop_report> loops;       ///< in the order of `Trivial_connection_solver::loops()`
  /// one per path joining two constrained faces (empty without directional constraints)
  std::vector<Constraint_report> constraints;
  double max_constraint_residual = 0;   ///< max of the `Constraint_report::residual`
  std::vector<Guidance_report> guidance; ///< one per guided face, in the order given to the constructor
  std::vector<Component_report> components; ///< one per connected component, in the order of `Trivial_connection_solver::component()`
};

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SOLVE_REPORT_H
