// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_CHECKED_SOLVE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_CHECKED_SOLVE_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>

#include <Eigen/Core>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The vectors of checked_connection(), kept by a caller that solves again and again (a refinement's trial solves):
// allocated afresh, megabytes each, every page of theirs is a fault (cheese_loop3's trial solves touched some 15k
// fresh pages each).
struct Connection_workspace
{
  Eigen::VectorXd ax, refined_ax, rhs, refined_x;
  Constraint_sums refined;
};

// the residual, relative to 1 + |b|, from which checked_connection() refines x by default: the rounding level
constexpr double refine_residuals_above = 1e-13;

/*
  The connection x = W^-1 A^T lambda of the multipliers `lambda` of A W^-1 A^T lambda = b, checked through the
  constraints it must satisfy: A x - b is M lambda - b, computed from x at the cost of one pass over the edges
  (cheaper than a product with M, and the sums are the ones the report needs). Refined while the residual
  drops, up to three steps, when it is above `refine_above` (a refinement's trial solves take 1e-11, still a
  hundred times below the promise, and save a solve each). `solve` is the unchecked b -> M^-1 b.
  Throws solver_failure when the residual stays above the package's promise.
*/
template <class Solve>
void checked_connection(const Constraint_rows& rows, Solve solve, const Eigen::VectorXd& b, Eigen::VectorXd& lambda,
                        Constraint_sums& sums, Eigen::VectorXd& xe, Connection_workspace& w,
                        double refine_above = refine_residuals_above)
{
  const double scale = 1 + b.template lpNorm<Eigen::Infinity>();
  rows.connection_of(lambda, xe);
  std::vector<double> slack = rows.slacks(lambda);
  rows.sums_of(xe, slack, sums);
  rows.row_sums(sums, w.ax);
  double res = (b - w.ax).template lpNorm<Eigen::Infinity>();
  // Refined in x itself: x += W^-1 A^T M^-1 (b - A x). Recomputing x from refined multipliers would divide
  // their rounding errors by the smallest weights again, which on needle triangles is the residual itself.
  for(int step = 0; step < 3 && std::isfinite(res) && res > refine_above * scale; ++step) {
    w.rhs = b - w.ax;
    const Eigen::VectorXd delta = solve(w.rhs);
    rows.connection_of(delta, w.refined_x);
    w.refined_x += xe;
    std::vector<double> refined_slack = rows.slacks(delta);
    for(std::size_t g = 0; g < slack.size(); ++g)
      refined_slack[g] += slack[g];
    rows.sums_of(w.refined_x, refined_slack, w.refined);
    rows.row_sums(w.refined, w.refined_ax);
    const double refined_res = (b - w.refined_ax).template lpNorm<Eigen::Infinity>();
    if(!(refined_res < res))
      break;
    lambda += delta;
    xe.swap(w.refined_x);
    slack.swap(refined_slack);
    std::swap(sums, w.refined);
    w.ax.swap(w.refined_ax);
    res = refined_res;
  }
  // the package promises holonomy residuals below 1e-9 rad (plus the rounding of 2 pi k for huge indices): a
  // mesh whose geometry double precision cannot carry that far (coordinates spanning some 15 orders of
  // magnitude) is refused rather than half solved
  if(!std::isfinite(res) || !xe.allFinite() || res > 1e-9 + 1e-14 * (scale - 1)) {
    std::ostringstream message;
    message << "the linear solve is inaccurate: constraint residual " << std::scientific << std::setprecision(2)
            << res << " rad after refinement (more than 1e-9; the mesh's geometry is too ill-conditioned for "
            << "double precision)";
    throw Invalid_input(Error_code::solver_failure, message.str());
  }
}

template <class Solve>
Eigen::VectorXd checked_connection(const Constraint_rows& rows, Solve solve, const Eigen::VectorXd& b,
                                   Eigen::VectorXd& lambda, Constraint_sums& sums)
{
  Eigen::VectorXd xe;
  Connection_workspace w;
  checked_connection(rows, solve, b, lambda, sums, xe, w);
  return xe;
}

// M^-1 b, checked and refined like the solution of a solve
template <class Solve>
Eigen::VectorXd checked_multipliers(const Constraint_rows& rows, Solve solve, const Eigen::VectorXd& b)
{
  Eigen::VectorXd lambda = solve(b);
  Constraint_sums sums;
  checked_connection(rows, solve, b, lambda, sums);
  return lambda;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_CHECKED_SOLVE_H
