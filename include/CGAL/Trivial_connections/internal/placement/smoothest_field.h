// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_SMOOTHEST_FIELD_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_SMOOTHEST_FIELD_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/solver_traits.h>
#include <CGAL/Trivial_connections/internal/factorization/fill_reducing_ordering.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The globally smoothest n-direction field of Knoeppel, Crane, Pinkall and Schroeder (SIGGRAPH 2013) on faces:
  one complex unknown u_f per face, the n-th power of the direction in the face's frame, and the Hermitian
  pencil (A, B) with
      u^H A u = sum over interior edges of w_e |u_g - r^n u_f|^2,   r = exp(i rho) the transport from f to g,
      u^H B u = sum over faces of area_f |u_f|^2.
  A is the connection Laplacian of the dual graph; it is block diagonal over the components.
*/
struct Smoothest_field_problem
{
  using Complex = std::complex<double>;
  using Sparse = Eigen::SparseMatrix<Complex>;

  Sparse A;                          // lower triangle and diagonal (the factorization reads only those)
  std::vector<double> area;          // per face: B's diagonal
  std::vector<Complex> start;        // per face: the first vector of the eigensolver
  std::vector<int> component_of_face;
  std::vector<int> component_of_vertex; // -1: a vertex without face
  int components = 0;

  template <class TriangleMesh>
  Smoothest_field_problem(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g, const Mesh_topology& t, int n)
    : component_of_face(t.component_of_face), components(int(t.components.size()))
  {
    component_of_vertex.assign(std::size_t(m.nv), -1);
    for(int v = 0; v < m.nv; ++v)
      if(t.node_of_vertex[v] >= 0)
        component_of_vertex[v] = t.component_of_node[t.node_of_vertex[v]];
    area.resize(std::size_t(m.nf));
    start.resize(std::size_t(m.nf));
    for(int f = 0; f < m.nf; ++f) {
      const Vec3& p0 = m.points[m.corner_vertex[3 * f]];
      const Vec3& p1 = m.points[m.corner_vertex[3 * f + 1]];
      const Vec3& p2 = m.points[m.corner_vertex[3 * f + 2]];
      area[f] = norm(cross(sub(p1, p0), sub(p2, p0))) / 2;
      // The start is the projection of an ambient field of the barycentre with incommensurate frequencies: it
      // depends on the geometry only (not on the numbering, nor on the frames), and has no symmetry a mesh
      // could share. A start built from the frames (u_f = 1) is symmetric on a subdivided icosahedron and
      // orthogonal to its smallest eigenvectors, which then never appear.
      const double x = (p0[0] + p1[0] + p2[0]) / 3, y = (p0[1] + p1[1] + p2[1]) / 3, z = (p0[2] + p1[2] + p2[2]) / 3;
      const Vec3 v = {{std::sin(1.31 * x + 2.17 * y + 0.73 * z + 0.3), std::cos(0.61 * x - 1.79 * y + 2.41 * z + 1.1),
                       std::sin(2.03 * x + 0.37 * y - 1.53 * z + 2.2) + 0.5}};
      Vec3 ex, ey;
      Mesh_geometry::frame(m, f, ex, ey);
      const double a = dot(v, ex), b = dot(v, ey);
      start[f] = std::polar(std::hypot(a, b), n * std::atan2(b, a));
    }
    std::vector<Eigen::Triplet<Complex>> entries;
    entries.reserve(std::size_t(3 * g.number_of_interior_edges() + m.nf));
    std::vector<double> diagonal(std::size_t(m.nf), 0.);
    for(int e = 0; e < g.number_of_interior_edges(); ++e) {
      const int i = g.edge_corner[e];
      const int f = Mesh_arrays<TriangleMesh>::face_of(i), h = Mesh_arrays<TriangleMesh>::face_of(m.opposite_corner[i]);
      const double w = g.weight[e];
      diagonal[f] += w;
      diagonal[h] += w;
      // the pairing of u_h and u_f is -w r^n (row h, column f), its conjugate above the diagonal
      const Complex coupling = -w * std::polar(1., n * g.transport[e]);
      if(h > f)
        entries.emplace_back(h, f, coupling);
      else if(h < f)
        entries.emplace_back(f, h, std::conj(coupling));
      else
        diagonal[f] -= 2 * w * std::cos(n * g.transport[e]); // an edge with one face on both sides (not manifold)
    }
    for(int f = 0; f < m.nf; ++f)
      entries.emplace_back(f, f, Complex(diagonal[f], 0.));
    A.resize(m.nf, m.nf);
    A.setFromTriplets(entries.begin(), entries.end());
  }

