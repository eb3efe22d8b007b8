// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_SELECTED_INVERSE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_SELECTED_INVERSE_H

#include <CGAL/Trivial_connections/solver_traits.h>
#include <CGAL/Trivial_connections/internal/concurrency.h>
#include <CGAL/Trivial_connections/internal/factorization/backend_view.h>
#include <CGAL/Trivial_connections/internal/factorization/factor_substitutions.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  A factor M = L D L^T read out of a backend: L unit lower triangular, stored strictly lower by columns with
  increasing rows (a supernodal factor brings the zeros of its dense blocks along), D its diagonal.
*/
struct Unit_lower_factor
{
  int n = 0;
  std::vector<int> start, row;
  std::vector<double> value, d;
};

// The parent of each column in the elimination tree of a factor's pattern (column-major, rows below the diagonal
// increasing): its first row, -1 for a root. Explicit zeros count: they are part of the pattern the tree is of.
inline std::vector<int> elimination_tree_parents(const std::vector<int>& start, const std::vector<int>& row)
{
  const std::size_t n = start.empty() ? 0 : start.size() - 1;
  std::vector<int> parent(n, -1);
  for(std::size_t j = 0; j < n; ++j)
    if(start[j] < start[j + 1])
      parent[j] = row[std::size_t(start[j])];
  return parent;
}

// Reads the factor of the last factorization, in the order of the factored system; false when the backend
// does not expose it (or permuted the system itself).
template <class SolverTraits>
struct Factor_reading
{
  static bool read(SolverTraits&, Unit_lower_factor&) { return false; }
};

template <int UpLo, class Index>
struct Factor_reading<CGAL::Eigen_solver_traits<
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, UpLo, Eigen::NaturalOrdering<Index>>>>
{
  template <class Traits>
  static bool read(Traits& traits, Unit_lower_factor& f)
  {
    const auto& solver = traits.solver();
    if(solver.info() != Eigen::Success || solver.permutationP().size() != 0)
      return false;
    const auto& L = solver.matrixL().nestedExpression(); // strictly lower, rows increasing (up-looking)
    if(!L.isCompressed())
      return false;
    f.n = int(L.cols());
    f.start.assign(L.outerIndexPtr(), L.outerIndexPtr() + f.n + 1);
    f.row.assign(L.innerIndexPtr(), L.innerIndexPtr() + L.nonZeros());
    f.value.assign(L.valuePtr(), L.valuePtr() + L.nonZeros());
    const Eigen::VectorXd d = solver.vectorD(); // a copy
    f.d.assign(d.data(), d.data() + f.n);
    return true;
  }
};

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
template <>
struct Factor_reading<CGAL::Eigen_solver_traits<Cholmod_supernodal_factorization>>
{
  // L L^T with dense supernodes: column c of supernode s is L_cc, then the rows below it in the block
  template <class Traits>
  static bool read(Traits& traits, Unit_lower_factor& f)
  {
    // L L^T in the order given, as the substitutions read it; supernodal
    if(!Factor_substitutions<Cholmod_solver_traits>::available(traits) || !traits.solver().factor()->is_super)
      return false;
    const cholmod_factor* F = traits.solver().factor();
    const int* super = static_cast<const int*>(F->super);
    const int* pi = static_cast<const int*>(F->pi);
    const int* px = static_cast<const int*>(F->px);
    const int* rows = static_cast<const int*>(F->s);
    const double* x = static_cast<const double*>(F->x);
    f.n = int(F->n);
    f.start.assign(std::size_t(f.n) + 1, 0);
    f.d.assign(std::size_t(f.n), 1.);
    for(std::size_t s = 0; s < F->nsuper; ++s)
      for(int c = super[s]; c < super[s + 1]; ++c)
        f.start[std::size_t(c) + 1] = pi[s + 1] - pi[s] - (c - super[s]) - 1;
    std::partial_sum(f.start.begin(), f.start.end(), f.start.begin());
    f.row.resize(std::size_t(f.start.back()));
    f.value.resize(std::size_t(f.start.back()));
    std::vector<std::pair<int, double>> column;
    for(std::size_t s = 0; s < F->nsuper; ++s) {
      const int c0 = super[s], nrows = pi[s + 1] - pi[s];
      // CHOLMOD's supernodal analysis lists a supernode's rows in order (then no sort: a tenth of the refinement's
      // set-up on cheese_loop1); checked
      const bool sorted = std::is_sorted(rows + pi[s], rows + pi[s + 1]);
      for(int c = c0; c < super[s + 1]; ++c) {
        const double* block = x + px[s] + std::size_t(c - c0) * std::size_t(nrows);
        const double diagonal = block[c - c0];
        if(!(diagonal > 0))
          return false;
        f.d[std::size_t(c)] = diagonal * diagonal;
        if(sorted) {
          int p = f.start[std::size_t(c)];
          for(int r = c - c0 + 1; r < nrows; ++r) {
            f.row[std::size_t(p)] = rows[pi[s] + r];
            f.value[std::size_t(p++)] = block[r] / diagonal;
          }
          continue;
        }
        column.clear();
        for(int r = c - c0 + 1; r < nrows; ++r)
          column.emplace_back(rows[pi[s] + r], block[r] / diagonal);
        std::sort(column.begin(), column.end());
        int p = f.start[std::size_t(c)];
        for(const auto& e : column) {
          f.row[std::size_t(p)] = e.first;
          f.value[std::size_t(p++)] = e.second;
        }
      }
    }
    return true;
  }
};

