// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// The layers under Trivial_connection_solver (include/CGAL/Trivial_connections/internal/), each on its own:
// every test builds the layers it needs by hand and checks them against a definition computed here
// (brute force, dense matrices, Gauss-Bonnet), never against the solver's answers.

#include "test_support.h"

#include <CGAL/Trivial_connections/internal/factorization/checked_solve.h>
#include <CGAL/Trivial_connections/internal/factorization/fill_reducing_ordering.h>
#include <CGAL/Trivial_connections/internal/factorization/ldlt_on_two_threads.h>
#include <CGAL/Trivial_connections/internal/factorization/prefactored_system.h>
#include <CGAL/Trivial_connections/internal/field/field_propagation.h>
#include <CGAL/Trivial_connections/internal/integers/closest_vector.h>
#include <CGAL/Trivial_connections/internal/integers/loop_periods.h>
#include <CGAL/Trivial_connections/internal/placement/move_integers.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>
#include <CGAL/Trivial_connections/internal/system/system_assembly.h>
#include <CGAL/Trivial_connections/internal/topology/dual_tree_paths.h>
#include <CGAL/Trivial_connections/internal/topology/loop_holonomy.h>

#include <array>
#include <cstring>
#include <optional>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

namespace {

using namespace tc_test;
namespace TCI = CGAL::Trivial_connections::internal;

// The lower layers of a mesh, built as the solver builds them (constraint links on `constrained` and `guided`)
struct Layers
{
  const Surface_mesh& mesh;
  TCI::Mesh_arrays<Surface_mesh> arrays;
  TCI::Mesh_geometry geometry;
  TCI::Mesh_topology topology;
  TCI::Constraint_links links;
  TCI::Constraint_rows rows;

  Layers(const Surface_mesh& m, const std::vector<int>& constrained = {}, const std::vector<int>& guided = {},
         bool align = false, double mu = 1, TC::Weighting weighting = TC::Weighting::hodge_star)
    : mesh(m), arrays(m, get(CGAL::vertex_point, m), K()), geometry(arrays, weighting), topology(arrays)
  {
    topology.build_trees(arrays, geometry.edge_of_corner, geometry.edge_corner);
    geometry.compute_angles(arrays);
    links = TCI::Constraint_links(arrays, topology, constrained, guided, align, mu);
    rows = TCI::Constraint_rows(arrays, geometry, topology, links);
    rows.compute_edge_nodes(arrays);
  }
  Layers(const Layers&) = delete;

  int edges() const { return geometry.number_of_interior_edges(); }
};

// The prefactored system of the layers, loaded, factored and with its metrics as the solver makes them; M,
// dense, into `dense` when given (loading releases M)
void prefactor(const Layers& l, TCI::Prefactored_system<TC::Default_solver_traits>& system,
               Eigen::MatrixXd* dense = nullptr)
{
  std::vector<int> node_start, node_rows;
  l.topology.node_adjacency(l.arrays, node_start, node_rows);
  Eigen::SparseMatrix<double> M = TCI::system_in_row_order(l.arrays, l.rows, node_start, node_rows);
  if(dense)
    *dense = Eigen::MatrixXd(M);
  std::vector<int> node_order;
  TCI::Fill_reducing_ordering<TC::Default_solver_traits>::compute(l.topology.number_of_nodes, node_start, node_rows,
                                                                  node_order);
  system.load(l.rows, M, node_order);
  system.factor(l.rows);
  system.compute_metrics(l.rows, l.links, l.topology.components.size());
}

// A x for every unit x_e and every unit slack, as dense columns: the definition of the system's matrix
Eigen::MatrixXd constraint_matrix(const Layers& l, Eigen::MatrixXd& slack_columns)
{
  const int ne = l.edges();
  const std::size_t ng = l.links.number_of_guided_faces();
  Eigen::MatrixXd A(l.rows.size(), ne);
  for(int e = 0; e < ne; ++e) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(ne);
    x[e] = 1;
    TCI::Constraint_sums sums;
    l.rows.sums_of(x, std::vector<double>(ng, 0.), sums);
    A.col(e) = l.rows.row_sums(sums);
  }
  slack_columns.resize(l.rows.size(), Eigen::Index(ng));
  for(std::size_t g = 0; g < ng; ++g) {
    std::vector<double> s(ng, 0.);
    s[g] = 1;
    TCI::Constraint_sums sums;
    l.rows.sums_of(Eigen::VectorXd::Zero(ne), s, sums);
    slack_columns.col(Eigen::Index(g)) = l.rows.row_sums(sums);
  }
  return A;
}

// the faces around a few vertices spread over the mesh
std::vector<int> spread_faces(int nf, int count, int offset)
{
  std::vector<int> faces;
  for(int i = 0; i < count; ++i)
    faces.push_back((offset + i * (nf / count)) % nf);
  return faces;
}

// --------------------------------------------------------------------------------------------------------
// integers: the closest vector search
// --------------------------------------------------------------------------------------------------------

double q_of(const Eigen::MatrixXd& G, const Eigen::VectorXd& c, const std::vector<std::int64_t>& m)
{
  Eigen::VectorXd d(c.size());
  for(Eigen::Index i = 0; i < c.size(); ++i)
    d[i] = double(m[i]) - c[i];
  return d.dot(G * d);
}

// the minimum of q over the integer box low <= m <= high, by enumeration
double minimum_over_box(const Eigen::MatrixXd& G, const Eigen::VectorXd& c, const std::vector<std::int64_t>& low,
                        const std::vector<std::int64_t>& high)
{
  const Eigen::Index k = c.size();
  std::vector<std::int64_t> m = low;
  double best = std::numeric_limits<double>::infinity();
  while(true) {
    best = (std::min)(best, q_of(G, c, m));
    Eigen::Index i = 0;
    for(; i < k; ++i) {
      if(++m[i] <= high[i])
        break;
      m[i] = low[i];
    }
    if(i == k)
      return best;
  }
}

// the minimum of q over the integer box of half-width `r` around the rounded center
double brute_force_minimum(const Eigen::MatrixXd& G, const Eigen::VectorXd& c, int r)
{
  const Eigen::Index k = c.size();
  std::vector<std::int64_t> low(k), high(k);
  for(Eigen::Index i = 0; i < k; ++i) {
    low[i] = std::int64_t(std::llround(c[i])) - r;
    high[i] = low[i] + 2 * r;
  }
  return minimum_over_box(G, c, low, high);
}

// a random symmetric positive definite matrix, badly conditioned on purpose (rounding is then far from optimal)
Eigen::MatrixXd random_metric(std::mt19937& rng, Eigen::Index k)
{
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd B(k, k);
  for(Eigen::Index i = 0; i < k; ++i)
    for(Eigen::Index j = 0; j < k; ++j)
      B(i, j) = u(rng) + (i == j ? 0.2 : 0.);
  return B.transpose() * B + 1e-3 * Eigen::MatrixXd::Identity(k, k);
}

TEST(Closest_vector, exact_when_proven)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4, 4);
  for(int trial = 0; trial < 60; ++trial) {
    const Eigen::Index k = 1 + trial % 5;
    const Eigen::MatrixXd G = random_metric(rng, k);
    Eigen::VectorXd c(k);
    for(Eigen::Index i = 0; i < k; ++i)
      c[i] = u(rng);
    const Eigen::MatrixXd R = G.llt().matrixU();
    std::vector<std::int64_t> rounded(k);
    for(Eigen::Index i = 0; i < k; ++i)
      rounded[i] = std::llround(c[i]);
    const TCI::Closest_vector_result r = TCI::closest_vector(G, c, {rounded});
    ASSERT_TRUE(r.proven);
    EXPECT_NEAR(r.value, q_of(G, c, r.m), 1e-9 * (1 + r.value));
    // the search radius of the brute force covers the optimum: |m - c|_inf <= sqrt(q(rounded) / lambda_min)
    const double lambda_min = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues()[0];
    const int radius = int(std::ceil(std::sqrt(q_of(G, c, rounded) / lambda_min))) + 1;
    if(std::pow(2 * radius + 1, double(k)) > 3e6)
      continue;
    EXPECT_NEAR(r.value, brute_force_minimum(G, c, radius), 1e-9 * (1 + r.value)) << "k = " << k;
    EXPECT_LE(r.value, r.candidate_values[0] + 1e-12);
  }
}

TEST(Closest_vector, out_of_budget_never_worse_than_candidates_and_locally_optimal)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-20, 20);
  const Eigen::Index k = 24;
  const Eigen::MatrixXd G = random_metric(rng, k);
  const Eigen::MatrixXd R = G.llt().matrixU();
  Eigen::VectorXd c(k);
  for(Eigen::Index i = 0; i < k; ++i)
    c[i] = u(rng);
  std::vector<std::int64_t> rounded(k), zero(k, 0);
  for(Eigen::Index i = 0; i < k; ++i)
    rounded[i] = std::llround(c[i]);
  const TCI::Closest_vector_result r = TCI::closest_vector(G, c, {rounded, zero}, 1.); // 1000 nodes at most
  EXPECT_FALSE(r.proven);
  ASSERT_EQ(r.candidate_values.size(), 2u);
  EXPECT_LE(r.value, (std::min)(r.candidate_values[0], r.candidate_values[1]) + 1e-9);
  for(Eigen::Index i = 0; i < k; ++i)
    for(int step : {-1, 1}) {
      std::vector<std::int64_t> m = r.m;
      m[i] += step;
      EXPECT_GE(q_of(G, c, m), r.value - 1e-9 * (1 + r.value));
    }
}

