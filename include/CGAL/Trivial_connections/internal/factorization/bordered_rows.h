// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_BORDERED_ROWS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_BORDERED_ROWS_H

#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/factorization/loop_metric.h>
#include <CGAL/Trivial_connections/internal/factorization/sparse_factor.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>

#include <CGAL/assertions.h>

#include <Eigen/Dense>

#include <map>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Links outside the factorization: set_constraints() with a backend whose factor and substitutions are
  exposed. The factor is that of the last full build: node rows N, then the free rows F (loops and the links
  made then). After set_constraints(), a link that is still there keeps its row in F, a link that is gone is
  dropped from the dense block (its multiplier is 0: the Schur complement of the remaining rows is the
  principal submatrix), and a new link e is a "bordered" row outside the factor: with its column K_e of the
  full system, z_e = L_NN^-1 K_e,N (a forward substitution through the node columns, sparse) gives its Schur
  complement entries S_Fe and S_ee' = M_ee' - z_e^T D_N^-1 z_e'. The integers then live on a dense block per
  component over its free rows and its bordered rows, factored by a dense Cholesky.
*/
template <class SolverTraits>
class Bordered_rows
{
public:
  // a link, by its ends (faces, and whether each is guided), which identify it across set_constraints()
  struct Link_key
  {
    int from_face, to_face;
    bool soft_from, soft_to;
    bool operator<(const Link_key& o) const
    {
      return std::tie(from_face, to_face, soft_from, soft_to) < std::tie(o.from_face, o.to_face, o.soft_from, o.soft_to);
    }
  };

  // the forward part of a solve of the full system for b (rows, then bordered rows): z after the forward
  // substitution, u = D^-1 z, per component the right-hand side y of its dense block (in the order of its
  // free slots), and b_N^T M_NN^-1 b_N
  struct Forward
  {
    Eigen::VectorXd z, u;
    std::vector<Eigen::VectorXd> y;
    double node_part = 0;
  };

  bool active() const { return m_active; }
  std::size_t size() const { return m_rows.size(); }

  // after a full factorization: the links in the factor, and the metric of its free rows
  void keep_factored_links(const Constraint_links& links, const Constraint_rows& rows,
                           const std::vector<Loop_metric>& metrics)
  {
    m_factored_links.clear();
    m_rows.clear();
    m_active = false;
    m_factor_metric = metrics;
    const std::size_t nl = rows.topology().loops.size();
    for(std::size_t j = 0; j < links.links.size(); ++j) {
      const std::size_t l = nl + j;
      if(rows.row_of_slot[l] < 0) // a decided link: no row (set_constraints() then factors again)
        continue;
      m_factored_links.push_back({key_of(links, j), rows.row_of_slot[l],
                                  std::vector<int>(rows.slot_edges.begin() + rows.slot_edge_start[l],
                                                   rows.slot_edges.begin() + rows.slot_edge_start[l + 1])});
    }
  }