  // A u (A stored as its lower triangle)
  Eigen::VectorXcd apply(const Eigen::VectorXcd& u) const
  {
    return A.selfadjointView<Eigen::Lower>() * u;
  }
};

// Result of one of the solves below
struct Smoothest_field
{
  std::vector<std::complex<double>> u;      // per face
  std::vector<double> rayleigh_quotient;    // per component: u^H A u / u^H B u
  int iterations = 0;                       // eigensolver iterations (0: linear solves only)
};

/*
  The factor of A + shift B, with Eigen's simplicial LDL^T on the complex Hermitian matrix (one complex
  factor rather than real 2x2 blocks: a quarter of the index storage, the same flops). The fill-reducing order
  (Eigen's AMD) is computed on the pattern alone, and the permuted upper triangle built from A directly, which
  the factorization then reads in place: Eigen's own ordering copies the complex matrix three times on the way
  (a full symmetric copy, A + A^T grown by reallocations, the permuted copy), a tenth of a small mesh's run.
*/
class Smoothest_field_factor
{
public:
  using Complex = std::complex<double>;

  Smoothest_field_factor(const Smoothest_field_problem& p, double shift)
    : Smoothest_field_factor(p, std::vector<double>(p.area.size(), shift))
  {}

  // A + diag(shift_f area_f)
  Smoothest_field_factor(const Smoothest_field_problem& p, const std::vector<double>& shift)
  {
    const Smoothest_field_problem::Sparse& A = p.A; // lower triangle and diagonal, compressed columns
    const int n = int(A.rows());
    // the symmetric pattern: column c holds its upper entries (from the earlier columns, ascending) before its
    // lower ones, so both come sorted
    std::vector<int> start(std::size_t(n) + 1, 0), rows;
    for(int c = 0; c < n; ++c)
      for(Smoothest_field_problem::Sparse::InnerIterator it(A, c); it; ++it) {
        ++start[std::size_t(c) + 1];
        if(it.row() != c)
          ++start[std::size_t(it.row()) + 1];
      }
    for(int c = 0; c < n; ++c)
      start[std::size_t(c) + 1] += start[std::size_t(c)];
    rows.resize(std::size_t(start[std::size_t(n)]));
    {
      std::vector<int> next(start.begin(), start.end() - 1);
      for(int c = 0; c < n; ++c)
        for(Smoothest_field_problem::Sparse::InnerIterator it(A, c); it; ++it) {
          rows[std::size_t(next[std::size_t(c)]++)] = int(it.row());
          if(it.row() != c)
            rows[std::size_t(next[std::size_t(it.row())]++)] = c;
        }
    }
    std::vector<int> order;
    amd_order(n, start, rows, order);
    m_position.resize(std::size_t(n));
    for(int i = 0; i < n; ++i)
      m_position[std::size_t(order[std::size_t(i)])] = i;

    // the permuted upper triangle, entry (i, j), i <= j, holding S(order[i], order[j]): bucketed by row, then
    // distributed to the columns in row order (sorted)
    std::vector<int> row_start(std::size_t(n) + 1, 0);
    for(int c = 0; c < n; ++c)
      for(Smoothest_field_problem::Sparse::InnerIterator it(A, c); it; ++it)
        ++row_start[std::size_t((std::min)(m_position[std::size_t(c)], m_position[std::size_t(it.row())])) + 1];
    for(int i = 0; i < n; ++i)
      row_start[std::size_t(i) + 1] += row_start[std::size_t(i)];
    const std::size_t nnz = std::size_t(row_start[std::size_t(n)]);
    std::vector<int> column_of(nnz);
    std::vector<Complex> value_of(nnz);
    std::vector<int> column_count(std::size_t(n) + 1, 0);
    {
      std::vector<int> next(row_start.begin(), row_start.end() - 1);
      for(int c = 0; c < n; ++c)
        for(Smoothest_field_problem::Sparse::InnerIterator it(A, c); it; ++it) {
          const int r = int(it.row()), pr = m_position[std::size_t(r)], pc = m_position[std::size_t(c)];
          Complex v = it.value(); // S(r, c)
          if(r == c)
            v += shift[std::size_t(c)] * p.area[std::size_t(c)];
          else if(pr > pc)
            v = std::conj(v); // S(c, r) at (pc, pr)
          const int i = (std::min)(pr, pc), j = (std::max)(pr, pc);
          const int q = next[std::size_t(i)]++;
          column_of[std::size_t(q)] = j;
          value_of[std::size_t(q)] = v;
          ++column_count[std::size_t(j) + 1];
        }
    }
    Smoothest_field_problem::Sparse upper(n, n);
    upper.resizeNonZeros(Eigen::Index(nnz));
    for(int j = 0; j < n; ++j)
      column_count[std::size_t(j) + 1] += column_count[std::size_t(j)];
    std::copy(column_count.begin(), column_count.end(), upper.outerIndexPtr());
    for(int i = 0; i < n; ++i)
      for(int q = row_start[std::size_t(i)]; q < row_start[std::size_t(i) + 1]; ++q) {
        const int j = column_of[std::size_t(q)];
        const int at = column_count[std::size_t(j)]++;
        upper.innerIndexPtr()[at] = i;
        upper.valuePtr()[at] = value_of[std::size_t(q)];
      }
    m_ldlt.compute(upper);
    if(m_ldlt.info() != Eigen::Success)
      throw Invalid_input(Error_code::solver_failure, "the factorization of the smoothest-field pencil failed");
  }

