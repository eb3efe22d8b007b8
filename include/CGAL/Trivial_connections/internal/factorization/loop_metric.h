// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_LOOP_METRIC_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_LOOP_METRIC_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/factorization/sparse_factor.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>

#include <Eigen/Dense>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The metric of the integers of one component: the Schur complement S of its free rows (loops and links) in
  the constraint system, and S^-1 = (M^-1) on those rows. The energy of a solve is quadratic in the integers
  with this metric (see the user manual), so it is all the closest vector search needs.
*/
struct Loop_metric
{
  Eigen::MatrixXd schur_factor;   // S = schur_factor diag(schur_diagonal) schur_factor^T, lower triangular
  Eigen::VectorXd schur_diagonal;
  Eigen::MatrixXd inverse;        // S^-1 = (M^-1) on the free rows of one component
  Eigen::MatrixXd inverse_factor; // R upper triangular with R^T R = S^-1
  std::vector<Eigen::Index> block; // per free slot of the component: its position after the first free row
  // with rows outside the factor (set_constraints()): per free slot, its position in the factor's free rows,
  // or -1 - e for outside row e; and the Cholesky factorization of the dense block
  std::vector<Eigen::Index> place;
  Eigen::LLT<Eigen::MatrixXd> system;
};

/*
  Per component, the metric of its free rows. The free rows are last in the factor, so S is read from the
  factor's trailing block when the backend exposes it (`read_from_factor` is then set when its substitutions
  are exposed too: solves can stop at the trailing block); otherwise it costs one back-substitution per free
  row, by `checked_solve` (b -> M^-1 b, checked and refined).
*/
template <class SolverTraits, class CheckedSolve>
std::vector<Loop_metric> loop_metrics(Sparse_factor<SolverTraits>& factor, const Constraint_rows& rows,
                                      std::size_t components, bool& read_from_factor, CheckedSolve checked_solve)
{
  std::vector<Loop_metric> metrics(components);
  const Eigen::Index k = Eigen::Index(rows.free_rows.size());
  const Eigen::Index first = rows.rows - k;
  Eigen::MatrixXd Lt;
  Eigen::VectorXd d;
  const bool from_factor = rows.rows > 0 && factor.read_trailing_block(k, Lt, d);
  read_from_factor = from_factor && factor.substitutions_exposed();
  if(k == 0)
    return metrics;
  for(std::size_t c = 0; c < components; ++c) {
    const std::vector<int>& free = rows.free_slots[c];
    const Eigen::Index kc = Eigen::Index(free.size());
    if(kc == 0)
      continue;
    Loop_metric& metric = metrics[c];
    std::vector<Eigen::Index>& block = metric.block; // increasing: the free rows are placed in this order
    block.resize(free.size());
    for(Eigen::Index a = 0; a < kc; ++a)
      block[a] = factor.permutation().indices()[rows.row_of_slot[free[a]]] - first;
    if(from_factor) {
      // M is block diagonal by component, so is the trailing factor: its block is this component's
      metric.schur_factor.resize(kc, kc);
      metric.schur_diagonal.resize(kc);
      for(Eigen::Index a = 0; a < kc; ++a) {
        metric.schur_diagonal[a] = d[block[a]];
        for(Eigen::Index r = 0; r < kc; ++r)
          metric.schur_factor(r, a) = r >= a ? Lt(block[r], block[a]) : 0.;
      }
      if(!(metric.schur_diagonal.minCoeff() > 0) || !metric.schur_factor.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
      // S^-1 = Y^T Y with Y = D^-1/2 L^-1, lower triangular
      Eigen::MatrixXd Y = metric.schur_factor.template triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(kc, kc));
      Y = metric.schur_diagonal.cwiseSqrt().cwiseInverse().asDiagonal() * Y;
      metric.inverse.noalias() = Y.transpose().template triangularView<Eigen::Upper>() * Y;
      metric.inverse = (metric.inverse + metric.inverse.transpose()) / 2;
    } else {
      metric.inverse.resize(kc, kc);
      for(Eigen::Index a = 0; a < kc; ++a) {
        Eigen::VectorXd unit_rhs = Eigen::VectorXd::Zero(rows.rows);
        unit_rhs[rows.row_of_slot[free[a]]] = 1;
        const Eigen::VectorXd column = checked_solve(unit_rhs);
        for(Eigen::Index r = 0; r < kc; ++r)
          metric.inverse(r, a) = column[rows.row_of_slot[free[r]]];
      }
      metric.inverse = (metric.inverse + metric.inverse.transpose()) / 2;
      Eigen::LLT<Eigen::MatrixXd> schur(metric.inverse.llt().solve(Eigen::MatrixXd::Identity(kc, kc)));
      if(schur.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
      metric.schur_factor = schur.matrixL();
      metric.schur_diagonal = Eigen::VectorXd::Ones(kc);
    }
    Eigen::LLT<Eigen::MatrixXd> llt(metric.inverse);
    if(llt.info() != Eigen::Success || !metric.inverse.allFinite())
      throw Invalid_input(Error_code::solver_failure, "the metric of the loop integers is not positive definite");
    metric.inverse_factor = llt.matrixU();
  }
  return metrics;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_LOOP_METRIC_H