// The refinement's price of a move with the free integers changed (Move_integers::best) is the energy change
// E(b') - E(b), E(b) = b^T M^-1 b, of actual integers s: b' = b + d (e_w - e_v) + u sum_a s_a e_{F_a}. Proven
// rounds (the integers of b nearest to the real minimiser): the best s. Unproven ones (any b): a descent from the
// integers kept and from Babai's point, never worse than keeping them.
TEST(Move_integers, prices_are_energy_changes_of_actual_integers)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u01(-1, 1);
  const Eigen::Index rows = 14;
  const std::vector<int> free = {2, 5, 7, 11};
  const double unit = 2 * CGAL_PI / 4;
  int exact = 0, priced = 0, improved = 0;
  for(int trial = 0; trial < 40; ++trial) {
    Eigen::MatrixXd B(rows, rows);
    for(Eigen::Index i = 0; i < rows; ++i)
      for(Eigen::Index j = 0; j < rows; ++j)
        B(i, j) = u01(rng);
    const Eigen::MatrixXd M = B * B.transpose() + 0.5 * Eigen::MatrixXd::Identity(rows, rows);
    const Eigen::MatrixXd G = M.inverse();
    const bool proven = trial % 2 == 0;
    // proven: lambda small on the free rows (the integers kept are the nearest); otherwise anything
    Eigen::VectorXd lambda(rows);
    for(Eigen::Index i = 0; i < rows; ++i)
      lambda[i] = 3 * u01(rng);
    if(proven)
      for(int r : free)
        lambda[r] *= 1e-3;
    const Eigen::VectorXd b = M * lambda;
    TCI::Move_integers integers({free}, rows, unit, [&](const Eigen::VectorXd& e) { return Eigen::VectorXd(G * e); });
    ASSERT_FALSE(integers.empty());
    integers.start_round(lambda, proven);
    auto energy = [&](const Eigen::VectorXd& v) { return v.dot(G * v); };
    for(int move = 0; move < 8; ++move) {
      const int rv = int(rng() % rows), rw = int(rng() % rows);
      if(rv == rw || std::count(free.begin(), free.end(), rv) || std::count(free.begin(), free.end(), rw))
        continue;
      const double d = unit * (1 + int(rng() % 3)) * (move % 2 == 0 ? 1 : -1);
      Eigen::VectorXd moved = b;
      moved[rw] += d;
      moved[rv] -= d;
      const double kept = energy(moved) - energy(b);
      const double price = integers.best(0, rv, rw, d, kept, -1e-12);
      EXPECT_LE(price, kept + 1e-9);
      // E(moved + u S s) = E(moved) + 2 u s^T (G moved)_F + u^2 s^T G_FF s; the real minimiser c1 within 3 of 0
      const Eigen::Index k = Eigen::Index(free.size());
      Eigen::MatrixXd G_FF(k, k);
      Eigen::VectorXd g_F(k);
      const Eigen::VectorXd g_moved = G * moved;
      for(Eigen::Index a = 0; a < k; ++a) {
        g_F[a] = g_moved[free[a]];
        for(Eigen::Index c = 0; c < k; ++c)
          G_FF(a, c) = G(free[a], free[c]);
      }
      const Eigen::VectorXd c1 = -G_FF.llt().solve(g_F) / unit;
      if(c1.lpNorm<Eigen::Infinity>() > 3)
        continue;
      // every integer change in a box around 0 that holds the optimum (the metric is well conditioned)
      double lowest = std::numeric_limits<double>::infinity(), nearest_to_price = lowest;
      const int span = 6;
      std::vector<int> s(free.size(), -span);
      while(true) {
        Eigen::VectorXd sv(k);
        for(Eigen::Index a = 0; a < k; ++a)
          sv[a] = s[std::size_t(a)];
        const double change = kept + 2 * unit * sv.dot(g_F) + unit * unit * sv.dot(G_FF * sv);
        lowest = (std::min)(lowest, change);
        nearest_to_price = (std::min)(nearest_to_price, std::abs(change - price));
        std::size_t a = 0;
        while(a < s.size() && ++s[a] > span)
          s[a++] = -span;
        if(a == s.size())
          break;
      }
      EXPECT_LT(nearest_to_price, 1e-8 * (1 + std::abs(price))) << "trial " << trial; // actual integers
      if(price < kept - 1e-9) { // and change() gives them
        ASSERT_EQ(integers.change().size(), free.size());
        Eigen::VectorXd sv(k);
        for(Eigen::Index a = 0; a < k; ++a)
          sv[a] = double(integers.change()[std::size_t(a)]);
        EXPECT_NEAR(kept + 2 * unit * sv.dot(g_F) + unit * unit * sv.dot(G_FF * sv), price, 1e-8 * (1 + std::abs(price)));
      }
      EXPECT_GE(price, lowest - 1e-8 * (1 + std::abs(lowest)));
      // proven: exact whenever some integers make the move pay off (best() searches only then)
      if(proven && lowest < -1e-9) {
        EXPECT_NEAR(price, lowest, 1e-8 * (1 + std::abs(lowest))) << "trial " << trial;
        // and so whenever they bring it below a threshold (the refinement's best change so far)
        EXPECT_NEAR(integers.best(0, rv, rw, d, kept, lowest / 2), lowest, 1e-8 * (1 + std::abs(lowest)));
        EXPECT_GE(integers.best(0, rv, rw, d, kept, lowest), lowest - 1e-8 * (1 + std::abs(lowest)));
        ++exact;
      }
      priced += proven ? 0 : 1;
      improved += price < kept - 1e-9 ? 1 : 0;
    }
  }
  // the cases this test is for: moves that pay off with proven integers, and unproven searches that found some
  EXPECT_GT(exact, 5);
  EXPECT_GT(priced, 20);
  EXPECT_GT(improved, 5);
}

// In a round of unproven integers the price of a move is never worse than Babai's nearest plane point of its own
// real minimiser c1 in the reduced lattice, computed here from its definition (coordinate by coordinate, last
// first, each rounded with the ones after it fixed), whether or not the move leaves that point where it was
// without the move (Move_integers reads it then from the point of the round, in O(k)). Moves of every size: tiny
// ones leave it, large ones change it. price_unproven() and best() give the same prices.
TEST(Move_integers, unproven_prices_are_never_worse_than_babais_point_of_the_moved_centre)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u01(-1, 1);
  const Eigen::Index rows = 60;
  std::vector<int> free;
  for(int r = 1; r < rows; r += 2)
    free.push_back(r);
  const Eigen::Index k = Eigen::Index(free.size());
  const double unit = 2 * CGAL_PI / 4;
  int checked = 0, improved = 0;
  for(int trial = 0; trial < 12; ++trial) {
    Eigen::MatrixXd B(rows, rows);
    for(Eigen::Index i = 0; i < rows; ++i)
      for(Eigen::Index j = 0; j < rows; ++j)
        B(i, j) = u01(rng) / std::sqrt(double(rows));
    const Eigen::MatrixXd M = B * B.transpose() + 0.2 * Eigen::MatrixXd::Identity(rows, rows);
    const Eigen::MatrixXd G = M.inverse();
    auto solve = [&](const Eigen::VectorXd& e) { return Eigen::VectorXd(G * e); };
    // from integers near the best (small lambda on the free rows) to far from it
    Eigen::VectorXd lambda(rows);
    for(Eigen::Index i = 0; i < rows; ++i)
      lambda[i] = u01(rng);
    const double scale = std::array<double, 4>{{0.05, 0.3, 1, 3}}[std::size_t(trial % 4)];
    for(int r : free)
      lambda[r] *= scale;
    const Eigen::VectorXd b = M * lambda;
    TCI::Move_integers integers({free}, rows, unit, solve);
    ASSERT_FALSE(integers.empty());
    integers.start_round(lambda, false);
    // the reduced lattice of G_FF, made as the constructor makes it
    Eigen::MatrixXd G_FF(k, k);
    for(Eigen::Index c = 0; c < k; ++c) {
      const Eigen::VectorXd column = solve(Eigen::VectorXd::Unit(rows, free[std::size_t(c)]));
      for(Eigen::Index a = 0; a < k; ++a)
        G_FF(a, c) = column[free[std::size_t(a)]];
    }
    G_FF = (G_FF + G_FF.transpose()).eval() / 2;
    const Eigen::LLT<Eigen::MatrixXd> llt(G_FF);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const TCI::Reduced_lattice lattice = TCI::reduce_lattice(G_FF, llt.matrixU(), TCI::lattice_reduction_budget(k));
    const Eigen::MatrixXd U = lattice.reduced ? Eigen::MatrixXd(lattice.basis) : Eigen::MatrixXd::Identity(k, k);
    const Eigen::MatrixXd& R = lattice.factor;
    auto energy = [&](const Eigen::VectorXd& v) { return v.dot(G * v); };
    std::vector<TCI::Move_integers::Unproven_search> searches;
    std::vector<double> prices;
    for(int move = 0; move < 30; ++move) {
      const int rv = 2 * int(rng() % (rows / 2)), rw = 2 * int(rng() % (rows / 2)); // rows without integers
      if(rv == rw)
        continue;
      const double d = unit * std::array<double, 3>{{1e-3, 0.1, 1}}[std::size_t(move % 3)] * (move % 2 == 0 ? 1 : -1);
      Eigen::VectorXd moved = b;
      moved[rw] += d;
      moved[rv] -= d;
      const double kept = energy(moved) - energy(b);
      // no threshold: best() searches every move
      const double price = integers.best(0, rv, rw, d, kept, std::numeric_limits<double>::infinity());
      EXPECT_LE(price, kept);
      const Eigen::VectorXd g_moved = G * moved;
      Eigen::VectorXd g_F(k);
      for(Eigen::Index a = 0; a < k; ++a)
        g_F[a] = g_moved[free[std::size_t(a)]];
      auto change_of = [&](const Eigen::VectorXd& s) { return kept + 2 * unit * s.dot(g_F) + unit * unit * s.dot(G_FF * s); };
      // Babai's point of c1 = -G_FF^-1 g_F / u, in reduced coordinates w = U^-1 c1
      const Eigen::VectorXd w = U.lu().solve(Eigen::VectorXd(-llt.solve(g_F) / unit));
      Eigen::VectorXd z(k);
      for(Eigen::Index i = k - 1; i >= 0; --i) {
        double tail = 0;
        for(Eigen::Index j = i + 1; j < k; ++j)
          tail += R(i, j) * (z[j] - w[j]);
        z[i] = std::round(w[i] - tail / R(i, i));
      }
      const Eigen::VectorXd babai = (U * z).array().round().matrix();
      EXPECT_LE(price, change_of(babai) + 1e-8 * (1 + std::abs(change_of(babai)))) << "trial " << trial << " move " << move;
      if(price < kept) { // actual integers, which change() gives
        ASSERT_EQ(integers.change().size(), free.size());
        Eigen::VectorXd s(k);
        for(Eigen::Index a = 0; a < k; ++a)
          s[a] = double(integers.change()[std::size_t(a)]);
        EXPECT_NEAR(change_of(s), price, 1e-8 * (1 + std::abs(price)));
        ++improved;
      }
      searches.push_back({0, rv, rw, d, kept});
      prices.push_back(price);
      ++checked;
    }
    integers.price_unproven(searches, std::numeric_limits<double>::infinity(), [](std::size_t count, const auto& f) { f(std::size_t(0), count); });
    for(std::size_t i = 0; i < searches.size(); ++i)
      EXPECT_EQ(searches[i].change, prices[i]);
  }
  EXPECT_GT(checked, 200);
  EXPECT_GT(improved, 20);
}

