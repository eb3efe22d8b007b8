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
#include <map>
#include <memory>
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
  sparse Cholesky factorization (SimplicialLDLT, AMD order) of its normal equations. A fixed unknown that is in
  no constraint is substituted, not added as a row: G grows with the constraints, not with the fixed values.

  Feature curves on iso-lines (optional: a flag per edge of the cut graph's numbering, border edges included).
  In the chart of the face of its canonical corner (of its other face when the canonical one is inside an acute
  sector, acute_sector_faces()), a flagged edge must run along the field's u or v direction (within
  `alignment_tolerance` radians, on both its faces but those in acute sectors; otherwise an Invalid_input names
  it), and the other
  coordinate is constant along it: w_source[k] = w_target[k]. Each side is (a sign) times a root coordinate plus
  integer combinations of translations (the wedges' expressions), so every such equation identifies two root
  coordinates up to sign and translations. They are merged by a union-find whose links carry that affine
  relation: a class of root coordinates (an iso-line through feature edges, along chains and across corners)
  becomes one unknown, its representative, and the others are eliminated (z = P z_kept, P sparse). No row is added
  per feature edge; only an equation that closes a loop of the classes (a feature loop, or two relations of one
  coordinate with opposite signs) adds a row to G, over representatives and translations. The representatives
  are the feature lines: the rounding makes them integers (feature_lines()). A vertex where two lines of
  different coordinates meet (a corner of the features) has both coordinates identified: an integer point.
*/
inline constexpr double default_feature_alignment_tolerance = 20 * CGAL_PI / 180;

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

  // a feature line: a class of root coordinates tied by flagged edges, one unknown (its representative)
  struct Feature_line
  {
    int variable;   // z index of the representative: root_variable(vertex) + coordinate
    int vertex;
    int coordinate;
    int edge;       // a flagged edge of the line (cut graph numbering), for messages
  };
  const std::vector<Feature_line>& feature_lines() const { return m_feature_lines; }
  // per flagged edge (cut graph numbering, -1 elsewhere): the coordinate (0: u, 1: v) constant along it in the
  // chart of its equation's face (its canonical corner's, but see acute_sector_faces())
  const std::vector<int>& feature_coordinate() const { return m_feature_coordinate; }
  // a root coordinate eliminated by a feature line (its value follows from the line's and the translations)
  bool is_eliminated(int j) const { return !m_eliminated.empty() && m_eliminated[j]; }

  /*
    feature_edges: empty, or a flag per edge of the cut graph's numbering (cut.edge_corner); a flagged edge is put
    on an iso-line (see above). Throws Invalid_input for H not positive and finite, a flag vector of the wrong
    size, and a flagged edge the field is not aligned with within alignment_tolerance (radians).
  */
  template <class TriangleMesh>
  Seamless_parametrization(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut, const std::vector<double>& angle,
                           double H, const std::vector<char>& feature_edges = {},
                           double alignment_tolerance = default_feature_alignment_tolerance)
    : m_nv(m.nv), m_nf(m.nf), m_arcs(int(cut.arcs.size()))
  {
    if(!(H > 0) || !std::isfinite(H))
      throw Invalid_input(Error_code::invalid_argument, "the quad size H must be positive and finite");
    if(!feature_edges.empty() && feature_edges.size() != cut.edge_corner.size())
      throw Invalid_input(Error_code::invalid_argument, "the feature flags must be one per edge (" +
                                                          std::to_string(cut.edge_corner.size()) + "), not " +
                                                          std::to_string(feature_edges.size()));
    if(!(alignment_tolerance >= 0 && alignment_tolerance < CGAL_PI / 4))
      throw Invalid_input(Error_code::invalid_argument, "the feature alignment tolerance must be in [0, pi/4) radians");
    CGAL_precondition(angle.size() == std::size_t(m.nf) && cut.combing.size() == std::size_t(m.nf));
    m_arc_turns.resize(m_arcs);
    for(int a = 0; a < m_arcs; ++a)
      m_arc_turns[a] = modulo_quarter_turns(-cut.arcs[a].matching);
    build_wedges(m, cut);
    build_feature_lines(m, cut, angle, feature_edges, alignment_tolerance);
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
    factor();
    return map_of(m_reduced_solution);
  }

  /*
    solve() without the map: reduces, factors the normal equations and solves them. The factor is kept (the
    rounding layer borders it with the unknowns it fixes later, see Kept_factor_fixing) until the next factor().
  */
  void factor()
  {
    reduce();
    m_least_squares = m_gradients * m_corner_basis;
    m_least_squares_rhs = m_target - m_gradients * m_corner_offset;
    const Sparse& M = m_least_squares;
    const Sparse normal = Sparse(M.transpose() * M);
    m_normal_matrix = normal;
    m_normal_rhs = M.transpose() * m_least_squares_rhs;
    Eigen::VectorXd y = Eigen::VectorXd::Zero(M.cols());
    m_factor.reset();
    if(M.cols() > 0) {
      auto ldlt = std::make_shared<Ldlt>(normal);
      if(ldlt->info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the seamless parametrisation's normal equations could not be factored");
      y = ldlt->solve(m_normal_rhs);
      if(ldlt->info() != Eigen::Success || !y.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the seamless parametrisation's solve failed");
      m_factor = ldlt;
    }
    m_reduced_solution = y;
  }

  // N^-1 b with the normal matrix N of the last factor() (b: one entry per reduced unknown)
  Eigen::VectorXd solve_normal(const Eigen::VectorXd& b) const
  {
    CGAL_precondition(b.size() == m_normal_matrix.rows());
    if(!m_factor)
      return Eigen::VectorXd::Zero(b.size());
    Eigen::VectorXd x = m_factor->solve(b);
    if(!x.allFinite())
      throw Invalid_input(Error_code::solver_failure, "the seamless parametrisation's solve failed");
    return x;
  }

  // the map of reduced unknowns y (in the coordinates of the last factor())
  Map map_of(const Eigen::VectorXd& y) const
  {
    CGAL_precondition(y.size() == m_corner_basis.cols());
    Map map;
    const Eigen::VectorXd corners = m_corner_basis * y + m_corner_offset;
    map.corner_uv.resize(3 * std::size_t(m_nf));
    for(int c = 0; c < 3 * m_nf; ++c)
      map.corner_uv[c] = {{corners[2 * c], corners[2 * c + 1]}};
    const Eigen::VectorXd z = m_substitution * (m_variable_basis * y + m_variable_offset);
    map.root_uv.resize(m_nv);
    for(int v = 0; v < m_nv; ++v)
      map.root_uv[v] = {{z[2 * v], z[2 * v + 1]}};
    map.translation.resize(m_arcs);
    for(int a = 0; a < m_arcs; ++a)
      map.translation[a] = {{z[translation_variable(a)], z[translation_variable(a) + 1]}};
    map.energy = (m_least_squares * y - m_least_squares_rhs).squaredNorm();
    return map;
  }

  /*
    Curl reduction (optional, before the rounding): the target d_f / H is a gradient only where the combed field
    is integrable; where it is not (curl), the map must distort and may fold. A per-face scale e^{s_f} can make it
    closer to a gradient: s and the map are fitted together, linearised (e^{s + ds} ~ e^s (1 + ds)),
        min  sum_f area_f |grad w - e^{s_f} (d_f, J d_f) / H|^2 + smoothness sum_{f|g} |e| / |c_f c_g| (s_f - s_g)^2
                                                            + anchor sum_f area_f / H^2 s_f^2 ,
    a sparse linear least squares per round (`rounds` Gauss-Newton rounds), with the constraints and the fixed
    values of the next solve() (normally none: the continuous map). smoothness is dimensionless: s varies over
    about sqrt(smoothness) H. The scales are then normalised to a mean (area-weighted) of e^{2 s} of 1, so that H
    stays the mean quad size, and applied to the target of every later solve() (a second call scales the scaled
    target). Returns the scales e^{s_f}. The anchor only excludes the zero map (s = -infinity); it is small so
    that s can follow what a singularity of index k needs, a cone map z -> z^(1 - k) of gradient length r^(-k):
    the folds of a unit target on fine meshes are around the singular vertices (manual, Quad Meshes).
  */
  std::vector<double> reduce_curl(double smoothness, int rounds = 3, double anchor = 1e-3)
  {
    CGAL_precondition(smoothness > 0 && rounds >= 1);
    std::vector<double> s(m_nf, 0.);
    const Eigen::VectorXd unscaled = m_target;
    for(int round = 0; round < rounds; ++round) {
      reduce();
      const Sparse M = m_gradients * m_corner_basis;
      const Eigen::VectorXd r = m_target - m_gradients * m_corner_offset;
      const int ny = int(M.cols());
      // rows: the fit [M, -B] (B: the current target per face), the smoothness and the small anchor of s
      std::vector<Eigen::Triplet<double>> t;
      for(int k = 0; k < M.outerSize(); ++k)
        for(Sparse::InnerIterator it(M, k); it; ++it)
          t.emplace_back(int(it.row()), int(it.col()), it.value());
      for(int f = 0; f < m_nf; ++f)
        for(int i = 0; i < 4; ++i)
          t.emplace_back(4 * f + i, ny + f, -m_target[4 * f + i]);
      int row = int(M.rows()); // after the faces' rows those of penalise_cone_modes(), if any
      std::vector<double> rhs(r.data(), r.data() + r.size());
      for(const auto& p : m_face_pairs) {
        const double w = std::sqrt(smoothness * p.weight);
        t.emplace_back(row, ny + p.f, w);
        t.emplace_back(row, ny + p.g, -w);
        rhs.push_back(-w * (s[p.f] - s[p.g]));
        ++row;
      }
      for(int f = 0; f < m_nf; ++f) {
        const double w = std::sqrt(anchor * m_face_area[f]) / m_H;
        t.emplace_back(row, ny + f, w);
        rhs.push_back(-w * s[f]);
        ++row;
      }
      Sparse A(row, ny + m_nf);
      A.setFromTriplets(t.begin(), t.end());
      const Eigen::VectorXd b = Eigen::Map<Eigen::VectorXd>(rhs.data(), row);
      const Sparse normal = Sparse(A.transpose() * A);
      Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt(normal);
      if(ldlt.info() != Eigen::Success)
        throw Invalid_input(Error_code::solver_failure, "the curl reduction's normal equations could not be factored");
      const Eigen::VectorXd x = ldlt.solve(A.transpose() * b);
      if(ldlt.info() != Eigen::Success || !x.allFinite())
        throw Invalid_input(Error_code::solver_failure, "the curl reduction's solve failed");
      for(int f = 0; f < m_nf; ++f) {
        s[f] += x[ny + f];
        for(int i = 0; i < 4; ++i)
          m_target[4 * f + i] = unscaled[4 * f + i] * std::exp(s[f]);
      }
    }
    // the mean quad size stays H
    double area = 0, scaled = 0;
    for(int f = 0; f < m_nf; ++f) {
      area += m_face_area[f];
      scaled += m_face_area[f] * std::exp(2 * s[f]);
    }
    const double norm = std::sqrt(area / scaled);
    std::vector<double> scale(m_nf);
    for(int f = 0; f < m_nf; ++f) {
      scale[f] = std::exp(s[f]) * norm;
      for(int i = 0; i < 4; ++i)
        m_target[4 * f + i] = unscaled[4 * f + i] * scale[f];
    }
    return scale;
  }

  /*
    Cone modes (manual: Cone modes, Untangling). Around an interior vertex v of index k, in the cone's coordinate
    zeta = r e^{i phi} (phi the angle around v scaled to 2 pi), a map with v's transitions, written in the chart of
    v's root relative to v's value (w = u + i v, the chart's quarter turn R = i), is a sum of harmonics
    e^{i (j - k) phi} over integers j. The cone wanted, zeta^(1 - k), is j = 1. zeta^(-k) (j = 0) winds a turn less
    and has finite energy for k < 0 although its gradient grows without bound at v; conj(zeta)^(1 + k) (j = -1)
    folds at v. The least squares use them to follow the field's asymmetry around v.
    cone_harmonic_rows(): rows (2 per harmonic j of `harmonics`, real then imaginary part, from first_row) over the
    corners' (u, v) (the columns of gradients()): the one-ring's trapezoidal Fourier coefficient
    (1 / 2 pi) sum over the ring of (w - w_v) e^{-i (j - k) phi} d phi, each ring value divided by
    (|p - v| / mean)^((1 - k) 2 pi / angle sum) so that the samples of zeta^(1 - k) have one amplitude; times factor.
    v must be an interior vertex.
  */
  template <class TriangleMesh>
  void cone_harmonic_rows(const Mesh_arrays<TriangleMesh>& m, int v, int k4, const std::vector<int>& harmonics,
                          int first_row, double factor, std::vector<Eigen::Triplet<double>>& out) const
  {
    using MA = Mesh_arrays<TriangleMesh>;
    int first = -1;
    for(int c = 0; c < 3 * m_nf && first < 0; ++c)
      if(m.source_of(c) == v)
        first = c;
    CGAL_precondition(first >= 0);
    std::vector<int> fan;
    for(int c = first;;) {
      fan.push_back(c);
      const int next = m.opposite_corner[MA::prev_corner(c)];
      CGAL_precondition(next >= 0);
      if(next == first)
        break;
      c = next;
    }
    std::vector<double> angle(fan.size());
    double total = 0, mean_radius = 0;
    for(std::size_t t = 0; t < fan.size(); ++t) {
      const Vec3 a = sub(m.points[m.target_of(fan[t])], m.points[v]);
      const Vec3 b = sub(m.points[m.source_of(MA::prev_corner(fan[t]))], m.points[v]);
      angle[t] = angle_between(a, b);
      total += angle[t];
      mean_radius += norm(a) / double(fan.size());
    }
    const double k = k4 / 4.;
    const double exponent = (1 - k) * 2 * CGAL_PI / total;
    for(std::size_t h = 0; h < harmonics.size(); ++h) {
      const double nu = harmonics[h] - k;
      const int row = first_row + 2 * int(h);
      double phi = 0;
      for(std::size_t t = 0; t < fan.size(); ++t) {
        const int c = fan[t];
        const int turns = m_wedge_expression[m_wedge_of_corner[c]].turns; // face chart = R^turns root chart
        const double delta = 2 * CGAL_PI * angle[t] / total;
        // the face's two ring corners: the halfedge's target at phi, the previous corner's source at phi + delta
        const std::array<int, 2> ring = {{MA::next_corner(c), MA::prev_corner(c)}};
        for(int s = 0; s < 2; ++s) {
          const double r = norm(sub(m.points[m.source_of(ring[s])], m.points[v])) / mean_radius;
          // beta = factor (delta / 2) e^{-i nu phi_s} i^{-turns} / (2 pi r^exponent): Re(beta w) = re u - im v,
          // Im(beta w) = im u + re v, for the ring corner and, negated, for v's corner of the same face
          const double magnitude = factor * delta / 2 / (2 * CGAL_PI * std::pow(r, exponent));
          const double argument = -nu * (phi + s * delta) - turns * CGAL_PI / 2;
          const double re = magnitude * std::cos(argument), im = magnitude * std::sin(argument);
          for(const auto& [corner, sign] : {std::pair<int, double>(ring[s], 1.), std::pair<int, double>(c, -1.)}) {
            out.emplace_back(row, 2 * corner, sign * re);
            out.emplace_back(row, 2 * corner + 1, -sign * im);
            out.emplace_back(row + 1, 2 * corner, sign * im);
            out.emplace_back(row + 1, 2 * corner + 1, sign * re);
          }
        }
        phi += delta;
      }
    }
  }

  /*
    Appends to the least squares, per singular vertex (vertex, 4k) with 0 < |k| < 1, the rows of its wrongly
    winding harmonics (j = 0, and j = -1 for k < 0) times sqrt(weight): every later solve(), rounding and
    untangling sees them, and Map::energy includes them. Call before the first solve.
  */
  template <class TriangleMesh>
  void penalise_cone_modes(const Mesh_arrays<TriangleMesh>& m, const std::vector<std::pair<int, int>>& cones,
                           double weight)
  {
    CGAL_precondition(weight >= 0);
    std::vector<Eigen::Triplet<double>> t;
    for(int k = 0; k < m_gradients.outerSize(); ++k)
      for(Sparse::InnerIterator it(m_gradients, k); it; ++it)
        t.emplace_back(int(it.row()), int(it.col()), it.value());
    int rows = int(m_gradients.rows());
    for(const auto& [v, k4] : cones) {
      if(k4 == 0 || k4 <= -4 || k4 >= 4)
        continue;
      const std::vector<int> harmonics = k4 < 0 ? std::vector<int>{0, -1} : std::vector<int>{0};
      cone_harmonic_rows(m, v, k4, harmonics, rows, std::sqrt(weight), t);
      rows += 2 * int(harmonics.size());
    }
    m_gradients.resize(rows, m_gradients.cols());
    m_gradients.setFromTriplets(t.begin(), t.end());
    const Eigen::VectorXd old = m_target;
    m_target = Eigen::VectorXd::Zero(rows);
    m_target.head(old.size()) = old;
  }

  int number_of_faces() const { return m_nf; }

  /*
    Replaces the target of the least squares (gradient_target(), all rows). The factor of the last factor() stays
    valid (the normal matrix does not depend on the target) and so does reduced_solution() (the minimiser for the
    old target: a map to start from); the right-hand side becomes the new target's, so that the energies of
    map_of() and the next minimisers refer to it.
  */
  void set_gradient_target(const Eigen::VectorXd& target)
  {
    CGAL_precondition(target.size() == m_target.size());
    m_target = target;
    if(m_least_squares.cols() == 0 && m_least_squares.rows() == 0)
      return; // not factored yet
    m_least_squares_rhs = m_target - m_gradients * m_corner_offset;
    m_normal_rhs = m_least_squares.transpose() * m_least_squares_rhs;
  }

  // After factor(): the kept unknowns z_kept = variable_basis() y + variable_offset() over the reduced unknowns y
  // (the kept unknowns are those not eliminated by feature lines; z = P z_kept)
  const Sparse& variable_basis() const { return m_variable_basis; }
  const Eigen::VectorXd& variable_offset() const { return m_variable_offset; }

  // After solve() or factor(), for checks: corner values = corner_basis() y + corner_offset() (2 per corner, u then
  // v) over the reduced unknowns y (every feasible map is of this form), the normal equations and their solution.
  const Sparse& corner_basis() const { return m_corner_basis; }
  const Eigen::VectorXd& corner_offset() const { return m_corner_offset; }
  const Sparse& normal_matrix() const { return m_normal_matrix; }
  const Eigen::VectorXd& normal_rhs() const { return m_normal_rhs; }
  const Eigen::VectorXd& reduced_solution() const { return m_reduced_solution; }
  // For the untangling (Map_untangling): per face 4 rows, sqrt(area) times (grad u, grad v) in the face's frame
  // over the corners' (u, v), and the same rows of the target sqrt(area) (d, J d) e^s / H (s: reduce_curl()'s
  // scale, 0 without it)
  const Sparse& gradients() const { return m_gradients; }
  const Eigen::VectorXd& gradient_target() const { return m_target; }
  // The linear constraints on z that hold whatever is fixed (closures around cut vertices, the gauges and the
  // feature lines' loops), as rows (row, unknown, coefficient) of G z = 0 with constraint_count() rows, over the
  // unknowns that are not eliminated: for the rounding layer, which must know which unknowns the integers it
  // fixed already determine.
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
      m_wedge_expression.push_back(w);
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
          m_wedge_expression.push_back(w);
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
    m_wedge_of_corner = wedge_of_corner;

    m_closure = Sparse(2 * closures, number_of_variables());
    m_closure.setFromTriplets(closure_rows.begin(), closure_rows.end());
    m_closure.prune(0.); // the terms of an arc through a regular vertex cancel exactly (integer entries)
    // the gauge: per component, a vertex at (0, 0): a singular vertex when there is one (its root must be an
    // integer in the next layer anyway, while a regular vertex pinned at (0, 0) would be one more integer
    // constraint on the rounding), else one not on the cut when there is one
    auto gauge_rank = [&](int v) {
      return (cut.is_singular[v] || cut.holonomy[v] != 0) ? 0 : m_wedges_of_vertex[v] == 1 ? 1 : 2;
    };
    m_gauge.assign(cut.number_of_components, -1);
    m_gauge_rank.assign(m.nv, -1);
    m_vertex_component.assign(m.nv, -1);
    for(int v = 0; v < m.nv; ++v) {
      if(first[v] < 0)
        continue;
      m_gauge_rank[v] = gauge_rank(v);
      m_vertex_component[v] = cut.component_of_face[MA::face_of(first[v])];
      int& g = m_gauge[m_vertex_component[v]];
      if(g < 0 || gauge_rank(v) < gauge_rank(g))
        g = v;
    }
    m_used.assign(number_of_variables(), 0);
    for(int v = 0; v < m.nv; ++v)
      if(first[v] >= 0)
        m_used[root_variable(v)] = m_used[root_variable(v) + 1] = 1;
    for(int a = 0; a < m_arcs; ++a)
      m_used[translation_variable(a)] = m_used[translation_variable(a) + 1] = 1;
  }

  // coordinate k of corner c's (u, v) as sign * (root coordinate) + integer combination of translations
  struct Coordinate
  {
    int variable;
    int sign;
    std::map<int, int> translations; // z index -> coefficient
  };
  Coordinate corner_coordinate(int vertex, int c, int k) const
  {
    const Expression& w = m_wedge_expression[m_wedge_of_corner[c]];
    Coordinate r{-1, 0, {}};
    const std::array<int, 4> R = rotation(w.turns);
    for(int j = 0; j < 2; ++j)
      if(R[2 * k + j] != 0) {
        r.variable = root_variable(vertex) + j;
        r.sign = R[2 * k + j];
      }
    for(const auto& t : w.terms) {
      const std::array<int, 4> T = rotation(t[1]);
      for(int j = 0; j < 2; ++j)
        if(T[2 * k + j] != 0)
          r.translations[translation_variable(t[0]) + j] += t[2] * T[2 * k + j];
    }
    return r;
  }

  // x = sign * parent + translations, for the union-find of root coordinates
  struct Link
  {
    int parent = -1; // -1: a representative
    int sign = 1;
    std::map<int, int> translations;
  };
  static void add_to(std::map<int, int>& into, const std::map<int, int>& a, int factor)
  {
    for(const auto& t : a)
      if((into[t.first] += factor * t.second) == 0)
        into.erase(t.first);
  }
  // the representative r of x, with x = sign * r + translations; compresses the path
  Link find(std::vector<Link>& links, int x) const
  {
    std::vector<int> path;
    int r = x;
    while(links[r].parent >= 0) {
      path.push_back(r);
      r = links[r].parent;
    }
    // from the top of the path down: each link made relative to r
    for(std::size_t j = path.size(); j-- > 0;) {
      Link& l = links[path[j]];
      if(l.parent == r)
        continue;
      const Link& up = links[l.parent]; // already relative to r
      std::map<int, int> t;
      add_to(t, up.translations, l.sign);
      add_to(t, l.translations, 1);
      l.sign *= up.sign;
      l.translations = t;
      l.parent = r;
    }
    if(links[x].parent < 0)
      return Link{x, 1, {}};
    Link out = links[x];
    return out;
  }

  /*
    The faces inside a sector of less than 45 degrees between two consecutive flagged edges around a vertex (a
    crease turning back, fandisk's cusp): a quad mesh puts one quad corner there, so the field turns by 90 degrees
    less the sector's angle across it (the sector rule: feature_curves.h, cusp_sector_directions()) and is aligned
    with neither edge. Their alignment is not checked, and a flagged edge takes its coordinate from its other face.
  */
  template <class TriangleMesh>
  static std::vector<char> acute_sector_faces(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut,
                                              const std::vector<char>& feature_edges)
  {
    using MA = Mesh_arrays<TriangleMesh>;
    std::vector<char> acute(std::size_t(m.nf), 0);
    if(feature_edges.empty())
      return acute;
    std::vector<char> flagged(std::size_t(3 * m.nf), 0); // per corner: its edge is flagged
    std::vector<int> flags_at(std::size_t(m.nv), 0);
    for(std::size_t e = 0; e < feature_edges.size(); ++e)
      if(feature_edges[e]) {
        const int i = cut.edge_corner[e], o = m.opposite_corner[i];
        flagged[std::size_t(i)] = 1;
        if(o >= 0)
          flagged[std::size_t(o)] = 1;
        ++flags_at[std::size_t(m.source_of(i))];
        ++flags_at[std::size_t(m.target_of(i))];
      }
    std::vector<char> done(std::size_t(m.nv), 0);
    std::vector<int> fan;
    for(int c0 = 0; c0 < 3 * m.nf; ++c0) {
      const int v = m.target_of(c0); // c0 enters v
      if(done[std::size_t(v)] || flags_at[std::size_t(v)] < 2)
        continue;
      done[std::size_t(v)] = 1;
      // the fan of v counter-clockwise, as the corners entering it, from a border when it is open
      int c = c0;
      while(m.opposite_corner[MA::next_corner(c)] >= 0 && m.opposite_corner[MA::next_corner(c)] != c0)
        c = m.opposite_corner[MA::next_corner(c)];
      const bool open = m.opposite_corner[MA::next_corner(c)] < 0;
      fan.clear();
      const int first = c;
      do {
        fan.push_back(c);
        const int o = m.opposite_corner[c];
        if(o < 0)
          break;
        c = MA::prev_corner(o);
      } while(c != first);
      // a sector starts at a face whose first edge (leaving v) is flagged; a border edge counts as flagged
      const std::size_t count = fan.size();
      std::size_t begin = count;
      for(std::size_t j = 0; j < count && begin == count; ++j)
        if(flagged[std::size_t(MA::next_corner(fan[j]))] || (open && j == 0))
          begin = j;
      if(begin == count)
        continue;
      for(std::size_t a = 0; a < count;) {
        double theta = 0;
        std::size_t b = a;
        do {
          const int corner = fan[(begin + b) % count];
          theta += angle_between(sub(m.points[m.target_of(MA::next_corner(corner))], m.points[v]),
                                 sub(m.points[m.source_of(corner)], m.points[v]));
          ++b;
        } while(b < count && !flagged[std::size_t(MA::next_corner(fan[(begin + b) % count]))]);
        // the sector ends at a flagged edge (the next sector's first, or the open fan's last border)
        if(theta < CGAL_PI / 4 && (b < count || open || a > 0))
          for(std::size_t j = a; j < b; ++j)
            acute[std::size_t(MA::face_of(fan[(begin + j) % count]))] = 1;
        a = b;
      }
    }
    return acute;
  }

  template <class TriangleMesh>
  void build_feature_lines(const Mesh_arrays<TriangleMesh>& m, const Cut_graph& cut, const std::vector<double>& angle,
                           const std::vector<char>& feature_edges, double tolerance)
  {
    using MA = Mesh_arrays<TriangleMesh>;
    const int nz = number_of_variables();
    std::vector<Link> links(nz);
    std::vector<int> class_size(nz, 1);
    std::vector<Eigen::Triplet<double>> loop_rows;
    int loops = 0;
    m_feature_coordinate.assign(cut.edge_corner.size(), -1);
    m_feature_corner.assign(cut.edge_corner.size(), -1);
    const double quarter = CGAL_PI / 2;
    const std::vector<char> acute = acute_sector_faces(m, cut, feature_edges);
    for(std::size_t e = 0; e < feature_edges.size(); ++e) {
      if(!feature_edges[e])
        continue;
      // the equation is written in the chart of the canonical corner's face, or of the other face when the
      // canonical one is inside an acute sector (aligned with neither of its feature edges) and the other is not
      const int o = m.opposite_corner[cut.edge_corner[e]];
      const int i = o >= 0 && acute[MA::face_of(cut.edge_corner[e])] && !acute[MA::face_of(o)] ? o : cut.edge_corner[e];
      m_feature_corner[e] = i;
      const int a = m.source_of(i), b = m.target_of(i);
      const Vec3 d = sub(m.points[b], m.points[a]);
      int k = -1;
      for(int side = 0; side < 2; ++side) {
        const int c = side == 0 ? i : m.opposite_corner[i];
        if(c < 0)
          continue;
        const int f = MA::face_of(c);
        Vec3 ex, ey;
        Mesh_geometry::frame(m, f, ex, ey);
        const double turns = (std::atan2(dot(d, ey), dot(d, ex)) - angle[f] - cut.combing[f] * quarter) / quarter;
        const double off = std::abs(turns - std::round(turns)) * quarter;
        if(!acute[f] && !(off <= tolerance)) // inside an acute sector the field turns: not checked there
          throw Invalid_input(Error_code::invalid_argument,
                              std::string("the cross field is not aligned with the ") +
                                (m.opposite_corner[i] < 0 ? "border" : "feature") + " edge from vertex " + std::to_string(a) +
                                " to vertex " + std::to_string(b) + " (off by " + std::to_string(off * 180 / CGAL_PI) +
                                " degrees in face " + std::to_string(f) + ", more than the tolerance of " +
                                std::to_string(tolerance * 180 / CGAL_PI) + ")" +
                                (m.opposite_corner[i] < 0 ? ": quads end on the border, align the field with it" : ""),
                              e);
        if(side == 0) // along +-d: u varies, v is constant; along +-J d: u is constant
          k = modulo_quarter_turns((long long)std::round(turns)) % 2 == 0 ? 1 : 0;
      }
      m_feature_coordinate[e] = k;
      // w_a[k] = w_b[k]: x = sa sb y + sa (Tb - Ta)
      const Coordinate ca = corner_coordinate(a, i, k), cb = corner_coordinate(b, MA::next_corner(i), k);
      const Link fx = find(links, ca.variable), fy = find(links, cb.variable);
      const int rx = fx.parent, ry = fy.parent;
      const int sigma = ca.sign * cb.sign;
      std::map<int, int> L;
      add_to(L, cb.translations, ca.sign);
      add_to(L, ca.translations, -ca.sign);
      // x = sx rx + Lx, y = sy ry + Ly, x = sigma y + L
      if(rx != ry) {
        // rx = sx sigma sy ry + sx (sigma Ly + L - Lx)
        Link l;
        l.sign = fx.sign * sigma * fy.sign;
        add_to(l.translations, fy.translations, fx.sign * sigma);
        add_to(l.translations, L, fx.sign);
        add_to(l.translations, fx.translations, -fx.sign);
        if(class_size[rx] <= class_size[ry]) {
          l.parent = ry;
          links[rx] = l;
          class_size[ry] += class_size[rx];
        } else { // ry = s rx - s T, the inverse
          Link inverse;
          inverse.parent = rx;
          inverse.sign = l.sign;
          add_to(inverse.translations, l.translations, -l.sign);
          links[ry] = inverse;
          class_size[rx] += class_size[ry];
        }
      } else {
        // (sx - sigma sy) r + Lx - sigma Ly - L = 0
        std::map<int, int> row;
        add_to(row, fx.translations, 1);
        add_to(row, fy.translations, -sigma);
        add_to(row, L, -1);
        const int coefficient = fx.sign - sigma * fy.sign;
        if(coefficient != 0 || !row.empty()) {
          if(coefficient != 0)
            loop_rows.emplace_back(loops, rx, double(coefficient));
          for(const auto& t : row)
            loop_rows.emplace_back(loops, t.first, double(t.second));
          ++loops;
        }
      }
    }
    // with feature lines, the gauge of a component without singular vertex goes to a vertex whose two coordinates
    // are on lines (both integers anyway), else one (its other coordinate is then the only one pinned): a vertex
    // off the lines pinned at (0, 0) would put the lines at non-integers the rounding then pays for
    if(!feature_edges.empty()) {
      std::vector<int> on_lines(m.nv, 0);
      for(int j = 0; j < 2 * m.nv; ++j)
        if(links[j].parent >= 0 || class_size[j] > 1)
          ++on_lines[j / 2];
      auto rank = [&](int v) { return m_gauge_rank[v] == 0 ? 0 : on_lines[v] == 2 ? 1 : on_lines[v] == 1 ? 2 : 3 + m_gauge_rank[v]; };
      for(int v = 0; v < m.nv; ++v)
        if(m_vertex_component[v] >= 0) {
          int& g = m_gauge[m_vertex_component[v]];
          if(rank(v) < rank(g))
            g = v;
        }
    }
    // the substitution z = P z_kept, the eliminated coordinates, the lines
    m_eliminated.assign(nz, 0);
    std::vector<Eigen::Triplet<double>> p;
    std::vector<int> line_of(nz, -1);
    for(int j = 0; j < nz; ++j) {
      if(links[j].parent < 0) {
        p.emplace_back(j, j, 1.);
        continue;
      }
      const Link l = find(links, j);
      m_eliminated[j] = 1;
      m_used[j] = 0;
      p.emplace_back(j, l.parent, double(l.sign));
      for(const auto& t : l.translations)
        p.emplace_back(j, t.first, double(t.second));
      if(line_of[l.parent] < 0) {
        line_of[l.parent] = int(m_feature_lines.size());
        m_feature_lines.push_back({l.parent, l.parent / 2, l.parent % 2, -1});
      }
    }
    for(std::size_t e = 0; e < feature_edges.size(); ++e)
      if(feature_edges[e]) {
        const int i = m_feature_corner[e];
        const Link l = find(links, corner_coordinate(m.source_of(i), i, m_feature_coordinate[e]).variable);
        Feature_line& line = m_feature_lines[line_of[l.parent]];
        if(line.edge < 0)
          line.edge = int(e);
      }
    m_substitution = Row_sparse(nz, nz);
    m_substitution.setFromTriplets(p.begin(), p.end());
    m_corner_map = Sparse(m_corner_map * m_substitution);
    m_corner_map.prune(0.);

    // the constraints over the kept unknowns: closures, gauges, the lines' loops
    m_constraint_rows.clear();
    m_constraint_count = 0;
    Sparse closure = m_closure * m_substitution;
    closure.prune(0.);
    std::vector<int> row_of(closure.rows(), -1);
    for(int k = 0; k < closure.outerSize(); ++k)
      for(Sparse::InnerIterator it(closure, k); it; ++it) {
        int& row = row_of[it.row()];
        if(row < 0)
          row = m_constraint_count++;
        m_constraint_rows.emplace_back(row, int(it.col()), it.value());
      }
    for(int g : m_gauge)
      for(int k = 0; k < 2; ++k) {
        for(Row_sparse::InnerIterator it(m_substitution, root_variable(g) + k); it; ++it)
          m_constraint_rows.emplace_back(m_constraint_count, int(it.col()), it.value());
        ++m_constraint_count;
      }
    for(const auto& t : loop_rows)
      m_constraint_rows.emplace_back(m_constraint_count + t.row(), t.col(), t.value());
    m_constraint_count += loops;
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
    // for reduce_curl(): the faces' areas, and the dual edges with the weight |e| / |c_f c_g| of a Dirichlet energy
    m_H = H;
    m_face_area.resize(m.nf);
    std::vector<Vec3> centroid(m.nf);
    for(int f = 0; f < m.nf; ++f) {
      const Vec3 &a = m.points[m.corner_vertex[3 * f]], &b = m.points[m.corner_vertex[3 * f + 1]],
                 &c = m.points[m.corner_vertex[3 * f + 2]];
      m_face_area[f] = norm(cross(sub(b, a), sub(c, a))) / 2;
      for(int k = 0; k < 3; ++k)
        centroid[f][k] = (a[k] + b[k] + c[k]) / 3;
    }
    for(int i = 0; i < 3 * m.nf; ++i) {
      const int o = m.opposite_corner[i];
      if(o < i)
        continue;
      const int f = i / 3, g = o / 3;
      const double dual = norm(sub(centroid[f], centroid[g]));
      if(dual > 0)
        m_face_pairs.push_back({f, g, norm(sub(m.points[m.target_of(i)], m.points[m.source_of(i)])) / dual});
    }
  }

  // z_kept = variable_basis y + variable_offset: the fixed unknowns substituted (a fixed eliminated coordinate
  // is a row: its substitution's), the special unknowns (those left in the constraints) from a particular solution
  // and a kernel basis of the dense constraint system, the others as they are
  void reduce()
  {
    const int nz = number_of_variables();
    std::vector<char> is_fixed(nz, 0);
    std::vector<double> fixed_value(nz, 0.);
    std::vector<std::pair<int, double>> fixed_rows; // eliminated coordinates fixed
    for(const auto& f : m_fixed) {
      if(is_eliminated(f.first)) {
        fixed_rows.push_back(f);
        continue;
      }
      if(is_fixed[f.first] && fixed_value[f.first] != f.second)
        throw Invalid_input(Error_code::invalid_argument,
                            "the seamless parametrisation has an unknown fixed to two different values");
      is_fixed[f.first] = 1;
      fixed_value[f.first] = f.second;
    }
    // the rows: constraints, then the fixed eliminated coordinates
    std::vector<Eigen::Triplet<double>> all(m_constraint_rows);
    int rows = m_constraint_count;
    std::vector<double> rhs(m_constraint_count, 0.);
    for(const auto& f : fixed_rows) {
      for(Row_sparse::InnerIterator it(m_substitution, f.first); it; ++it)
        all.emplace_back(rows, int(it.col()), it.value());
      rhs.push_back(f.second);
      ++rows;
    }
    std::vector<int> special_of(nz, -1), specials;
    for(const auto& t : all)
      if(!is_fixed[t.col()] && special_of[t.col()] < 0) {
        special_of[t.col()] = int(specials.size());
        specials.push_back(t.col());
      }
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(rows, int(specials.size()));
    Eigen::VectorXd h = Eigen::Map<Eigen::VectorXd>(rhs.data(), rows);
    for(const auto& t : all) {
      if(is_fixed[t.col()])
        h[t.row()] -= t.value() * fixed_value[t.col()];
      else
        G(t.row(), special_of[t.col()]) += t.value();
    }
    Eigen::VectorXd particular = Eigen::VectorXd::Zero(int(specials.size()));
    Eigen::MatrixXd kernel(int(specials.size()), 0);
    if(rows > 0) {
      if(!specials.empty()) {
        Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
        lu.setThreshold(1e-10); // the entries are small integers
        particular = lu.solve(h);
        if(lu.dimensionOfKernel() > 0)
          kernel = lu.kernel();
      }
      if(!((G * particular - h).norm() <= 1e-9 * (1 + h.norm())))
        throw Invalid_input(Error_code::invalid_argument,
                            "the fixed values of the seamless parametrisation contradict its transitions");
    }
    // the reduced unknowns: the free z (used, neither special nor fixed), then tau
    std::vector<Eigen::Triplet<double>> basis;
    int free_count = 0;
    for(int j = 0; j < nz; ++j)
      if(m_used[j] && special_of[j] < 0 && !is_fixed[j])
        basis.emplace_back(j, free_count++, 1.);
    for(int s = 0; s < int(specials.size()); ++s)
      for(int k = 0; k < kernel.cols(); ++k)
        if(std::abs(kernel(s, k)) > 1e-14) // exact zeros up to the elimination's rounding
          basis.emplace_back(specials[s], free_count + k, kernel(s, k));
    m_variable_basis.resize(nz, free_count + int(kernel.cols()));
    m_variable_basis.setFromTriplets(basis.begin(), basis.end());
    m_variable_offset = Eigen::VectorXd::Zero(nz);
    for(int j = 0; j < nz; ++j)
      if(is_fixed[j])
        m_variable_offset[j] = fixed_value[j];
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
  using Row_sparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  std::vector<Expression> m_wedge_expression; // per wedge
  std::vector<int> m_wedge_of_corner;
  Sparse m_closure;                           // closures over all z
  std::vector<int> m_gauge;                   // per component
  std::vector<int> m_gauge_rank, m_vertex_component; // per vertex
  Row_sparse m_substitution;                  // z = P z_kept
  std::vector<char> m_eliminated;
  std::vector<Feature_line> m_feature_lines;
  std::vector<int> m_feature_coordinate;
  std::vector<int> m_feature_corner; // per flagged edge: the corner whose face's chart its equation is written in
  struct Face_pair { int f, g; double weight; };
  std::vector<Face_pair> m_face_pairs; // interior edges, for reduce_curl()
  std::vector<double> m_face_area;
  double m_H = 1;
  Sparse m_gradients;            // 4 rows per face over the corners' (u, v)
  Eigen::VectorXd m_target;
  Sparse m_variable_basis, m_corner_basis, m_normal_matrix, m_least_squares;
  Eigen::VectorXd m_variable_offset, m_corner_offset, m_normal_rhs, m_reduced_solution, m_least_squares_rhs;
  using Ldlt = Eigen::SimplicialLDLT<Sparse, Eigen::Lower, Eigen::AMDOrdering<int>>;
  std::shared_ptr<const Ldlt> m_factor; // of the last factor(); shared: the class stays copyable
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_SEAMLESS_PARAMETRIZATION_H
