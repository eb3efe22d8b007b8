// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_INTEGERS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_INTEGERS_H

#include <CGAL/Trivial_connections/internal/integers/closest_vector.h>
#include <CGAL/Trivial_connections/internal/integers/lattice_reduction.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  What changing the free integers (of loops and links) can add to a move's energy change. A move may lower the
  energy only with some of them changed, by s. With lambda_F their multipliers, G_F their block of M^-1 and
  p = lambda_F + d (G_Fw - G_Fv), the change is that of the move plus 2 u s.p + u^2 s^T G_F s (u = 2 pi / n):
  a closest vector problem, searched when its real minimum -p^T G_F^-1 p could make the move pay off.
  M is block diagonal by component, and a move stays in its component, so only that component's integers can
  change: one block per component, each searched in its own (small) lattice. A block costs a column of M^-1
  per integer, once, for at most 64 in all (made through the factor eight at a time where it is readable); the
  integers of the other components are kept.
  In a round whose solve could not prove its integers optimal, its integers are taken as the nearest all the same
  (bound()), and each search is a descent in the reduced basis from them and from Babai's point, the trial
  solve's own start points (its hint and Babai's), without enumeration (local()): the prices stay those of actual
  integers, a change the solve could not find is only missed. The centre in the reduced basis is linear in the
  move: from two vectors kept per row it costs O(k), not the O(k^2) products of closest_vector(); Babai's point
  too, corrected from the round's (a third vector per row, see local()). dino's curvature
  guidance (63 link integers, never proven): 8.8 s and energy 76.0 with every candidate enumerated, 0.08 s and
  82.0 with the integers kept; 0.21 s and 76.4 with closest_vector() without budget, 0.12 s and 77.7 so, and
  0.08 s and 79.3 with the descent from the integers kept only (over ten CGAL meshes so: energies -2.2 % to
  +2.6 %, about +0.3 % on average, in 0.6-0.8 x the time).
*/
class Move_integers
{
public:
  static constexpr std::size_t largest_block = 64;