// LLL with deep insertions: U unimodular with U^-1 exact, H = U^T G U, and the basis size reduced and Lovasz
// reduced (delta 0.99, checked at 0.98) when the reduction completes
TEST(Lattice_reduction, unimodular_and_reduced)
{
  std::mt19937 rng(5);
  for(int trial = 0; trial < 30; ++trial) {
    const Eigen::Index k = 2 + 2 * trial;
    const Eigen::MatrixXd G = random_metric(rng, k);
    const TCI::Reduced_lattice L = TCI::reduce_lattice(G, G.llt().matrixU(), 1e12);
    ASSERT_TRUE(L.complete) << "k = " << k;
    const Eigen::MatrixXd U(L.basis), V(L.inverse_basis);
    EXPECT_EQ((U - U.array().round().matrix()).cwiseAbs().maxCoeff(), 0.);
    EXPECT_EQ((U * V - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff(), 0.) << "integer inverse, exactly";
    const Eigen::MatrixXd H = U.transpose() * G * U;
    EXPECT_LT((H - L.gram).cwiseAbs().maxCoeff(), 1e-9 * H.cwiseAbs().maxCoeff());
    EXPECT_LT((L.factor.transpose() * L.factor - H).cwiseAbs().maxCoeff(), 1e-9 * H.cwiseAbs().maxCoeff());
    // Gram-Schmidt of the reduced basis, from its own Cholesky factor
    const Eigen::MatrixXd R = H.llt().matrixU();
    for(Eigen::Index j = 1; j < k; ++j) {
      const double mu = R(j - 1, j) / R(j - 1, j - 1);
      EXPECT_GE(R(j, j) * R(j, j), (0.98 - mu * mu) * R(j - 1, j - 1) * R(j - 1, j - 1)) << "Lovasz, k = " << k;
      for(Eigen::Index i = 0; i < j; ++i)
        EXPECT_LE(std::abs(R(i, j) / R(i, i)), 0.52) << "size reduced, k = " << k;
    }
    // the Gram-Schmidt lengths multiply to the same volume: sqrt(det G)
    EXPECT_NEAR(R.diagonal().array().log().sum(), G.llt().matrixU().toDenseMatrix().diagonal().array().log().sum(),
                1e-8 * double(k));
  }
}

// A metric whose reduction needs a quotient beyond 2^40: the step is not made, the basis stays exact (the loop
// basis here) and the search still answers, no worse than rounding
TEST(Lattice_reduction, stops_before_entries_lose_exactness)
{
  const double s = 2e12, t = 2e6; // b_1 - s b_0 is short: G = B^T B, B = [1 s; 0 t]
  Eigen::MatrixXd G(2, 2);
  G << 1, s, s, s * s + t * t;
  const TCI::Reduced_lattice L = TCI::reduce_lattice(G, G.llt().matrixU(), 1e9);
  EXPECT_FALSE(L.complete);
  const Eigen::MatrixXd U(L.basis), V(L.inverse_basis);
  EXPECT_EQ((U * V - Eigen::MatrixXd::Identity(2, 2)).cwiseAbs().maxCoeff(), 0.);
  EXPECT_LE(U.cwiseAbs().maxCoeff(), 1099511627776.);
  const Eigen::VectorXd c = Eigen::Vector2d(0.3, -0.2);
  const TCI::Closest_vector_result r = TCI::closest_vector(L, G, c, {{0, 0}}, 1e5);
  EXPECT_TRUE(std::isfinite(r.value));
  EXPECT_LE(r.value, r.candidate_values[0] * (1 + 1e-12));
  EXPECT_LE(r.lower_bound, r.value);
}

// the exact minimum of q: every integer point of the box that bounds the ellipsoid q(m) <= q_max, whose
// half-widths are sqrt(q_max (G^-1)_ii); nullopt when the box has more than `limit` points
std::optional<double> brute_force_in_ellipsoid(const Eigen::MatrixXd& G, const Eigen::VectorXd& c, double q_max,
                                               double limit = 4e6)
{
  const Eigen::Index k = c.size();
  const Eigen::MatrixXd inverse = G.inverse();
  std::vector<std::int64_t> low(k), high(k);
  double points = 1;
  for(Eigen::Index i = 0; i < k; ++i) {
    const double r = std::sqrt(q_max * inverse(i, i)) + 1e-9;
    low[i] = std::int64_t(std::ceil(c[i] - r));
    high[i] = std::int64_t(std::floor(c[i] + r));
    points *= double(high[i] - low[i] + 1);
  }
  if(points > limit)
    return std::nullopt;
  return minimum_over_box(G, c, low, high);
}

// Random lattices of dimension 2 to 12: the search proves the optimum, which brute force confirms, and its lower
// bound is then the optimum; with a tiny budget, the bound still holds and the point is no worse than rounding
TEST(Closest_vector, random_lattices_exact_optimum_and_valid_bound)
{
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-6, 6);
  int checked = 0, checked_small_budget = 0;
  for(int trial = 0; trial < 110; ++trial) {
    const Eigen::Index k = 2 + trial % 11;
    // mildly conditioned, so that the brute-force box stays small; skewed, so that rounding is poor
    Eigen::MatrixXd B = Eigen::MatrixXd::Identity(k, k);
    std::uniform_real_distribution<double> shear(-1.5, 1.5);
    for(Eigen::Index i = 0; i < k; ++i)
      for(Eigen::Index j = i + 1; j < k; ++j)
        B(i, j) = shear(rng) / double(k);
    const Eigen::MatrixXd G = B.transpose() * B;
    Eigen::VectorXd c(k);
    for(Eigen::Index i = 0; i < k; ++i)
      c[i] = u(rng);
    std::vector<std::int64_t> rounded(k);
    for(Eigen::Index i = 0; i < k; ++i)
      rounded[i] = std::llround(c[i]);
    const TCI::Closest_vector_result r = TCI::closest_vector(G, c, {rounded});
    ASSERT_TRUE(r.proven) << "k = " << k;
    EXPECT_NEAR(r.value, q_of(G, c, r.m), 1e-9 * (1 + r.value));
    EXPECT_EQ(r.lower_bound, r.value);
    const std::optional<double> exact = brute_force_in_ellipsoid(G, c, r.value * (1 + 1e-9) + 1e-12);
    if(exact) {
      ++checked;
      EXPECT_NEAR(r.value, *exact, 1e-9 * (1 + r.value)) << "k = " << k;
    }
    const TCI::Closest_vector_result small = TCI::closest_vector(G, c, {rounded}, 1.);
    EXPECT_LE(small.value, small.candidate_values[0] + 1e-12);
    EXPECT_LE(small.lower_bound, r.value + 1e-9 * (1 + r.value)) << "k = " << k;
    EXPECT_GE(small.value, r.value - 1e-9 * (1 + r.value));
    checked_small_budget += small.proven ? 0 : 1;
    // no budget (the refinement's searches when the integers are not proven): no enumeration, an actual lattice
    // point at least as near as the candidate, its distance exact, and no claim
    const TCI::Closest_vector_result none = TCI::closest_vector(G, c, {rounded}, 0.);
    EXPECT_FALSE(none.proven);
    EXPECT_EQ(none.lower_bound, 0.);
    EXPECT_EQ(none.work, 0.);
    EXPECT_NEAR(none.value, q_of(G, c, none.m), 1e-9 * (1 + none.value));
    EXPECT_LE(none.value, none.candidate_values[0] + 1e-12);
    EXPECT_GE(none.value, r.value - 1e-9 * (1 + r.value));
  }
  EXPECT_GE(checked, 80) << "brute force ran on most lattices";
  std::cout << "brute force on " << checked << " of 110 lattices; " << checked_small_budget
            << " searches out of budget with a valid bound\n";
}