  Eigen::VectorXcd solve(const Eigen::VectorXcd& r) const
  {
    const Eigen::Index n = r.size();
    Eigen::VectorXcd permuted(n);
    for(Eigen::Index f = 0; f < n; ++f)
      permuted[m_position[std::size_t(f)]] = r[f];
    permuted = m_ldlt.solve(permuted).eval();
    Eigen::VectorXcd u(n);
    for(Eigen::Index f = 0; f < n; ++f)
      u[f] = permuted[m_position[std::size_t(f)]];
    if(!u.allFinite())
      throw Invalid_input(Error_code::solver_failure, "a solve of the smoothest-field pencil did not give finite values");
    return u;
  }

private:
  std::vector<int> m_position; // face -> position in the factored order
  Eigen::SimplicialLDLT<Smoothest_field_problem::Sparse, Eigen::Upper, Eigen::NaturalOrdering<int>> m_ldlt;
};

// per component, sum over its faces of area |v_f|^2
inline std::vector<double> component_norms(const Smoothest_field_problem& p, const Eigen::VectorXcd& v)
{
  std::vector<double> s(std::size_t(p.components), 0.);
  for(Eigen::Index f = 0; f < v.size(); ++f)
    s[p.component_of_face[f]] += p.area[f] * std::norm(v[f]);
  return s;
}

// per component, a scale of its block of A's spectrum: the largest diagonal entry over the face's area (an upper
// bound of the block's largest eigenvalue up to a factor 2, by Gershgorin); 0 for a component without interior
// edge, whose block is 0
inline std::vector<double> component_spectral_scales(const Smoothest_field_problem& p)
{
  std::vector<double> s(std::size_t(p.components), 0.);
  for(int f = 0; f < int(p.area.size()); ++f) {
    double& c = s[p.component_of_face[f]];
    c = (std::max)(c, p.A.coeff(f, f).real() / p.area[f]);
  }
  return s;
}

