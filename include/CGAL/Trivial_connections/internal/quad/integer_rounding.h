// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_INTEGER_ROUNDING_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_INTEGER_ROUNDING_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/quad/cut_graph.h>
#include <CGAL/Trivial_connections/internal/quad/kept_factor_fixing.h>
#include <CGAL/Trivial_connections/internal/quad/seamless_parametrization.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The third layer of quad meshing (issue 43): the seamless parametrisation made an integer-grid map. The integer
  unknowns are the (u, v) of the root of every singular vertex (given as singular to the cut graph, or with a
  non-zero holonomy) and the translation t_a of every arc. Once they are integers, every corner at a singular
  vertex is an integer point (its wedges are the root moved by quarter turns and integer translations) and every
  transition is a grid automorphism (a quarter turn plus an integer translation).

  Not every set of integers is feasible: the closure around a singular vertex of quarter turns Q,
  (R^Q - I) root + sum (quarter turns of) t_a = 0, ties its root to the translations around it, and R^Q - I has
  determinant 2 (Q odd) or 4 (Q = 2): integer translations may put the root on a half-integer point. So the
  rounding tracks, exactly, which integer unknowns the ones already fixed determine through the constraints
  (Affine_set below, a small dense affine parametrisation of the constrained unknowns): a determined unknown is
  not rounded but checked, and one determined to a non-integer value is a contradiction, reported by an
  Invalid_input exception that names it, never a silently non-integer map. To make contradictions rare the roots
  are rounded before the translations (integer roots and translations rounded one by one keep every closure
  with a single free translation integer, as the turns are unimodular).

  Even so, the integers fixed first can leave a later unknown determined at a half or a quarter (a feature line
  through a singular vertex, tied to its root by a closure). So each unknown is fixed to the integer nearest to
  its value among those that keep every unknown it determines an integer: the nearest, then the next ones by
  distance (up to integer_candidates; the divisors are 2 and 4, so 5 cover every residue). Counted in
  shifted_unknowns; with 1 candidate the schemes are the plain ones below.

  Two schemes:
  - greedy (the scheme of Bommes, Zimmer and Kobbelt, "Mixed-integer quadrangulation", 2009, in our words): solve
    the least squares, fix the free integer unknown closest to an integer (roots first, then translations; ties
    to the first in the order vertices then arcs) to that integer, solve again with it fixed, and so on. The
    solves after a fix do not factor the normal equations again: Kept_factor_fixing borders the kept factor with
    the fixed unknowns (a back-substitution and a dense update per fix) and factors again, with every fixed
    unknown eliminated, only every `max_block` fixes (default_rounding_block below; 0: a factorization per solve,
    the scheme before the kept factor, for comparisons). The same minimisers up to floating point rounding.
    `batch_distance` > 0 trades quality for time: with the closest one, every other free unknown of the same
    kind within that distance of an integer is fixed before the next solve (those within 1e-9 always are).
  - naive: one solve, every free integer unknown rounded from it at once (in the same order, the determined ones
    checked), one more solve. The baseline the greedy scheme is measured against.
  The energy after either is >= the continuous one (a relaxation); nothing guarantees that the greedy one is
  lower than the naive one (on the test meshes it is lower or equal). In the closest_first order both schemes
  were infeasible on the tests' sphere with eight +1/4 (a root implied at a half-integer): hence roots_first.

  Feature lines (Seamless_parametrization::feature_lines(), when edges were flagged as features) are a third kind
  of integer unknown, one per line, rounded after the singular roots and before the translations: a line through
  a singular vertex (a cube's corner) is tied to its root, so the roots go first, and a line's integer then fixes
  the translations that carry it across the cut. A singular root coordinate eliminated by a line is not an unknown
  of its own (it follows from the line and the translations) but is checked like the others at the end.

  The rounding owns the parametrisation's fixed values: it clears them before it starts.
*/

enum class Rounding_scheme { greedy, naive };

// The fixes between two factorizations of the greedy rounding. A fix costs a back-substitution plus (integer
// unknowns) x (fixes on the factor) of dense work: with a few hundred integer unknowns and 256 fixes that is
// ~1e5 flops, below a back-substitution; refactoring only bounds the dense block and its rounding. On elephant,
// bunny00 and fandisk (manual, quad-mesh section) no rounding reached 256 fixes: 2 factorizations in all.
inline constexpr int default_rounding_block = 256;
// roots_first: the roots of the singular vertices before the translations (the default, see above);
// closest_first: the plain literature order, by distance to an integer only, which can fix translations that
// put a singular root on a half-integer point (then the rounding throws): kept to measure that choice
enum class Rounding_order { roots_first, closest_first };

struct Integer_rounding_result
{
  Seamless_parametrization::Map map; // the integer-grid map; map.energy is the energy after rounding
  double continuous_energy = 0;      // before rounding
  int integer_unknowns = 0;          // the (u or v) roots of singular vertices, feature lines, translations of arcs
  int feature_lines = 0;             // of which feature lines
  int fixed_unknowns = 0;            // rounded and fixed by the scheme
  int implied_unknowns = 0;          // made integers by the fixed ones through the transitions
  int shifted_unknowns = 0;          // fixed to an integer other than the nearest, to keep the implied ones integers
  int solves = 0;                    // least-squares minimisers, the continuous one included
  int factorizations = 0;            // sparse factorizations of the normal equations behind them (and the map's)
  int back_substitutions = 0;        // with the kept factor, one per fix
  double seconds = 0;                // the rounding's wall time
  bool naive_fallback = false;       // greedy asked, its integers contradicted each other: the naive ones (below)
};

class Integer_rounding
{
public:
  // param: built on `cut`; it is kept by reference and its fixed values are the rounding's
  Integer_rounding(Seamless_parametrization& param, const Cut_graph& cut)
    : m_param(param)
  {
    CGAL_precondition(cut.holonomy.size() == cut.is_singular.size());
    std::vector<char> taken(param.number_of_variables(), 0);
    for(int v = 0; v < int(cut.is_singular.size()); ++v)
      if(cut.is_singular[v] || cut.holonomy[v] != 0)
        for(int k = 0; k < 2; ++k) {
          const int z = param.root_variable(v) + k;
          if(param.is_eliminated(z)) {
            m_implied.push_back({z, v, -1, k, false});
          } else {
            m_unknowns.push_back({z, v, -1, k, false});
            taken[z] = 1;
          }
        }
    for(const Seamless_parametrization::Feature_line& line : param.feature_lines())
      if(!taken[line.variable]) {
        m_unknowns.push_back({line.variable, line.vertex, -1, line.coordinate, true});
        ++m_feature_lines;
      }
    for(int a = 0; a < int(cut.arcs.size()); ++a)
      for(int k = 0; k < 2; ++k)
        m_unknowns.push_back({param.translation_variable(a) + k, -1, a, k, false});
  }

  // the integer unknowns (z indices of the parametrisation), in the order the schemes visit them
  std::vector<int> integer_variables() const
  {
    std::vector<int> z;
    for(const Unknown& u : m_unknowns)
      z.push_back(u.z);
    return z;
  }

  // Throws Invalid_input when the integers fixed determine another integer unknown to a non-integer value, or
  // when a solve fails.
  // integer_candidates: how many integers, nearest first, may be tried for an unknown (see fix below; 1: the
  // nearest only, the plain schemes)
  // max_block: the greedy scheme's fixes between two factorizations (see Kept_factor_fixing; 0: one per solve)
  //
  // The greedy scheme re-solves between its fixes, and the later values can leave an unknown that a closure ties
  // to the earlier integers at a half (a feature line through a singular vertex): then its integers contradict
  // each other where the naive ones, all from the continuous map in the same order, need not (fandisk with the
  // sector rule at its cusp: at the diagonal / 40 with the placed singularities, at / 50 and / 80 with them moved
  // off the features). So a contradiction of the greedy scheme is followed by the naive one (naive_fallback), whose
  // own contradiction is thrown.
  Integer_rounding_result round(Rounding_scheme scheme, Rounding_order order = Rounding_order::roots_first,
                                double batch_distance = 0, int integer_candidates = 5,
                                int max_block = default_rounding_block)
  {
    if(scheme != Rounding_scheme::greedy)
      return round_once(scheme, order, batch_distance, integer_candidates, max_block);
    try {
      return round_once(scheme, order, batch_distance, integer_candidates, max_block);
    } catch(const Invalid_input& e) {
      if(e.code() != Error_code::invalid_argument) // a failed solve (solver_failure) is not a contradiction
        throw;
    }
    Integer_rounding_result r = round_once(Rounding_scheme::naive, order, batch_distance, integer_candidates, max_block);
    r.naive_fallback = true;
    return r;
  }

private:
  Integer_rounding_result round_once(Rounding_scheme scheme, Rounding_order order, double batch_distance,
                                     int integer_candidates, int max_block)
  {
    CGAL_precondition(batch_distance >= 0 && integer_candidates >= 1 && max_block >= 0);
    const auto start = std::chrono::steady_clock::now();
    m_order = order;
    Integer_rounding_result result;
    result.integer_unknowns = int(m_unknowns.size());
    result.feature_lines = m_feature_lines;
    m_param.clear_fixed();
    Seamless_parametrization::Map map = m_param.solve();
    result.solves = 1;
    result.factorizations = 1;
    result.continuous_energy = map.energy;
    // greedy: the minimisers after each fix on the factor of the continuous one
    std::unique_ptr<Kept_factor_fixing> kept;
    if(scheme == Rounding_scheme::greedy)
      kept = std::make_unique<Kept_factor_fixing>(m_param, integer_variables(), max_block);
    Affine_set set = constrained_unknowns();
    std::vector<char> done(m_unknowns.size(), 0);
    // the unknowns the fixed ones determine: checked, not rounded
    auto settle_implied = [&] {
      for(std::size_t k = 0; k < m_unknowns.size(); ++k)
        if(!done[k] && set.determined(m_special[k])) {
          const double value = set.point[m_special[k]];
          if(distance_to_integer(value) > 1e-6)
            throw Invalid_input(Error_code::invalid_argument,
                                "the integer rounding of the parametrisation is infeasible: the integers fixed "
                                "determine " + describe(m_unknowns[k]) + " to be " + std::to_string(value) +
                                ", not an integer");
          done[k] = 1;
          ++result.implied_unknowns;
        }
    };
    // the nearest integer that leaves every unknown it determines an integer: the closures and the lines' loops
    // divide by 2 or 4 at most, so among the 5 nearest integers one does whenever the earlier integers allow it
    // (tried in order of distance; none: the nearest, and settle_implied() reports the contradiction)
    // Distances are compared to tie_tolerance: the minimisers of the kept factor and of a new factorization
    // differ by rounding, and an exact tie (a symmetric mesh) must not be broken by it; a half goes up.
    auto fix = [&](std::size_t k, double value) {
      const double nearest = std::floor(value + 0.5 + tie_tolerance);
      std::vector<double> candidates = {nearest, nearest - 1, nearest + 1, nearest - 2, nearest + 2};
      auto quantised = [&](double a) { return std::round(std::abs(a - value) / tie_tolerance); };
      std::stable_sort(candidates.begin(), candidates.end(),
                       [&](double a, double b) { return quantised(a) < quantised(b); });
      double integer = nearest;
      if(integer_candidates > 1) {
        // the unknowns it determines do not depend on the integer, their values do, linearly (step)
        const Eigen::VectorXd step = set.step(m_special[k]);
        Affine_set trial = set;
        trial.fix(m_special[k], nearest);
        std::vector<std::size_t> determined;
        for(std::size_t j = 0; j < m_unknowns.size(); ++j)
          if(!done[j] && j != k && trial.determined(m_special[j]))
            determined.push_back(j);
        for(int n = 0; n < std::min(integer_candidates, int(candidates.size())); ++n) {
          bool integers = true;
          for(std::size_t j : determined)
            integers = integers && distance_to_integer(trial.point[m_special[j]] +
                                                       step[m_special[j]] * (candidates[n] - nearest)) <= 1e-6;
          if(integers) {
            integer = candidates[n];
            break;
          }
        }
      }
      if(integer != nearest)
        ++result.shifted_unknowns;
      if(kept)
        kept->fix(int(k), integer);
      else
        m_param.fix(m_unknowns[k].z, integer);
      set.fix(m_special[k], integer);
      done[k] = 1;
      ++result.fixed_unknowns;
    };
    if(scheme == Rounding_scheme::naive) {
      const Seamless_parametrization::Map continuous = map;
      // the visiting order: by kind, then (closest_first) by distance to an integer; stable for ties
      std::vector<std::size_t> visit(m_unknowns.size());
      for(std::size_t k = 0; k < visit.size(); ++k)
        visit[k] = k;
      auto key = [&](std::size_t k) {
        return std::make_pair(kind_of(m_unknowns[k]), m_order == Rounding_order::closest_first
                                                        ? distance_to_integer(value_of(continuous, m_unknowns[k]))
                                                        : 0.);
      };
      std::stable_sort(visit.begin(), visit.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
      for(std::size_t k : visit) {
        settle_implied();
        if(!done[k])
          fix(k, value_of(continuous, m_unknowns[k]));
      }
      settle_implied();
      if(result.fixed_unknowns > 0) {
        map = m_param.solve();
        ++result.solves;
        ++result.factorizations;
      }
    } else {
      for(;;) {
        const Eigen::VectorXd& values = kept->values();
        settle_implied();
        // the closest to an integer among the free unknowns of the first kind left
        std::size_t best = m_unknowns.size();
        int best_kind = 3;
        double best_distance = 1;
        for(std::size_t k = 0; k < m_unknowns.size(); ++k) {
          if(done[k])
            continue;
          const double d = distance_to_integer(values[Eigen::Index(k)]);
          const int kind = kind_of(m_unknowns[k]);
          if(kind < best_kind || (kind == best_kind && d < best_distance - tie_tolerance)) {
            best = k;
            best_kind = kind;
            best_distance = d;
          }
        }
        if(best == m_unknowns.size())
          break;
        // the values of this minimiser: fix() moves `values` to the next one
        const Eigen::VectorXd current = values;
        fix(best, current[Eigen::Index(best)]);
        // with it, those of its kind within batch_distance of an integer, and always those already integers
        // (to 1e-9: fixing them moves the minimiser by no more), which need no solve of their own
        const double batch = std::max(batch_distance, 1e-9);
        for(std::size_t k = 0; k < m_unknowns.size(); ++k)
          if(!done[k] && kind_of(m_unknowns[k]) == best_kind && !set.determined(m_special[k]) &&
             distance_to_integer(current[Eigen::Index(k)]) <= batch)
            fix(k, current[Eigen::Index(k)]);
        ++result.solves;
      }
      // the map itself from scratch, every integer eliminated
      if(kept->fixes_since_factorization() == 0) {
        map = m_param.map_of(m_param.reduced_solution()); // the last factorization has every fix (max_block 0)
      } else {
        map = m_param.solve();
        ++result.factorizations;
      }
      result.factorizations += kept->factorizations();
      result.back_substitutions = kept->back_substitutions();
    }
    // the map itself, not only the bookkeeping: every integer unknown an integer
    std::vector<Unknown> checked(m_unknowns);
    checked.insert(checked.end(), m_implied.begin(), m_implied.end());
    for(const Unknown& u : checked) {
      const double value = value_of(map, u);
      if(!(std::abs(value - std::round(value)) <= 1e-9 * (1 + std::abs(value))))
        throw Invalid_input(Error_code::solver_failure, "the integer rounding left " + describe(u) + " at " +
                                                          std::to_string(value) + ", not an integer");
    }
    result.map = map;
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }

private:
  struct Unknown
  {
    int z;      // index in the parametrisation's unknowns
    int vertex; // a singular vertex's root, or -1
    int arc;    // an arc's translation, or -1
    int coordinate; // 0: u, 1: v
    bool feature;   // a feature line (vertex: the vertex of its representative)
  };

  // z_S = point + directions tau over the constrained unknowns S: every value they can take under the
  // constraints and the values fixed so far. Fixing one eliminates a direction.
  struct Affine_set
  {
    Eigen::VectorXd point;
    Eigen::MatrixXd directions; // columns scaled to a largest entry of 1

    // how the point moves per unit of z_s when fix(s, .) is called
    Eigen::VectorXd step(int s) const
    {
      Eigen::Index pivot = 0;
      directions.row(s).cwiseAbs().maxCoeff(&pivot);
      return directions.col(pivot) / directions(s, pivot);
    }
    bool determined(int s) const
    {
      return directions.cols() == 0 || directions.row(s).cwiseAbs().maxCoeff() <= 1e-9;
    }
    void fix(int s, double value)
    {
      CGAL_precondition(!determined(s));
      Eigen::Index pivot = 0;
      directions.row(s).cwiseAbs().maxCoeff(&pivot);
      const Eigen::VectorXd step = directions.col(pivot) / directions(s, pivot);
      point += step * (value - point[s]);
      point[s] = value;
      for(Eigen::Index c = 0; c < directions.cols(); ++c)
        if(c != pivot) {
          const double along = directions(s, c);
          directions.col(c) -= step * along;
          directions(s, c) = 0;
          const double scale = directions.col(c).cwiseAbs().maxCoeff();
          if(scale > 0)
            directions.col(c) /= scale;
        }
      const Eigen::Index last = directions.cols() - 1;
      directions.col(pivot) = directions.col(last);
      directions.conservativeResize(Eigen::NoChange, last);
    }
  };

  static constexpr double tie_tolerance = 1e-9;
  static double distance_to_integer(double x) { return std::abs(x - std::round(x)); }
  int kind_of(const Unknown& u) const
  {
    return m_order == Rounding_order::closest_first ? 0 : u.feature ? 1 : u.vertex >= 0 ? 0 : 2;
  }

  static double value_of(const Seamless_parametrization::Map& map, const Unknown& u)
  {
    return u.vertex >= 0 ? map.root_uv[u.vertex][u.coordinate] : map.translation[u.arc][u.coordinate];
  }

  static std::string describe(const Unknown& u)
  {
    const std::string coordinate = u.coordinate == 0 ? "u" : "v";
    if(u.feature)
      return "the " + coordinate + " of the feature line through vertex " + std::to_string(u.vertex);
    return u.vertex >= 0 ? "the " + coordinate + " of singular vertex " + std::to_string(u.vertex)
                         : "the " + coordinate + " of the translation of arc " + std::to_string(u.arc);
  }

  // the affine set of the unknowns in the parametrisation's constraints and of the integer unknowns, under the
  // constraints alone; m_special: the integer unknowns' rows in it
  Affine_set constrained_unknowns()
  {
    std::vector<int> special_of(m_param.number_of_variables(), -1);
    int count = 0;
    for(const auto& t : m_param.constraint_rows())
      if(special_of[t.col()] < 0)
        special_of[t.col()] = count++;
    m_special.clear();
    for(const Unknown& u : m_unknowns) {
      if(special_of[u.z] < 0)
        special_of[u.z] = count++;
      m_special.push_back(special_of[u.z]);
    }
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(m_param.constraint_count(), count);
    for(const auto& t : m_param.constraint_rows())
      G(t.row(), special_of[t.col()]) += t.value();
    Affine_set set;
    set.point = Eigen::VectorXd::Zero(count); // the constraints are homogeneous
    if(G.rows() == 0) {
      set.directions = Eigen::MatrixXd::Identity(count, count);
    } else {
      Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
      lu.setThreshold(1e-10); // small integer entries, as in the parametrisation
      set.directions = lu.dimensionOfKernel() > 0 ? Eigen::MatrixXd(lu.kernel()) : Eigen::MatrixXd(count, 0);
      for(Eigen::Index c = 0; c < set.directions.cols(); ++c)
        set.directions.col(c) /= set.directions.col(c).cwiseAbs().maxCoeff();
    }
    return set;
  }

  Seamless_parametrization& m_param;
  std::vector<Unknown> m_unknowns;
  std::vector<Unknown> m_implied; // singular root coordinates eliminated by feature lines: checked only
  int m_feature_lines = 0;
  std::vector<int> m_special;
  Rounding_order m_order = Rounding_order::roots_first;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_INTEGER_ROUNDING_H