  // New links (`links`, just built, crossings not yet coded) on the kept factorization: numbers their rows
  // in `rows`, computes the new bordered rows and the dense blocks into `metrics`.
  Constraint_update set_links(Sparse_factor<SolverTraits>& factor, Constraint_links& links, Constraint_rows& rows,
                              std::vector<Loop_metric>& metrics)
  {
    Constraint_update update;
    const Mesh_topology& t = rows.topology();
    const std::size_t nl = t.loops.size();
    const Eigen::Index k = Eigen::Index(rows.free_rows.size()), first = rows.rows - k;

    // the row of every new link: in the factor, or bordered (computed before, or now)
    std::map<Link_key, int> factored;
    for(const Factored_link& link : m_factored_links)
      factored[link.key] = link.row;
    std::map<Link_key, std::size_t> previous;
    for(std::size_t e = 0; e < m_rows.size(); ++e)
      previous[m_rows[e].key] = e;
    std::vector<Bordered_row> bordered;
    std::vector<char> fresh;
    std::vector<int> row_of_link(links.links.size());
    for(std::size_t j = 0; j < links.links.size(); ++j) {
      const Link_key key = key_of(links, j);
      const auto f = factored.find(key);
      if(f != factored.end()) {
        row_of_link[j] = f->second;
        continue;
      }
      row_of_link[j] = int(rows.rows) + int(bordered.size());
      const auto p = previous.find(key);
      if(p != previous.end()) {
        bordered.push_back(std::move(m_rows[p->second]));
        fresh.push_back(0);
      } else {
        Bordered_row row;
        row.key = key;
        row.component = links.links[j].component;
        for(int i : links.links[j].crossings)
          row.codes.push_back(rows.coded_crossing(i));
        bordered.push_back(std::move(row));
        fresh.push_back(1);
      }
    }
    m_rows = std::move(bordered);
    rows.set_link_rows(links, row_of_link, Eigen::Index(m_rows.size()));

    // K_e of the new bordered rows on the factor's rows: its nodes, the factor's crossing rows (generators and
    // links) through shared edges, and the slacks it shares with the factor's links
    std::unordered_map<int, std::vector<std::pair<int, double>>> crossers; // edge -> (factor row, sign)
    for(std::size_t e = 0; e < m_rows.size(); ++e)
      if(fresh[e])
        for(int code : m_rows[e].codes)
          crossers.emplace(index_of_code(code), std::vector<std::pair<int, double>>());
    auto note_crossings = [&](int row, const int* begin, const int* end) {
      for(const int* c = begin; c != end; ++c) {
        const auto it = crossers.find(index_of_code(*c));
        if(it != crossers.end())
          it->second.push_back({row, sign_of_code(*c)});
      }
    };
    for(std::size_t l = 0; l < nl; ++l)
      if(t.loops[l].kind == Loop_kind::generator)
        note_crossings(rows.row_of_slot[l], rows.slot_edges.data() + rows.slot_edge_start[l],
                       rows.slot_edges.data() + rows.slot_edge_start[l + 1]);
    for(const Factored_link& link : m_factored_links)
      note_crossings(link.row, link.codes.data(), link.codes.data() + link.codes.size());
    for(std::size_t e = 0; e < m_rows.size(); ++e) {
      if(!fresh[e])
        continue;
      Bordered_row& row = m_rows[e];
      Eigen::VectorXd column = Eigen::VectorXd::Zero(rows.rows);
      for(int code : row.codes) {
        const int edge = index_of_code(code);
        const double v = sign_of_code(code) * rows.inverse_weight[std::size_t(edge)];
        const std::array<int, 2> ends = rows.edge_nodes[edge];
        if(ends[0] != ends[1]) {
          if(rows.row_of_node[ends[1]] >= 0) column[rows.row_of_node[ends[1]]] += v;
          if(rows.row_of_node[ends[0]] >= 0) column[rows.row_of_node[ends[0]]] -= v;
        }
        for(const auto& c : crossers[edge])
          column[c.first] += v * c.second;
      }
      for(const Factored_link& link : m_factored_links)
        column[link.row] += slack_coupling(row.key, link.key, links.guidance_weight);
      Eigen::VectorXd z = factor.permutation() * column;
      factor.forward(z, first);
      const Eigen::VectorXd trailing =
        Sparse_factor<SolverTraits>::leading_columns ? Eigen::VectorXd(z.tail(k)) : trailing_times_lower(z.tail(k), false);
      row.z_index.clear();
      row.z_value.clear();
      for(Eigen::Index i = 0; i < first; ++i)
        if(z[i] != 0) {
          row.z_index.push_back(int(i));
          row.z_value.push_back(z[i]);
        }
      row.schur_free = trailing;
    }
    metrics = dense_blocks(factor, rows, links.guidance_weight);
    m_active = true;
    update.links = links.links.size();
    update.links_outside_the_factor = m_rows.size();
    for(char f : fresh)
      update.new_forward_substitutions += std::size_t(f);
    return update;
  }

