// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_DECIDED_LINKS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_DECIDED_LINKS_H

#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The integers of the decided links (between touching pins) and the connection they fix. A decided link's row
  reads H + sum_L x = 2 pi p / n: its integer is the rounding of H n / 2 pi, the smallest turn along the link
  (|sum x| <= pi / n) that meets both pins. Writes the integers into `periods`; returns x per interior edge,
  fixed on the edges of the links that cross one edge (H + s x_e = 2 pi p / n, s = +-1) and 0 elsewhere.
*/
inline Eigen::VectorXd decided_connection(const Constraint_rows& rows, const std::vector<double>& holonomy, double unit,
                                          std::vector<std::int64_t>& periods)
{
  Eigen::VectorXd x = Eigen::VectorXd::Zero(rows.geometry().number_of_interior_edges());
  for(int l : rows.decided_slots) {
    const double p = std::round(holonomy[std::size_t(l)] / unit);
    periods[std::size_t(l)] = std::int64_t(p);
    if(rows.row_of_slot[std::size_t(l)] >= 0)
      continue;
    const int code = rows.slot_edges[std::size_t(rows.slot_edge_start[std::size_t(l)])];
    x[index_of_code(code)] = sign_of_code(code) * (unit * p - holonomy[std::size_t(l)]);
  }
  return x;
}

// sum_e w_e x_e^2 over the edges the decided links fix
inline double decided_energy(const Constraint_rows& rows, const Eigen::VectorXd& x_fixed)
{
  double energy = 0;
  for(int l : rows.decided_slots) {
    if(rows.row_of_slot[std::size_t(l)] >= 0)
      continue;
    const int e = index_of_code(rows.slot_edges[std::size_t(rows.slot_edge_start[std::size_t(l)])]);
    energy += rows.geometry().weight[std::size_t(e)] * x_fixed[e] * x_fixed[e];
  }
  return energy;
}

/*
  A lower bound on the energy of every choice in which some decided integer differs from its rounding, the larger
  of two bounds.
  (1) Alone: a link whose sum sum_L x moves by a nonzero multiple of 2 pi / n from c_j = 2 pi p_j / n - H_j
  (|c_j| <= pi / n) costs at least (2 pi / n - |c_j|)^2 / (sum_L 1 / w_e), the least energy of a connection with
  that sum.
  (2) Around the relaxed solve: E_r, the energy with the free integers (loops, links between clusters) relaxed to
  real numbers and the decided ones rounded, `lambda` its multipliers. Let the decided links be rows of the full
  system, z the integers (free ones m, decided ones d), G = (2 pi / n)^2 P^T M^-1 P their metric. Changing d by
  s != 0 (and m by anything) costs, over E_r, at least 2 g^T s + s^T (G / G_mm) s, where g = (2 pi / n) mu is the
  gradient in d at the relaxed point (mu the decided rows' multipliers: for a link across one edge,
  w_e x_e - (A^T lambda)_e up to the sign of the crossing; for a fan link, its row's multiplier) and G / G_mm the
  Schur complement of the free block. G / G_mm = (2 pi / n)^2 ((M / M_NN)_dd)^-1 and (M / M_NN)_dd <= M_dd <= D,
  the diagonal of M_dd's absolute row sums (D - M_dd is diagonally dominant), so G / G_mm >= (2 pi / n)^2 D^-1 and
  the cost separates per link: at least sum_j t0_j + min_j (t1_j - t0_j), with
  t(s) = (2 pi / n)^2 s^2 / D_jj + 2 g_j s, t0 its minimum over the integers and t1 over the nonzero ones. A link
  across one edge shares it with no other decided link: its D_jj is 1 / w_e; a fan link's D_jj is bounded by the
  sum over its crossings of 1 / w_e times the number of decided links crossing e.
  Both are weak when a link's neighbours hold it (then (M / M_NN)_jj is much less than M_jj): with many pins the
  choice is rarely proven, and the report says so.
*/
inline double decided_links_bound(const Constraint_rows& rows, const Eigen::VectorXd& lambda, double relaxed_energy,
                                  const Eigen::VectorXd& x_fixed, const std::vector<double>& holonomy,
                                  const std::vector<std::int64_t>& periods, double unit)
{
  if(rows.decided_slots.empty())
    return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd product = rows.transposed_product(lambda);
  const std::vector<double>& weight = rows.geometry().weight;
  std::vector<int> crossers(weight.size(), 0); // decided fan links per edge
  for(int l : rows.decided_slots)
    if(rows.row_of_slot[std::size_t(l)] >= 0)
      for(int p = rows.slot_edge_start[std::size_t(l)]; p < rows.slot_edge_start[std::size_t(l) + 1]; ++p)
        ++crossers[std::size_t(index_of_code(rows.slot_edges[std::size_t(p)]))];
  double sum_t0 = 0, step = std::numeric_limits<double>::infinity(), alone = std::numeric_limits<double>::infinity();
  for(int l : rows.decided_slots) {
    const int row = rows.row_of_slot[std::size_t(l)];
    double g = 0, d = 0, inverse_weights = 0;
    if(row < 0) {
      const int code = rows.slot_edges[std::size_t(rows.slot_edge_start[std::size_t(l)])], e = index_of_code(code);
      const double w = weight[std::size_t(e)];
      g = unit * sign_of_code(code) * (w * x_fixed[e] - product[e]);
      d = inverse_weights = 1 / w;
    } else {
      g = unit * lambda[row];
      for(int p = rows.slot_edge_start[std::size_t(l)]; p < rows.slot_edge_start[std::size_t(l) + 1]; ++p) {
        const std::size_t e = std::size_t(index_of_code(rows.slot_edges[std::size_t(p)]));
        d += crossers[e] / weight[e];
        inverse_weights += 1 / weight[e];
      }
    }
    const double c = std::abs(unit * double(periods[std::size_t(l)]) - holonomy[std::size_t(l)]);
    alone = (std::min)(alone, (unit - c) * (unit - c) / inverse_weights);
    const double a = unit * unit / d;
    auto t = [&](double s) { return a * s * s + 2 * g * s; };
    const double s_min = -g / a, below = std::floor(s_min), above = below + 1;
    double t0 = (std::min)({0., t(below), t(above)}), t1 = (std::min)(t(-1.), t(1.));
    for(double s : {below, above})
      if(s != 0)
        t1 = (std::min)(t1, t(s));
    sum_t0 += t0;
    step = (std::min)(step, t1 - t0);
  }
  return (std::max)(alone, relaxed_energy + sum_t0 + step);
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_DECIDED_LINKS_H
