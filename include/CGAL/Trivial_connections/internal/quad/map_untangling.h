// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_MAP_UNTANGLING_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_MAP_UNTANGLING_H

#include <CGAL/Trivial_connections/internal/quad/quad_extraction.h>
#include <CGAL/Trivial_connections/internal/quad/seamless_parametrization.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The layer between the rounding and the extraction of quad meshing (issue 43): the integer-grid map made free of
  folds where the integers allow it. The least squares of the parametrisation do not see orientation: near a
  singular vertex whose cone the target cannot follow, or where the integers pulled an iso-line across a thin
  region, some triangles come out inverted, and the extraction skips them (their quads are missing or not quads).

  The map is moved inside the set the integers left, the reduced unknowns y of the parametrisation's last factor()
  (every transition, gauge, feature line and integer holds for every y), to a minimiser of the least squares plus,
  on the faces that are or were close to inverted, the barrier energy of Garanzha, Kaporin, Kudryavtseva, Protais,
  Ray and Sokolov ("Foldover-free maps in 50 lines of code", 2021):
      E_eps(y) = sum_f |grad w_f - t_f|^2
               + sum_{f active} |t_f|^2 [ (1 - theta) |J_f|^2 + theta (det J_f^2 + 1) ] / (2 chi(det J_f, eps)),
      chi(D, eps) = (D + sqrt(eps^2 + D^2)) / 2,
  with t_f the target (the field's frame over H, times sqrt(area): |t_f|^2 is the face's weight in the least
  squares) and J_f the map's Jacobian relative to it (a rotation where the map follows the field). chi is positive
  for every D and tends to max(D, 0) with eps: for a small eps the barrier is one that no minimiser crosses from
  det > 0. Their schedule lowers eps from 1 as the minimum det rises. A face is active once its det falls below
  1/2 (checked before each eps), so that away from the folds the map stays the least squares' one. Measured on the
  layers' torus and genus-2 surface (least-squares energy of the rounded map -> untangled, both without a fold
  after): the barrier alone on every face, 562 -> 1040 and 382 -> 570 (it pulls the map towards conformal and away
  from the field); with the least squares, 671 and 416 (everywhere) or 684 and 429 (active faces only, here; on
  fandisk's naive rounding, 99 and 89 folds left of 159 after 2,000 iterations). Each eps is minimised by L-BFGS
  preconditioned with the parametrisation's factored normal equations (the Hessian of the least squares, exact
  away from the active faces: one back-substitution per iteration).

  A triangle whose every map under the integers is inverted or flat keeps a non-positive det; the schedule then
  stops at its budget. The result is kept only when it has fewer folded and degenerate triangles than the rounded
  map. Its least-squares energy is higher (the rounded map is that energy's minimiser over the same integers).

  Not untangled: a fold-free map can still wind the wrong way around a singular vertex (fandisk at the diagonal
  / 40: three -1/4 vertices whose one-rings cover a quarter turn instead of five; the extraction then finds
  valence 1 or 2 there and cells that are not quads). The continuous map already winds so there, before any
  rounding (its one-ring is dominated by the harmonic z^(-k) of finite energy, manual: Untangling). Nor does
  the untangling hold a winding it starts from: a face not yet active carries no barrier and can pass through
  det = 0 within a round (it joins the barrier at the next one), and an active one can too while eps is large
  (chi(D, 1) > 0 for every D). Measured: rightly wound one-rings of a rounded map were wound wrongly again, also
  with them active from the start; a strict barrier on them from the start (eps 1e-6) held the winding.
*/

struct Untangling_result
{
  Seamless_parametrization::Map map;
  int inverted_before = 0; // folded + degenerate triangles of the rounded map
  int inverted_after = 0;  // of `map`
  int iterations = 0;      // L-BFGS iterations, all rounds
  int rounds = 0;          // values of eps
  bool applied = false;    // map is the untangled one (fewer inverted triangles); else the rounded one
  double seconds = 0;
};

class Map_untangling
{
public:
  // param: factored with every integer fixed (after Integer_rounding::round(), whose map is untangle()'s input)
  Map_untangling(const Seamless_parametrization& param, double theta = 0.5)
    : m_param(param), m_theta(theta)
  {
    CGAL_precondition(theta >= 0 && theta <= 1);
    const Eigen::VectorXd& target = param.gradient_target();
    m_nf = param.number_of_faces(); // rows after the faces' (Seamless_parametrization::penalise_cone_modes()) have no Jacobian
    m_scale.resize(m_nf);
    for(int f = 0; f < m_nf; ++f) // |target row| = sqrt(area) e^s / H: the gradient rows over it are J_f, rotated
      m_scale[f] = 1 / std::hypot(target[4 * f], target[4 * f + 1]);
    m_target = target;
  }

  /*
    The faces (of the one-rings of singular vertices the start winds right) whose winding must not change: they are
    in the barrier from the start, with eps at most `eps` in every round (a strict barrier: no minimiser crosses
    det = 0 from det > 0), while the others follow the schedule. Each must have a positive det in the start.
  */
  void hold(const std::vector<int>& faces, double eps = 1e-6)
  {
    CGAL_precondition(eps > 0);
    m_held.assign(m_nf, 0);
    for(int f : faces)
      m_held[f] = 1;
    m_held_eps = eps;
  }

  Untangling_result untangle(const Seamless_parametrization::Map& rounded, int max_rounds = 60,
                             int max_iterations = 2000)
  {
    const auto start = std::chrono::steady_clock::now();
    Untangling_result result;
    result.map = rounded;
    result.inverted_before = result.inverted_after = inverted_triangles(rounded);
    if(result.inverted_before == 0 || m_param.reduced_solution().size() == 0) {
      result.seconds = seconds_since(start);
      return result;
    }
    m_basis = m_param.gradients() * m_param.corner_basis();
    m_offset = m_param.gradients() * m_param.corner_offset();
    Eigen::VectorXd y = m_param.reduced_solution();
#ifndef CGAL_NO_PRECONDITIONS
    // the parametrisation must be the rounding's: its minimiser is the rounded map (a map built for nothing else)
    const Seamless_parametrization::Map start_map = m_param.map_of(y);
    for(std::size_t c = 0; c < rounded.corner_uv.size(); ++c)
      for(int k = 0; k < 2; ++k)
        CGAL_precondition(std::abs(start_map.corner_uv[c][k] - rounded.corner_uv[c][k]) <=
                          1e-6 * (1 + std::abs(rounded.corner_uv[c][k])));
#endif
    double eps = 1;
    int iterations = 0;
    m_is_active.assign(m_nf, 0);
    m_active.clear();
    for(int f = 0; f < int(m_held.size()); ++f)
      if(m_held[f]) {
        m_is_active[f] = 1;
        m_active.push_back(f);
      }
    for(int round = 0; round < max_rounds && iterations < max_iterations; ++round) {
      activate(y);
      const double before = evaluate(y, eps, nullptr);
      iterations += minimise(y, eps, max_iterations - iterations);
      const double after = evaluate(y, eps, nullptr);
      ++result.rounds;
      const double min_det = minimum_det(y);
      if(min_det > 0 && std::abs(before - after) <= 1e-5 * after)
        break;
      // the paper's schedule: eps follows the minimum det, down to 1e-10 once it is positive
      const double sigma = std::max(1 - after / before, 0.1);
      const double mu = (1 - sigma) * chi(min_det, eps);
      eps = min_det < mu ? 2 * std::sqrt(mu * (mu - min_det)) : 1e-10;
    }
    result.iterations = iterations;
    Seamless_parametrization::Map untangled = m_param.map_of(y);
    const int inverted = inverted_triangles(untangled);
    if(inverted < result.inverted_before) {
      result.map = std::move(untangled);
      result.inverted_after = inverted;
      result.applied = true;
    }
    result.seconds = seconds_since(start);
    return result;
  }

private:
  static double seconds_since(std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  // chi(D, eps) without the cancellation of D + sqrt(eps^2 + D^2) for D << 0
  static double chi(double D, double eps)
  {
    const double root = std::sqrt(eps * eps + D * D);
    return D >= 0 ? (D + root) / 2 : eps * eps / (2 * (root - D));
  }

  // the relative Jacobians' entries, 4 per face
  Eigen::VectorXd jacobians(const Eigen::VectorXd& y) const
  {
    Eigen::VectorXd a = m_basis * y + m_offset;
    for(int f = 0; f < m_nf; ++f)
      a.segment<4>(4 * f) *= m_scale[f];
    return a;
  }

  // det J_f from the 4 entries a of J_f (grad u, grad v)
  template <class Entries>
  static double det(const Entries& a)
  {
    return a[0] * a[3] - a[1] * a[2];
  }

  double minimum_det(const Eigen::VectorXd& y) const
  {
    const Eigen::VectorXd a = jacobians(y);
    double d = std::numeric_limits<double>::infinity();
    for(int f = 0; f < m_nf; ++f)
      d = std::min(d, det(a.segment<4>(4 * f)));
    return d;
  }

  // E_eps(y), and its gradient when asked
  double evaluate(const Eigen::VectorXd& y, double eps, Eigen::VectorXd* gradient) const
  {
    const Eigen::VectorXd g = m_basis * y + m_offset;
    Eigen::VectorXd dg;
    if(gradient)
      dg = 2 * (g - m_target);
    double energy = (g - m_target).squaredNorm();
    const double schedule_eps = eps;
    for(int f : m_active) {
      const double eps = !m_held.empty() && m_held[f] ? std::min(schedule_eps, m_held_eps) : schedule_eps;
      const Eigen::Vector4d a = g.segment<4>(4 * f) * m_scale[f];
      const double S = a.squaredNorm(), D = det(a);
      const double root = std::sqrt(eps * eps + D * D);
      const double c = chi(D, eps);
      const double value = ((1 - m_theta) * S + m_theta * (D * D + 1)) / (2 * c);
      // |t_f|^2 = 1 / scale^2: the face's weight in the least squares
      const double w = 1 / (m_scale[f] * m_scale[f]);
      energy += w * value;
      if(gradient) {
        // d chi / d D = chi / root; d D / d a = (a3, -a2, -a1, a0); d a / d g = scale
        const double along_D = m_theta * D / c - value / root, s = (1 - m_theta) / c;
        const Eigen::Vector4d da(s * a[0] + along_D * a[3], s * a[1] - along_D * a[2], s * a[2] - along_D * a[1],
                                 s * a[3] + along_D * a[0]);
        dg.segment<4>(4 * f) += (w * m_scale[f]) * da;
      }
    }
    if(gradient)
      *gradient = m_basis.transpose() * dg;
    return energy;
  }

  // the faces whose det is below active_det join the barrier's faces (they never leave)
  void activate(const Eigen::VectorXd& y)
  {
    const Eigen::VectorXd a = jacobians(y);
    for(int f = 0; f < m_nf; ++f)
      if(!m_is_active[f] && det(a.segment<4>(4 * f)) < active_det) {
        m_is_active[f] = 1;
        m_active.push_back(f);
      }
  }

  // L-BFGS on E_eps from y, at most `budget` iterations; returns the iterations made
  int minimise(Eigen::VectorXd& y, double eps, int budget) const
  {
    constexpr int memory = 8;
    std::deque<Eigen::VectorXd> s_list, g_list;
    std::deque<double> rho_list;
    Eigen::VectorXd gradient;
    double energy = evaluate(y, eps, &gradient);
    int iterations = 0;
    for(; iterations < budget; ++iterations) {
      // two-loop recursion, initial inverse Hessian gamma N^-1 (the least squares' normal matrix)
      Eigen::VectorXd q = gradient;
      std::vector<double> alpha(s_list.size());
      for(int k = int(s_list.size()) - 1; k >= 0; --k) {
        alpha[k] = rho_list[k] * s_list[k].dot(q);
        q -= alpha[k] * g_list[k];
      }
      // gamma: the last step's curvature against N's, s^T N s / s^T y (N = basis^T basis: a product, not a solve)
      Eigen::VectorXd r = m_param.solve_normal(q);
      if(!s_list.empty())
        r *= (m_basis * s_list.back()).squaredNorm() / s_list.back().dot(g_list.back());
      for(std::size_t k = 0; k < s_list.size(); ++k) {
        const double beta = rho_list[k] * g_list[k].dot(r);
        r += s_list[k] * (alpha[k] - beta);
      }
      Eigen::VectorXd direction = -r;
      double slope = gradient.dot(direction);
      if(!(slope < 0)) { // not a descent direction: the preconditioned gradient alone
        s_list.clear(), g_list.clear(), rho_list.clear();
        direction = -m_param.solve_normal(gradient);
        slope = gradient.dot(direction);
        if(!(slope < 0))
          break;
      }
      // backtracking to the Armijo condition
      double step = 1;
      Eigen::VectorXd next, next_gradient;
      double next_energy = energy;
      bool found = false;
      for(int k = 0; k < 40 && !found; ++k, step /= 2) {
        next = y + step * direction;
        next_energy = evaluate(next, eps, &next_gradient);
        found = std::isfinite(next_energy) && next_energy <= energy + 1e-4 * step * slope;
      }
      if(!found)
        break;
      const Eigen::VectorXd s = next - y, g = next_gradient - gradient;
      const double sg = s.dot(g);
      if(sg > 1e-16 * s.norm() * g.norm()) {
        s_list.push_back(s), g_list.push_back(g), rho_list.push_back(1 / sg);
        if(int(s_list.size()) > memory)
          s_list.pop_front(), g_list.pop_front(), rho_list.pop_front();
      }
      const double decrease = energy - next_energy;
      y = next;
      gradient = next_gradient;
      energy = next_energy;
      if(decrease <= 1e-12 * std::abs(energy))
        break;
    }
    return iterations;
  }

  const Seamless_parametrization& m_param;
  Eigen::SparseMatrix<double> m_basis;
  double m_theta;
  static constexpr double active_det = 0.5; // a face joins the barrier below it
  Eigen::VectorXd m_target;
  std::vector<char> m_is_active;
  std::vector<int> m_active;
  int m_nf = 0;
  std::vector<double> m_scale;
  Eigen::VectorXd m_offset;
  std::vector<char> m_held; // per face: in hold()
  double m_held_eps = 1;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_MAP_UNTANGLING_H
