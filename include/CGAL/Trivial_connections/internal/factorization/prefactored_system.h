// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_PREFACTORED_SYSTEM_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_PREFACTORED_SYSTEM_H

#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/internal/factorization/bordered_rows.h>
#include <CGAL/Trivial_connections/internal/factorization/checked_solve.h>
#include <CGAL/Trivial_connections/internal/factorization/loop_metric.h>
#include <CGAL/Trivial_connections/internal/factorization/selected_inverse.h>
#include <CGAL/Trivial_connections/internal/factorization/sparse_factor.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>
#include <CGAL/Trivial_connections/internal/system/system_assembly.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The constraint system M = A W^-1 A^T once factored, and the solves through it. A solve that chooses the
  integers of the free rows F (loops, links) is split in two around that choice: forward() gives, per
  component, the right-hand side y of the Schur complement S of its free rows with those integers 0, so
  that the loop part of the energy is t^T S^-1 t with t = y + 2 pi m / n; backward() then finishes the
  solve for the chosen t. How depends on the backend and on set_constraints():
  - links outside the factor (Bordered_rows): a forward substitution, the dense blocks, a backward one;
  - the free rows read from the factor with its substitutions exposed: one forward and one backward
    substitution in all, F last: the forward substitution through the node columns N leaves on F
    y = b_F - M_FN M_NN^-1 b_N, and lambda_F = S^-1 t with S = L_FF D_F L_FF^T (the trailing block);
  - any other backend: a checked solve with the integers 0 gives y = S lambda_F, then a second solve.
*/
template <class SolverTraits>
class Prefactored_system
{
public:
  struct Loop_forward
  {
    std::vector<Eigen::VectorXd> y; // per component, over its free slots
    double node_part = 0;           // the energy of the solve without the loop part (set by backward())
    typename Bordered_rows<SolverTraits>::Forward bordered;
    Eigen::VectorXd z;              // the forward substitution, rows at their positions
  };

  // M = A W^-1 A^T (from system_in_row_order(); released here) handed to the backend with its node rows in the
  // fill-reducing order `node_order` (released too) and the free rows last. Both are released before the
  // factorization, whose memory is the peak.
  void load(const Constraint_rows& rows, Eigen::SparseMatrix<double>& M, std::vector<int>& node_order)
  {
    if(rows.rows == 0)
      return;
    const Row_permutation permutation = loop_rows_last(rows, node_order);
    Eigen::SparseMatrix<double> ordered =
      ordered_system(M, permutation, Sparse_factor<SolverTraits>::stored_triangle);
    M = Eigen::SparseMatrix<double>();
    std::vector<int>().swap(node_order);
    m_factor.load(ordered, permutation);
  }

  void factor(const Constraint_rows& rows) { m_factor.factor(rows.rows); }