  Forward forward(Sparse_factor<SolverTraits>& factor, const Constraint_rows& rows,
                  const std::vector<Loop_metric>& metrics, const Eigen::VectorXd& b) const
  {
    const Eigen::Index k = Eigen::Index(rows.free_rows.size()), first = rows.rows - k;
    Forward f;
    f.z = factor.permutation() * b.head(rows.rows);
    factor.forward(f.z, first);
    const Eigen::VectorXd trailing = Sparse_factor<SolverTraits>::leading_columns
                                       ? Eigen::VectorXd(f.z.tail(k))
                                       : trailing_times_lower(f.z.tail(k), false);
    f.u = f.z;
    factor.scale(f.u);
    f.node_part = f.z.head(first).dot(f.u.head(first));
    f.y.resize(metrics.size());
    for(std::size_t c = 0; c < metrics.size(); ++c) {
      const Loop_metric& metric = metrics[c];
      f.y[c].resize(Eigen::Index(metric.place.size()));
      for(Eigen::Index a = 0; a < f.y[c].size(); ++a) {
        const Eigen::Index p = metric.place[a];
        if(p >= 0) {
          f.y[c][a] = trailing[p];
        } else {
          const Bordered_row& row = m_rows[-1 - p];
          double v = b[rows.rows + (-1 - p)];
          for(std::size_t q = 0; q < row.z_index.size(); ++q)
            v -= row.z_value[q] * f.u[row.z_index[q]];
          f.y[c][a] = v;
        }
      }
    }
    return f;
  }

  // the multipliers (rows, then bordered rows) from the forward part and the dense blocks' solutions
  Eigen::VectorXd backward(Sparse_factor<SolverTraits>& factor, const Constraint_rows& rows,
                           const std::vector<Loop_metric>& metrics, Forward& f,
                           const std::vector<Eigen::VectorXd>& lambda_blocks) const
  {
    const Eigen::Index k = Eigen::Index(rows.free_rows.size()), first = rows.rows - k;
    Eigen::VectorXd lambda_free = Eigen::VectorXd::Zero(k), lambda_bordered = Eigen::VectorXd::Zero(rows.outside);
    for(std::size_t c = 0; c < metrics.size(); ++c)
      for(std::size_t a = 0; a < metrics[c].place.size(); ++a) {
        const Eigen::Index p = metrics[c].place[a];
        (p >= 0 ? lambda_free[p] : lambda_bordered[-1 - p]) = lambda_blocks[c][Eigen::Index(a)];
      }
    Eigen::VectorXd& z = f.z;
    for(Eigen::Index e = 0; e < lambda_bordered.size(); ++e) {
      const Bordered_row& row = m_rows[std::size_t(e)];
      for(std::size_t q = 0; q < row.z_index.size(); ++q)
        z[row.z_index[q]] -= row.z_value[q] * lambda_bordered[e];
    }
    factor.scale(z);
    z.tail(k) = Sparse_factor<SolverTraits>::leading_columns ? lambda_free : trailing_times_lower(lambda_free, true);
    factor.backward(z, first);
    Eigen::VectorXd lambda(rows.size());
    lambda.head(rows.rows) = factor.permutation().transpose() * z;
    lambda.tail(lambda_bordered.size()) = lambda_bordered;
    return lambda;
  }

  // M^-1 b
  Eigen::VectorXd solve(Sparse_factor<SolverTraits>& factor, const Constraint_rows& rows,
                        const std::vector<Loop_metric>& metrics, const Eigen::VectorXd& b) const
  {
    Forward f = forward(factor, rows, metrics, b);
    std::vector<Eigen::VectorXd> lambda(metrics.size());
    for(std::size_t c = 0; c < metrics.size(); ++c)
      lambda[c] = f.y[c].size() > 0 ? Eigen::VectorXd(metrics[c].system.solve(f.y[c])) : Eigen::VectorXd();
    return backward(factor, rows, metrics, f, lambda);
  }

private:
  struct Factored_link
  {
    Link_key key;
    int row;
    std::vector<int> codes; // crossings, as in Constraint_rows::slot_edges
  };
  struct Bordered_row
  {
    Link_key key;
    int component = 0;
    std::vector<int> codes;
    std::vector<int> z_index;    // z_e = L_NN^-1 K_e,N: positions (< first) ...
    std::vector<double> z_value; // ... and values
    Eigen::VectorXd schur_free;  // S_Fe, over the positions of F
  };