  // without a way to make the columns at once: one solve() per column
  struct Column_by_column
  {
    template <class Matrix>
    bool operator()(const std::vector<int>&, Matrix&) const { return false; }
  };
  // `free_rows[c]`: the rows of component c's free integers; `solve(e)`: M^-1 e; `columns_at(rows, out)`: the
  // columns of M^-1 at those rows into out (rows of the system x rows), all at once, or false
  template <class Solve, class Columns = Column_by_column>
  Move_integers(const std::vector<std::vector<int>>& free_rows, Eigen::Index system_rows, double unit, Solve solve,
                Columns columns_at = Columns())
    : m_unit(unit), m_block_of_component(free_rows.size(), -1), m_gamma(std::size_t(system_rows), -1.),
      m_beta(std::size_t(system_rows), 0.), m_beta_round(std::size_t(system_rows), -1),
      m_slot_of_row(std::size_t(system_rows), -1)
  {
    // At most 64 columns in all (columns_at(), or a back-substitution each) and 2 x 128 MB of them, the components
    // with fewest integers first: a mesh of many parts, each with a few boundary loops, has them searched on most
    // parts.
    std::vector<std::size_t> order(free_rows.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return free_rows[a].size() < free_rows[b].size(); });
    std::size_t columns_left = largest_block;
    for(std::size_t c : order) {
      const std::vector<int>& rows = free_rows[c];
      const Eigen::Index k = Eigen::Index(rows.size());
      if(k == 0 || rows.size() > columns_left || 2 * double(m_columns_made + rows.size()) * double(system_rows) > 32e6)
        continue;
      columns_left -= rows.size();
      Block b;
      b.rows = rows;
      Row_major columns;
      if(!columns_at(rows, columns)) {
        columns.resize(system_rows, k);
        Eigen::VectorXd e = Eigen::VectorXd::Zero(system_rows);
        for(Eigen::Index a = 0; a < k; ++a) {
          e[rows[std::size_t(a)]] = 1;
          columns.col(a) = solve(e);
          e[rows[std::size_t(a)]] = 0;
        }
      }
      m_columns_made += std::size_t(k);
      b.metric.resize(k, k);
      for(Eigen::Index a = 0; a < k; ++a)
        b.metric.row(a) = columns.row(rows[std::size_t(a)]);
      b.metric = (b.metric + b.metric.transpose()).eval() / 2;
      const Eigen::LLT<Eigen::MatrixXd> llt(b.metric);
      if(llt.info() != Eigen::Success)
        continue; // not positive definite in double precision: that component's integers are kept
      b.inverse = llt.solve(Eigen::MatrixXd::Identity(k, k));
      b.lattice = reduce_lattice(b.metric, llt.matrixU(), lattice_reduction_budget(k));
      b.weighted = columns * b.inverse;
      b.columns = std::move(columns);
      b.lambda = Eigen::VectorXd::Zero(k);
      m_block_of_component[c] = int(m_blocks.size());
      m_blocks.push_back(std::move(b));
    }
  }

  bool empty() const { return m_blocks.empty(); }
  // whether this round's solve proved its integers (start_round())
  bool proven() const
  {
    return std::all_of(m_blocks.begin(), m_blocks.end(), [](const Block& b) { return b.proven; });
  }
  std::size_t column_solves() const { return m_columns_made; }

  // the multipliers of the current solve; `proven`: its integers are the optimal ones
  void start_round(const Eigen::VectorXd& multipliers, bool proven)
  {
    ++m_round;
    for(Block& b : m_blocks) {
      for(std::size_t a = 0; a < b.rows.size(); ++a)
        b.lambda[Eigen::Index(a)] = multipliers[b.rows[a]];
      b.lambda_norm = b.lambda.dot(b.inverse * b.lambda);
      b.rho = std::sqrt((std::max)(b.lambda_norm, 0.)) / m_unit;
      b.proven = proven;
      if(!proven) {
        // the real minimiser without a move, in the reduced basis, and H_red times it: w0 = -U^-1 H lambda / u,
        // H_red w0 = -U^T lambda / u (H_red = U^T G_F U, G_F H = I)
        const Eigen::VectorXd c0 = -(b.inverse * b.lambda) / m_unit;
        b.w0 = b.lattice.reduced ? Eigen::VectorXd(b.lattice.inverse_basis * c0) : c0;
        b.h0 = b.lattice.reduced ? Eigen::VectorXd(-(b.lattice.basis.transpose() * b.lambda) / m_unit)
                                 : Eigen::VectorXd(-b.lambda / m_unit);
        // Babai's point of w0 and R (z0 - w0), from which local() reads that of a move's centre in O(k)
        const Eigen::Index k = b.w0.size();
        Eigen::VectorXd z0(k), d0(k);
        b.babai_r0.resize(k);
        nearest_plane_point(b.lattice.factor, b.w0, z0, d0, b.babai_r0);
        b.babai_inverse_diagonal = b.lattice.factor.diagonal().cwiseInverse();
        b.babai_z0 = z0;
      }
    }
  }

  /*
    A lower bound on what changing the integers can give the move of d from the vertex of row rv to that of rw
    in component c (<= 0; rows -1 for vertices without one). With c0 = -H lambda_F / u the real minimiser now and c1 that after
    the move, the integers now are the lattice point nearest to c0 (when the solve proved it): at distance
    rho = |c0| in the norm of G_F. The move shifts the centre by delta = |c1 - c0|, so no lattice point is nearer
    to c1 than rho - delta, and the gain is at least u^2 (rho - delta)_+^2 - |c1|^2 u^2. Without it the bound
    would be -|c1|^2 u^2 (every integer real), and every pair would be searched. When the solve did not prove
    its integers, rho = |c0| all the same: no longer a proof, the heuristic the solve itself settled for.
  */
  double bound(std::size_t c, int rv, int rw, double d)
  {
    const int block = m_block_of_component[c];
    if(block < 0)
      return 0;
    const Block& b = m_blocks[std::size_t(block)];
    const double shift2 = shift(b, rv, rw);
    const double relaxed = b.lambda_norm + 2 * d * (beta(b, rw) - beta(b, rv)) + d * d * shift2; // |c1|^2 u^2
    const double gap = (std::max)(b.rho - std::abs(d) / m_unit * std::sqrt(shift2), 0.);
    return (std::min)(0., m_unit * m_unit * gap * gap - relaxed);
  }

  // what bound() reads of a row: lambda_F^T H C_r (this round) and |C_r|_H
  struct Row_terms
  {
    double beta = 0, norm = 0;
  };
  Row_terms terms(std::size_t c, int r)
  {
    const int block = m_block_of_component[c];
    if(block < 0 || r < 0)
      return {};
    const Block& b = m_blocks[std::size_t(block)];
    return {beta(b, r), std::sqrt(gamma(b, r))};
  }

  // At most bound(c, rv, rw, d), from the terms of the two rows only: |C_w - C_v|_H replaced by its upper bound
  // |C_v|_H + |C_w|_H, which bound() decreases with. For the many pairs of a cancellation search.
  double quick_bound(std::size_t c, const Row_terms& v, const Row_terms& w, double d) const
  {
    const int block = m_block_of_component[c];
    if(block < 0)
      return 0;
    const Block& b = m_blocks[std::size_t(block)];
    const double reach = v.norm + w.norm;
    const double relaxed = b.lambda_norm + 2 * d * (w.beta - v.beta) + d * d * reach * reach;
    const double gap = (std::max)(b.rho - std::abs(d) / m_unit * reach, 0.);
    return (std::min)(0., m_unit * m_unit * gap * gap - relaxed);
  }

  // the energy change of that move with the integers kept (`kept`), or with the best of them when some bring it
  // below `threshold`; otherwise a change at most `kept`, not below `threshold`
  double best(std::size_t c, int rv, int rw, double d, double kept, double threshold)
  {
    const int block = m_block_of_component[c];
    if(block < 0 || kept + bound(c, rv, rw, d) >= threshold)
      return kept;
    Block& b = m_blocks[std::size_t(block)];
    m_change_component = c;
    if(!b.proven) {
      make_row_terms(b, rv, rw);
      const double change = kept + m_unit * m_unit * local(b, rv, rw, d, m_workspace);
      if(!(change < kept))
        return kept;
      m_change.resize(b.rows.size());
      const Eigen::VectorXd& reduced = m_workspace.reduced_change;
      const Eigen::VectorXd s = b.lattice.reduced ? Eigen::VectorXd(b.lattice.basis * reduced) : reduced;
      for(std::size_t a = 0; a < m_change.size(); ++a)
        m_change[a] = std::int64_t(nearest_integer(s[Eigen::Index(a)]));
      return change;
    }
    Eigen::VectorXd p = b.lambda;
    if(rw >= 0)
      p += d * b.columns.row(rw).transpose();
    if(rv >= 0)
      p -= d * b.columns.row(rv).transpose();
    const Eigen::VectorXd center = -(b.inverse * p) / m_unit; // the real minimiser
    // the change is kept + u^2 ((s - c)^T G_F (s - c) - c^T G_F c), c = center: below `threshold` only for the
    // points within the ball searched (most moves pay with none: bunny00's curvature guidance, a first round's
    // 877 searches 66 -> 29 ms, the same 471 candidates)
    const double centre_norm = center.dot(b.metric * center);
    if(!b.cost)
      b.cost.emplace(b.lattice.factor); // its k lgamma and log, a fifth of a search, once per block
    const Closest_vector_result nearest = closest_vector(b.lattice, b.metric, center, {}, 1e5,
                                                         centre_norm + (threshold - kept) / (m_unit * m_unit),
                                                         &*b.cost);
    const double change = kept + m_unit * m_unit * (nearest.value - centre_norm);
    if(!(change < kept))
      return kept;
    m_change = nearest.m;
    return change;
  }

  // The change of the integers behind the last price best() gave below `kept`: per free row of component
  // `component()` (in the order given to the constructor), what its integer gains. A trial solve given the
  // integers so changed as its hint meets the price even where its own search, not proven, would not find them.
  std::size_t change_component() const { return m_change_component; }
  const std::vector<std::int64_t>& change() const { return m_change; }

  // A move to price in a round of unproven integers (price_unproven()).
  struct Unproven_search
  {
    std::size_t component;
    int rv, rw;
    double d, kept;
    double bounded = 0; // kept + bound(): best() searches only below a threshold above it
    double change = 0;  // what best() gives then
  };

  /*
    best() of many moves of a round whose integers are not proven, for thresholds above `threshold` (the
    searches below it): with `split(count, f)` running f(begin, end) over [0, count), possibly f(0, half) and
    f(half, count) on two threads. The searches only read: the terms of their rows and the bounds are made
    first, here. A caller that wants the integers behind one of the changes calls best() for it again (the same
    arithmetic, the same change). homer's curvature guidance: about 1,700 searches a round in 64 dimensions.
  */
  template <class Split>
  void price_unproven(std::vector<Unproven_search>& searches, double threshold, const Split& split)
  {
    for(Unproven_search& q : searches) {
      q.bounded = q.kept + bound(q.component, q.rv, q.rw, q.d);
      q.change = q.kept;
      const int block = m_block_of_component[q.component];
      if(block >= 0)
        make_row_terms(m_blocks[std::size_t(block)], q.rv, q.rw);
    }
    split(searches.size(), [&](std::size_t begin, std::size_t end) {
      Workspace workspace;
      for(std::size_t i = begin; i < end; ++i) {
        Unproven_search& q = searches[i];
        const int block = m_block_of_component[q.component];
        if(block < 0 || q.bounded >= threshold)
          continue;
        const Block& b = m_blocks[std::size_t(block)];
        CGAL_assertion(!b.proven);
        const double change = q.kept + m_unit * m_unit * local(b, q.rv, q.rw, q.d, workspace);
        if(change < q.kept)
          q.change = change;
      }
    });
  }