template <class Crossover>
struct Factor_reading<Cost_based_solver_traits<Crossover>>
{
  static bool read(Cost_based_solver_traits<Crossover>& traits, Unit_lower_factor& f)
  {
    return on_backend(
      traits, [&](auto& view) { return Factor_reading<Automatic_simplicial_traits>::read(view, f); },
      [&](auto& view) { return Factor_reading<Cholmod_solver_traits>::read(view, f); }, false);
  }
};
#endif

// Per column of a factor's pattern: the first column of its supernode, the columns j0..j1 where each but the last
// has exactly the rows of the next below it, and the next itself (within one owner when `owner` is given).
inline std::vector<int> supernode_firsts(const std::vector<int>& start, const std::vector<int>& row,
                                         const std::vector<char>* owner = nullptr)
{
  const int n = start.empty() ? 0 : int(start.size()) - 1;
  std::vector<int> first(static_cast<std::size_t>(n));
  for(int c = 0; c < n; ++c) {
    first[std::size_t(c)] = c;
    if(c == 0 || (owner && (*owner)[std::size_t(c - 1)] != (*owner)[std::size_t(c)]))
      continue;
    const int b = start[std::size_t(c - 1)], e = start[std::size_t(c)], ce = start[std::size_t(c) + 1];
    if(e - b == ce - e + 1 && row[std::size_t(b)] == c &&
       std::equal(row.begin() + e, row.begin() + ce, row.begin() + b + 1))
      first[std::size_t(c)] = first[std::size_t(c - 1)];
  }
  return first;
}

// The work of Selected_inverse on a factor, in the units of a column's length squared (what a column costs in
// sparse merges): a supernode of width s >= 2 over r rows costs the gathering of its r x r block of Z and dense
// products (2 r^2 s flops, about eight times faster than merges: cheese_loop3 with Eigen's LDLT, 1.1M faces,
// 4.1 s against 21.9 s column by column; armadillo 0.056 s against 0.088 s).
inline double selected_inversion_work(const std::vector<int>& start, const std::vector<int>& row)
{
  const std::vector<int> first = supernode_firsts(start, row);
  double work = 0;
  for(int j = int(first.size()) - 1; j >= 0; --j) {
    const double r = double(start[std::size_t(j) + 1] - start[std::size_t(j)]);
    const double s = double(j - first[std::size_t(j)] + 1);
    work += s >= 2 ? r * r / 2 + r * r * s / 4 + s * s * s / 3 : (r + 1) * (r + 1);
    j = first[std::size_t(j)];
  }
  return work;
}

