// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_INTEGER_SOLVE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_INTEGER_SOLVE_H

#include <CGAL/Trivial_connections/internal/factorization/prefactored_system.h>
#include <CGAL/Trivial_connections/internal/integers/loop_periods.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The multipliers of M lambda = b with the free integers not prescribed chosen on the way, in one forward and
  one backward pass: the forward pass leaves their right-hand side y, the closest vector search chooses them
  (written into `periods`, 0 there on entry; `proven` as choose_loop_periods()), b gets them (2 pi m / n on
  their rows, `unit` = 2 pi / n) and the backward pass finishes. `holonomy`: per slot, the H of its row.
  `rounding_energy`: the energy for the integers rounded one by one (Solve_report::rounding_energy).
  `notify(fraction)` is called before (0) and after (1) the choice.
*/
template <class SolverTraits, class Notify>
Eigen::VectorXd solve_choosing_integers(Prefactored_system<SolverTraits>& system, const Constraint_rows& rows,
                                        Eigen::VectorXd& b, double unit, const std::vector<char>& prescribed,
                                        const std::vector<double>& holonomy, std::vector<std::int64_t>& periods,
                                        bool& proven, double& rounding_energy, Notify notify)
{
  typename Prefactored_system<SolverTraits>::Loop_forward forward = system.forward(rows, b);
  notify(0.);
  // the budget of the enumeration: about the work of a few back-substitutions, so that a re-solve stays cheap
  const double loop_energy = choose_loop_periods(rows.free_slots, system.metrics(), forward.y, unit, prescribed,
                                                 holonomy, (std::max)(2e5, 10. * double(rows.rows)), periods, proven);
  notify(1.);
  const std::vector<Eigen::VectorXd> t = loop_right_hand_sides(rows.free_slots, forward.y, unit, prescribed, periods);
  add_chosen_periods(rows, periods, prescribed, unit, b);
  const Eigen::VectorXd lambda = system.backward(rows, forward, t, b);
  rounding_energy = forward.node_part + loop_energy;
  return lambda;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_INTEGER_SOLVE_H