// "Can q get below this?": above the optimum, the optimum, proven; at or below it, an actual point no better than
// the optimum and the threshold as a lower bound, unproven
TEST(Closest_vector, wanted_below_a_threshold)
{
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-4, 4);
  int below = 0, above = 0;
  for(int trial = 0; trial < 60; ++trial) {
    const Eigen::Index k = 2 + trial % 4;
    const Eigen::MatrixXd G = random_metric(rng, k);
    Eigen::VectorXd c(k);
    for(Eigen::Index i = 0; i < k; ++i)
      c[i] = u(rng);
    std::vector<std::int64_t> rounded(k);
    for(Eigen::Index i = 0; i < k; ++i)
      rounded[i] = std::llround(c[i]);
    const std::optional<double> brute_force = brute_force_in_ellipsoid(G, c, q_of(G, c, rounded));
    if(!brute_force)
      continue;
    const double optimum = *brute_force;
    const Eigen::MatrixXd R = G.llt().matrixU();
    const TCI::Reduced_lattice lattice = TCI::reduce_lattice(G, R, TCI::lattice_reduction_budget(k));
    for(double f : {0., 0.5, 0.999, 1.001, 2.}) {
      const double wanted = f * optimum + (f > 1 ? 1e-9 : 0.);
      const TCI::Closest_vector_result r = TCI::closest_vector(lattice, G, c, {}, 1e5, wanted);
      EXPECT_NEAR(r.value, q_of(G, c, r.m), 1e-9 * (1 + r.value)); // an actual point
      if(f > 1) {
        EXPECT_TRUE(r.proven);
        EXPECT_NEAR(r.value, optimum, 1e-9 * (1 + optimum));
        ++above;
      } else {
        EXPECT_GE(r.value, optimum - 1e-9 * (1 + optimum));
        EXPECT_LE(r.lower_bound, optimum + 1e-9 * (1 + optimum));
        if(!r.proven) {
          EXPECT_NEAR(r.lower_bound, wanted, 1e-9 * (1 + wanted));
          ++below;
        } else {
          EXPECT_NEAR(r.value, optimum, 1e-9 * (1 + optimum)); // the descent found the optimum (q = wanted = 0)
        }
      }
    }
  }
  EXPECT_GT(below, 50);
  EXPECT_GT(above, 50);
}

// +-1 local search from rounding in the basis V (columns): the reference of the integer choice's tests
double local_search_in_basis(const Eigen::MatrixXd& G, const Eigen::VectorXd& c, const Eigen::MatrixXd& V)
{
  const Eigen::Index k = c.size();
  const Eigen::MatrixXd H = V.transpose() * G * V;
  const Eigen::VectorXd w = V.fullPivLu().solve(c);
  Eigen::VectorXd z = w.array().round().matrix();
  Eigen::VectorXd d = z - w, Hd = H * d;
  for(bool improved = true; improved;) {
    improved = false;
    for(Eigen::Index i = 0; i < k; ++i)
      for(double step : {-1., 1.}) {
        const double gain = 2 * step * Hd[i] + H(i, i);
        if(gain < -1e-12 * (1 + std::abs(d.dot(Hd)))) {
          z[i] += step;
          d[i] += step;
          Hd += step * H.col(i);
          improved = true;
        }
      }
  }
  return d.dot(H * d);
}

// a random unimodular matrix: the identity changed by `operations` random column additions of +-1 times another
Eigen::MatrixXd random_unimodular(std::mt19937& rng, Eigen::Index k, int operations)
{
  Eigen::MatrixXd V = Eigen::MatrixXd::Identity(k, k);
  std::uniform_int_distribution<Eigen::Index> pick(0, k - 1);
  std::bernoulli_distribution sign(0.5);
  for(int o = 0; o < operations; ++o) {
    const Eigen::Index i = pick(rng), j = pick(rng);
    if(i != j)
      V.col(i) += (sign(rng) ? 1. : -1.) * V.col(j);
  }
  return V;
}

// The integers of real and generated meshes with 50 to 300 free integers (high genus, many holes, many
// constraint links), n = 1, 2, 4, 6, for right-hand sides from the forward pass of the prefactored system: the
// loop energy the package chooses is no higher than the best of 20 +-1 local searches from rounding in random
// unimodular changes of the loop basis and in the loop basis itself, and every such search stays above the
// reported lower bound.
TEST(Loop_periods, better_than_local_searches_in_any_basis_and_bounded)
{
  struct Case
  {
    std::string name;
    Surface_mesh mesh;
    bool align;
  };
  std::vector<Case> cases;
  for(const char* file : {"elephant-with-holes.off", "cheese.off"}) {
    Surface_mesh sm;
    std::string why;
    if(read_cgal_mesh(file, sm, why))
      cases.push_back({file, std::move(sm), false});
    else
      std::cout << "skipped " << file << ": " << why << "\n";
  }
  cases.push_back({"annulus, aligned with its boundary", annulus(1, 2, 6, 60), true});
  cases.push_back({"genus 2, warped", to_surface_mesh(warped(genus2_soup(2), 0.05)), false});
  {
    std::set<std::array<int, 3>> cells; // a plate of 3 x 61 cubes with 30 holes: genus 30, 60 integers
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 61; ++j)
        if(!(i == 1 && j % 2 == 1))
          cells.insert({{i, j, 0}});
    cases.push_back({"voxel plate of genus 30", to_surface_mesh(warped(voxel_surface_soup(cells, 1), 0.05)), false});
  }
  std::mt19937 rng(23);
  std::normal_distribution<double> normal(0, 1);
  for(const Case& m : cases) {
    Layers l(m.mesh, {}, {}, m.align);
    TCI::Prefactored_system<TC::Default_solver_traits> system;
    prefactor(l, system);
    const std::vector<TCI::Reduced_lattice> lattices = TCI::reduced_loop_lattices(system.metrics());
    ASSERT_EQ(l.rows.free_slots.size(), 1u) << m.name;
    const Eigen::Index k = Eigen::Index(l.rows.free_slots[0].size());
    if(m.name.find("genus 2") == std::string::npos) {
      EXPECT_GE(k, 50) << m.name;
      EXPECT_LE(k, 300) << m.name;
    }
    const Eigen::MatrixXd& G = system.metrics()[0].inverse;
    for(int n : {1, 2, 4, 6}) {
      SCOPED_TRACE(m.name + ", k = " + std::to_string(k) + ", n = " + std::to_string(n));
      const double unit = 2 * CGAL_PI / n;
      Eigen::VectorXd b(l.rows.rows);
      for(Eigen::Index i = 0; i < b.size(); ++i)
        b[i] = normal(rng);
      const auto forward = system.forward(l.rows, b);
      const Eigen::VectorXd& y = forward.y[0];
      const std::vector<int>& free = l.rows.free_slots[0]; // slot numbers, loops then links
      const std::size_t slots = std::size_t(*std::max_element(free.begin(), free.end())) + 1;
      const std::vector<char> prescribed(slots, 0);
      const std::vector<double> holonomy(slots, 0.);
      std::vector<std::int64_t> periods(slots, 0);
      const TCI::Loop_period_choice choice = TCI::choose_loop_periods(
        l.rows.free_slots, system.metrics(), lattices, forward.y, unit, prescribed, holonomy, 1e5, periods);
      // the loop energy t^T G t, t = y + unit m, is unit^2 q(m) with q centred at c = -y / unit
      const Eigen::VectorXd c = -y / unit;
      Eigen::VectorXd t = y;
      for(Eigen::Index a = 0; a < k; ++a)
        t[a] += unit * double(periods[std::size_t(free[std::size_t(a)])]);
      const double ours = t.dot(G * t);
      EXPECT_LE(ours, choice.rounding_part + 1e-9 * (1 + ours)) << "never worse than rounding";
      EXPECT_LE(choice.lower_bound_part, ours + 1e-9 * (1 + ours));
      double best_local = unit * unit * local_search_in_basis(G, c, Eigen::MatrixXd::Identity(k, k));
      for(int s = 0; s < 20; ++s)
        best_local = (std::min)(best_local,
                                unit * unit * local_search_in_basis(G, c, random_unimodular(rng, k, int(k) / 2)));
      EXPECT_LE(ours, best_local + 1e-9 * (1 + ours));
      EXPECT_GE(best_local, choice.lower_bound_part - 1e-9 * (1 + best_local)) << "the bound holds";
      if(n == 1)
        std::cout << m.name << ": k = " << k << ", loop energy " << ours << ", best local search " << best_local
                  << ", lower bound " << choice.lower_bound_part << (choice.proven ? " (proven)" : "") << "\n";
    }
  }
}