/*
  The entries of M^-1 on the pattern of L (Takahashi's recurrences), from the last column to the first:
  Z_ij = -sum_{k in L_:j} Z_ik L_kj for i in L_:j, and Z_jj = 1/d_j - sum_{k in L_:j} L_kj Z_kj. The rows of a
  column below any of its rows k are rows of column k (the filled graph is chordal), so every Z_ik needed is
  on the pattern; a supernodal factor's padded rows are the exception, and there L_kj = 0, so the term is 0.
  Column by column the cost is that of the factorization in sparse merges (sum over columns of their length
  squared). The columns of a supernode go at once, in dense blocks (Lin et al., "SelInv", 2011, in our words):
  with J its columns and R the rows below them, Z_RJ = -Z_RR L_RJ L_JJ^-1 and
  Z_JJ = L_JJ^-T D_J^-1 L_JJ^-1 - (L_RJ L_JJ^-1)^T Z_RJ, Z_RR gathered from the columns done (on the pattern:
  chordality again; when a padded row leaves an entry off it, that supernode goes column by column). Cost: see
  selected_inversion_work(). On two threads.
*/
class Selected_inverse
{
public:
  // takes the factor's storage (the pattern is kept); `keep_factor`: its values are kept too, for factor() (a
  // caller that reads the factor after the inversion needs no copy of it: hundreds of megabytes, each page a fault)
  explicit Selected_inverse(Unit_lower_factor&& f, bool keep_factor = false)
    : m_factor(std::move(f)), m_start(m_factor.start), m_row(m_factor.row), m_l(m_factor.value), m_d(m_factor.d),
      m_factor_kept(keep_factor)
  {
    const int n = m_factor.n;
    m_value.assign(m_l.size(), 0.);
    m_diagonal.assign(std::size_t(n), 0.);
    // A column needs those of its ancestors in the elimination tree only: two disjoint subtrees go on two
    // threads once the rest (their ancestors and the small subtrees) is done.
    const std::vector<char> owner = split_in_two_subtrees(n);
    const std::vector<int> first = supernode_firsts(m_start, m_row, &owner);
    auto columns_of = [&](char which) {
      Scratch scratch;
      for(int j = n - 1; j >= 0; --j)
        if(owner[std::size_t(j)] == which) {
          const int j0 = first[std::size_t(j)];
          if(j0 == j || !block(j0, j, scratch))
            for(int c = j; c >= j0; --c)
              column(c, scratch.sum);
          j = j0;
        }
      return true;
    };
    columns_of(0);
    auto second = concurrently([&] { return columns_of(2); });
    columns_of(1);
    second.get();
    if(!m_factor_kept) {
      std::vector<double>().swap(m_l);
      std::vector<double>().swap(m_d);
    }
  }
  Selected_inverse(const Selected_inverse&) = delete;
  Selected_inverse& operator=(const Selected_inverse&) = delete;

  // the factor inverted, when kept
  bool factor_kept() const { return m_factor_kept; }
  const Unit_lower_factor& factor() const
  {
    CGAL_precondition(m_factor_kept);
    return m_factor;
  }

  // (M^-1)_ij for positions i, j of the factored system; NaN when (i, j) is off the pattern
  double entry(int i, int j) const
  {
    if(i == j)
      return m_diagonal[std::size_t(i)];
    if(i < j)
      std::swap(i, j);
    const auto b = m_row.begin() + m_start[std::size_t(j)], e = m_row.begin() + m_start[std::size_t(j) + 1];
    const auto p = std::lower_bound(b, e, i);
    return p != e && *p == i ? m_value[std::size_t(p - m_row.begin())] : std::numeric_limits<double>::quiet_NaN();
  }

private:
  // the blocks of a supernode, in buffers that only grow: a fresh allocation per supernode (sizes vary) would be
  // fresh pages, each a fault
  struct Scratch
  {
    std::vector<double> sum, zrr, lrj, u, z, small;
    static double* at_least(std::vector<double>& buffer, std::size_t size)
    {
      if(buffer.size() < size)
        buffer.resize(size);
      return buffer.data();
    }
  };

