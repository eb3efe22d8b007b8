// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_LATTICE_REDUCTION_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_LATTICE_REDUCTION_H

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The lattice Z^k of the free integers in the metric G of their energy, with a reduced basis: the columns of
  the unimodular integer matrix U, so that m = U z for integer z, and q(m) = (z - w)^T H (z - w) with
  H = U^T G U and w = U^-1 c. A reduced basis is short and nearly orthogonal in the metric, so rounding,
  nearest plane and enumeration work in it much better than in the loop basis the trees happen to give.
  U and U^-1 have integer entries, checked to stay below 2^40 (see reduce_lattice()), so the products that
  map between the two bases are exact for integer vectors; both are sparse in practice (a few entries per
  column on CGAL's meshes), and stored so.
*/
struct Reduced_lattice
{
  Eigen::SparseMatrix<double> basis;          // U: integer entries, unimodular
  Eigen::SparseMatrix<double> inverse_basis;  // U^-1: integer entries
  Eigen::MatrixXd gram;    // H = U^T G U, formed from G and U once the reduction is done
  Eigen::MatrixXd factor;  // R upper triangular, R^T R = H: its diagonal holds the Gram-Schmidt lengths
  bool reduced = false;    // false when U = I
  bool complete = true;    // the reduction ended by its own criterion, not by its work budget
  std::size_t swaps = 0;   // adjacent swaps made (a deep insertion is several)

  Eigen::Index dimension() const { return gram.rows(); }
};

namespace lattice_reduction_detail {

// Gram-Schmidt data of a basis in the metric: mu(j, i) = <b_i, b_j*> / |b_j*|^2 for j < i (column i holds
// the row i of the usual mu, contiguous) and B[j] = |b_j*|^2, with the basis in U and its inverse in V.
struct State
{
  Eigen::MatrixXd U;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> V, mu;
  Eigen::VectorXd B;
  double work = 0;
  std::size_t operations = 0; // size-reduction steps and swaps
  bool too_large = false;

  // the Gram-Schmidt data from R, upper triangular with R^T R = U^T G U: mu(j, i) = R(j, i) / R(j, j), B[j] = R(j, j)^2
  bool read_factor(const Eigen::MatrixXd& R)
  {
    const Eigen::VectorXd diagonal = R.diagonal();
    if(!(diagonal.minCoeff() > 0) || !R.allFinite())
      return false;
    mu = diagonal.cwiseInverse().asDiagonal() * R.triangularView<Eigen::StrictlyUpper>().toDenseMatrix();
    B = diagonal.cwiseAbs2();
    return true;
  }

  // b_i -= q b_j, j < i; refused (too_large set) when an entry of U or U^-1 could pass 2^40, so that every
  // entry stays an exact integer in double precision
  void subtract(Eigen::Index i, Eigen::Index j, double q)
  {
    const double limit = 1099511627776.; // 2^40
    if(!(std::abs(q) * U.col(j).cwiseAbs().maxCoeff() + U.col(i).cwiseAbs().maxCoeff() <= limit) ||
       !(std::abs(q) * V.row(i).cwiseAbs().maxCoeff() + V.row(j).cwiseAbs().maxCoeff() <= limit)) {
      too_large = true;
      return;
    }
    U.col(i) -= q * U.col(j);
    V.row(j) += q * V.row(i);
    mu.col(i).head(j) -= q * mu.col(j).head(j);
    mu(j, i) -= q;
    work += 5. * double(U.rows());
    ++operations;
  }

  // size reduction of b_i against b_j for j < i, from j = i - 1 down to `last`
  void size_reduce(Eigen::Index i, Eigen::Index last = 0)
  {
    for(Eigen::Index j = i - 1; j >= last && !too_large; --j)
      if(std::abs(mu(j, i)) > 0.51)
        subtract(i, j, std::round(mu(j, i)));
  }

  // exchange b_{i-1} and b_i, with the classical update of mu and B (Cohen, A Course in Computational
  // Algebraic Number Theory, Algorithm 2.6.3, sub-algorithm SWAP)
  void swap(Eigen::Index i)
  {
    const Eigen::Index k = U.rows();
    U.col(i).swap(U.col(i - 1));
    V.row(i).swap(V.row(i - 1));
    mu.col(i).head(i - 1).swap(mu.col(i - 1).head(i - 1));
    const double m = mu(i - 1, i);
    const double Bi = B[i] + m * m * B[i - 1];
    mu(i - 1, i) = m * B[i - 1] / Bi;
    B[i] = B[i - 1] * B[i] / Bi;
    B[i - 1] = Bi;
    for(Eigen::Index l = i + 1; l < k; ++l) {
      const double t = mu(i, l);
      mu(i, l) = mu(i - 1, l) - m * t;
      mu(i - 1, l) = t + mu(i - 1, i) * mu(i, l);
    }
    work += 6. * double(k);
    ++operations;
  }
};

} // namespace lattice_reduction_detail

/*
  LLL reduction with deep insertions (Lenstra, Lenstra and Lovasz 1982; deep insertions: Schnorr and Euchner,
  "Lattice basis reduction: improved practical algorithms and solving subset sum problems", Math.
  Programming 66, 1994) of Z^k in the metric G, in floating point: size reduction |mu_ij| <= 0.51, and b_i is
  inserted at the first position p where its projection orthogonal to b_0 ... b_{p-1} is shorter than
  delta |b_p*|^2 (delta = 0.99), by adjacent swaps; p = i - 1 is the plain LLL swap, other positions are
  tried among the first `deep` ones (the usual restriction that keeps the cost polynomial in practice).

  The Gram-Schmidt data are updated by the classical formulas (O(k) per swap or size-reduction step, where
  recomputing a row from the Gram matrix costs O(k^2)); rounding in those updates can only make the basis
  less reduced, never wrong, because U is changed by integer operations only. When the loop ends the data
  are computed again from G and U, and the loop runs again (at most three times) if they show a condition
  broken. H = U^T G U and its Cholesky factor are formed from G and the final U.

  `work_budget` bounds the multiply-adds of the reduction: when it is used up, or when an entry of U or U^-1
  would exceed 2^40 (the step is then not made), the reduction stops with the basis it has (a basis of the same lattice, only less
  reduced) and `complete` is false.
*/
inline Reduced_lattice reduce_lattice(const Eigen::MatrixXd& G, const Eigen::MatrixXd& factor_of_G,
                                      double work_budget, int deep = 8)
{
  const Eigen::Index k = G.rows();
  lattice_reduction_detail::State s;
  s.U = Eigen::MatrixXd::Identity(k, k);
  s.V = s.U;
  Reduced_lattice lattice;
  lattice.gram = G;
  lattice.factor = factor_of_G;
  if(k < 2) { // nothing to reduce
    lattice.basis = Eigen::MatrixXd::Identity(k, k).sparseView();
    lattice.inverse_basis = lattice.basis;
    return lattice;
  }
  bool stopped = !s.read_factor(factor_of_G), failed = stopped;
  std::size_t stored_at = 0; // s.operations when `lattice` last got the basis (0: the loop basis)
  // H and its factor from G and the integer U, without the drift of the updates, into `lattice`; the
  // Gram-Schmidt data again from them
  auto store = [&G, k](Reduced_lattice& lattice, lattice_reduction_detail::State& s) {
    const Eigen::SparseMatrix<double> U = s.U.sparseView(); // a few entries per column
    const Eigen::MatrixXd GU = G * U;
    Eigen::MatrixXd H = U.transpose() * GU;
    H = (H + H.transpose()) / 2;
    Eigen::LLT<Eigen::MatrixXd> llt(H);
    s.work += double(k) * double(k) * double(k) / 3 + 2. * double(k) * double(U.nonZeros());
    if(llt.info() != Eigen::Success || !s.read_factor(llt.matrixU()))
      return false; // not for a positive definite G and a unimodular U short of overflow: keep the basis before
    lattice.gram = std::move(H);
    lattice.factor = llt.matrixU();
    lattice.basis = U;
    lattice.inverse_basis = s.V.sparseView();
    return true;
  };
  // a quick pass with a weak Lovasz condition first: most of the gain for a few per cent of the swaps, so that
  // a reduction stopped by its budget still leaves a basis reduced everywhere
  for(const double delta : {0.6, 0.99}) {
    for(int round = 0; round < 3 && !stopped; ++round) {
      Eigen::Index i = 1;
      while(i < k) {
        if(s.work > work_budget || s.too_large) {
          stopped = true; // the basis so far is stored below
          break;
        }
        s.size_reduce(i, i - 1);
        if(s.B[i] < (delta - s.mu(i - 1, i) * s.mu(i - 1, i)) * s.B[i - 1]) {
          s.swap(i);
          ++lattice.swaps;
          i = (std::max)(Eigen::Index(1), i - 1);
          continue;
        }
        s.size_reduce(i);
        // deep insertion at the first position p < deep where |pi_p(b_i)|^2 < delta |b_p*|^2
        const Eigen::Index positions = (std::min)(Eigen::Index(deep), i - 1);
        Eigen::Index p = positions;
        if(positions > 0) {
          double projected = s.B[i];
          for(Eigen::Index j = 0; j < i; ++j)
            projected += s.mu(j, i) * s.mu(j, i) * s.B[j];
          for(p = 0; p < positions; ++p) {
            if(projected < delta * s.B[p])
              break;
            projected -= s.mu(p, i) * s.mu(p, i) * s.B[p];
          }
          s.work += double(i);
        }
        if(p < positions) {
          for(Eigen::Index j = i; j > p; --j, ++lattice.swaps)
            s.swap(j);
          i = (std::max)(Eigen::Index(1), p);
          continue;
        }
        ++i;
      }
      if(s.operations == stored_at)
        break; // the stored basis is this one
      if(delta < 0.99 && !stopped)
        break; // straight on to the strong condition, whose end is checked
      if(!store(lattice, s)) {
        stopped = failed = true;
        break;
      }
      stored_at = s.operations;
      if(stopped)
        break;
      bool reduced = true;
      for(Eigen::Index j = 1; j < k && reduced; ++j) {
        reduced = s.B[j] >= (delta - 0.01 - s.mu(j - 1, j) * s.mu(j - 1, j)) * s.B[j - 1];
        for(Eigen::Index l = 0; l < j && reduced; ++l)
          reduced = std::abs(s.mu(l, j)) <= 0.52;
      }
      if(reduced)
        break;
    }
  }
  if(!failed && s.operations != stored_at && !store(lattice, s))
    stopped = true; // a budget stop in the first pass: its basis
  lattice.complete = !stopped;
  if(lattice.basis.size() == 0) { // no round finished: the loop basis
    lattice.basis = Eigen::MatrixXd::Identity(k, k).sparseView();
    lattice.inverse_basis = lattice.basis;
  }
  lattice.reduced = lattice.basis.nonZeros() != k || !Eigen::MatrixXd(lattice.basis).isIdentity();
  return lattice;
}

// The work the solver allows a reduction: half the k^3 of computing the metric itself, so that the reduction
// costs about as much as the metric (and two million multiply-adds at least: about a millisecond)
inline double lattice_reduction_budget(Eigen::Index k)
{
  return double(k) * double(k) * double(k) / 2 + 2e6;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_INTEGERS_LATTICE_REDUCTION_H