// per face, the shift of the preconditioner A + shift B: 1e-9 times its component's spectral scale (A is singular
// when a component carries a parallel field, a flat torus for instance; the shift changes no eigenvector). Each
// component its own, so that a component's shift does not depend on the others beside it. Where a component's
// block of A is 0 (no interior edge: one triangle, or a fan of triangles with no shared edge), every field is an
// eigenvector and any positive shift does: 1 over the component's area, which has the units of A / B.
inline std::vector<double> preconditioner_shifts(const Smoothest_field_problem& p,
                                                 const std::vector<double>& scales)
{
  std::vector<double> area(std::size_t(p.components), 0.);
  for(int f = 0; f < int(p.area.size()); ++f)
    area[p.component_of_face[f]] += p.area[f];
  std::vector<double> shift(p.area.size());
  for(int f = 0; f < int(p.area.size()); ++f) {
    const int c = p.component_of_face[f];
    shift[f] = scales[c] > 0 ? 1e-9 * scales[c] : 1 / area[c];
  }
  return shift;
}
inline std::vector<double> preconditioner_shifts(const Smoothest_field_problem& p)
{
  return preconditioner_shifts(p, component_spectral_scales(p));
}

// per component, the B inner product of a and b (sum over its faces of area conj(a) b)
inline std::vector<std::complex<double>> component_products(const Smoothest_field_problem& p, const Eigen::VectorXcd& a,
                                                            const Eigen::VectorXcd& b)
{
  std::vector<std::complex<double>> s(std::size_t(p.components), 0.);
  for(Eigen::Index f = 0; f < a.size(); ++f)
    s[p.component_of_face[f]] += p.area[f] * std::conj(a[f]) * b[f];
  return s;
}

// per component, the A inner product, from a and A b
inline std::vector<std::complex<double>> component_energies(const Smoothest_field_problem& p, const Eigen::VectorXcd& a,
                                                            const Eigen::VectorXcd& Ab)
{
  std::vector<std::complex<double>> s(std::size_t(p.components), 0.);
  for(Eigen::Index f = 0; f < a.size(); ++f)
    s[p.component_of_face[f]] += std::conj(a[f]) * Ab[f];
  return s;
}

/*
  The problem with the faces of `fixed` held at `fixed_value` (Dirichlet values): their rows and columns of A
  become identity rows with B's entry 0 (so that no shift reaches them), and their couplings move to `rhs`, which
  receives -A_FP u_P on the free faces and u_P on the fixed ones. The free faces' unknowns of a solve with the
  reduced A (plus any shift times B) then minimise the energy with the fixed faces held.
*/
inline Smoothest_field_problem dirichlet_reduced(const Smoothest_field_problem& p, const std::vector<char>& fixed,
                                                 const std::vector<std::complex<double>>& fixed_value,
                                                 Eigen::VectorXcd& rhs)
{
  using Complex = std::complex<double>;
  const int nf = int(p.area.size());
  Smoothest_field_problem reduced(p);
  rhs = Eigen::VectorXcd::Zero(nf);
  std::vector<Eigen::Triplet<Complex>> entries;
  for(int c = 0; c < p.A.outerSize(); ++c)
    for(Smoothest_field_problem::Sparse::InnerIterator it(p.A, c); it; ++it) {
      const int r = int(it.row()), col = int(it.col());
      if(r == col) {
        entries.emplace_back(r, r, fixed[r] ? Complex(1., 0.) : it.value());
      } else if(fixed[r] && fixed[col]) {
      } else if(fixed[col]) {
        rhs[r] -= it.value() * fixed_value[col];
      } else if(fixed[r]) {
        rhs[col] -= std::conj(it.value()) * fixed_value[r];
      } else {
        entries.emplace_back(r, col, it.value());
      }
    }
  for(int f = 0; f < nf; ++f)
    if(fixed[f]) {
      rhs[f] = fixed_value[f];
      reduced.area[f] = 0; // no shift on an identity row
    }
  reduced.A.setZero();
  reduced.A.setFromTriplets(entries.begin(), entries.end());
  return reduced;
}