// choose_loop_periods with some integers prescribed: the others minimise t^T G t, t = y + unit m
TEST(Loop_periods, partial_prescription_minimises_the_loop_energy)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-9, 9);
  const double unit = 2 * CGAL_PI / 4;
  for(int trial = 0; trial < 20; ++trial) {
    const Eigen::Index k = 4;
    TCI::Loop_metric metric;
    metric.inverse = random_metric(rng, k) + 0.5 * Eigen::MatrixXd::Identity(k, k);
    metric.inverse_factor = metric.inverse.llt().matrixU();
    const std::vector<std::vector<int>> free_slots = {{0, 1, 2, 3}};
    std::vector<char> prescribed = {0, char(trial % 2), 0, char(trial % 3 == 0)};
    Eigen::VectorXd y(k);
    for(Eigen::Index i = 0; i < k; ++i)
      y[i] = u(rng);
    const std::vector<double> holonomy(k, 0.);
    std::vector<std::int64_t> periods(k, 0);
    bool proven = false;
    const std::vector<TCI::Loop_metric> metrics = {metric};
    proven = TCI::choose_loop_periods(free_slots, metrics, TCI::reduced_loop_lattices(metrics), {y}, unit, prescribed,
                                      holonomy, 1e6, periods)
               .proven;
    EXPECT_TRUE(proven);
    auto energy = [&](const std::vector<std::int64_t>& m) {
      Eigen::VectorXd t = y;
      for(Eigen::Index i = 0; i < k; ++i)
        if(!prescribed[i])
          t[i] += unit * double(m[i]);
      return t.dot(metric.inverse * t);
    };
    for(Eigen::Index i = 0; i < k; ++i) {
      if(prescribed[i]) {
        EXPECT_EQ(periods[i], 0) << "a prescribed integer is left as given";
      }
    }
    // the continuous optimum of the free integers, then every integer vector within 6 of it
    std::vector<Eigen::Index> chosen;
    for(Eigen::Index i = 0; i < k; ++i)
      if(!prescribed[i])
        chosen.push_back(i);
    Eigen::MatrixXd G_QQ(chosen.size(), chosen.size());
    Eigen::VectorXd g(chosen.size());
    for(std::size_t i = 0; i < chosen.size(); ++i) {
      g[Eigen::Index(i)] = (metric.inverse * y)[chosen[i]];
      for(std::size_t j = 0; j < chosen.size(); ++j)
        G_QQ(Eigen::Index(i), Eigen::Index(j)) = metric.inverse(chosen[i], chosen[j]);
    }
    const Eigen::VectorXd continuous = -G_QQ.ldlt().solve(g) / unit;
    double best = std::numeric_limits<double>::infinity();
    std::vector<std::int64_t> m(k, 0), low(chosen.size());
    for(std::size_t i = 0; i < chosen.size(); ++i)
      low[i] = m[chosen[i]] = std::llround(continuous[Eigen::Index(i)]) - 6;
    while(true) {
      best = (std::min)(best, energy(m));
      std::size_t i = 0;
      for(; i < chosen.size(); ++i) {
        if(++m[chosen[i]] <= low[i] + 12)
          break;
        m[chosen[i]] = low[i];
      }
      if(i == chosen.size())
        break;
    }
    EXPECT_NEAR(energy(periods), best, 1e-9 * (1 + best));
  }
}

// --------------------------------------------------------------------------------------------------------
// topology: Gauss-Bonnet through the loop holonomies, loops and tree paths as dual paths
// --------------------------------------------------------------------------------------------------------

// crossings form a dual path: each enters the face the next one leaves
void expect_dual_path(const TCI::Mesh_arrays<Surface_mesh>& m, const std::vector<int>& crossings, int from, int to)
{
  int face = from;
  for(int i : crossings) {
    ASSERT_EQ(i / 3, face);
    ASSERT_GE(m.opposite_corner[i], 0);
    face = m.opposite_corner[i] / 3;
  }
  EXPECT_EQ(face, to);
}

TEST(Topology, gauss_bonnet_and_dual_loops)
{
  const std::vector<std::pair<const char*, Surface_mesh>> meshes = {
    {"disk", disk(5, 12)}, {"annulus", annulus(0.4, 1, 4, 16)}, {"torus", torus(2, 0.7, 16, 9)},
    {"genus 2", genus2()}, {"two spheres", two_spheres(2)}};
  for(const auto& [name, mesh] : meshes) {
    SCOPED_TRACE(name);
    const Layers l(mesh);
    const std::vector<double> H = TCI::levi_civita_holonomies(l.arrays, l.geometry, l.topology);
    ASSERT_EQ(H.size(), l.topology.loops.size());
    ASSERT_GE(l.arrays.nf, 100);
    // per component: sum of the interior angle defects + geodesic curvature of the boundary = 2 pi chi
    std::vector<double> total(l.topology.components.size(), 0.);
    for(int v = 0; v < l.arrays.nv; ++v)
      if(l.arrays.faces_at_vertex[v] > 0 && !l.geometry.on_boundary[v])
        total[l.topology.component_of_node[l.topology.node_of_vertex[v]]] += l.geometry.angle_defect(v);
    std::vector<int> generators(l.topology.components.size(), 0);
    for(std::size_t j = 0; j < l.topology.loops.size(); ++j) {
      const TCI::Mesh_topology::Loop& loop = l.topology.loops[j];
      if(loop.kind == TC::Loop_kind::boundary) {
        total[loop.component] += H[j];
      } else {
        ++generators[loop.component];
        EXPECT_GT(H[j], -CGAL_PI);
        EXPECT_LE(H[j], CGAL_PI);
        expect_dual_path(l.arrays, loop.crossings, loop.crossings.front() / 3, loop.crossings.front() / 3);
      }
    }
    for(std::size_t c = 0; c < total.size(); ++c) {
      const TCI::Mesh_topology::Component& comp = l.topology.components[c];
      EXPECT_NEAR(total[c], 2 * CGAL_PI * double(comp.euler_characteristic), 1e-9);
      EXPECT_EQ(generators[c], 2 * comp.genus);
      EXPECT_EQ(comp.euler_characteristic, 2 - 2 * comp.genus - comp.boundary_loops);
    }
    // paths in the dual tree between faces of a component
    const TCI::Dual_tree_order order(l.topology.parent_corner, l.topology.face_order);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> face(0, l.arrays.nf - 1);
    for(int trial = 0; trial < 50; ++trial) {
      const int a = face(rng), b = face(rng);
      if(l.topology.component_of_face[a] != l.topology.component_of_face[b])
        continue;
      std::vector<int> crossings;
      TCI::append_dual_tree_path(l.arrays.opposite_corner, l.topology.parent_corner, order.depth, a, b, crossings);
      expect_dual_path(l.arrays, crossings, a, b);
      EXPECT_LE(int(crossings.size()), order.depth[a] + order.depth[b]);
    }
  }
}

// --------------------------------------------------------------------------------------------------------
// system: the links, and the assembled matrix against A W^-1 A^T + C C^T / mu formed densely
// --------------------------------------------------------------------------------------------------------

