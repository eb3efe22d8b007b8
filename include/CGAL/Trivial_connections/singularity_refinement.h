// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_REFINEMENT_H
#define CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_REFINEMENT_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>

#include <boost/property_map/vector_property_map.hpp>

#include <algorithm>
#include <type_traits>
#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
One accepted move of `refine_singularities()`: `index` went from `from` to `to` (a whole singularity to a
neighbouring vertex, or one unit of 1/n of a positive singularity cancelling one of a negative singularity at `to`).
*/
template <class VertexDescriptor>
struct Singularity_move
{
  VertexDescriptor from;   ///< the vertex the index left
  VertexDescriptor to;     ///< the neighbour it went to, or the negative singularity it cancelled against
  Singularity_index index; ///< the index moved
  double energy = 0;       ///< the minimised energy after the move
};

/*!
\ingroup PkgTrivialConnectionsRef
What `refine_singularities()` did.
*/
template <class VertexDescriptor>
struct Refinement_report
{
  /// the refined singularities, by increasing vertex index
  std::vector<std::pair<VertexDescriptor, Singularity_index>> singularities;
  double energy_before = 0;  ///< minimised energy (`energy + guidance_energy`) of the starting set
  double energy_after = 0;   ///< and of the refined set (never more)
  std::vector<Singularity_move<VertexDescriptor>> moves; ///< in the order made
  std::size_t trials = 0;    ///< solves tried (the first solve not counted)
  bool local_minimum = false; ///< stopped because no candidate move lowered the energy (not the budget)
  Solve_report report;       ///< the solve of the refined set (its connection is the last one written)
};

/*!
\ingroup PkgTrivialConnectionsRef

Moves singularities to where they cost least: starting from a valid set (automatic or the user's), it
repeatedly moves one singularity to a neighbouring interior vertex (or, with `cancel_pairs`, cancels a unit of a
positive singularity against one of a negative singularity) when that lowers the minimised energy of the
trivial connection (`energy + guidance_energy` of `solve()`, its integers chosen again for each trial). Each
trial is one `solve()` on the prefactored solver (back-substitutions only). The candidates of a round are all
moves of a free singularity to a free neighbour, tried in the order of their first-order change `k (g_w - g_v)`
(`energy_gradient`), those that predict a decrease only; the first that lowers the energy is made. It stops at a
local minimum (no candidate lowers the energy) or when the budget of trials is spent.
Poincare-Hopf is kept: a move keeps every component's index sum.

\tparam Solver a `Trivial_connection_solver`
\tparam SingularityRange as for `solve()`
\param solver the prefactored solver
\param start the starting singularities (checked as by `solve()`)
\param x a writable property map `halfedge_descriptor -> double`: receives the connection of the refined set
\param np an optional sequence of named parameters: those of `solve()` (`symmetry_order`, `loop_periods`,
       `face_directions`), and
\cgalNamedParamsBegin
  \cgalParamNBegin{fixed_vertices}
    \cgalParamDescription{vertices whose singularity does not move and onto which none moves}
    \cgalParamType{a range of `vertex_descriptor`} \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{cancel_pairs}
    \cgalParamDescription{a pair of opposite singularities of a component may also cancel, one unit of 1/n each,
      whatever their distance (candidates like the moves, by their first-order change `(g_w - g_v) / n`);
      otherwise singularities never move onto each other}
    \cgalParamType{`bool`} \cgalParamDefault{`false`}
  \cgalParamNEnd
  \cgalParamNBegin{maximum_trials} \cgalParamType{`std::size_t`} \cgalParamDefault{500} \cgalParamNEnd
\cgalNamedParamsEnd
\throws Invalid_input as `solve()` for the starting set
\returns the refined set, the energies before and after, the moves made
*/
template <class Solver, class SingularityRange, class HalfedgeAngleMap,
          class NamedParameters = parameters::Default_named_parameters>
