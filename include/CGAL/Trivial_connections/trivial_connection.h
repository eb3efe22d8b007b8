// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_H
#define CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_H

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
One-shot version of `Trivial_connection_solver::solve()`: builds the solver and solves once.
`np` may hold every named parameter of the solver's constructor and of `solve()`
(`vertex_point_map`, `geom_traits`, `weighting`, `symmetry_order`, `loop_periods`).
To solve several singularity sets on the same mesh, keep a `Trivial_connection_solver` instead: it
factors once.
\param tm the triangle mesh
\param singularities as for `Trivial_connection_solver::solve()`: a range of pairs of a `vertex_descriptor`
       (`first`) and its `Singularity_index` (`second`)
\param x a writable property map with `halfedge_descriptor` as key type and `double` as value type:
       receives the connection, as in `Trivial_connection_solver::solve()`
\param np a sequence of named parameters of the solver's constructor and of
       `Trivial_connection_solver::solve()`
\returns the report of the solve
\throws Invalid_input as the constructor and `solve()`
*/
template <class TriangleMesh, class SingularityRange, class HalfedgeAngleMap,
          class NamedParameters = parameters::Default_named_parameters>
Solve_report compute_trivial_connection(const TriangleMesh& tm, const SingularityRange& singularities,
                                        HalfedgeAngleMap x,
                                        const NamedParameters& np = parameters::default_values())
{
  Trivial_connection_solver<TriangleMesh> solver(tm, np);
  return solver.solve(singularities, x, np);
}

/*!
\ingroup PkgTrivialConnectionsRef
One-shot computation of the connection and of the direction field it defines
(`Trivial_connection_solver::solve()` then `Trivial_connection_solver::compute_field()`).
\param tm the triangle mesh
\param singularities as for `Trivial_connection_solver::solve()`
\param x a writable property map `halfedge_descriptor -> double`, receives the connection
\param field a writable property map `face_descriptor -> Vector_3` of the geometric traits
\param np the named parameters of the solver's constructor, of `Trivial_connection_solver::solve()` and of
       `Trivial_connection_solver::compute_field()` (`seed_face`, `seed_angle`)
\returns the report of the solve
\throws Invalid_input as the constructor and `solve()`
*/
template <class TriangleMesh, class SingularityRange, class HalfedgeAngleMap, class FaceVectorMap,
          class NamedParameters = parameters::Default_named_parameters>
Solve_report compute_direction_field(const TriangleMesh& tm, const SingularityRange& singularities,
                                     HalfedgeAngleMap x, FaceVectorMap field,
                                     const NamedParameters& np = parameters::default_values())
{
  Trivial_connection_solver<TriangleMesh> solver(tm, np);
  Solve_report report = solver.solve(singularities, x, np);
  solver.compute_field(x, field, np);
  return report;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_TRIVIAL_CONNECTION_H