TEST(Constraint_system, links_form_a_tree_of_dual_paths)
{
  const Surface_mesh mesh = annulus(0.4, 1, 4, 16);
  TCI::Mesh_arrays<Surface_mesh> arrays(mesh, get(CGAL::vertex_point, mesh), K());
  const TCI::Mesh_geometry geometry(arrays, TC::Weighting::hodge_star);
  TCI::Mesh_topology topology(arrays);
  topology.build_trees(arrays, geometry.edge_of_corner, geometry.edge_corner);
  const std::vector<int> constrained = {36, 48, 70}, guided = {52, 80}; // off the boundary rings
  const TCI::Constraint_links links(arrays, topology, constrained, guided, true, 0.5);
  // one link fewer than constrained faces per component, each a dual path between its faces
  EXPECT_EQ(links.links.size(), links.faces.size() - 1);
  for(const auto& link : links.links)
    expect_dual_path(arrays, link.crossings, links.faces[link.from].face, links.faces[link.to].face);
  // the links connect every constrained face: union-find over them
  std::vector<int> parent(links.faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  for(const auto& link : links.links)
    parent[find(link.from)] = find(link.to);
  for(std::size_t a = 0; a < links.faces.size(); ++a)
    EXPECT_EQ(find(int(a)), find(0));
  // aligned boundary faces first (each following a border edge of its face), then targets, then guides
  EXPECT_EQ(links.first_guided, int(links.faces.size()) - 2);
  for(std::size_t a = 0; a + 5 < links.faces.size(); ++a) {
    const int i = links.faces[a].border_corner;
    ASSERT_GE(i, 0);
    EXPECT_EQ(i / 3, links.faces[a].face);
    EXPECT_LT(arrays.opposite_corner[i], 0);
  }
  EXPECT_GE(links.seed_constraint[0], 0);
  EXPECT_FALSE(links.faces[links.seed_constraint[0]].soft);
}

TEST(Constraint_system, assembly_is_A_W_inverse_A_transpose)
{
  const Surface_mesh mesh = genus2(2);
  for(const bool with_links : {false, true}) {
    SCOPED_TRACE(with_links ? "with links and guided faces" : "cycles only");
    const int nf = int(num_faces(mesh));
    const double mu = 0.7;
    const Layers l(mesh, with_links ? spread_faces(nf, 3, 1) : std::vector<int>(),
                   with_links ? spread_faces(nf, 4, 7) : std::vector<int>(), false, mu);
    Eigen::MatrixXd C;
    const Eigen::MatrixXd A = constraint_matrix(l, C);
    Eigen::VectorXd w_inverse(l.edges());
    for(int e = 0; e < l.edges(); ++e)
      w_inverse[e] = 1 / l.geometry.weight[e];
    const Eigen::MatrixXd expected = A * w_inverse.asDiagonal() * A.transpose() + C * C.transpose() / mu;
    // the node pattern as the solver makes it
    std::vector<int> node_start, node_rows;
    l.topology.node_adjacency(l.arrays, node_start, node_rows);
    const Eigen::SparseMatrix<double> M = TCI::system_in_row_order(l.arrays, l.rows, node_start, node_rows);
    const Eigen::MatrixXd dense = Eigen::MatrixXd(M);
    ASSERT_EQ(dense.rows(), expected.rows());
    // genus 2: four generator rows; with links, slacks that couple them
    ASSERT_GT(dense.rows(), 100);
    EXPECT_EQ(l.topology.loops.size(), 4u);
    if(with_links) {
      EXPECT_EQ(l.links.links.size(), 6u);
      EXPECT_EQ(C.cols(), 4);
      EXPECT_GT((C * C.transpose()).cwiseAbs().maxCoeff(), 0.);
    }
    EXPECT_LT((dense - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
    // positive definite: the rows are independent (one node per component dropped)
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(dense).info(), Eigen::Success);
    // x = W^-1 A^T lambda and the slacks C^T lambda / mu
    Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(dense.rows(), -1, 2);
    EXPECT_LT((l.rows.connection_of(lambda) - w_inverse.asDiagonal() * A.transpose() * lambda).cwiseAbs().maxCoeff(),
              1e-12 * (1 + lambda.cwiseAbs().maxCoeff()));
    const std::vector<double> s = l.rows.slacks(lambda);
    for(std::size_t g = 0; g < s.size(); ++g)
      EXPECT_NEAR(s[g], C.col(Eigen::Index(g)).dot(lambda) / mu, 1e-12);
    // in factor order: the fill-reducing order of the nodes, then the free rows last, upper triangle kept
    std::vector<int> node_order(std::size_t(l.topology.number_of_nodes));
    std::iota(node_order.rbegin(), node_order.rend(), 0);
    const TCI::Row_permutation P = TCI::loop_rows_last(l.rows, node_order);
    const Eigen::Index first = l.rows.rows - Eigen::Index(l.rows.free_rows.size());
    for(int r : l.rows.free_rows)
      EXPECT_GE(P.indices()[r], first);
    const Eigen::SparseMatrix<double> ordered = TCI::ordered_system(M, P, Eigen::Upper);
    const Eigen::MatrixXd permuted = Eigen::MatrixXd(P * dense * P.transpose());
    EXPECT_EQ((Eigen::MatrixXd(ordered) - Eigen::MatrixXd(permuted.triangularView<Eigen::Upper>())).cwiseAbs().maxCoeff(), 0.);
  }
}

// With the boundary aligned (n = 4), the decided fans of the boundary vertices are rows of the factor, each placed
// right after the last of its nodes that are not free rows. A boundary loop's node is a free row, last in the
// factor: were the rows anchored at it, every fan of the boundary would sit at the top of the elimination tree,
// on the path of every vertex (holes.off: four times the work per path).
TEST(Constraint_system, decided_fan_rows_follow_their_last_node_not_the_boundary_loop)
{
  const Surface_mesh mesh = annulus(1, 2, 6, 60);
  TCI::Mesh_arrays<Surface_mesh> arrays(mesh, get(CGAL::vertex_point, mesh), K());
  TCI::Mesh_geometry geometry(arrays, TC::Weighting::hodge_star);
  TCI::Mesh_topology topology(arrays);
  topology.build_trees(arrays, geometry.edge_of_corner, geometry.edge_corner);
  geometry.compute_angles(arrays);
  TCI::Constraint_links links(arrays, topology, {}, {}, true, 1., {}, 4, 4);
  const TCI::Constraint_rows rows(arrays, geometry, topology, links);
  std::vector<char> is_free(std::size_t(rows.rows), 0);
  for(int r : rows.free_rows)
    is_free[std::size_t(r)] = 1;
  // the node order a factorization hands back (Prefactored_system::node_order()): the free rows' nodes last
  std::vector<int> node_order(std::size_t(topology.number_of_nodes));
  std::iota(node_order.begin(), node_order.end(), 0);
  std::stable_partition(node_order.begin(), node_order.end(), [&](int node) {
    const int r = rows.row_of_node[std::size_t(node)];
    return r < 0 || !is_free[std::size_t(r)];
  });
  const TCI::Row_permutation P = TCI::loop_rows_last(rows, node_order);
  std::vector<int> row_at(std::size_t(rows.rows));
  for(int r = 0; r < int(rows.rows); ++r)
    row_at[std::size_t(P.indices()[r])] = r;
  std::vector<char> is_decided(std::size_t(rows.rows), 0);
  for(int l : rows.decided_slots)
    if(rows.row_of_slot[std::size_t(l)] >= 0)
      is_decided[std::size_t(rows.row_of_slot[std::size_t(l)])] = 1;
  const int first_free = int(rows.rows) - int(rows.free_rows.size());
  std::size_t d = 0, checked = 0;
  for(int l : rows.decided_slots) {
    const int r = rows.row_of_slot[std::size_t(l)];
    if(r < 0)
      continue;
    int last = -1; // the position of its last node row that is not free
    bool touches_the_boundary = false;
    for(int p = rows.decided_row_node_start[d]; p < rows.decided_row_node_start[d + 1]; ++p) {
      const int node_row = rows.row_of_node[std::size_t(rows.decided_row_nodes[std::size_t(p)])];
      if(node_row >= 0 && is_free[std::size_t(node_row)])
        touches_the_boundary = true;
      else if(node_row >= 0)
        last = (std::max)(last, P.indices()[node_row]);
    }
    ++d;
    const int position = P.indices()[r];
    EXPECT_LT(position, first_free);
    EXPECT_GT(position, last);
    for(int q = last + 1; q < position; ++q)
      EXPECT_TRUE(is_decided[std::size_t(row_at[std::size_t(q)])]) << "only decided rows between row " << r
                                                                    << " and its last node";
    checked += touches_the_boundary;
  }
  // one circle's node is the pinned node (no row); the other's 60 fans, but those left free
  EXPECT_GE(checked, 50u) << "the fans of the boundary circle with a row";
}

// The prefactored system's split solve (forward, then the integers, then backward) gives the multipliers of
// the full system M lambda = b with the integers added to b on the free rows; checked against a dense solve.
TEST(Prefactored_system, split_solve_matches_a_dense_solve)
{
  const Surface_mesh mesh = genus2();
  const int nf = int(num_faces(mesh));
  Layers l(mesh, spread_faces(nf, 3, 1), spread_faces(nf, 2, 9), false, 2.);
  Eigen::MatrixXd dense;
  TCI::Prefactored_system<TC::Default_solver_traits> system;
  prefactor(l, system, &dense);
  ASSERT_TRUE(system.loop_rows_in_factor());

  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(dense.rows(), -0.5, 0.8);
  const Eigen::VectorXd direct = dense.ldlt().solve(b);
  EXPECT_LT((system.solve(l.rows, b) - direct).cwiseAbs().maxCoeff(), 1e-10 * direct.cwiseAbs().maxCoeff());
  // the metric is (M^-1) on the free rows
  const Eigen::MatrixXd inverse = dense.inverse();
  const std::vector<int>& free = l.rows.free_slots[0];
  const TCI::Loop_metric& metric = system.metrics()[0];
  for(std::size_t a = 0; a < free.size(); ++a)
    for(std::size_t c = 0; c < free.size(); ++c)
      EXPECT_NEAR(metric.inverse(Eigen::Index(a), Eigen::Index(c)),
                  inverse(l.rows.row_of_slot[free[a]], l.rows.row_of_slot[free[c]]), 1e-9);
  // integers m on the free rows: backward(y + m) solves M lambda = b + m on those rows
  auto forward = system.forward(l.rows, b);
  std::vector<Eigen::VectorXd> t = forward.y;
  Eigen::VectorXd b_with = b;
  for(std::size_t a = 0; a < free.size(); ++a) {
    const double m = double(int(a % 3) - 1) * 0.25;
    t[0][Eigen::Index(a)] += m;
    b_with[l.rows.row_of_slot[free[a]]] += m;
  }
  const Eigen::VectorXd lambda = system.backward(l.rows, forward, t, b_with);
  const Eigen::VectorXd expected = dense.ldlt().solve(b_with);
  EXPECT_LT((lambda - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
  // the loop part of the energy b^T M^-1 b is t^T S^-1 t, the rest is the node part
  EXPECT_NEAR(forward.node_part + t[0].dot(metric.inverse * t[0]), b_with.dot(expected), 1e-9 * b_with.dot(expected));
}

// --------------------------------------------------------------------------------------------------------
// field: propagation along the dual tree, rotations onto targets and guides
// --------------------------------------------------------------------------------------------------------

// a connection that carries a given angle per face to its neighbours exactly: trivial by construction
std::vector<double> connection_carrying(const Layers& l, const std::vector<double>& theta)
{
  std::vector<double> x(3 * std::size_t(l.arrays.nf), 0.);
  for(int i = 0; i < 3 * l.arrays.nf; ++i) {
    const int o = l.arrays.opposite_corner[i];
    if(o >= 0)
      x[i] = theta[o / 3] - theta[i / 3] - l.geometry.transport_angle(i);
  }
  return x;
}

// per corner halfedge values as a map on the mesh's halfedges
std::unordered_map<Surface_mesh::Halfedge_index, double> per_halfedge(const Layers& l, const std::vector<double>& x)
{
  std::unordered_map<Surface_mesh::Halfedge_index, double> map;
  for(int i = 0; i < 3 * l.arrays.nf; ++i)
    map[l.arrays.halfedges[i]] = x[i];
  return map;
}

TEST(Field, propagation_reproduces_a_parallel_field)
{
  const Surface_mesh mesh = two_spheres(2);
  const Layers l(mesh);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-CGAL_PI, CGAL_PI);
  std::vector<double> theta(std::size_t(l.arrays.nf));
  for(double& t : theta)
    t = u(rng);
  const std::vector<double> x = connection_carrying(l, theta);
  const auto by_halfedge = per_halfedge(l, x);
  const boost::const_associative_property_map<std::unordered_map<Surface_mesh::Halfedge_index, double>> xmap(by_halfedge);
  // seed on the second sphere: it gets theta exactly, the first sphere theta up to one rotation
  const int seed = l.arrays.nf - 1;
  const std::vector<double> angle =
    TCI::field_angles(l.arrays, l.geometry, l.topology, l.links, xmap, {}, std::nullopt, seed, theta[seed]);
  const int root = l.topology.components[0].root_face;
  for(int f = 0; f < l.arrays.nf; ++f) {
    const double expected = l.topology.component_of_face[f] == l.topology.component_of_face[seed]
                              ? theta[f]
                              : theta[f] - theta[root]; // the first component starts at angle 0 in its root
    EXPECT_NEAR(wrap(angle[f] - expected), 0., 1e-9) << "face " << f;
  }
  // the vectors: unit, tangent, at that angle in the face frame
  std::unordered_map<Surface_mesh::Face_index, Vector> by_face;
  TCI::write_field(l.arrays, angle, K(), boost::associative_property_map<std::unordered_map<Surface_mesh::Face_index, Vector>>(by_face));
  for(int f = 0; f < l.arrays.nf; ++f) {
    const Vector v = by_face.at(l.arrays.face_descriptors[f]);
    TCI::Vec3 ex, ey;
    TCI::Mesh_geometry::frame(l.arrays, f, ex, ey);
    const TCI::Vec3 n = TCI::cross(ex, ey);
    EXPECT_NEAR(v.squared_length(), 1., 1e-12);
    EXPECT_NEAR(v.x() * n[0] + v.y() * n[1] + v.z() * n[2], 0., 1e-12);
    EXPECT_NEAR(std::atan2(v.x() * ey[0] + v.y() * ey[1] + v.z() * ey[2], v.x() * ex[0] + v.y() * ex[1] + v.z() * ex[2]),
                angle[f], 1e-12);
  }
}

TEST(Field, rotations_onto_targets_and_guides)
{
  const Surface_mesh mesh = two_spheres(2);
  const int nf = int(num_faces(mesh));
  // a target on the first sphere, guides only on the second
  const Layers l(mesh, {3}, {nf - 5, nf - 40, nf - 77});
  ASSERT_NE(l.topology.component_of_face[3], l.topology.component_of_face[nf - 5]);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-CGAL_PI, CGAL_PI);
  std::vector<double> theta((std::size_t(nf))); // not a declaration
  for(double& t : theta)
    t = u(rng);
  const std::vector<double> x = connection_carrying(l, theta);
  const auto by_halfedge = per_halfedge(l, x);
  const boost::const_associative_property_map<std::unordered_map<Surface_mesh::Halfedge_index, double>> xmap(by_halfedge);
  std::vector<double> target(l.links.faces.size());
  for(double& t : target)
    t = u(rng);
  const int n = 4;
  // without n, guides only cannot be honoured
  EXPECT_THROW(TCI::field_angles(l.arrays, l.geometry, l.topology, l.links, xmap, target, std::nullopt, -1, 0.),
               TC::Invalid_input);
  const std::vector<double> angle = TCI::field_angles(l.arrays, l.geometry, l.topology, l.links, xmap, target, n, -1, 0.);
  // the target is met exactly
  EXPECT_NEAR(wrap(angle[3] - target[0]), 0., 1e-9);
  // the guided component's rotation minimises sum_g d_g^2 (d_g modulo 2 pi / n): compare with a fine scan
  const double period = 2 * CGAL_PI / n;
  auto cost = [&](double phi) {
    double s = 0;
    for(std::size_t a = std::size_t(l.links.first_guided); a < l.links.faces.size(); ++a) {
      const double d = wrap(theta[l.links.faces[a].face] + phi - target[a], period);
      s += d * d;
    }
    return s;
  };
  const int g = l.links.faces[std::size_t(l.links.first_guided)].face;
  const double phi = angle[g] - theta[g];
  double best = std::numeric_limits<double>::infinity();
  for(int i = 0; i < 200000; ++i)
    best = (std::min)(best, cost(period * i / 200000.));
  EXPECT_LE(cost(phi), best + 1e-9);
  // and the rotation is one rotation of the whole component
  for(int f = 0; f < nf; ++f) {
    if(l.topology.component_of_face[f] == l.topology.component_of_face[g]) {
      EXPECT_NEAR(wrap(angle[f] - theta[f] - phi), 0., 1e-9);
    }
  }
}

// The pattern of the node rows of a mesh's system (both triangles and the diagonal, compressed columns)
struct Node_pattern
{
  std::vector<int> start, rows;
  int n = 0;
};

Node_pattern node_pattern(const Surface_mesh& sm)
{
  const Layers l(sm);
  Node_pattern pattern;
  l.topology.node_adjacency(l.arrays, pattern.start, pattern.rows);
  pattern.n = l.topology.number_of_nodes;
  return pattern;
}

} // namespace

/*
  The cost of a factor predicted from the pattern alone (elimination tree, internal/factorization/factor_cost.h)
  is Eigen's own symbolic analysis: the same nonzeros of L in any order. METIS's nested dissection (when built
  with it) is a permutation whose factor is cheaper than the natural order's on a grid-like mesh. The backend
  chosen by predicted cost (with CHOLMOD) keeps the simplicial factor on a small mesh, CHOLMOD when its crossover
  says so, and solves as Eigen does either way.
*/
TEST(Factor_cost, predicted_from_the_pattern_as_the_analysis_counts_it)
{
  const Node_pattern pattern = node_pattern(icosphere(4));
  const std::vector<int>&node_start = pattern.start, &node_rows = pattern.rows;
  const int n = pattern.n;
  // an SPD matrix of that pattern (a shifted graph Laplacian): the analysis reads the pattern only
  std::vector<Eigen::Triplet<double>> entries;
  for(int c = 0; c < n; ++c)
    for(int p = node_start[std::size_t(c)]; p < node_start[std::size_t(c) + 1]; ++p) {
      const int r = node_rows[std::size_t(p)];
      entries.emplace_back(r, c, r == c ? node_start[std::size_t(c) + 1] - node_start[std::size_t(c)] + 1. : -1.);
    }
  Eigen::SparseMatrix<double> nodes(n, n);
  nodes.setFromTriplets(entries.begin(), entries.end());
  std::vector<int> natural(static_cast<std::size_t>(n)), amd;
  for(int i = 0; i < n; ++i) natural[std::size_t(i)] = i;
  TCI::amd_order(n, node_start, node_rows, amd);
  std::vector<std::vector<int>> orders = {natural, amd};
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_METIS
  // 100 rows: the dissection of large patterns, the first separator and then both halves at once on two threads
  for(const int parallel_rows : {100000, 100}) {
    std::vector<int> nested;
    ASSERT_TRUE(TCI::metis_order(n, node_start, node_rows, nested, parallel_rows));
    std::vector<int> sorted = nested;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, natural) << "METIS's order is a permutation";
    EXPECT_LT(TCI::elimination_cost(n, node_start, node_rows, nested).flops,
              TCI::elimination_cost(n, node_start, node_rows, natural).flops);
    orders.push_back(nested);
  }
#endif
  for(const std::vector<int>& order : orders) {
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
    for(int k = 0; k < n; ++k) P.indices()[order[std::size_t(k)]] = k; // row -> position
    Eigen::SparseMatrix<double> ordered(n, n);
    ordered = nodes.twistedBy(P);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(ordered);
    ASSERT_EQ(ldlt.info(), Eigen::Success);
    const TCI::Factor_cost cost = TCI::elimination_cost(n, node_start, node_rows, order);
    EXPECT_EQ(cost.nonzeros, double(ldlt.matrixL().nestedExpression().nonZeros()));
    EXPECT_GE(cost.flops, cost.nonzeros);
  }
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
  for(int k = 0; k < n; ++k) P.indices()[amd[std::size_t(k)]] = k;
  Eigen::SparseMatrix<double> full(n, n);
  full = nodes.twistedBy(P);
  CGAL::Eigen_sparse_matrix<double> ordered(n, n);
  ordered.eigen_object() = full.triangularView<Eigen::Lower>();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1., 2.);
  const Eigen::VectorXd expected = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>(full).solve(b);
  const TCI::Factor_cost cost = TCI::elimination_cost(n, node_start, node_rows, amd);
  auto check = [&](auto& traits, TC::Factorization_backend backend) {
    double d = 0;
    ASSERT_TRUE(traits.factor(ordered, d));
    EXPECT_EQ(traits.backend(), backend);
    EXPECT_EQ(traits.factor_nonzeros(), cost.nonzeros);
    EXPECT_EQ(traits.factor_flops(), cost.flops);
    CGAL::Eigen_vector<double> rhs(n), x(n);
    rhs.eigen_object() = b;
    ASSERT_TRUE(traits.linear_solver(rhs, x));
    EXPECT_LT((x.eigen_object() - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
  };
  TC::Automatic_solver_traits automatic; // 2.5k nodes: far below the crossover
  check(automatic, TC::Factorization_backend::simplicial_ldlt);
  TC::Cost_based_solver_traits<Always_supernodal> supernodal;
  check(supernodal, TC::Factorization_backend::cholmod_supernodal);
#endif
}

namespace {

// An SPD matrix of a node pattern (a shifted graph Laplacian with uneven weights) in Eigen's AMD order.
Eigen::SparseMatrix<double> amd_ordered_laplacian(const Node_pattern& pattern)
{
  const int n = pattern.n;
  std::vector<Eigen::Triplet<double>> entries;
  for(int c = 0; c < n; ++c) {
    double diagonal = 1e-3;
    for(int p = pattern.start[std::size_t(c)]; p < pattern.start[std::size_t(c) + 1]; ++p) {
      const int r = pattern.rows[std::size_t(p)];
      if(r == c)
        continue;
      const double w = 1. + 0.25 * double((std::min(r, c) * 7 + std::max(r, c) * 3) % 5);
      entries.emplace_back(r, c, -w);
      diagonal += w;
    }
    entries.emplace_back(c, c, diagonal);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  std::vector<int> amd;
  TCI::amd_order(n, pattern.start, pattern.rows, amd);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
  for(int k = 0; k < n; ++k) P.indices()[amd[std::size_t(k)]] = k; // row -> position
  Eigen::SparseMatrix<double> ordered(n, n);
  ordered = A.twistedBy(P);
  return ordered;
}

// Factors `full` (its triangle UpLo) with Eigen and with Ldlt_on_two_threads; returns whether the latter ran, and
// in `full_top_block` whether it factored the top rows as a dense block.
template <int UpLo>
bool expect_two_threads_equal_eigen(const Eigen::SparseMatrix<double>& full, Eigen::ComputationInfo expected,
                                    bool* full_top_block = nullptr)
{
  using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, UpLo, Eigen::NaturalOrdering<int>>;
  const Eigen::SparseMatrix<double> stored = full.triangularView<UpLo>();
  Ldlt eigen, ours;
  eigen.compute(stored);
  ours.analyzePattern(stored);
  const bool on_two_threads = TCI::Ldlt_on_two_threads<Ldlt>::factorize(ours, stored, full_top_block);
  if(!on_two_threads)
    ours.factorize(stored);
  EXPECT_EQ(eigen.info(), expected);
  EXPECT_EQ(ours.info(), expected);
  if(expected != Eigen::Success)
    return on_two_threads;
  const auto& L0 = eigen.matrixL().nestedExpression();
  const auto& L1 = ours.matrixL().nestedExpression();
  EXPECT_EQ(L0.nonZeros(), L1.nonZeros());
  if(L0.nonZeros() != L1.nonZeros())
    return on_two_threads;
  int different_rows = 0;
  double worst = 0;
  for(Eigen::Index p = 0; p < L0.nonZeros(); ++p) {
    different_rows += L0.innerIndexPtr()[p] != L1.innerIndexPtr()[p];
    worst = (std::max)(worst, std::abs(L0.valuePtr()[p] - L1.valuePtr()[p]) / (1 + std::abs(L0.valuePtr()[p])));
  }
  for(Eigen::Index j = 0; j < full.rows(); ++j)
    worst = (std::max)(worst, std::abs(eigen.vectorD()[j] - ours.vectorD()[j]) / std::abs(eigen.vectorD()[j]));
  EXPECT_EQ(different_rows, 0) << "the same entries of L, in the same places";
  EXPECT_LT(worst, 1e-12) << "the same values up to rounding";
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(full.rows(), -1., 2.);
  const Eigen::VectorXd x = ours.solve(b);
  EXPECT_LT((full * x - b).norm(), 1e-9 * b.norm());
  return on_two_threads;
}

} // namespace

/*
  The numeric factorization on two threads (internal/factorization/ldlt_on_two_threads.h) is Eigen's own up to
  rounding: the same entries of L in the same places, values and pivots within 1e-12, on patterns whose
  elimination trees split differently (one closed surface; two components, a forest; a disk, whose boundary is
  one node joined to every boundary vertex), from either triangle, with the top rows factored as a dense block
  (the sphere) and row by row (the others). A zero pivot is reported as Eigen reports it,
  and a small matrix is left to Eigen. Without a second thread the same steps run on one (see below).
*/
TEST(Ldlt_on_two_threads, equals_eigens_factorization_up_to_rounding)
{
  const bool expected_threads = true; // ours above the threshold, with or without a second thread
  // just above the threshold of two threads, so that the sanitizer build stays quick
  const std::vector<std::pair<std::string, Surface_mesh>> meshes = {
    {"icosphere", icosphere(5)}, {"two spheres", two_spheres(5)}, {"disk", disk(60, 240)}};
  Eigen::SparseMatrix<double> sphere;
  int full_top_blocks = 0, sparse_top_blocks = 0;
  for(const auto& [name, mesh] : meshes) {
    SCOPED_TRACE(name);
    const Eigen::SparseMatrix<double> full = amd_ordered_laplacian(node_pattern(mesh));
    for(bool upper : {true, false}) {
      bool full_top_block = false;
      EXPECT_EQ(upper ? expect_two_threads_equal_eigen<Eigen::Upper>(full, Eigen::Success, &full_top_block)
                      : expect_two_threads_equal_eigen<Eigen::Lower>(full, Eigen::Success, &full_top_block),
                expected_threads);
      if(name == "icosphere")
        EXPECT_EQ(full_top_block, expected_threads) << "a sphere's root separator is a dense block";
      ++(full_top_block ? full_top_blocks : sparse_top_blocks);
    }
    if(name == "icosphere")
      sphere = full;
  }
  if(expected_threads)
    EXPECT_GT(sparse_top_blocks, 0) << "the top rows' sparse path is tried too";
  // a row and column of zeros: a zero pivot
  Eigen::SparseMatrix<double> singular = sphere;
  const Eigen::Index zero = singular.rows() / 3;
  singular.prune([zero](Eigen::Index r, Eigen::Index c, double) { return r != zero && c != zero; });
  EXPECT_EQ(expect_two_threads_equal_eigen<Eigen::Upper>(singular, Eigen::NumericalIssue), expected_threads);
  // below the threshold (about 3 ms of work): Eigen's
  EXPECT_FALSE(expect_two_threads_equal_eigen<Eigen::Upper>(amd_ordered_laplacian(node_pattern(icosphere(3))),
                                                            Eigen::Success));
}

/*
  The factor does not depend on the cores: on one usable core (this thread's affinity, as a batch pins its
  workers' programs) the same steps run on one thread and give the factor of two threads to the last bit, so a
  program's files are the same bytes on any machine.
*/
TEST(Ldlt_on_two_threads, the_same_factor_to_the_last_bit_on_one_core)
{
#if defined(__linux__) && defined(CPU_COUNT)
  cpu_set_t all;
  CPU_ZERO(&all);
  ASSERT_EQ(sched_getaffinity(0, sizeof(all), &all), 0);
  using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>;
  const Eigen::SparseMatrix<double> stored =
    Eigen::SparseMatrix<double>(amd_ordered_laplacian(node_pattern(icosphere(5))).triangularView<Eigen::Upper>());
  auto factor = [&stored] {
    Ldlt s;
    s.analyzePattern(stored);
    EXPECT_TRUE(TCI::Ldlt_on_two_threads<Ldlt>::factorize(s, stored));
    const auto& L = s.matrixL().nestedExpression();
    // the entries of the columns (the storage may hold more, unused)
    std::vector<double> values(L.valuePtr(), L.valuePtr() + L.outerIndexPtr()[L.outerSize()]);
    const Eigen::VectorXd D = s.vectorD(); // a copy: vectorD() returns by value
    values.insert(values.end(), D.data(), D.data() + D.size());
    return values;
  };
  const std::vector<double> free = factor();
  int first = 0;
  while(first < CPU_SETSIZE && !CPU_ISSET(first, &all))
    ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);
  EXPECT_EQ(TCI::usable_cores(), 1u);
  const std::vector<double> pinned = factor();
  ASSERT_EQ(sched_setaffinity(0, sizeof(all), &all), 0);
  ASSERT_EQ(free.size(), pinned.size());
  EXPECT_EQ(std::memcmp(free.data(), pinned.data(), free.size() * sizeof(double)), 0);
#else
  GTEST_SKIP() << "the affinity of a thread is read on Linux only";
#endif
}