Refinement_report<typename Solver::vertex_descriptor>
refine_singularities(Solver& solver, const SingularityRange& start, HalfedgeAngleMap x,
                     const NamedParameters& np = parameters::default_values())
{
  using vertex_descriptor = typename Solver::vertex_descriptor;
  using Access = internal::Solver_access<Solver>;
  const auto& m = Access::mesh(solver);
  const internal::Mesh_geometry& g = Access::geometry(solver);
  const internal::Mesh_topology& t = Access::topology(solver);
  const int n = internal::checked_symmetry_order(
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1));
  const bool cancel = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::cancel_pairs), false);
  const std::size_t budget =
    CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::maximum_trials), std::size_t(500));

  std::vector<char> fixed(std::size_t(m.nv), 0);
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, tc_np::fixed_vertices_t>::value)
    for(const vertex_descriptor v : CGAL::parameters::get_parameter(np, tc_np::fixed_vertices)) {
      const std::size_t i = std::size_t(get(m.vertex_index, v));
      if(i >= std::size_t(m.nv) || m.vertex_descriptors[i] != v)
        throw Invalid_input(Error_code::invalid_vertex, "a fixed vertex is not a vertex of the mesh");
      fixed[i] = 1;
    }

  // n times the index per vertex; the set as solve() takes it
  std::vector<std::int64_t> k(std::size_t(m.nv), 0);
  auto as_set = [&](const std::vector<std::int64_t>& kk) {
    std::vector<std::pair<vertex_descriptor, Singularity_index>> s;
    for(int v = 0; v < m.nv; ++v)
      if(kk[v] != 0)
        s.emplace_back(m.vertex_descriptors[v], Singularity_index(kk[v], n));
    return s;
  };
  using Gradient = boost::vector_property_map<double, typename std::decay_t<decltype(m)>::Vertex_index_map>;
  auto solve = [&](const std::vector<std::int64_t>& kk, std::vector<double>& gradient, Solve_report& report) {
    Gradient map(std::size_t(m.nv), m.vertex_index);
    report = solver.solve(as_set(kk), x, parameters::energy_gradient(map, np));
    gradient.resize(std::size_t(m.nv));
    for(int v = 0; v < m.nv; ++v)
      gradient[v] = map[m.vertex_descriptors[v]];
    return report.energy + report.guidance_energy;
  };

  Refinement_report<vertex_descriptor> result;
  std::vector<double> gradient;
  double energy = 0;
  {
    // the first solve checks the set (vertices, multiples of 1/n, Poincare-Hopf) before it is read
    std::vector<std::pair<vertex_descriptor, Singularity_index>> given;
    for(const auto& s : start)
      given.emplace_back(s.first, s.second);
    Gradient map(std::size_t(m.nv), m.vertex_index);
    result.report = solver.solve(given, x, parameters::energy_gradient(map, np));
    for(const auto& s : given)
      k[std::size_t(get(m.vertex_index, s.first))] = s.second.times(n);
    gradient.resize(std::size_t(m.nv));
    for(int v = 0; v < m.nv; ++v)
      gradient[v] = map[m.vertex_descriptors[v]];
    energy = result.report.energy + result.report.guidance_energy;
  }
  result.energy_before = energy;

  // vertex neighbours (each interior edge once per direction; border edges from their one corner)
  std::vector<std::vector<int>> neighbours(std::size_t(m.nv));
  for(int i = 0; i < 3 * m.nf; ++i) {
    neighbours[m.source_of(i)].push_back(m.target_of(i));
    if(m.opposite_corner[i] < 0)
      neighbours[m.target_of(i)].push_back(m.source_of(i));
  }
  struct Candidate
  {
    int from, to;
    std::int64_t units;
    double predicted;
  };
  std::vector<double> trial_gradient;
  Solve_report trial_report;
  bool last_trial_accepted = true;
  while(result.trials < budget) {
    std::vector<Candidate> candidates;
    for(int v = 0; v < m.nv; ++v) {
      if(k[v] == 0 || fixed[v])
        continue;
      for(int w : neighbours[v]) {
        if(fixed[w] || g.on_boundary[w] || w == v || k[w] != 0)
          continue;
        const double predicted = double(k[v]) / n * (gradient[w] - gradient[v]);
        if(predicted < 0)
          candidates.push_back({v, w, k[v], predicted});
      }
    }
    if(cancel) {
      // one unit of a positive singularity onto a negative one of its component, at any distance: both lose a unit
      std::vector<int> positive, negative;
      for(int v = 0; v < m.nv; ++v)
        if(k[v] != 0 && !fixed[v])
          (k[v] > 0 ? positive : negative).push_back(v);
      for(int v : positive)
        for(int w : negative) {
          if(t.component_of_node[t.node_of_vertex[v]] != t.component_of_node[t.node_of_vertex[w]])
            continue;
          const double predicted = (gradient[w] - gradient[v]) / n;
          if(predicted < 0)
            candidates.push_back({v, w, 1, predicted});
        }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.predicted < b.predicted; });
    bool moved = false;
    for(const Candidate& c : candidates) {
      if(result.trials >= budget)
        break;
      std::vector<std::int64_t> kk(k);
      kk[c.from] -= c.units;
      kk[c.to] += c.units;
      ++result.trials;
      const double e = solve(kk, trial_gradient, trial_report);
      last_trial_accepted = e < energy * (1 - 1e-12); // a strict decrease, beyond rounding: no cycling on ties
      if(last_trial_accepted) {
        k.swap(kk);
        gradient.swap(trial_gradient);
        result.report = trial_report;
        energy = e;
        result.moves.push_back({m.vertex_descriptors[c.from], m.vertex_descriptors[c.to], Singularity_index(c.units, n), e});
        moved = true;
        break;
      }
    }
    if(!moved) {
      result.local_minimum = result.trials < budget || candidates.empty();
      break;
    }
  }
  result.energy_after = energy;
  result.singularities = as_set(k);
  // x holds the last trial's connection: solved again when that trial was rejected
  if(!last_trial_accepted)
    result.report = solver.solve(result.singularities, x, np);
  return result;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_REFINEMENT_H