  static Link_key key_of(const Constraint_links& links, std::size_t j)
  {
    const int from = links.links[j].from, to = links.links[j].to;
    return {links.faces[from].face, links.faces[to].face, links.faces[from].soft, links.faces[to].soft};
  }

  // C C^T / mu between two links: the guided faces they share, +1 at the face a link leaves, -1 where it arrives
  static double slack_coupling(const Link_key& a, const Link_key& b, double mu)
  {
    double sum = 0;
    for(int i = 0; i < 2; ++i)
      for(int j = 0; j < 2; ++j) {
        const int fa = i == 0 ? a.from_face : a.to_face, fb = j == 0 ? b.from_face : b.to_face;
        const bool sa = i == 0 ? a.soft_from : a.soft_to, sb = j == 0 ? b.soft_from : b.soft_to;
        if(fa == fb && sa && sb)
          sum += (i == 0 ? 1. : -1.) * (j == 0 ? 1. : -1.);
      }
    return sum / mu;
  }

  // L_FF v (or L_FF^T v) over the positions of F, component by component (L_FF: the factor's trailing block)
  Eigen::VectorXd trailing_times_lower(const Eigen::VectorXd& v, bool transposed) const
  {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(v.size());
    for(std::size_t c = 0; c < m_factor_metric.size(); ++c) {
      const std::vector<Eigen::Index>& block = m_factor_metric[c].block;
      if(block.empty())
        continue;
      Eigen::VectorXd t(Eigen::Index(block.size()));
      for(Eigen::Index a = 0; a < t.size(); ++a)
        t[a] = v[block[a]];
      const auto L = m_factor_metric[c].schur_factor.template triangularView<Eigen::Lower>();
      t = transposed ? Eigen::VectorXd(L.transpose() * t) : Eigen::VectorXd(L * t);
      for(Eigen::Index a = 0; a < t.size(); ++a)
        out[block[a]] = t[a];
    }
    return out;
  }