/*
  The smallest eigenvector of the pencil on every component, by the locally optimal block preconditioned conjugate
  gradient method (LOBPCG, Knyazev 2001) with block size 1, preconditioned by one factor of A + sigma B
  (preconditioner_shifts()). Each iteration is one solve with that factor (the residual A x - lambda B x
  preconditioned, which is inverse iteration's direction), then the Rayleigh-Ritz step over x, that direction and
  the previous step, per component (the components are independent blocks: one solve serves all). Plain inverse
  iteration converges as lambda_1 / lambda_2 per solve, which is slow where the smallest eigenvalues cluster (60
  solves on a 90k-face elephant); the Ritz step over three vectors converges about as the square root of that.

  Each component runs as it would alone: its own scale, its own stopping rule, and once it stops it is frozen
  (taken out of the solves' right-hand sides and the Ritz steps) while the others go on. Iterating past
  convergence is not harmless: the residual is then rounding noise, the three vectors of the Ritz step are nearly
  dependent, and the step can throw a converged component far off (a femur's quotient went from 41 to 15,000 while
  a knot beside it was still converging). For the same reason a step that raises a component's Rayleigh quotient
  (which LOBPCG never does in exact arithmetic) is undone, and the component stops there.
  Stopping rule of a component, after at least three iterations: its Rayleigh quotient lambda changed by at most
  1e-10 (lambda + 1e-8 scale) in the last iteration (converged: the quotient converges as the square of the
  vector, so the directions are then within about 1e-5 of the eigenvector's); or the singularities its field has
  (`singularities_of(u)`: n k_v per vertex, read on its vertices) were the same in the last three iterations while
  its quotient changed by at most 1e-6 (lambda + 1e-8 scale): what is read off the field is settled, though the
  vector may still drift inside a cluster of nearly equal eigenvalues (on a surface of revolution, or a sphere,
  where any field of the cluster is as smooth); or `max_iterations`.
  `fixed` (optional, per face, with `fixed_value`): faces whose u is prescribed (the boundary alignment); a
  component with such faces is solved once, with these Dirichlet values, instead of iterated.
  `on_iteration` (optional): called after each iteration with the number of iterations done and `max_iterations`.
*/
template <class SingularityReader>
Smoothest_field smoothest_field(const Smoothest_field_problem& p, const std::vector<char>& fixed,
                                const std::vector<std::complex<double>>& fixed_value,
                                const SingularityReader& singularities_of, int max_iterations = 100,
                                const std::function<void(int, int)>& on_iteration = {})
{
  using Complex = std::complex<double>;
  const int nf = int(p.area.size());
  const int nc = p.components;
  const std::vector<double> scale = component_spectral_scales(p);

  // per component: 1 while it iterates (neither Dirichlet nor stopped)
  std::vector<char> active(std::size_t(nc), 1), dirichlet(std::size_t(nc), 0);
  for(int f = 0; f < nf; ++f)
    if(!fixed.empty() && fixed[f])
      dirichlet[p.component_of_face[f]] = 1;
  for(int c = 0; c < nc; ++c)
    active[c] = !dirichlet[c];

  // with fixed faces, the free faces' unknowns solve A_FF u_F = -A_FP u_P
  Eigen::VectorXcd dirichlet_rhs = Eigen::VectorXcd::Zero(nf);
  std::optional<Smoothest_field_problem> reduced; // only with fixed faces: a copy of A costs as much as its assembly
  if(!fixed.empty())
    reduced.emplace(dirichlet_reduced(p, fixed, fixed_value, dirichlet_rhs));
  const Smoothest_field_factor factor(reduced ? *reduced : p, preconditioner_shifts(p, scale));

  Smoothest_field result;
  result.rayleigh_quotient.assign(std::size_t(nc), 0.);
  const bool any_dirichlet = std::find(dirichlet.begin(), dirichlet.end(), 1) != dirichlet.end();
  auto iterating = [&](int f) { return active[p.component_of_face[f]] != 0; };
  auto any_active = [&] { return std::find(active.begin(), active.end(), 1) != active.end(); };

  // the Dirichlet components: one solve; the others start from the geometric start vector, B-normalised
  Eigen::VectorXcd x = Eigen::Map<const Eigen::VectorXcd>(p.start.data(), nf);
  if(any_dirichlet) {
    Eigen::VectorXcd r = Eigen::VectorXcd::Zero(nf);
    for(int f = 0; f < nf; ++f)
      if(dirichlet[p.component_of_face[f]])
        r[f] = dirichlet_rhs[f];
    const Eigen::VectorXcd d = factor.solve(r);
    for(int f = 0; f < nf; ++f)
      if(dirichlet[p.component_of_face[f]])
        x[f] = d[f];
  }
  // scales a vector per active component to B-norm 1, leaving the others alone
  auto normalise = [&](Eigen::VectorXcd& v, Eigen::VectorXcd* Av) {
    const std::vector<double> norms = component_norms(p, v);
    for(int f = 0; f < nf; ++f)
      if(iterating(f) && norms[p.component_of_face[f]] > 0) {
        const double s = 1 / std::sqrt(norms[p.component_of_face[f]]);
        v[f] *= s;
        if(Av)
          (*Av)[f] *= s;
      }
  };
  normalise(x, nullptr);
  Eigen::VectorXcd Ax = p.apply(x);
  Eigen::VectorXcd P = Eigen::VectorXcd::Zero(nf), AP = Eigen::VectorXcd::Zero(nf);
  // the quotient of x per component (x is B-unit on the active ones)
  std::vector<double> lambda(std::size_t(nc), 0.);
  {
    const std::vector<Complex> e = component_energies(p, x, Ax);
    for(int c = 0; c < nc; ++c)
      lambda[c] = e[c].real();
  }
  std::vector<double> previous(lambda);
  // the singularities read at the last reading, and per component how many iterations in a row they stayed
  std::vector<std::int64_t> singularities, last_singularities;
  int last_reading = -2;
  std::vector<int> settled(std::size_t(nc), 0);
  Eigen::VectorXcd kept_x, kept_Ax; // x before the step, to undo it on a component whose quotient rose
  bool have_step = false;
  for(int it = 0; it < max_iterations && any_active(); ++it) {
    // the preconditioned residual
    Eigen::VectorXcd r(nf);
    for(int f = 0; f < nf; ++f)
      r[f] = iterating(f) ? Ax[f] - lambda[p.component_of_face[f]] * p.area[f] * x[f] : Complex(0., 0.);
    Eigen::VectorXcd W = factor.solve(r);
    for(int f = 0; f < nf; ++f)
      if(!iterating(f))
        W[f] = 0;
    // per component, the B-orthonormal basis x, w, p: Gram-Schmidt, twice (once leaves a vector whose remainder
    // is small far from orthogonal, and the Ritz step then finds quotients below the smallest eigenvalue, even
    // negative ones); a vector whose remainder after the first pass is below 1e-8 of its norm is dropped (it is
    // rounding noise in the span of the others: directions converge long before that). The A images of the kept
    // vectors are computed from them, not updated by the same subtractions, whose rounding is of the size of
    // the remainder of a vector nearly in the span of the others.
    auto orthogonalise = [&](Eigen::VectorXcd& v, const Eigen::VectorXcd& q) {
      const std::vector<Complex> d = component_products(p, q, v);
      for(int f = 0; f < nf; ++f)
        v[f] -= d[p.component_of_face[f]] * q[f];
    };
    auto orthogonalised = [&](Eigen::VectorXcd& v, const Eigen::VectorXcd* q0, const Eigen::VectorXcd* q1,
                              std::vector<char>& keep) {
      const std::vector<double> before = component_norms(p, v);
      for(int pass = 0; pass < 2; ++pass) {
        for(const Eigen::VectorXcd* q : {q0, q1})
          if(q)
            orthogonalise(v, *q);
        if(pass == 0) {
          const std::vector<double> after = component_norms(p, v);
          for(int c = 0; c < nc; ++c)
            keep[c] = active[c] && after[c] > 1e-16 * before[c] && after[c] > 0;
          for(int f = 0; f < nf; ++f)
            if(!keep[p.component_of_face[f]])
              v[f] = 0;
        }
      }
      normalise(v, nullptr);
      return p.apply(v);
    };
    std::vector<char> keep_w(std::size_t(nc), 0), keep_p(std::size_t(nc), 0);
    const Eigen::VectorXcd AW = orthogonalised(W, &x, nullptr, keep_w);
    if(have_step)
      AP = orthogonalised(P, &x, &W, keep_p);
    // the Ritz step: per component, the smallest eigenvector of the (at most) 3 x 3 Hermitian matrix Q^H A Q
    const Eigen::VectorXcd* basis[3] = {&x, &W, &P};
    const Eigen::VectorXcd* images[3] = {&Ax, &AW, &AP};
    std::vector<Eigen::Matrix3cd> H(std::size_t(nc), Eigen::Matrix3cd::Zero());
    for(int f = 0; f < nf; ++f) { // one pass for the six entries
      Eigen::Matrix3cd& h = H[p.component_of_face[f]];
      for(int a = 0; a < 3; ++a)
        for(int b = a; b < 3; ++b)
          h(a, b) += std::conj((*basis[a])[f]) * (*images[b])[f];
    }
    for(Eigen::Matrix3cd& h : H)
      for(int a = 0; a < 3; ++a)
        for(int b = 0; b < a; ++b)
          h(a, b) = std::conj(h(b, a));
    std::vector<Eigen::Vector3cd> y(std::size_t(nc), Eigen::Vector3cd(1., 0., 0.));
    for(int c = 0; c < nc; ++c) {
      if(!active[c])
        continue;
      const int k = 1 + (keep_w[c] ? 1 : 0) + (keep_p[c] ? 1 : 0);
      // the kept vectors first (w may be dropped while p is kept)
      int index[3] = {0, 1, 2}, used = 1;
      if(keep_w[c])
        index[used++] = 1;
      if(keep_p[c])
        index[used++] = 2;
      Eigen::MatrixXcd h(k, k);
      for(int a = 0; a < k; ++a)
        for(int b = 0; b < k; ++b)
          h(a, b) = H[c](index[a], index[b]);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> eigen(h);
      if(eigen.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the Ritz step of the smoothest field failed");
      Eigen::Vector3cd v = Eigen::Vector3cd::Zero();
      for(int a = 0; a < k; ++a)
        v[index[a]] = eigen.eigenvectors()(a, 0);
      y[c] = v;
    }
    // the new x, and the step (its part orthogonal to the old x)
    kept_x = x;
    kept_Ax = Ax;
    for(int f = 0; f < nf; ++f) {
      if(!iterating(f))
        continue;
      const Eigen::Vector3cd& v = y[p.component_of_face[f]];
      const Complex step = v[1] * W[f] + v[2] * P[f], Astep = v[1] * AW[f] + v[2] * AP[f];
      x[f] = v[0] * x[f] + step;
      Ax[f] = v[0] * Ax[f] + Astep;
      P[f] = step;
      AP[f] = Astep;
    }
    have_step = true;
    normalise(x, &Ax); // against the drift of rounding: x is B-unit already
    // the quotient of the new x itself (the Ritz value, but for the rounding of a step through nearly dependent
    // vectors): a component whose quotient rose gets its x back and stops
    std::vector<char> undone(std::size_t(nc), 0);
    {
      const std::vector<Complex> e = component_energies(p, x, Ax);
      for(int c = 0; c < nc; ++c) {
        if(!active[c])
          continue;
        const double q = e[c].real();
        if(q > previous[c] + 1e-12 * (std::abs(previous[c]) + 1e-8 * scale[c])) {
          undone[c] = 1;
          active[c] = 0;
        } else {
          lambda[c] = q;
        }
      }
      for(int f = 0; f < nf; ++f)
        if(undone[p.component_of_face[f]]) {
          x[f] = kept_x[f];
          Ax[f] = kept_Ax[f];
        }
    }
    result.iterations = it + 1;
    // each component's stopping rule
    std::vector<char> nearly(std::size_t(nc), 0);
    bool read = false;
    for(int c = 0; c < nc; ++c) {
      if(!active[c])
        continue;
      const double change = std::abs(lambda[c] - previous[c]), tolerance = std::abs(lambda[c]) + 1e-8 * scale[c];
      previous[c] = lambda[c];
      if(it + 1 < 3)
        continue;
      if(change <= 1e-10 * tolerance) {
        active[c] = 0; // converged
        continue;
      }
      nearly[c] = change <= 1e-6 * tolerance;
      read = read || nearly[c] || settled[c] > 0;
    }
    if(read) {
      singularities = singularities_of(x);
      std::vector<char> same(std::size_t(nc), last_reading == it - 1 ? 1 : 0);
      if(last_reading == it - 1)
        for(std::size_t v = 0; v < singularities.size(); ++v) {
          const int c = p.component_of_vertex[v];
          if(c >= 0 && singularities[v] != last_singularities[v])
            same[c] = 0;
        }
      for(int c = 0; c < nc; ++c) {
        if(!active[c] || !(nearly[c] || settled[c] > 0))
          continue;
        settled[c] = same[c] && settled[c] > 0 ? settled[c] + 1 : 1;
        if(nearly[c] && settled[c] >= 3)
          active[c] = 0; // settled
      }
      last_singularities.swap(singularities);
      last_reading = it;
    }
    if(on_iteration)
      on_iteration(it + 1, max_iterations);
  }
  // the quotients of the result, every component
  {
    const std::vector<Complex> e = component_energies(p, x, p.apply(x));
    const std::vector<double> norms = component_norms(p, x);
    for(int c = 0; c < nc; ++c)
      result.rayleigh_quotient[c] = norms[c] > 0 ? e[c].real() / norms[c] : 0.;
  }
  result.u.assign(x.data(), x.data() + nf);
  return result;
}

/*
  Knoeppel et al.'s field aligned with a guide q (per face, the n-th power of the guide's direction times its
  weight): the minimiser of u^H A u + s |u - q|_B^2, i.e. (A + s B) u = s B q, one linear solve. s has the
  units of A / B (1 / length^2); it is `strength` divided by the area of the component, so that the trade-off
  does not depend on the mesh's scale or resolution: the field follows the guide over distances longer than
  about sqrt(area / strength) and smooths it over shorter ones.
  `fixed` (optional, per face, with `fixed_value`): faces whose u is prescribed (pins); the minimiser is then
  taken over the other faces, the fixed ones held (dirichlet_reduced()).
*/
inline Smoothest_field aligned_field(const Smoothest_field_problem& p, const std::vector<std::complex<double>>& q,
                                     double strength, const std::vector<char>& fixed = {},
                                     const std::vector<std::complex<double>>& fixed_value = {})
{
  const int nf = int(p.area.size());
  std::vector<double> component_area(std::size_t(p.components), 0.);
  for(int f = 0; f < nf; ++f)
    component_area[p.component_of_face[f]] += p.area[f];
  // one factor for every component, each block with its own s_c = strength / area_c
  std::vector<double> shift(static_cast<std::size_t>(nf));
  for(int f = 0; f < nf; ++f)
    shift[f] = strength / component_area[p.component_of_face[f]];
  Eigen::VectorXcd r = Eigen::VectorXcd::Zero(nf);
  std::optional<Smoothest_field_problem> reduced;
  if(std::find(fixed.begin(), fixed.end(), 1) != fixed.end())
    reduced.emplace(dirichlet_reduced(p, fixed, fixed_value, r));
  Smoothest_field_factor factor(reduced ? *reduced : p, shift);
  for(int f = 0; f < nf; ++f)
    if(!reduced || !fixed[f])
      r[f] += shift[f] * p.area[f] * q[f];
  const Eigen::VectorXcd u = factor.solve(r);
  Smoothest_field result;
  result.u.assign(u.data(), u.data() + nf);
  const Eigen::VectorXcd Au = p.apply(u);
  result.rayleigh_quotient.assign(std::size_t(p.components), 0.);
  std::vector<double> energy(std::size_t(p.components), 0.);
  for(int f = 0; f < nf; ++f)
    energy[p.component_of_face[f]] += std::real(std::conj(u[f]) * Au[f]);
  const std::vector<double> norms = component_norms(p, u);
  for(int c = 0; c < p.components; ++c)
    result.rayleigh_quotient[c] = norms[c] > 0 ? energy[c] / norms[c] : 0.;
  return result;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_SMOOTHEST_FIELD_H
