// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SOLVER_ACCESS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SOLVER_ACCESS_H

// What the functions above the coordinator (placement/, the refinement, the Python module's mesh input) may
// read or ask of a Trivial_connection_solver: its layers, read-only, and the few hooks the refinement needs.
// Included at the end of Trivial_connection_solver.h, whose class declares it a friend.

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

template <class TriangleMesh, class GeomTraits, class SolverTraits>
struct Solver_access<Trivial_connection_solver<TriangleMesh, GeomTraits, SolverTraits>>
{
  using Solver = Trivial_connection_solver<TriangleMesh, GeomTraits, SolverTraits>;
  static const TriangleMesh& triangle_mesh(const Solver& s) { return s.m_tm; }
  static const Mesh_arrays<TriangleMesh>& mesh(const Solver& s) { return s.m_mesh; }
  static const Mesh_geometry& geometry(const Solver& s) { return s.m_geometry; }
  static const Mesh_topology& topology(const Solver& s) { return s.m_topology; }
  // the constrained and guided faces (read-only: the placement holds the constrained ones)
  static const Constraint_links& links(const Solver& s) { return s.m_links; }
  // the rows of the constraint system and its factorization (the refinement reads M^-1 from it)
  static const Constraint_rows& rows(const Solver& s) { return s.m_rows; }
  static Prefactored_system<typename Solver::Solver_traits>& system(Solver& s) { return s.m_system; }
  // M^-1 b of the last solve() given an energy_gradient
  static const Eigen::VectorXd& multipliers(const Solver& s) { return s.m_multipliers; }
  // the integers of every slot (loops, then links) of the last solve; a candidate for the next solve only, which
  // then gives an energy no higher than with them (when its search cannot prove the optimum)
  static const std::vector<std::int64_t>& last_periods(const Solver& s) { return s.m_last_periods; }
  static void hint_periods(Solver& s, std::vector<std::int64_t> periods) { s.m_period_hint = std::move(periods); }
  // the residual from which solve() refines its connection (see checked_connection())
  static void refine_residuals_above(Solver& s, double relative) { s.m_refine_residuals_above = relative; }
  // whether solve() bounds the other choices of the links decided by rounding (report only: a solve more)
  static void bound_decided_choices(Solver& s, bool bound) { s.m_bound_decided_choices = bound; }
  // whether the last solve() proved its free integers optimal, the links decided by rounding held
  static bool free_integers_proven(const Solver& s) { return s.m_free_integers_proven; }
  // after set_constraints() on a kept factorization: its links into the factor (factored again)
  static void factor_bordered_links(Solver& s) { s.factor_bordered_links(); }
  // a solver of tm from its arrays, made from the connectivity tm is built from (see Mesh_arrays); with a
  // vertex_point_map in np, nothing of tm is read until the constructor has returned
  template <class NamedParameters = parameters::Default_named_parameters>
  static std::unique_ptr<Solver> make(const TriangleMesh& tm, Mesh_arrays<TriangleMesh>&& mesh,
                                      const NamedParameters& np = parameters::default_values())
  {
    return std::unique_ptr<Solver>(new Solver(tm, std::move(mesh), np));
  }
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SOLVER_ACCESS_H