  // The columns j0..j1 of a supernode at once, with dense blocks (J its columns, R the rows below them):
  // Z_RJ = -Z_RR L_RJ L_JJ^-1 and Z_JJ = L_JJ^-T D_J^-1 L_JJ^-1 - (L_RJ L_JJ^-1)^T Z_RJ. False (nothing written)
  // when an entry of Z_RR is off the pattern (a supernodal factor's padded rows): then column by column.
  bool block(int j0, int j1, Scratch& w)
  {
    using Matrix = Eigen::Map<Eigen::MatrixXd>;
    const int s = j1 - j0 + 1;
    const int rb = m_start[std::size_t(j1)], re = m_start[std::size_t(j1) + 1];
    const int r = re - rb;
    const int* R = m_row.data() + rb;
    const std::size_t rs = std::size_t(r) * std::size_t(s);
    Matrix zrr(Scratch::at_least(w.zrr, std::size_t(r) * std::size_t(r)), r, r);
    for(int a = 0; a < r; ++a) {
      zrr(a, a) = m_diagonal[std::size_t(R[a])];
      int p = m_start[std::size_t(R[a])];
      const int pe = m_start[std::size_t(R[a]) + 1];
      for(int b = a + 1; b < r; ++b) {
        while(p < pe && m_row[std::size_t(p)] < R[b])
          ++p;
        if(p == pe || m_row[std::size_t(p)] != R[b])
          return false;
        zrr(b, a) = m_value[std::size_t(p)];
      }
    }
    double* small = Scratch::at_least(w.small, 3 * std::size_t(s) * std::size_t(s));
    Matrix l(small, s, s), inverse(small + s * s, s, s), zjj(small + 2 * s * s, s, s);
    Matrix lrj(Scratch::at_least(w.lrj, rs), r, s);
    l.setZero();
    for(int c = 0; c < s; ++c) {
      const int b = m_start[std::size_t(j0 + c)];
      l(c, c) = 1;
      for(int i = c + 1; i < s; ++i)
        l(i, c) = m_l[std::size_t(b + (i - c - 1))];
      for(int t = 0; t < r; ++t)
        lrj(t, c) = m_l[std::size_t(b + (s - 1 - c) + t)];
    }
    inverse.setIdentity();
    l.triangularView<Eigen::UnitLower>().solveInPlace(inverse);
    zjj.noalias() = inverse.transpose() *
                    Eigen::Map<const Eigen::VectorXd>(m_d.data() + j0, s).cwiseInverse().asDiagonal() * inverse;
    Matrix z(Scratch::at_least(w.z, rs), r, s);
    if(r > 0) { // (Eigen's blocked products divide by the sizes)
      Matrix u(Scratch::at_least(w.u, rs), r, s);
      u.noalias() = lrj * inverse; // L_RJ L_JJ^-1
      z.noalias() = -(zrr.selfadjointView<Eigen::Lower>() * u);
      zjj.noalias() -= u.transpose() * z;
    }
    for(int c = 0; c < s; ++c) {
      const int b = m_start[std::size_t(j0 + c)];
      m_diagonal[std::size_t(j0 + c)] = zjj(c, c);
      for(int i = c + 1; i < s; ++i)
        m_value[std::size_t(b + (i - c - 1))] = zjj(i, c);
      for(int t = 0; t < r; ++t)
        m_value[std::size_t(b + (s - 1 - c) + t)] = z(t, c);
    }
    return true;
  }