  // The nodes in the order of their rows in the factor (pinned nodes first), to factor a new system of the same
  // mesh in the same fill-reducing order.
  std::vector<int> node_order(const Constraint_rows& rows, int number_of_nodes) const
  {
    std::vector<int> order((std::size_t(number_of_nodes))); // not a declaration
    for(int node = 0; node < number_of_nodes; ++node)
      order[std::size_t(node)] = node;
    if(rows.rows > 0) {
      const int* position = m_factor.permutation().indices().data();
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        const int ra = rows.row_of_node[a], rb = rows.row_of_node[b];
        return (ra < 0 ? -1 : position[ra]) < (rb < 0 ? -1 : position[rb]);
      });
    }
    return order;
  }

  // A new system on the same mesh (set_constraints() with a backend that does not expose its factor):
  // assembled, factored in the node order `node_order` (from node_order() of the previous one), its metric.
  template <class TriangleMesh>
  void refactor(const Mesh_arrays<TriangleMesh>& m, const Constraint_rows& rows, const Constraint_links& links,
                std::vector<int>& node_order, std::size_t components)
  {
    std::vector<int> node_start, node_rows;
    rows.topology().node_adjacency(m, node_start, node_rows);
    Eigen::SparseMatrix<double> M = system_in_row_order(m, rows, node_start, node_rows);
    std::vector<int>().swap(node_start);
    std::vector<int>().swap(node_rows);
    load(rows, M, node_order);
    factor(rows);
    compute_metrics(rows, links, components);
  }

  const Row_permutation& permutation() const { return m_factor.permutation(); }
  const SolverTraits& solver_traits() const { return m_factor.solver_traits(); }
  const std::vector<Loop_metric>& metrics() const { return m_metrics; }
  // rows live outside the factor (set_constraints() on a kept factorization)
  bool has_bordered_rows() const { return m_bordered.active(); }
  // the metric was read from the factor, whose substitutions are exposed (set_constraints() keeps the factor)
  bool loop_rows_in_factor() const { return m_loop_rows_in_factor; }

  // after the factorization of a full build: the metric of the integers and the links in the factor
  void compute_metrics(const Constraint_rows& rows, const Constraint_links& links, std::size_t components)
  {
    m_metrics = loop_metrics(m_factor, rows, components, m_loop_rows_in_factor,
                             [&](const Eigen::VectorXd& b) { return checked_solve(rows, b); });
    m_bordered.keep_factored_links(links, rows, m_metrics);
  }

  // new links on the kept factorization (loop_rows_in_factor() only)
  Constraint_update set_links(Constraint_links& links, Constraint_rows& rows)
  {
    return m_bordered.set_links(m_factor, links, rows, m_metrics);
  }

  // M^-1 b (rows in their own order), to be checked by the caller
  Eigen::VectorXd solve(const Constraint_rows& rows, const Eigen::VectorXd& b)
  {
    if(b.size() == 0)
      return b;
    if(m_bordered.active())
      return m_bordered.solve(m_factor, rows, m_metrics, b);
    return m_factor.solve(b);
  }

  // the factor L D L^T of M in the order of the factored system (positions: permutation()); false when the
  // backend does not expose it, or rows live outside it (set_constraints() on a kept factorization)
  bool read_factor(const Constraint_rows& rows, Unit_lower_factor& f)
  {
    return rows.rows > 0 && !m_bordered.active() && m_factor.read_factor(f) && f.n == int(rows.rows);
  }

  // M^-1 b, checked and refined
  Eigen::VectorXd checked_solve(const Constraint_rows& rows, const Eigen::VectorXd& b)
  {
    return checked_multipliers(rows, [&](const Eigen::VectorXd& r) { return solve(rows, r); }, b);
  }

  Loop_forward forward(const Constraint_rows& rows, const Eigen::VectorXd& b)
  {
    Loop_forward f;
    if(m_bordered.active()) {
      f.bordered = m_bordered.forward(m_factor, rows, m_metrics, b);
      f.y = std::move(f.bordered.y); // the bordered backward pass does not read it
      f.node_part = f.bordered.node_part;
    } else if(m_loop_rows_in_factor) {
      const Eigen::Index first = rows.rows - Eigen::Index(rows.free_rows.size());
      f.z = m_factor.permutation() * b;
      m_factor.forward(f.z, first);
      f.y.resize(m_metrics.size());
      for(std::size_t c = 0; c < m_metrics.size(); ++c) {
        const Loop_metric& metric = m_metrics[c];
        f.y[c].resize(Eigen::Index(metric.block.size()));
        for(Eigen::Index a = 0; a < f.y[c].size(); ++a)
          f.y[c][a] = f.z[first + metric.block[a]];
        if constexpr(!Sparse_factor<SolverTraits>::leading_columns) // the whole forward substitution gave L_FF^-1 y
          f.y[c] = metric.schur_factor.template triangularView<Eigen::Lower>() * f.y[c];
      }
    } else {
      const Eigen::VectorXd lambda = checked_solve(rows, b);
      f.y.resize(m_metrics.size());
      double loop_part = 0; // y^T S^-1 y = lambda_F . y
      for(std::size_t c = 0; c < m_metrics.size(); ++c) {
        const Loop_metric& metric = m_metrics[c];
        Eigen::VectorXd lf(Eigen::Index(rows.free_slots[c].size()));
        for(std::size_t a = 0; a < rows.free_slots[c].size(); ++a)
          lf[Eigen::Index(a)] = lambda[rows.row_of_slot[rows.free_slots[c][a]]];
        const auto L = metric.schur_factor.template triangularView<Eigen::Lower>();
        f.y[c] = L * (metric.schur_diagonal.asDiagonal() * (L.transpose() * lf)); // S lambda_F
        loop_part += lf.dot(f.y[c]);
      }
      f.node_part = b.dot(lambda) - loop_part;
    }
    return f;
  }

  // The multipliers for `t` (per component, y + 2 pi m / n over its free slots); `b`: the right-hand side
  // with the chosen integers
  Eigen::VectorXd backward(const Constraint_rows& rows, Loop_forward& f, const std::vector<Eigen::VectorXd>& t,
                           const Eigen::VectorXd& b)
  {
    if(m_bordered.active()) {
      std::vector<Eigen::VectorXd> blocks(m_metrics.size());
      for(std::size_t c = 0; c < m_metrics.size(); ++c)
        blocks[c] = t[c].size() > 0 ? Eigen::VectorXd(m_metrics[c].system.solve(t[c])) : t[c];
      return m_bordered.backward(m_factor, rows, m_metrics, f.bordered, blocks);
    }
    if(!m_loop_rows_in_factor)
      return solve(rows, b);
    const Eigen::Index first = rows.rows - Eigen::Index(rows.free_rows.size());
    Eigen::VectorXd& z = f.z;
    for(std::size_t c = 0; c < m_metrics.size(); ++c) {
      const Loop_metric& metric = m_metrics[c];
      Eigen::VectorXd tc = t[c];
      metric.schur_factor.template triangularView<Eigen::Lower>().solveInPlace(tc);
      for(Eigen::Index a = 0; a < tc.size(); ++a)
        z[first + metric.block[a]] = tc[a];
    }
    f.node_part = m_factor.scaled_square_norm(z, first); // b_N^T M_NN^-1 b_N = z_N^T D_N^-1 z_N, no copy of z_N
    m_factor.scale(z);
    if constexpr(Sparse_factor<SolverTraits>::leading_columns) {
      for(std::size_t c = 0; c < m_metrics.size(); ++c) {
        const Loop_metric& metric = m_metrics[c];
        Eigen::VectorXd tc(Eigen::Index(metric.block.size()));
        for(Eigen::Index a = 0; a < tc.size(); ++a)
          tc[a] = z[first + metric.block[a]];
        metric.schur_factor.template triangularView<Eigen::Lower>().transpose().solveInPlace(tc);
        for(Eigen::Index a = 0; a < tc.size(); ++a)
          z[first + metric.block[a]] = tc[a];
      }
    }
    m_factor.backward(z, first);
    z = m_factor.permutation().transpose() * z; // in place
    return std::move(z);
  }

private:
  Sparse_factor<SolverTraits> m_factor;
  std::vector<Loop_metric> m_metrics; // per component
  bool m_loop_rows_in_factor = false;
  Bordered_rows<SolverTraits> m_bordered;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_PREFACTORED_SYSTEM_H
