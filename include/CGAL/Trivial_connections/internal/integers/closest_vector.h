// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_CLOSEST_VECTOR_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_CLOSEST_VECTOR_H

#include <CGAL/number_type_config.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/integers/lattice_reduction.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Closest vector problem of the loop integers: minimise q(m) = (m - c)^T G (m - c) over integer vectors m,
  with G symmetric positive definite (the energy restricted to the loop integers) and c its real minimiser.
  Everything runs in a reduced basis of the lattice (lattice_reduction.h): m = U z, q = (z - w)^T H (z - w),
  H = R^T R, w = U^-1 c.

  - Candidates given by the caller (componentwise rounding of c, ...) and Babai's nearest plane point in the
    reduced basis; the best of them is kept, so the result is never worse than any candidate.
  - Greedy descent: shift one reduced coordinate by its best integer step while q decreases (at the end, in
    the loop basis and the reduced one in turn, so that no single loop's integer can be improved either).
  - Schnorr-Euchner enumeration (depth first, zig-zag order, levels k-1 down to 0) within a node budget:
    1. complete passes inside balls q < rho: rho the best value found when the estimated work (Gaussian
       heuristic over the Gram-Schmidt lengths) fits half the budget, otherwise growing radii from the one
       whose estimate fits an eighth, within half the budget. A pass that finishes proves that no point has
       q below its radius; one that runs out still proves q >= the smallest partial cost left on its stack
       (the zig-zag order visits the children of a node by increasing cost). That is the lower bound.
    2. with what is left of the budget, passes pruned linearly (the first d levels may use at most
       min(1, a d / k) of the best value) with a = 4, 64, 1024, ...: a heuristic search for better points whose
       last pass, once a >= k, is complete and proves the optimum.
  `proven`: the optimum is certain (up to rounding); `lower_bound` <= q of every integer point, = `value`
  when proven. With `wanted_below`, points with q >= it are of no interest: when the candidates, Babai's point
  and the descent give none below it, only the ball q < wanted_below is enumerated, and a pass that finds it
  empty ends the search (lower_bound = wanted_below, not proven): the usual answer to "can q get below this?".
*/
struct Closest_vector_result
{
  std::vector<std::int64_t> m;
  double value = 0;        // q(m)
  double lower_bound = 0;  // no integer point has a smaller q
  bool proven = false;
  std::vector<double> candidate_values; // q of each candidate given
  double work = 0;         // multiply-adds of the enumeration
};

// q = |R (z - w)|^2 with R upper triangular
inline double quadratic_distance(const Eigen::MatrixXd& R, const Eigen::VectorXd& w, const Eigen::VectorXd& z)
{
  return (R.triangularView<Eigen::Upper>() * (z - w)).squaredNorm();
}

struct Enumeration
{
  const Eigen::MatrixXd& R;
  const Eigen::VectorXd& w;
  Eigen::VectorXd best_z;
  double best_value;
  double radius = std::numeric_limits<double>::infinity(); // the ball of the pass (besides best_value)
  double pruning = 0;      // a > 0: the first d levels use at most min(1, a d / k) of best_value
  double work = 0;         // multiply-adds of the pass: a node at level l costs l + 1
  double work_budget = 0;
  bool out_of_budget = false;
  double frontier = std::numeric_limits<double>::infinity(); // smallest partial cost left unexplored
  Eigen::VectorXd z;
  // sum[l] = sum_{j > l} R(l, j) (z_j - w_j) for the current z, kept up to date when a coordinate
  // changes: a change at level j costs j, so the many nodes near the leaves are cheap.
  std::vector<double> sum, sum_at_zero;
  bool improved = false;

  Enumeration(const Eigen::MatrixXd& R, const Eigen::VectorXd& w, const Eigen::VectorXd& z0, double value)
    : R(R), w(w), best_z(z0), best_value(value)
  {
    const Eigen::Index k = w.size();
    Eigen::VectorXd s = -(R.triangularView<Eigen::StrictlyUpper>() * w);
    sum_at_zero.assign(s.data(), s.data() + k);
  }

  void start(double budget)
  {
    work_budget = budget;
    work = 0;
    out_of_budget = false;
    frontier = std::numeric_limits<double>::infinity();
    z = Eigen::VectorXd::Zero(w.size());
    sum = sum_at_zero;
  }

  void assign(Eigen::Index level, double v)
  {
    const double delta = v - z[level];
    z[level] = v;
    if(delta != 0) {
      const double* column = R.col(level).data();
      for(Eigen::Index l = 0; l < level; ++l)
        sum[l] += column[l] * delta;
    }
  }

  double bound(Eigen::Index level) const
  {
    double b = (std::min)(best_value, radius);
    if(pruning > 0) {
      const double depth = double(w.size() - level);
      b = (std::min)(b, best_value * (std::min)(1., pruning * depth / double(w.size())));
    }
    return b;
  }

  void search(Eigen::Index level, double partial)
  {
    const double r = R(level, level);
    const double center = w[level] - sum[level] / r;
    // candidates by increasing distance to the center: the first one beyond the bound ends the level
    double up = std::ceil(center), down = up - 1;
    while(true) {
      const bool take_up = (up - center) <= (center - down);
      const double v = take_up ? up : down;
      const double cost = partial + r * r * (v - center) * (v - center);
      if(!(cost < bound(level)))
        return;
      if(out_of_budget || (work += double(level + 1)) > work_budget) {
        // this candidate and the ones after it are left: none can cost less than it
        out_of_budget = true;
        frontier = (std::min)(frontier, cost);
        return;
      }
      (take_up ? up : down) += take_up ? 1 : -1;
      assign(level, v);
      if(level == 0) {
        best_value = cost;
        best_z = z;
        improved = true;
      } else {
        search(level - 1, cost);
      }
    }
  }
};

// The expected work of a complete enumeration of the ball q < rho, after the Gaussian heuristic: at depth d
// (level k - d) about vol(d-ball of radius sqrt(rho)) / (R_{k-d,k-d} ... R_{k-1,k-1}) nodes, at k - d + 1
// multiply-adds each. log(work at depth d) = d/2 log(rho) + offset[d - 1]; the largest term is within a
// factor k of the sum, which is enough to choose a radius.
struct Enumeration_cost
{
  std::vector<double> offset;

  explicit Enumeration_cost(const Eigen::MatrixXd& R)
  {
    const Eigen::Index k = R.rows();
    offset.resize(std::size_t(k));
    double log_det = 0;
    for(Eigen::Index d = 1; d <= k; ++d) {
      log_det += std::log(R(k - d, k - d));
      const double half = double(d) / 2;
      offset[std::size_t(d - 1)] = half * std::log(CGAL_PI) - std::lgamma(half + 1) - log_det + std::log(double(k - d + 1));
    }
  }

  double log_work(double rho) const
  {
    const double log_rho = std::log(rho);
    double largest = -std::numeric_limits<double>::infinity();
    for(std::size_t d = 1; d <= offset.size(); ++d)
      largest = (std::max)(largest, double(d) / 2 * log_rho + offset[d - 1]);
    return largest;
  }

  // the largest rho <= high whose expected work is at most `work`
  double radius_for(double work, double high) const
  {
    const double target = std::log(work);
    if(!(high > 0) || log_work(high) <= target)
      return high;
    double low = 0;
    for(int it = 0; it < 30; ++it) {
      const double mid = (low + high) / 2;
      (log_work(mid) > target ? high : low) = mid;
    }
    return low;
  }
};

// std::round without libm's call (x86-64 has no rounding instruction before SSE4.1): the refinement's searches
// round a few hundred values each, thousands of times a round. Halves away from zero, as std::round.
inline double nearest_integer(double x)
{
  if(!(std::abs(x) < 4503599627370496.)) // 2^52: x is an integer already (or not finite)
    return x;
  double t = double(std::int64_t(x)); // truncated; x - t is exact
  const double fraction = x - t;
  if(fraction >= 0.5)
    t += 1;
  else if(fraction <= -0.5)
    t -= 1;
  return t;
}

// Babai's nearest plane point of w for R (upper triangular, R^T R = H): z, d = z - w and R d (size k); returns
// q(z) = |R d|^2. Column by column: Rd[j] gathers sum_{i > j} R(j, i) d[i] until row j is reached, contiguous
// reads of R with no chain of dependent additions (a row's dot product through column-major R was most of a
// search in the refinement's rounds of unproven integers).
inline double nearest_plane_point(const Eigen::MatrixXd& R, const Eigen::VectorXd& w, Eigen::VectorXd& z,
                                  Eigen::VectorXd& d, Eigen::VectorXd& Rd)
{
  const Eigen::Index k = w.size();
  Rd.setZero();
  z = R.diagonal().cwiseInverse(); // independent divisions, out of the chain from row to row
  for(Eigen::Index i = k - 1; i >= 0; --i) {
    const double tail = Rd[i];
    z[i] = nearest_integer(w[i] - tail * z[i]);
    d[i] = z[i] - w[i];
    Rd[i] = R(i, i) * d[i] + tail;
    Rd.head(i) += d[i] * R.col(i).head(i);
  }
  return Rd.squaredNorm();
}

// Greedy coordinate descent in the reduced basis: shift one coordinate by its best integer step while q
// decreases. The gradient of q is 2 H (z - w). Leaves `z` optimal against every single-coordinate change.
// On entry and exit d = z - w and Hd = H d; returns q(z).
inline double greedy_descent(const Eigen::MatrixXd& H, Eigen::VectorXd& z, Eigen::VectorXd& d, Eigen::VectorXd& Hd)
{
  const Eigen::Index k = z.size();
  double value = d.dot(Hd);
  for(int sweep = 0; sweep < 1000; ++sweep) {
    bool improved = false;
    for(Eigen::Index i = 0; i < k; ++i) {
      if(std::abs(Hd[i]) < 0.49 * H(i, i))
        continue; // its step rounds to 0: most coordinates, without a division
      const double step = nearest_integer(-Hd[i] / H(i, i));
      if(step == 0)
        continue;
      const double gain = 2 * step * Hd[i] + step * step * H(i, i);
      if(gain < -1e-12 * (1 + std::abs(value))) {
        z[i] += step;
        d[i] += step;
        Hd += step * H.col(i);
        value += gain;
        improved = true;
      }
    }
    if(!improved)
      break;
  }
  return d.dot(Hd); // the same, without the rounding drift of the updates
}

/*
  The closest vector in `lattice` (reduce_lattice() of G) to c; the result is locally optimal against every
  single-coordinate change in both bases (or proven optimal). The enumeration may do `work_budget`
  multiply-adds, and at least k^2 (a first descent costs about k^2 / 2); with `work_budget` <= 0 there is none:
  the candidates and Babai's point, then a descent in the reduced basis only (lower_bound 0).
*/
inline Closest_vector_result closest_vector(const Reduced_lattice& lattice, const Eigen::MatrixXd& G,
                                            const Eigen::VectorXd& c,
                                            const std::vector<std::vector<std::int64_t>>& candidates,
                                            double work_budget = 2e6,
                                            double wanted_below = std::numeric_limits<double>::infinity(),
                                            const Enumeration_cost* lattice_cost = nullptr)
{
  const Eigen::Index k = c.size();
  Closest_vector_result best;
  if(k == 0) {
    best.proven = true;
    return best;
  }
  const Eigen::MatrixXd& R = lattice.factor;
  const Eigen::MatrixXd& H = lattice.gram;
  const Eigen::VectorXd w = lattice.reduced ? Eigen::VectorXd(lattice.inverse_basis * c) : c;

  // the candidates, then Babai's nearest plane point
  Eigen::VectorXd z(k), best_z(k);
  double best_value = std::numeric_limits<double>::infinity();
  for(const std::vector<std::int64_t>& m : candidates) {
    for(Eigen::Index i = 0; i < k; ++i)
      z[i] = double(m[i]);
    if(lattice.reduced)
      z = lattice.inverse_basis * z;
    const double q = quadratic_distance(R, w, z);
    best.candidate_values.push_back(q);
    if(q < best_value) { best_value = q; best_z = z; }
  }
  Eigen::VectorXd d(k), Hd(k);
  {
    Eigen::VectorXd Rd(k); // R (z - w), for q and H (z - w) = R^T R (z - w) without a product by H
    const double q = nearest_plane_point(R, w, z, d, Rd);
    if(q < best_value) {
      best_value = q;
      best_z = z;
      Hd.noalias() = R.transpose().triangularView<Eigen::Lower>() * Rd;
    } else {
      d = best_z - w;
      Hd.noalias() = H * d;
    }
  }
  best_value = greedy_descent(H, best_z, d, Hd);
  if(!(work_budget > 0)) {
    // no enumeration: not even the set-up of its costs (k lgamma and log), which a descent in 64 dimensions
    // costs about as much as (the refinement's searches in rounds of unproven integers, see Move_integers)
    const Eigen::VectorXd m = lattice.reduced ? Eigen::VectorXd(lattice.basis * best_z) : best_z;
    best.value = best_value;
    best.proven = false;
    best.lower_bound = 0;
    best.m.resize(std::size_t(k));
    for(Eigen::Index i = 0; i < k; ++i)
      best.m[std::size_t(i)] = std::int64_t(nearest_integer(m[i]));
    return best;
  }

  const double budget = (std::max)(work_budget, double(k) * double(k));
  // the ball searched: below the best point, or below what is wanted when that is less
  const bool bounded = wanted_below < best_value;
  Enumeration e(R, w, best_z, bounded ? (std::max)(wanted_below, 0.) : best_value);
  // 1. complete passes in growing balls, for the lower bound (and the optimum when the ball of the best value
  // fits), with half the budget: the first in the ball whose expected work is an eighth of it, each next one
  // in a ball of about twice the expected work, until a pass runs out or proves the optimum
  std::optional<Enumeration_cost> own_cost;
  const Enumeration_cost& cost = lattice_cost ? *lattice_cost : own_cost.emplace(R);
  double rho = e.best_value;
  if(cost.log_work(rho) > std::log(budget / 2))
    rho = cost.radius_for(budget / 8, e.best_value);
  double used = 0, lower_bound = 0;
  bool proven = false;
  for(int pass = 0; pass < 4; ++pass) { // each pass starts with a descent of about k^2 / 2
    e.radius = rho;
    e.start(budget / 2 - used);
    e.search(k - 1, 0.);
    used += (std::min)(e.work, budget / 2 - used);
    lower_bound = (std::max)(lower_bound, (std::min)({e.best_value, rho, e.frontier}));
    if(e.out_of_budget)
      break;
    if(e.best_value <= rho) {
      proven = true; // the optimum, or (bounded, nothing found) no point below wanted_below
      break;
    }
    if(used >= budget / 4)
      break; // the next pass would likely not finish
    rho = (std::min)(e.best_value, (std::max)(1.01 * rho, cost.radius_for(2 * std::exp(cost.log_work(rho)), e.best_value)));
  }
  const bool none_below = bounded && proven && !e.improved;
  if(none_below)
    proven = false; // best_value stands, unproven, above lower_bound = wanted_below
  // 2. pruned passes with the rest of the budget, each wider than the one before
  e.radius = std::numeric_limits<double>::infinity();
  if(none_below)
    used = budget;
  for(double a = 4; !proven && used < budget; a *= 16) {
    e.pruning = a >= double(k) ? 0. : a;
    e.start(budget - used);
    e.search(k - 1, 0.);
    used += (std::min)(e.work, budget - used);
    if(e.pruning == 0) {
      // complete: proves the optimum, or at least bounds it
      if(!e.out_of_budget)
        proven = true;
      else
        lower_bound = (std::max)(lower_bound, (std::min)(e.best_value, e.frontier));
      break;
    }
  }
  best.work = used;
  if(e.improved) {
    // H d follows the coordinates that changed (few, usually), and is formed again when many did
    std::vector<Eigen::Index> changed;
    for(Eigen::Index i = 0; i < k; ++i)
      if(e.best_z[i] != best_z[i])
        changed.push_back(i);
    if(4 * Eigen::Index(changed.size()) > k) {
      best_z = e.best_z;
      d = best_z - w;
      Hd.noalias() = H * d;
    } else {
      for(Eigen::Index i : changed) {
        Hd += (e.best_z[i] - best_z[i]) * H.col(i);
        best_z[i] = e.best_z[i];
        d[i] = best_z[i] - w[i];
      }
    }
    best_value = d.dot(Hd);
    if(!proven)
      best_value = greedy_descent(H, best_z, d, Hd); // a pruned or interrupted pass's point may not be locally optimal
  }
  Eigen::VectorXd m = lattice.reduced ? Eigen::VectorXd(lattice.basis * best_z) : best_z;
  if(!proven && lattice.reduced) {
    // locally optimal in the loop basis too (single-loop changes are what a user tries first), then in the
    // reduced one again, until neither moves. With m - c = U d: G (m - c) = U^-T H d and H d = U^T G (m - c),
    // sparse products.
    for(int round = 0; round < 10; ++round) {
      Eigen::VectorXd dm = m - c;
      Eigen::VectorXd Gdm = lattice.inverse_basis.transpose() * Hd;
      const double before = best_value;
      best_value = greedy_descent(G, m, dm, Gdm);
      if(!(best_value < before - 1e-12 * (1 + std::abs(before))))
        break;
      best_z = lattice.inverse_basis * m;
      d = best_z - w;
      Hd = lattice.basis.transpose() * Gdm;
      const double after_loop_basis = best_value;
      best_value = greedy_descent(H, best_z, d, Hd);
      m = lattice.basis * best_z;
      if(!(best_value < after_loop_basis - 1e-12 * (1 + std::abs(after_loop_basis))))
        break;
    }
  }
  best.value = best_value;
  best.proven = proven;
  best.lower_bound = proven ? best_value : (std::min)(lower_bound, best_value);
  best.m.resize(std::size_t(k));
  for(Eigen::Index i = 0; i < k; ++i) {
    const double r = nearest_integer(m[i]);
    // a metric so ill-conditioned (near-degenerate faces) that the integers leave int64: an error, not a cast
    if(!(std::abs(r) < 4e18))
      throw Invalid_input(Error_code::solver_failure,
                          "the loop integers are out of range: the loops' metric is too ill-conditioned (near-"
                          "degenerate faces?)");
    best.m[std::size_t(i)] = std::int64_t(r);
  }
  return best;
}

// The same for a metric reduced on the spot (see lattice_reduction_budget()).
inline Closest_vector_result closest_vector(const Eigen::MatrixXd& G, const Eigen::VectorXd& c,
                                            const std::vector<std::vector<std::int64_t>>& candidates,
                                            double work_budget = 2e6)
{
  const Eigen::MatrixXd R = G.llt().matrixU();
  return closest_vector(reduce_lattice(G, R, lattice_reduction_budget(G.rows())), G, c, candidates, work_budget);
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_CLOSEST_VECTOR_H