  void column(int j, std::vector<double>& sum)
  {
    const int b = m_start[std::size_t(j)], e = m_start[std::size_t(j) + 1];
    sum.assign(std::size_t(e - b), 0.);
    for(int q = b; q < e; ++q) {
      const int k = m_row[std::size_t(q)];
      const double lk = m_l[std::size_t(q)];
      sum[std::size_t(q - b)] += m_diagonal[std::size_t(k)] * lk;
      // the rows i > k of column j against column k of Z: Z_ik enters Z_ij (times L_kj) and Z_kj (times L_ij)
      const int kb = m_start[std::size_t(k)], ke = m_start[std::size_t(k) + 1];
      if(q + 1 == e || kb == ke)
        continue;
      if(ke - kb == e - q - 1 && std::equal(m_row.begin() + kb, m_row.begin() + ke, m_row.begin() + q + 1)) {
        // column k has the rows of column j below k, no more: no merge (the columns of a supernode, and chains of
        // the elimination tree; compared, as a supernodal factor's padded rows need not be in column k)
        const double* z = m_value.data() + kb;
        const double* l = m_l.data() + q + 1;
        double* below = sum.data() + (q + 1 - b);
        double to_q = 0;
        for(int t = 0; t < ke - kb; ++t) {
          below[t] += z[t] * lk;
          to_q += z[t] * l[t];
        }
        sum[std::size_t(q - b)] += to_q;
        continue;
      }
      const bool search = std::ptrdiff_t(e - q) * 16 < std::ptrdiff_t(ke - kb);
      int r = kb;
      for(int p = q + 1; p < e; ++p) {
        const int i = m_row[std::size_t(p)];
        if(search)
          r = int(std::lower_bound(m_row.begin() + r, m_row.begin() + ke, i) - m_row.begin());
        else
          while(r < ke && m_row[std::size_t(r)] < i)
            ++r;
        if(r == ke)
          break;
        if(m_row[std::size_t(r)] != i)
          continue;
        const double z = m_value[std::size_t(r)];
        sum[std::size_t(p - b)] += z * lk;
        sum[std::size_t(q - b)] += z * m_l[std::size_t(p)];
      }
    }
    double diagonal = 1 / m_d[std::size_t(j)];
    for(int q = b; q < e; ++q) {
      m_value[std::size_t(q)] = -sum[std::size_t(q - b)];
      diagonal += m_l[std::size_t(q)] * sum[std::size_t(q - b)];
    }
    m_diagonal[std::size_t(j)] = diagonal;
  }

  // Per column: 1 or 2 in one of two disjoint subtrees of about equal work (squared column lengths), 0 elsewhere.
  // From the roots down, the heaviest subtree is replaced by its children until the two heaviest are balanced.
  std::vector<char> split_in_two_subtrees(int n) const
  {
    std::vector<char> owner(std::size_t(n), 0);
    if(n < 1000)
      return owner; // not worth a thread
    const std::vector<int> parent = elimination_tree_parents(m_start, m_row);
    std::vector<double> work(std::size_t(n), 0.);
    std::vector<std::vector<int>> children((std::size_t(n)));
    std::vector<int> roots;
    for(int j = 0; j < n; ++j) {
      const int b = m_start[std::size_t(j)], e = m_start[std::size_t(j) + 1];
      work[std::size_t(j)] += double(e - b + 1) * double(e - b + 1);
      if(parent[std::size_t(j)] >= 0) {
        work[std::size_t(parent[std::size_t(j)])] += work[std::size_t(j)];
        children[std::size_t(parent[std::size_t(j)])].push_back(j);
      } else
        roots.push_back(j);
    }
    double total = 0;
    for(int r : roots)
      total += work[std::size_t(r)];
    std::vector<int> candidates = roots;
    auto heavier = [&](int a, int b) { return work[std::size_t(a)] > work[std::size_t(b)]; };
    for(int step = 0; step < 10000 && !candidates.empty(); ++step) {
      std::sort(candidates.begin(), candidates.end(), heavier);
      if(candidates.size() >= 2 && work[std::size_t(candidates[1])] >= 0.6 * work[std::size_t(candidates[0])])
        break;
      const int top = candidates.front();
      if(work[std::size_t(top)] < 0.2 * total)
        return owner; // no pair of heavy subtrees
      candidates.erase(candidates.begin());
      candidates.insert(candidates.end(), children[std::size_t(top)].begin(), children[std::size_t(top)].end());
    }
    if(candidates.size() < 2)
      return owner;
    owner[std::size_t(candidates[0])] = 1;
    owner[std::size_t(candidates[1])] = 2;
    for(int j = n - 1; j >= 0; --j)
      if(owner[std::size_t(j)] == 0 && parent[std::size_t(j)] >= 0)
        owner[std::size_t(j)] = owner[std::size_t(parent[std::size_t(j)])];
    return owner;
  }

  Unit_lower_factor m_factor;
  std::vector<int>& m_start;  // its pattern, kept
  std::vector<int>& m_row;
  std::vector<double>& m_l;   // its values, while the inverse is made (or kept)
  std::vector<double>& m_d;
  bool m_factor_kept;
  std::vector<double> m_value, m_diagonal;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_SELECTED_INVERSE_H
