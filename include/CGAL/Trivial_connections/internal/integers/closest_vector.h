// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_CLOSEST_VECTOR_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_CLOSEST_VECTOR_H

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Closest vector problem of the loop integers: minimise q(m) = (m - c)^T G (m - c) over integer vectors m,
  with G symmetric positive definite (the energy restricted to the loop integers) and c its real minimiser.

  - Candidates given by the caller (componentwise rounding of c, ...) and the best of them is kept, so the
    result is never worse than any of them.
  - Greedy descent: shift one coordinate by its best integer step while q decreases.
  - Schnorr-Euchner enumeration inside the ellipsoid q < best, depth first with zig-zag order, on the
    Cholesky factor of G. When it finishes within `node_budget` nodes the result is the exact optimum
    (`proven`); otherwise the best point met so far is kept.
*/
struct Closest_vector_result
{
  std::vector<std::int64_t> m;
  double value = 0;    // q(m)
  bool proven = false;
  std::vector<double> candidate_values; // q of each candidate given
};

// q(m) = |R (m - c)|^2 with G = R^T R: a triangular product, half the work of one with G
inline double quadratic_distance(const Eigen::MatrixXd& R, const Eigen::VectorXd& c, const std::vector<std::int64_t>& m)
{
  Eigen::VectorXd d(c.size());
  for(Eigen::Index i = 0; i < c.size(); ++i)
    d[i] = double(m[i]) - c[i];
  return (R.triangularView<Eigen::Upper>() * d).squaredNorm();
}

struct Enumeration
{
  const Eigen::MatrixXd& R;
  const Eigen::VectorXd& c;
  std::vector<std::int64_t> best_m;
  double best_value;
  std::size_t nodes;
  std::size_t node_budget;
  bool out_of_budget;
  std::vector<std::int64_t> m;
  // sum[l] = sum_{j > l} R(l, j) (m_j - c_j) for the current m, kept up to date when a coordinate
  // changes: a change at level j costs j, so the many nodes near the leaves are cheap.
  std::vector<double> sum;
  bool improved = false;

  void start()
  {
    const Eigen::Index k = c.size();
    m.assign(std::size_t(k), 0);
    sum.assign(std::size_t(k), 0.);
    for(Eigen::Index j = 1; j < k; ++j)
      for(Eigen::Index l = 0; l < j; ++l)
        sum[l] -= R(l, j) * c[j];
  }

  void assign(Eigen::Index level, std::int64_t v)
  {
    const double delta = double(v - m[level]);
    m[level] = v;
    if(delta != 0) {
      const double* column = R.col(level).data();
      for(Eigen::Index l = 0; l < level; ++l)
        sum[l] += column[l] * delta;
    }
  }

  void search(Eigen::Index level, double partial)
  {
    const double r = R(level, level);
    const double center = c[level] - sum[level] / r;
    // candidates by increasing distance to the center: the first one beyond the bound ends the level
    std::int64_t up = std::int64_t(std::ceil(center)), down = up - 1;
    while(true) {
      if(out_of_budget)
        return;
      if(++nodes > node_budget) {
        out_of_budget = true;
        return;
      }
      const bool take_up = (double(up) - center) <= (center - double(down));
      const std::int64_t v = take_up ? up++ : down--;
      const double d = double(v) - center;
      const double cost = partial + r * r * d * d;
      if(!(cost < best_value))
        return;
      assign(level, v);
      if(level == 0) {
        best_value = cost;
        best_m = m;
        improved = true;
      } else {
        search(level - 1, cost);
      }
    }
  }
};

// Greedy coordinate descent: shift one coordinate by its best integer step while q decreases.
// The gradient of q is 2 G (m - c). Leaves `best` optimal against every single-coordinate change.
// On entry and exit r = best.m - c and Gr = G r.
inline void greedy_descent(const Eigen::MatrixXd& G, Closest_vector_result& best, Eigen::VectorXd& r,
                           Eigen::VectorXd& Gr)
{
  const Eigen::Index k = r.size();
  for(int sweep = 0; sweep < 1000; ++sweep) {
    bool improved = false;
    for(Eigen::Index i = 0; i < k; ++i) {
      const double step = std::round(-Gr[i] / G(i, i));
      if(step == 0)
        continue;
      const double gain = 2 * step * Gr[i] + step * step * G(i, i);
      if(gain < -1e-12 * (1 + std::abs(best.value))) {
        best.m[i] += std::int64_t(step);
        r[i] += step;
        Gr += step * G.col(i);
        best.value += gain;
        improved = true;
      }
    }
    if(!improved)
      break;
  }
  best.value = r.dot(Gr); // the same, without the rounding drift of the updates
}

// G = R^T R with R upper triangular. The enumeration may visit work_budget / k nodes (at least 1000): its
// first descent costs about k^2 / 2, a node at level l about l.
inline Closest_vector_result closest_vector(const Eigen::MatrixXd& G, const Eigen::MatrixXd& R,
                                            const Eigen::VectorXd& c,
                                            const std::vector<std::vector<std::int64_t>>& candidates,
                                            double work_budget = 2e6)
{
  const Eigen::Index k = c.size();
  Closest_vector_result best;
  best.value = std::numeric_limits<double>::infinity();
  if(k == 0) {
    best.value = 0;
    best.proven = true;
    return best;
  }
  for(const std::vector<std::int64_t>& m : candidates) {
    const double q = quadratic_distance(R, c, m);
    best.candidate_values.push_back(q);
    if(q < best.value) { best.value = q; best.m = m; }
  }

  Eigen::VectorXd r(k);
  for(Eigen::Index i = 0; i < k; ++i)
    r[i] = double(best.m[i]) - c[i];
  Eigen::VectorXd Gr = G * r;
  greedy_descent(G, best, r, Gr);

  // Schnorr-Euchner: q = sum_i R_ii^2 (m_i - center_i)^2 with G = R^T R, R upper triangular and
  // center_i = c_i - sum_{j>i} R_ij (m_j - c_j) / R_ii; levels are fixed from k-1 down to 0.
  const std::size_t node_budget = std::size_t((std::max)(1000., work_budget / double(k)));
  Enumeration e{R, c, best.m, best.value, 0, node_budget, false, {}, {}};
  e.start();
  e.search(k - 1, 0.);
  if(e.improved) {
    // G r follows the coordinates that changed (few, usually), and is recomputed when many did
    std::vector<Eigen::Index> changed;
    for(Eigen::Index i = 0; i < k; ++i)
      if(e.best_m[i] != best.m[i])
        changed.push_back(i);
    for(Eigen::Index i : changed)
      r[i] = double(e.best_m[i]) - c[i];
    if(4 * Eigen::Index(changed.size()) > k) {
      Gr.noalias() = G * r;
    } else {
      for(Eigen::Index i : changed)
        Gr += double(e.best_m[i] - best.m[i]) * G.col(i);
    }
    best.m = e.best_m;
    best.value = r.dot(Gr); // without the drift of the enumeration's running sums
  }
  best.proven = !e.out_of_budget;
  if(!best.proven)
    greedy_descent(G, best, r, Gr); // the interrupted enumeration's point may not be locally optimal
  return best;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_CLOSEST_VECTOR_H
