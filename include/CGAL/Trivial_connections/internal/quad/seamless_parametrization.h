// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_SEAMLESS_PARAMETRIZATION_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_SEAMLESS_PARAMETRIZATION_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/quad/cut_graph.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The second layer of quad meshing (issue 43): a map (u, v) per corner, linear on each face, minimising
      E = sum_f area_f ( |grad u - d_f / H|^2 + |grad v - J d_f / H|^2 )
  with d_f the combed direction of the cross field on f (angle + combing quarter turns) and J the quarter turn
  about the face normal, under the seamless transitions of the cut graph: across every interior cut edge of arc
  a, the corners of the right side are those of the left side turned by R^q_a plus t_a,
      w_right = R^q_a w_left + t_a ,   R = the counter-clockwise quarter turn of the (u, v) plane,
  q_a = -(the arc's combed matching): a field turned by r quarter turns from left to right has its (u, v) turned
  back by r. t_a is one unknown per arc (continuous: integer rounding is the next layer's).

  The unknowns z are a "root" (u, v) per vertex (the value of its first wedge, a wedge being a maximal fan of
  corners at the vertex not separated by the cut) and t_a per arc: the other wedges of a vertex follow from the
  root by the transitions crossed going counter-clockwise around it. Going all the way around an interior vertex
  gives its closure (R^Q - I) root + (a combination of the t_a) = 0: at a regular vertex inside an arc it is
  0 = 0, at a branch vertex a relation between the t_a, and at a singular vertex (Q != 0, R^Q - I invertible) it
  makes the root the fixed point of the transitions around it. The closures, one gauge per component (a vertex
  at (0, 0)) and any values the caller fixes (fix(): the next layer's integers, for singular roots and t_a) form
  a small dense system G z_S = h on the few unknowns they involve; z_S = z_particular + K tau with K a basis of
  its kernel, the other unknowns stay as they are, and the least squares in (free unknowns, tau) is solved by a
  sparse Cholesky factorization (SimplicialLDLT, AMD order) of its normal equations.
*/
class Seamless_parametrization
{
public:
  using Sparse = Eigen::SparseMatrix<double>;
  using UV = std::array<double, 2>;

  struct Map
  {
    std::vector<UV> corner_uv;     // per corner halfedge i: (u, v) at its source, in the chart of its face
    std::vector<UV> root_uv;       // per vertex: its root (the first wedge's value)
    std::vector<UV> translation;   // per arc: t_a
    double energy = 0;             // E at the minimiser
  };

  // the unknowns z: index of the u of vertex v's root (v is the next one), of the u of arc a's translation
  int root_variable(int v) const { return 2 * v; }
  int translation_variable(int a) const { return 2 * m_nv + 2 * a; }
  int number_of_variables() const { return 2 * m_nv + 2 * m_arcs; }
  // the quarter turns q_a of arc a's transition
  int arc_turns(int a) const { return m_arc_turns[a]; }

  template <class TriangleMesh>
  Seamless_parametrization(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut, const std::vector<double>& angle,
                           double H)
    : m_nv(m.nv), m_nf(m.nf), m_arcs(int(cut.arcs.size()))
  {
    if(!(H > 0) || !std::isfinite(H))
      throw Invalid_input(Error_code::invalid_argument, "the quad size H must be positive and finite");
    CGAL_precondition(angle.size() == std::size_t(m.nf) && cut.combing.size() == std::size_t(m.nf));
    m_arc_turns.resize(m_arcs);
    for(int a = 0; a < m_arcs; ++a)
      m_arc_turns[a] = modulo_quarter_turns(-cut.arcs[a].matching);
    build_wedges(m, cut);
    build_least_squares(m, cut, angle, H);
  }

  // Fixes unknown z_j (root_variable(), translation_variable(), + 1 for the v) to `value` in the next solve().
  void fix(int j, double value)
  {
    CGAL_precondition(j >= 0 && j < number_of_variables());
    m_fixed.emplace_back(j, value);
  }
  void clear_fixed() { m_fixed.clear(); }

  /*
    The minimiser under the transitions, the gauges and the fixed values. Throws Invalid_input when fixed values
    contradict the transitions (a singular root fixed away from the fixed point of its fixed translations), or
    when the factorization fails.
  */
  Map solve()
  {
    reduce();
    const Sparse M = m_gradients * m_corner_basis;
    const Eigen::VectorXd r = m_target - m_gradients * m_corner_offset;
    const Sparse normal = Sparse(M.transpose() * M);
    m_normal_matrix = normal;
    m_normal_rhs = M.transpose() * r;
    Eigen::VectorXd y = Eigen::VectorXd::Zero(M.cols());
    if(M.cols() > 0) {
      Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt(normal);
      if(ldlt.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the seamless parametrisation's normal equations could not be factored");
      y = ldlt.solve(m_normal_rhs);
      if(ldlt.info() != Eigen::Success || !y.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the seamless parametrisation's solve failed");
    }
    m_reduced_solution = y;
    Map map;
    const Eigen::VectorXd corners = m_corner_basis * y + m_corner_offset;
    map.corner_uv.resize(3 * std::size_t(m_nf));
    for(int c = 0; c < 3 * m_nf; ++c)
      map.corner_uv[c] = {{corners[2 * c], corners[2 * c + 1]}};
    const Eigen::VectorXd z = m_variable_basis * y + m_variable_offset;
    map.root_uv.resize(m_nv);
    for(int v = 0; v < m_nv; ++v)
      map.root_uv[v] = {{z[2 * v], z[2 * v + 1]}};
    map.translation.resize(m_arcs);
    for(int a = 0; a < m_arcs; ++a)
      map.translation[a] = {{z[translation_variable(a)], z[translation_variable(a) + 1]}};
    map.energy = (M * y - r).squaredNorm();
    return map;
  }

  // After solve(), for checks: corner values = corner_basis() y + corner_offset() (2 per corner, u then v) over
  // the reduced unknowns y (every feasible map is of this form), the normal equations and their solution.
  const Sparse& corner_basis() const { return m_corner_basis; }
  const Eigen::VectorXd& corner_offset() const { return m_corner_offset; }
  const Sparse& normal_matrix() const { return m_normal_matrix; }
  const Eigen::VectorXd& normal_rhs() const { return m_normal_rhs; }
  const Eigen::VectorXd& reduced_solution() const { return m_reduced_solution; }
  // The linear constraints on z that hold whatever is fixed (closures around cut vertices and the gauges), as
  // rows (row, unknown, coefficient) of G z = 0 with constraint_count() rows: for the rounding layer, which must
  // know which unknowns the integers it fixed already determine.
  const std::vector<Eigen::Triplet<double>>& constraint_rows() const { return m_constraint_rows; }
  int constraint_count() const { return m_constraint_count; }

private:
  // w = R^turns root + sum_k sign_k R^turn_k t_arc_k: a wedge's value from its vertex's root and the translations
  struct Expression
  {
    int turns = 0;
    std::vector<std::array<int, 3>> terms; // (arc, quarter turns, sign)
  };

  // R^q as a 2x2 integer matrix, row-major
  static std::array<int, 4> rotation(int q)
  {
    switch(modulo_quarter_turns(q)) {
      case 0: return {{1, 0, 0, 1}};
      case 1: return {{0, -1, 1, 0}};
      case 2: return {{-1, 0, 0, -1}};
      default: return {{0, 1, -1, 0}};
    }
  }

  // the expression across interior cut corner halfedge i (from face(i) to the other side)
  Expression crossed(const Expression& w, int i) const
  {
    const int a = m_arc_of_corner[i];
    const int q = m_arc_turns[a];
    const bool from_left = m_is_left_corner[i];
    const int turn = from_left ? q : -q; // w' = R^q w + t  or  w' = R^-q (w - t)
    Expression result;
    result.turns = modulo_quarter_turns(w.turns + turn);
    for(const auto& t : w.terms)
      result.terms.push_back({{t[0], modulo_quarter_turns(t[1] + turn), t[2]}});
    result.terms.push_back(from_left ? std::array<int, 3>{{a, 0, 1}} : std::array<int, 3>{{a, modulo_quarter_turns(-q), -1}});
    return result;
  }

  // the rows of w (2 per expression) over z: added to `rows` with factor `sign`, at row `row`
  void add_expression(const Expression& w, int v, int row, double sign, std::vector<Eigen::Triplet<double>>& out) const
  {
    const std::array<int, 4> R = rotation(w.turns);
    for(int r = 0; r < 2; ++r)
      for(int c = 0; c < 2; ++c)
        if(R[2 * r + c] != 0)
          out.emplace_back(row + r, root_variable(v) + c, sign * R[2 * r + c]);
    for(const auto& t : w.terms) {
      const std::array<int, 4> T = rotation(t[1]);
      for(int r = 0; r < 2; ++r)
        for(int c = 0; c < 2; ++c)
          if(T[2 * r + c] != 0)
            out.emplace_back(row + r, translation_variable(t[0]) + c, sign * t[2] * T[2 * r + c]);
    }
  }

  template <class TriangleMesh>
  void build_wedges(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut)
  {
    using MA = Mesh_arrays<TriangleMesh>;
    const int nc = 3 * m.nf;
    m_arc_of_corner.assign(nc, -1);
    m_is_left_corner.assign(nc, 0);
    for(int a = 0; a < m_arcs; ++a)
      for(int l : cut.arcs[a].left_corners) {
        m_is_left_corner[l] = 1;
        m_arc_of_corner[l] = m_arc_of_corner[m.opposite_corner[l]] = a;
      }
    // the first corner of each vertex: on a boundary vertex the one whose halfedge is a border edge (the most
    // clockwise), so that the counter-clockwise walk sees the whole open fan
    std::vector<int> first(m.nv, -1);
    for(int c = 0; c < nc; ++c) {
      const int v = m.source_of(c);
      if(first[v] < 0 || (m.opposite_corner[c] < 0 && m.opposite_corner[first[v]] >= 0))
        first[v] = c;
    }
    std::vector<Eigen::Triplet<double>> wedge_rows, closure_rows;
    std::vector<int> wedge_of_corner(nc, -1);
    int wedges = 0, closures = 0;
    m_wedges_of_vertex.assign(m.nv, 0);
    for(int v = 0; v < m.nv; ++v) {
      if(first[v] < 0)
        continue;
      const int start = first[v];
      Expression w;
      int c = start;
      int wedge = wedges++;
      add_expression(w, v, 2 * wedge, 1., wedge_rows);
      ++m_wedges_of_vertex[v];
      bool crossed_cut = false;
      for(;;) {
        wedge_of_corner[c] = wedge;
        const int i = MA::prev_corner(c); // the halfedge into v: crossing it turns counter-clockwise around v
        const int next = m.opposite_corner[i];
        if(next < 0)
          break; // the end of a boundary vertex's fan
        const bool cut_here = m_arc_of_corner[i] >= 0;
        if(cut_here) {
          w = crossed(w, i);
          crossed_cut = true;
        }
        if(next == start) { // around an interior vertex: the closure w = root
          if(crossed_cut) {
            std::vector<Eigen::Triplet<double>> rows;
            add_expression(w, v, 2 * closures, 1., rows);
            add_expression(Expression(), v, 2 * closures, -1., rows);
            closure_rows.insert(closure_rows.end(), rows.begin(), rows.end());
            ++closures;
          }
          break;
        }
        if(cut_here) {
          wedge = wedges++;
          add_expression(w, v, 2 * wedge, 1., wedge_rows);
          ++m_wedges_of_vertex[v];
        }
        c = next;
      }
    }
    Sparse wedge_map(2 * wedges, number_of_variables());
    wedge_map.setFromTriplets(wedge_rows.begin(), wedge_rows.end());
    // per corner: the rows of its wedge
    Sparse select(2 * nc, 2 * wedges);
    std::vector<Eigen::Triplet<double>> s;
    for(int c = 0; c < nc; ++c) {
      s.emplace_back(2 * c, 2 * wedge_of_corner[c], 1.);
      s.emplace_back(2 * c + 1, 2 * wedge_of_corner[c] + 1, 1.);
    }
    select.setFromTriplets(s.begin(), s.end());
    m_corner_map = select * wedge_map;
    m_corner_map.prune(0.);

    Sparse closure(2 * closures, number_of_variables());
    closure.setFromTriplets(closure_rows.begin(), closure_rows.end());
    closure.prune(0.); // the terms of an arc through a regular vertex cancel exactly (integer entries)
    // the gauge: per component, a vertex at (0, 0): a singular vertex when there is one (its root must be an
    // integer in the next layer anyway, while a regular vertex pinned at (0, 0) would be one more integer
    // constraint on the rounding), else one not on the cut when there is one
    auto gauge_rank = [&](int v) {
      return (cut.is_singular[v] || cut.holonomy[v] != 0) ? 0 : m_wedges_of_vertex[v] == 1 ? 1 : 2;
    };
    std::vector<int> gauge(cut.number_of_components, -1);
    for(int v = 0; v < m.nv; ++v) {
      if(first[v] < 0)
        continue;
      int& g = gauge[cut.component_of_face[MA::face_of(first[v])]];
      if(g < 0 || gauge_rank(v) < gauge_rank(g))
        g = v;
    }
    // the closures that are not 0 = 0, renumbered
    m_constraint_rows.clear();
    std::vector<int> row_of(2 * std::size_t(closures), -1);
    m_constraint_count = 0;
    for(int k = 0; k < closure.outerSize(); ++k)
      for(Sparse::InnerIterator it(closure, k); it; ++it) {
        int& row = row_of[it.row()];
        if(row < 0)
          row = m_constraint_count++;
        m_constraint_rows.emplace_back(row, int(it.col()), it.value());
      }
    for(int g : gauge) {
      m_constraint_rows.emplace_back(m_constraint_count++, root_variable(g), 1.);
      m_constraint_rows.emplace_back(m_constraint_count++, root_variable(g) + 1, 1.);
    }
    m_used.assign(number_of_variables(), 0);
    for(int v = 0; v < m.nv; ++v)
      if(first[v] >= 0)
        m_used[root_variable(v)] = m_used[root_variable(v) + 1] = 1;
    for(int a = 0; a < m_arcs; ++a)
      m_used[translation_variable(a)] = m_used[translation_variable(a) + 1] = 1;
  }

  // per face, 4 rows: sqrt(area) times the two gradients, and the targets sqrt(area) (d, J d) / H
  template <class TriangleMesh>
  void build_least_squares(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut, const std::vector<double>& angle,
                           double H)
  {
    std::vector<Eigen::Triplet<double>> rows;
    m_target.resize(4 * m.nf);
    for(int f = 0; f < m.nf; ++f) {
      Vec3 ex, ey;
      Mesh_geometry::frame(m, f, ex, ey);
      std::array<std::array<double, 2>, 3> p;
      for(int k = 0; k < 3; ++k) {
        const Vec3 d = sub(m.points[m.corner_vertex[3 * f + k]], m.points[m.corner_vertex[3 * f]]);
        p[k] = {{dot(d, ex), dot(d, ey)}};
      }
      const double twice_area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
      CGAL_assertion(twice_area > 0);
      const double root_area = std::sqrt(twice_area / 2);
      for(int k = 0; k < 3; ++k) {
        // grad of the hat function of corner k: J e_k / (2 area), e_k the edge opposite k, counter-clockwise
        const std::array<double, 2> e = {{p[(k + 2) % 3][0] - p[(k + 1) % 3][0], p[(k + 2) % 3][1] - p[(k + 1) % 3][1]}};
        const double gx = -e[1] / twice_area * root_area, gy = e[0] / twice_area * root_area;
        const int c = 3 * f + k;
        rows.emplace_back(4 * f + 0, 2 * c, gx);
        rows.emplace_back(4 * f + 1, 2 * c, gy);
        rows.emplace_back(4 * f + 2, 2 * c + 1, gx);
        rows.emplace_back(4 * f + 3, 2 * c + 1, gy);
      }
      const double phi = angle[f] + cut.combing[f] * CGAL_PI / 2;
      const double dx = std::cos(phi) * root_area / H, dy = std::sin(phi) * root_area / H;
      m_target[4 * f + 0] = dx;
      m_target[4 * f + 1] = dy;
      m_target[4 * f + 2] = -dy;
      m_target[4 * f + 3] = dx;
    }
    m_gradients.resize(4 * m.nf, 6 * m.nf);
    m_gradients.setFromTriplets(rows.begin(), rows.end());
  }

  // z = variable_basis y + variable_offset: the special unknowns (those of the constraints and the fixed ones)
  // from a particular solution and a kernel basis of the dense constraint system, the others as they are
  void reduce()
  {
    const int nz = number_of_variables();
    std::vector<int> special_of(nz, -1), specials;
    auto mark = [&](int j) {
      if(special_of[j] < 0) {
        special_of[j] = int(specials.size());
        specials.push_back(j);
      }
    };
    for(const auto& t : m_constraint_rows)
      mark(t.col());
    for(const auto& f : m_fixed)
      mark(f.first);
    const int rows = m_constraint_count + int(m_fixed.size());
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(rows, int(specials.size()));
    Eigen::VectorXd h = Eigen::VectorXd::Zero(rows);
    for(const auto& t : m_constraint_rows)
      G(t.row(), special_of[t.col()]) += t.value();
    for(std::size_t k = 0; k < m_fixed.size(); ++k) {
      G(m_constraint_count + int(k), special_of[m_fixed[k].first]) = 1;
      h[m_constraint_count + int(k)] = m_fixed[k].second;
    }
    Eigen::VectorXd particular = Eigen::VectorXd::Zero(int(specials.size()));
    Eigen::MatrixXd kernel(int(specials.size()), 0);
    if(!specials.empty()) {
      Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
      lu.setThreshold(1e-10); // the entries are small integers but for the fixed values' rows
      particular = lu.solve(h);
      if(!((G * particular - h).norm() <= 1e-9 * (1 + h.norm())))
        throw Invalid_input(Error_code::invalid_argument,
                            "the fixed values of the seamless parametrisation contradict its transitions");
      if(lu.dimensionOfKernel() > 0)
        kernel = lu.kernel();
    }
    // the reduced unknowns: the free z (used, not special), then tau
    std::vector<Eigen::Triplet<double>> basis;
    int free_count = 0;
    for(int j = 0; j < nz; ++j)
      if(m_used[j] && special_of[j] < 0)
        basis.emplace_back(j, free_count++, 1.);
    for(int s = 0; s < int(specials.size()); ++s)
      for(int k = 0; k < kernel.cols(); ++k)
        if(std::abs(kernel(s, k)) > 1e-14) // exact zeros up to the elimination's rounding
          basis.emplace_back(specials[s], free_count + k, kernel(s, k));
    m_variable_basis.resize(nz, free_count + int(kernel.cols()));
    m_variable_basis.setFromTriplets(basis.begin(), basis.end());
    m_variable_offset = Eigen::VectorXd::Zero(nz);
    for(int s = 0; s < int(specials.size()); ++s)
      m_variable_offset[specials[s]] = particular[s];
    m_corner_basis = m_corner_map * m_variable_basis;
    m_corner_offset = m_corner_map * m_variable_offset;
  }

  int m_nv, m_nf, m_arcs;
  std::vector<int> m_arc_turns;
  std::vector<int> m_arc_of_corner;
  std::vector<char> m_is_left_corner;
  std::vector<int> m_wedges_of_vertex;
  std::vector<char> m_used;
  Sparse m_corner_map;           // corners' (u, v) from z
  std::vector<Eigen::Triplet<double>> m_constraint_rows;
  int m_constraint_count = 0;
  std::vector<std::pair<int, double>> m_fixed;
  Sparse m_gradients;            // 4 rows per face over the corners' (u, v)
  Eigen::VectorXd m_target;
  Sparse m_variable_basis, m_corner_basis, m_normal_matrix;
  Eigen::VectorXd m_variable_offset, m_corner_offset, m_normal_rhs, m_reduced_solution;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_SEAMLESS_PARAMETRIZATION_H