private:
  using Row_major = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>; // rows read one by one

  struct Block
  {
    std::vector<int> rows;
    Eigen::MatrixXd metric, inverse; // G_F, H = G_F^-1
    Reduced_lattice lattice;
    std::optional<Enumeration_cost> cost; // of closest_vector()'s enumeration in it, made at its first search
    Row_major columns, weighted;     // M^-1 on the free rows (C_r is row r), and C H
    Eigen::VectorXd lambda;          // per round
    double lambda_norm = 0, rho = 0; // lambda^T H lambda, and the distance of the integers to the centre
    bool proven = true;              // this round: the solve proved its integers optimal
    Eigen::VectorXd w0, h0;          // unproven rounds: see start_round()
    // per row r (local()): a_r = U^-1 H C_r^T / u, H_red a_r = U^T C_r^T / u and R a_r, at slot_of_row[r] * k
    std::vector<double> a, ha, ra;
    // unproven rounds: z0 Babai's point of w0, R (z0 - w0); and 1 / R_ii
    Eigen::VectorXd babai_z0, babai_r0, babai_inverse_diagonal;
  };

  // local() corrects Babai's point of w0 into that of a move's centre only when each of its roundings is this
  // far from a tie (in units of the integers): its arithmetic and nearest_plane_point()'s differ by far less
  static constexpr double babai_margin = 1e-6;

  // local()'s vectors, kept from search to search (thousands a round), one set per thread
  struct Workspace
  {
    Eigen::VectorXd w, hw, z, difference, h_difference, Rd, r;
    Eigen::VectorXd reduced_change; // the best point, reduced coordinates
  };

  /*
    The change of q(z) = (z - w)^T H_red (z - w) from z = 0 (the integers kept, reduced coordinates) to the better
    of the descents from z = 0 and from Babai's point, for the move of d from row rv to row rw: its centre is
    w = w0 - d (a_w - a_v). Reads the rows' terms made by make_row_terms().
  */
  double local(const Block& b, int rv, int rw, double d, Workspace& ws) const
  {
    const Eigen::Index k = b.w0.size();
    ws.w = b.w0;
    ws.hw = b.h0;
    ws.r = b.babai_r0;
    for(const auto& end : {std::make_pair(rw, -d), std::make_pair(rv, d)}) {
      if(end.first < 0)
        continue;
      const int slot = m_slot_of_row[std::size_t(end.first)];
      CGAL_assertion(slot >= 0);
      const std::size_t at = std::size_t(slot) * std::size_t(k);
      ws.w += end.second * Eigen::Map<const Eigen::VectorXd>(&b.a[at], k);
      ws.hw += end.second * Eigen::Map<const Eigen::VectorXd>(&b.ha[at], k);
      ws.r -= end.second * Eigen::Map<const Eigen::VectorXd>(&b.ra[at], k);
    }
    const double before = ws.w.dot(ws.hw);
    ws.z.setZero(k);
    ws.difference = -ws.w;
    ws.h_difference = -ws.hw;
    const double kept_descent = greedy_descent(b.lattice.gram, ws.z, ws.difference, ws.h_difference);
    ws.reduced_change = ws.z;
#ifndef CGAL_NO_ASSERTIONS
    Workspace check = ws;
    const double full = local_from_babai(b, kept_descent, before, check);
#endif
    const double change = local_from_corrected_babai(b, kept_descent, before, ws);
    CGAL_assertion(std::abs(change - full) <= 1e-9 * (1 + std::abs(full)));
    return change;
  }

  // local() after the descent from 0 (ws.reduced_change, value kept_descent)
  double local_from_corrected_babai(const Block& b, double kept_descent, double before, Workspace& ws) const
  {
    const Eigen::Index k = b.w0.size();
    // Babai's point of w = w0 + e, from z0, that of w0, corrected level by level as nearest_plane_point() rounds,
    // the last first: with r = R (z - w) and the levels above i final, the coordinate i rounds to
    // z_i + round(-r_i / R_ii); a correction by t adds t R_.i to r. R (z0 - w) = R (z0 - w0) - R e is linear in
    // the move (ws.r), so the point and its value |r|^2 cost O(k) plus O(i) per level corrected, not the O(k^2)
    // of nearest_plane_point() with its chain of dependent additions (homer: about 1,700 searches a round in 63
    // dimensions, a dozen levels corrected in each). The same point, its value and H_red (z - w) = R^T r differ
    // from nearest_plane_point()'s in the last bits only; a rounding near a tie is left to it.
    const Eigen::MatrixXd& R = b.lattice.factor;
    ws.Rd = b.babai_z0; // Babai's point, built here
    bool near_tie = false;
    for(Eigen::Index i = k - 1; i >= 0 && !near_tie; --i) {
      const double x = -ws.r[i] * b.babai_inverse_diagonal[i];
      if(std::abs(x) < 0.5 - babai_margin)
        continue;
      const double t = nearest_integer(x);
      near_tie = !(0.5 - std::abs(x - t) >= babai_margin);
      ws.Rd[i] += t;
      ws.r.head(i + 1) += t * R.col(i).head(i + 1);
    }
    if(near_tie)
      return local_from_babai(b, kept_descent, before, ws);
    if(ws.r.squaredNorm() >= kept_descent)
      return kept_descent - before;
    // descended from when it is nearer
    ws.z = ws.Rd;
    ws.difference = ws.z - ws.w;
    ws.h_difference.noalias() = R.transpose().triangularView<Eigen::Lower>() * ws.r;
    return descend_from_babai(b, kept_descent, before, ws);
  }

  // the same from nearest_plane_point() of ws.w (near a tie of local_from_corrected_babai()'s roundings)
  double local_from_babai(const Block& b, double kept_descent, double before, Workspace& ws) const
  {
    const Eigen::Index k = b.w0.size();
    const Eigen::MatrixXd& R = b.lattice.factor;
    ws.Rd.resize(k);
    if(nearest_plane_point(R, ws.w, ws.z, ws.difference, ws.Rd) >= kept_descent)
      return kept_descent - before;
    ws.h_difference.noalias() = R.transpose().triangularView<Eigen::Lower>() * ws.Rd;
    return descend_from_babai(b, kept_descent, before, ws);
  }

  // the greedy descent from Babai's point (ws.z, with ws.difference = z - w and ws.h_difference = H_red (z - w)):
  // its change kept in ws.reduced_change when it ends below the descent from 0 (value kept_descent)
  double descend_from_babai(const Block& b, double kept_descent, double before, Workspace& ws) const
  {
    const double babai_descent = greedy_descent(b.lattice.gram, ws.z, ws.difference, ws.h_difference);
    if(babai_descent >= kept_descent)
      return kept_descent - before;
    ws.reduced_change = ws.z;
    return babai_descent - before;
  }

  // a_r, H_red a_r and R a_r of the rows rv and rw (-1: none) in b.a, b.ha and b.ra, at slot_of_row[r] * k
  void make_row_terms(Block& b, int rv, int rw)
  {
    const Eigen::Index k = b.w0.size();
    for(int r : {rv, rw}) {
      if(r < 0 || m_slot_of_row[std::size_t(r)] >= 0)
        continue;
      m_slot_of_row[std::size_t(r)] = int(b.a.size() / std::size_t(k));
      const Eigen::VectorXd hc = b.weighted.row(r).transpose() / m_unit; // H C_r^T / u
      const Eigen::VectorXd c = b.columns.row(r).transpose() / m_unit;
      const Eigen::VectorXd a = b.lattice.reduced ? Eigen::VectorXd(b.lattice.inverse_basis * hc) : hc;
      const Eigen::VectorXd ha = b.lattice.reduced ? Eigen::VectorXd(b.lattice.basis.transpose() * c) : c;
      const Eigen::VectorXd ra = b.lattice.factor.triangularView<Eigen::Upper>() * a;
      b.a.insert(b.a.end(), a.data(), a.data() + k);
      b.ha.insert(b.ha.end(), ha.data(), ha.data() + k);
      b.ra.insert(b.ra.end(), ra.data(), ra.data() + k);
    }
  }

  // |C_w - C_v|_H^2
  double shift(const Block& b, int rv, int rw)
  {
    auto dot = [&](int ra, int rb) { return ra < 0 || rb < 0 ? 0. : b.columns.row(ra).dot(b.weighted.row(rb)); };
    return (std::max)(gamma(b, rv) + gamma(b, rw) - 2 * dot(rv, rw), 0.);
  }

  double gamma(const Block& b, int r) // |C_r|_H^2, kept
  {
    if(r < 0)
      return 0;
    double& g = m_gamma[std::size_t(r)];
    if(g < 0)
      g = (std::max)(b.columns.row(r).dot(b.weighted.row(r)), 0.);
    return g;
  }

  double beta(const Block& b, int r) // lambda_F^T H C_r, per round
  {
    if(r < 0)
      return 0;
    if(m_beta_round[std::size_t(r)] != m_round) {
      m_beta[std::size_t(r)] = b.weighted.row(r).dot(b.lambda.transpose());
      m_beta_round[std::size_t(r)] = m_round;
    }
    return m_beta[std::size_t(r)];
  }

  double m_unit;
  std::vector<Block> m_blocks;
  std::vector<int> m_block_of_component;
  std::vector<double> m_gamma, m_beta;
  std::vector<int> m_beta_round;
  std::vector<int> m_slot_of_row; // local(): where a row's terms are in its block (-1: not made yet)
  int m_round = 0;
  std::size_t m_columns_made = 0;
  std::size_t m_change_component = 0;  // change(): the last improving price's integers
  std::vector<std::int64_t> m_change;
  Workspace m_workspace;                // best()'s searches
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_MOVE_INTEGERS_H
