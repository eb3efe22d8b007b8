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
  in the reduced lattices `lattices` (written into `periods`, 0 there on entry), b gets them (2 pi m / n on
  their rows, `unit` = 2 pi / n) and the backward pass finishes. `holonomy`: per slot, the H of its row.
  `energies`: the energy of the solve with the integers rounded one by one and a lower bound on its energy over
  every choice of them (Solve_report::rounding_energy, energy_lower_bound), and whether the choice is proven
  optimal. `notify(fraction)` is called before (0) and after (1) the choice.
  With `want_relaxed`, `relaxed_rhs` gets the b whose solve has every free integer relaxed to a real number
  (its multipliers vanish on the free rows: b_F less the forward pass's y there).
*/
struct Integer_choice_energies
{
  double rounding_energy = 0;
  double lower_bound = 0;
  bool proven = true;
  bool want_relaxed = false;
  Eigen::VectorXd relaxed_rhs;
};

template <class SolverTraits, class Notify>
Eigen::VectorXd solve_choosing_integers(Prefactored_system<SolverTraits>& system, const Constraint_rows& rows,
                                        const std::vector<Reduced_lattice>& lattices, Eigen::VectorXd& b,
                                        double unit, const std::vector<char>& prescribed,
                                        const std::vector<double>& holonomy, std::vector<std::int64_t>& periods,
                                        Integer_choice_energies& energies, Notify notify,
                                        const std::vector<std::int64_t>* hint = nullptr)
{
  typename Prefactored_system<SolverTraits>::Loop_forward forward = system.forward(rows, b);
  notify(0.);
  // the budget of the enumeration: about the work of one back-substitution, so that a re-solve stays cheap
  // (in the reduced basis, nearest plane and descent already find most of what a longer search would)
  const Loop_period_choice choice = choose_loop_periods(rows.free_slots, system.metrics(), lattices, forward.y, unit,
                                                        prescribed, holonomy, (std::max)(1e5, 5. * double(rows.rows)),
                                                        periods, hint);
  notify(1.);
  if(energies.want_relaxed) {
    energies.relaxed_rhs = b;
    for(std::size_t c = 0; c < rows.free_slots.size(); ++c)
      for(std::size_t a = 0; a < rows.free_slots[c].size(); ++a)
        energies.relaxed_rhs[rows.row_of_slot[std::size_t(rows.free_slots[c][a])]] -= forward.y[c][Eigen::Index(a)];
  }
  const std::vector<Eigen::VectorXd> t = loop_right_hand_sides(rows.free_slots, forward.y, unit, prescribed, periods);
  add_chosen_periods(rows, periods, prescribed, unit, b);
  const Eigen::VectorXd lambda = system.backward(rows, forward, t, b);
  energies.rounding_energy = forward.node_part + choice.rounding_part;
  energies.lower_bound = forward.node_part + choice.lower_bound_part;
  energies.proven = choice.proven;
  return lambda;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_INTEGER_SOLVE_H