  // The dense block of the integers per component over its free rows (loops, links in the factor) and its
  // bordered rows, in the order of its free slots, and its Cholesky factorization
  std::vector<Loop_metric> dense_blocks(Sparse_factor<SolverTraits>& factor, const Constraint_rows& rows, double mu) const
  {
    const Eigen::Index k = Eigen::Index(rows.free_rows.size()), first = rows.rows - k;
    // S over the positions of F, per component of the factor: L D L^T
    std::vector<Eigen::Index> component_at(std::size_t(k), 0), index_at(std::size_t(k), 0);
    std::vector<Eigen::MatrixXd> S(m_factor_metric.size());
    for(std::size_t c = 0; c < m_factor_metric.size(); ++c) {
      const Loop_metric& metric = m_factor_metric[c];
      for(std::size_t a = 0; a < metric.block.size(); ++a) {
        component_at[std::size_t(metric.block[a])] = Eigen::Index(c);
        index_at[std::size_t(metric.block[a])] = Eigen::Index(a);
      }
      if(!metric.block.empty())
        S[c] = metric.schur_factor * metric.schur_diagonal.asDiagonal() * metric.schur_factor.transpose();
    }
    Eigen::VectorXd d_inverse = Eigen::VectorXd::Ones(rows.rows); // D^-1
    if(rows.rows > 0)
      factor.scale(d_inverse);
    // shared edges between bordered rows
    std::unordered_map<int, std::vector<std::pair<int, double>>> on_edge;
    for(std::size_t e = 0; e < m_rows.size(); ++e)
      for(int code : m_rows[e].codes)
        on_edge[index_of_code(code)].push_back({int(e), sign_of_code(code)});
    const Eigen::Index ne = Eigen::Index(m_rows.size());
    Eigen::MatrixXd M_EE = Eigen::MatrixXd::Zero(ne, ne);
    for(const auto& edge : on_edge)
      for(const auto& a : edge.second)
        for(const auto& b : edge.second)
          M_EE(a.first, b.first) += a.second * b.second * rows.inverse_weight[std::size_t(edge.first)];
    for(Eigen::Index a = 0; a < ne; ++a)
      for(Eigen::Index b = 0; b < ne; ++b)
        M_EE(a, b) += slack_coupling(m_rows[a].key, m_rows[b].key, mu);
    // z_e^T D^-1 z_e' through a dense scatter of z_e'
    Eigen::VectorXd scattered = Eigen::VectorXd::Zero(first);
    for(Eigen::Index b = 0; b < ne; ++b) {
      const Bordered_row& rb = m_rows[b];
      for(std::size_t q = 0; q < rb.z_index.size(); ++q)
        scattered[rb.z_index[q]] = rb.z_value[q] * d_inverse[rb.z_index[q]];
      for(Eigen::Index a = 0; a < ne; ++a) {
        if(m_rows[a].component != rb.component)
          continue;
        double dot = 0;
        const Bordered_row& ra = m_rows[a];
        for(std::size_t q = 0; q < ra.z_index.size(); ++q)
          dot += ra.z_value[q] * scattered[ra.z_index[q]];
        M_EE(a, b) -= dot;
      }
      for(int i : rb.z_index)
        scattered[i] = 0;
    }
    std::vector<Loop_metric> metrics(rows.free_slots.size());
    for(std::size_t c = 0; c < metrics.size(); ++c) {
      const std::vector<int>& free = rows.free_slots[c];
      const Eigen::Index kc = Eigen::Index(free.size());
      if(kc == 0)
        continue;
      Loop_metric& metric = metrics[c];
      metric.place.resize(free.size());
      for(Eigen::Index a = 0; a < kc; ++a) {
        const int row = rows.row_of_slot[free[a]];
        metric.place[a] = row < rows.rows ? factor.permutation().indices()[row] - first : -1 - (row - rows.rows);
      }
      Eigen::MatrixXd system(kc, kc);
      for(Eigen::Index a = 0; a < kc; ++a)
        for(Eigen::Index b = 0; b < kc; ++b) {
          const Eigen::Index pa = metric.place[a], pb = metric.place[b];
          if(pa >= 0 && pb >= 0) {
            CGAL_assertion(component_at[pa] == component_at[pb]);
            system(a, b) = S[component_at[pa]](index_at[pa], index_at[pb]);
          } else if(pa >= 0) {
            system(a, b) = m_rows[-1 - pb].schur_free[pa];
          } else if(pb >= 0) {
            system(a, b) = m_rows[-1 - pa].schur_free[pb];
          } else {
            system(a, b) = M_EE(-1 - pa, -1 - pb);
          }
        }
      system = (system + system.transpose()) / 2;
      metric.system.compute(system);
      if(metric.system.info() != Eigen::Success || !system.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the metric of the integers is not positive definite");
      metric.inverse = metric.system.solve(Eigen::MatrixXd::Identity(kc, kc));
      metric.inverse = (metric.inverse + metric.inverse.transpose()) / 2;
      Eigen::LLT<Eigen::MatrixXd> llt(metric.inverse);
      if(llt.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the metric of the integers is not positive definite");
      metric.inverse_factor = llt.matrixU();
    }
    return metrics;
  }

  std::vector<Factored_link> m_factored_links; // the links in the factor
  std::vector<Loop_metric> m_factor_metric;    // the metric of the factor's free rows
  std::vector<Bordered_row> m_rows;            // links outside the factor
  bool m_active = false;                       // solves go through forward() and backward()
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_BORDERED_ROWS_H
