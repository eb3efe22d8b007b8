// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_LOOP_PERIODS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_LOOP_PERIODS_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/factorization/loop_metric.h>
#include <CGAL/Trivial_connections/internal/integers/closest_vector.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Per component, the lattice of its free integers in their metric, reduced (lattice_reduction.h): it depends on
  the factorization only, so the solver reduces it once, when the metrics are computed.
*/
inline std::vector<Reduced_lattice> reduced_loop_lattices(const std::vector<Loop_metric>& metrics)
{
  std::vector<Reduced_lattice> lattices(metrics.size());
  for(std::size_t c = 0; c < metrics.size(); ++c)
    if(metrics[c].inverse.rows() > 0)
      lattices[c] = reduce_lattice(metrics[c].inverse, metrics[c].inverse_factor,
                                   lattice_reduction_budget(metrics[c].inverse.rows()));
  return lattices;
}

// What choose_loop_periods() found, as parts of the energy of the solve
struct Loop_period_choice
{
  double rounding_part = 0;    // the loop part of the energy with the integers rounded one by one
  double lower_bound_part = 0; // no choice of the integers gives a smaller loop part
  bool proven = true;          // every component's choice is the optimum
};

/*
  The integers of the free slots not prescribed, minimising the energy, per component, written into
  `periods` (0 there on entry). `free_slots[c]`: component c's free slots, in the order of its metric;
  `lattices[c]`: its metric's reduced lattice (reduced_loop_lattices()); `y[c]`: the right-hand side of the
  Schur complement S of its free rows with those integers 0 (the prescribed ones are in it), so that the loop
  part of the energy is t^T S^-1 t with t = y + unit m. `holonomy`: per slot, for the candidate that makes
  each slot's own connection sum smallest. `work_budget`: for the enumeration (see closest_vector()).
*/
inline Loop_period_choice choose_loop_periods(const std::vector<std::vector<int>>& free_slots,
                                              const std::vector<Loop_metric>& metrics,
                                              const std::vector<Reduced_lattice>& lattices,
                                              const std::vector<Eigen::VectorXd>& y, double unit,
                                              const std::vector<char>& prescribed, const std::vector<double>& holonomy,
                                              double work_budget, std::vector<std::int64_t>& periods,
                                              const std::vector<std::int64_t>* hint = nullptr)
{
  Loop_period_choice choice;
  for(std::size_t c = 0; c < free_slots.size(); ++c) {
    const std::vector<int>& free = free_slots[c];
    if(free.empty())
      continue;
    const Loop_metric& metric = metrics[c];
    std::vector<Eigen::Index> chosen, fixed; // positions in the component's block
    for(std::size_t a = 0; a < free.size(); ++a)
      (prescribed[free[a]] ? fixed : chosen).push_back(Eigen::Index(a));
    const Eigen::Index kc = Eigen::Index(chosen.size());
    if(kc == 0) {
      const double fixed_part = y[c].dot(metric.inverse * y[c]);
      choice.rounding_part += fixed_part;
      choice.lower_bound_part += fixed_part;
      continue;
    }
    // With G = S^-1 and the prescribed part t_P = y_P fixed, t^T G t = (t_Q - t_Q*)^T G_QQ (t_Q - t_Q*) +
    // const with t_Q* = -G_QQ^-1 G_QP y_P: the minimiser of (m - center)^T G_QQ (m - center), with
    // center = (t_Q* - y_Q) / unit. Without prescribed slots G_QQ = G, whose reduced lattice is kept; with
    // them G_QQ is reduced here.
    Eigen::VectorXd center(kc);
    double constant = 0;
    Reduced_lattice partial;
    Eigen::MatrixXd G_QQ;
    const Reduced_lattice* lattice = c < lattices.size() ? &lattices[c] : nullptr;
    const Eigen::MatrixXd* G = &metric.inverse;
    if(fixed.empty()) {
      center = -y[c] / unit;
      if(!lattice || lattice->dimension() != kc) { // not reduced for this metric (not through the solver)
        partial = reduce_lattice(metric.inverse, metric.inverse_factor, lattice_reduction_budget(kc));
        lattice = &partial;
      }
    } else {
      G_QQ.resize(kc, kc);
      Eigen::MatrixXd G_QP(kc, Eigen::Index(fixed.size()));
      Eigen::VectorXd y_P(Eigen::Index(fixed.size()));
      for(Eigen::Index i = 0; i < kc; ++i) {
        for(Eigen::Index j = 0; j < kc; ++j)
          G_QQ(i, j) = metric.inverse(chosen[i], chosen[j]);
        for(Eigen::Index j = 0; j < Eigen::Index(fixed.size()); ++j)
          G_QP(i, j) = metric.inverse(chosen[i], fixed[j]);
      }
      for(Eigen::Index j = 0; j < Eigen::Index(fixed.size()); ++j)
        y_P[j] = y[c][fixed[j]];
      const Eigen::LLT<Eigen::MatrixXd> llt(G_QQ);
      if(llt.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
      const Eigen::VectorXd g = G_QP * y_P;
      const Eigen::VectorXd t_star = -llt.solve(g);
      for(Eigen::Index i = 0; i < kc; ++i)
        center[i] = (t_star[i] - y[c][chosen[i]]) / unit;
      double fixed_part = 0;
      for(Eigen::Index i = 0; i < Eigen::Index(fixed.size()); ++i)
        for(Eigen::Index j = 0; j < Eigen::Index(fixed.size()); ++j)
          fixed_part += y_P[i] * metric.inverse(fixed[i], fixed[j]) * y_P[j];
      constant = fixed_part + g.dot(t_star); // y_P^T (G_PP - G_PQ G_QQ^-1 G_QP) y_P
      partial = reduce_lattice(G_QQ, llt.matrixU(), lattice_reduction_budget(kc));
      lattice = &partial;
      G = &G_QQ;
    }
    std::vector<std::int64_t> rounded(kc), own(kc);
    for(Eigen::Index a = 0; a < kc; ++a) {
      rounded[a] = std::int64_t(std::llround(center[a]));
      // each slot on its own: the integer making its own connection sum smallest
      own[a] = std::int64_t(std::llround(holonomy[free[chosen[a]]] / unit));
    }
    std::vector<std::vector<std::int64_t>> candidates{rounded, own};
    if(hint && hint->size() == periods.size()) { // never worse than the integers of a solve before
      candidates.emplace_back(std::size_t(kc));
      for(Eigen::Index a = 0; a < kc; ++a)
        candidates.back()[std::size_t(a)] = (*hint)[std::size_t(free[chosen[a]])];
    }
    const Closest_vector_result best = closest_vector(*lattice, *G, center, candidates, work_budget);
    choice.proven = choice.proven && best.proven;
    // t^T S^-1 t = unit^2 q(m) + constant
    choice.rounding_part += unit * unit * best.candidate_values[0] + constant;
    choice.lower_bound_part += unit * unit * best.lower_bound + constant;
    for(Eigen::Index a = 0; a < kc; ++a)
      periods[free[chosen[a]]] = best.m[a];
  }
  return choice;
}

// t = y + unit m per component over its free slots, for the chosen integers (the prescribed ones are in y)
inline std::vector<Eigen::VectorXd> loop_right_hand_sides(const std::vector<std::vector<int>>& free_slots,
                                                          const std::vector<Eigen::VectorXd>& y, double unit,
                                                          const std::vector<char>& prescribed,
                                                          const std::vector<std::int64_t>& periods)
{
  std::vector<Eigen::VectorXd> t(y);
  for(std::size_t c = 0; c < t.size(); ++c)
    for(Eigen::Index a = 0; a < t[c].size(); ++a)
      if(!prescribed[free_slots[c][a]])
        t[c][a] += unit * double(periods[free_slots[c][a]]);
  return t;
}

// A prescribed period of loop l, checked against max_scaled_index()
inline std::int64_t checked_loop_period(std::int64_t period, std::size_t l, const Mesh_topology& topology, int n)
{
  const std::int64_t bound = max_scaled_index(n);
  if(period > bound || period < -bound)
    throw Invalid_input(Error_code::invalid_loop_periods,
                        "the period " + std::to_string(period) + " of loop " + std::to_string(l) + " (" +
                          (topology.loops[l].kind == Loop_kind::boundary ? "a boundary loop" : "a generator") +
                          ") is too large: at most " + std::to_string(bound) + " in absolute value (" +
                          max_index_text(n) + " turns)",
                        l);
  return period;
}

/*
  `loop_periods` of a solve: one entry per loop of the tree-cotree decomposition, empty where the solver
  chooses, read into `periods` and `prescribed`, each bounded by max_scaled_index(). The boundary loops of a
  component are prescribed all or none, and then, with the vertex index sums of `components` (from
  checked_vertex_indices()), they must satisfy Poincare-Hopf.
*/
inline void read_prescribed_periods(const std::vector<std::optional<std::int64_t>>& given, const Mesh_topology& topology,
                                    const std::vector<Component_report>& components, int n, std::vector<std::int64_t>& periods, std::vector<char>& prescribed)
{
  const std::vector<Mesh_topology::Loop>& loops = topology.loops;
  if(given.size() != loops.size())
    throw Invalid_input(Error_code::invalid_loop_periods, "loop_periods has " + std::to_string(given.size()) +
                                                            " values, the mesh has " + std::to_string(loops.size()) +
                                                            " loops");
  std::vector<std::size_t> boundary_given(components.size(), 0);
  for(std::size_t l = 0; l < loops.size(); ++l) {
    prescribed[l] = given[l].has_value() ? 1 : 0;
    periods[l] = given[l] ? checked_loop_period(*given[l], l, topology, n) : 0;
    if(loops[l].kind == Loop_kind::boundary && given[l])
      ++boundary_given[loops[l].component];
  }
  std::vector<std::int64_t> total = scaled_vertex_index_sums(components, n);
  for(std::size_t l = 0; l < loops.size(); ++l)
    if(loops[l].kind == Loop_kind::boundary)
      total[loops[l].component] += periods[l];
  for(std::size_t c = 0; c < components.size(); ++c) {
    const std::size_t b = components[c].number_of_boundary_loops;
    if(boundary_given[c] != 0 && boundary_given[c] != b)
      throw Invalid_input(Error_code::invalid_loop_periods,
                          std::to_string(boundary_given[c]) + " of the " + std::to_string(b) +
                            " boundary loops of component " + std::to_string(c) +
                            " are prescribed: prescribe all of them or none (Poincare-Hopf ties their sum)",
                          c);
    if(b > 0 && boundary_given[c] == b && total[c] != n * components[c].euler_characteristic)
      throw Invalid_input(Error_code::invalid_loop_periods,
                          "Poincare-Hopf violated by the prescribed boundary loop indices of component " +
                            std::to_string(c) + ": vertex and boundary indices sum to " +
                            Singularity_index(total[c], n).to_string() + ", expected " +
                            std::to_string(components[c].euler_characteristic),
                          c);
  }
}

inline std::vector<std::optional<std::int64_t>> optional_periods(const std::vector<std::int64_t>& given)
{
  return std::vector<std::optional<std::int64_t>>(given.begin(), given.end());
}
inline const std::vector<std::optional<std::int64_t>>& optional_periods(const std::vector<std::optional<std::int64_t>>& given)
{
  return given;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_LOOP_PERIODS_H
