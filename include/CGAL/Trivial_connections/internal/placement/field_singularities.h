// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_FIELD_SINGULARITIES_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_FIELD_SINGULARITIES_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <CGAL/number_type_config.h>

#include <algorithm>
#include <climits>
#include <optional>
#include <cmath>
#include <complex>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The indices a face field has at the vertices, with what reading them cost.
struct Field_singularities
{
  std::vector<std::int64_t> k;        // per vertex: n times its index (0 on boundary and isolated vertices)
  double connection_energy = 0;       // sum_e w_e (d_e / n)^2: the energy of the connection making the field parallel
  double max_rounding = 0;            // largest distance of (n K_v + sum d) / 2 pi from the integer taken
};

/*
  The index of every interior vertex for the face field whose n-th powers are `u`: going counter-clockwise
  around v (the crossings of the corner halfedges that end at v), d = the change of n times the angle across
  the edge beyond n times the transport, wrapped to (-pi, pi]; then n k_v = (n K_v + sum d) / 2 pi, an integer
  up to rounding. The connection x = d / n makes the field parallel and has exactly these singularities, so
  every closed component's n k_v sum to n chi: each d enters the sums of its edge's two ends with opposite signs
  and the n K_v sum to 2 pi n chi. This is checked, and a component whose sum rounding broke (a vertex whose
  sum lies near a half-integer, which only a numerically degenerate field gives) is an error.
*/
template <class TriangleMesh>
Field_singularities read_field_singularities(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                                             const std::vector<std::complex<double>>& u, int n)
{
  Field_singularities result;
  std::vector<double> turn(std::size_t(m.nv), 0.);
  std::vector<double> angle(std::size_t(m.nf)); // once per face rather than twice per edge
  for(int f = 0; f < m.nf; ++f)
    angle[f] = std::arg(u[f]);
  for(int e = 0; e < g.number_of_interior_edges(); ++e) {
    const int i = g.edge_corner[e];
    const int f = Mesh_arrays<TriangleMesh>::face_of(i), h = Mesh_arrays<TriangleMesh>::face_of(m.opposite_corner[i]);
    const double d = wrap_angle(angle[h] - angle[f] - n * g.transport[e]);
    turn[m.target_of(i)] += d;
    turn[m.source_of(i)] -= d;
    result.connection_energy += g.weight[e] * (d / n) * (d / n);
  }
  result.k.assign(std::size_t(m.nv), 0);
  for(int v = 0; v < m.nv; ++v) {
    if(m.faces_at_vertex[v] == 0 || g.on_boundary[v])
      continue;
    const double value = (n * g.angle_defect(v) + turn[v]) / (2 * CGAL_PI);
    const double k = std::round(value);
    result.max_rounding = (std::max)(result.max_rounding, std::abs(value - k));
    result.k[v] = std::abs(k) < 1e15 ? std::int64_t(k) : 0; // only a NaN or a numerically absurd field gets here
  }
  return result;
}

// the same, checked: a field that vanishes or is not finite somewhere, and Poincare-Hopf on closed components
template <class TriangleMesh>
Field_singularities field_singularities(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                                        const Mesh_topology& t, const std::vector<std::complex<double>>& u, int n)
{
  for(int f = 0; f < m.nf; ++f)
    if(!(std::abs(u[f]) > 0) || !std::isfinite(std::abs(u[f])))
      throw Invalid_input(Error_code::solver_failure,
                          "the smoothest field vanishes or is not finite on face " + std::to_string(f) +
                            ": its singularities cannot be read", std::size_t(f));
  Field_singularities result = read_field_singularities(m, g, u, n);
  std::vector<std::int64_t> sums(t.components.size(), 0);
  for(int v = 0; v < m.nv; ++v)
    if(result.k[v] != 0)
      sums[t.component_of_node[t.node_of_vertex[v]]] += result.k[v];
  for(std::size_t c = 0; c < t.components.size(); ++c) {
    const Mesh_topology::Component& comp = t.components[c];
    if(comp.boundary_loops > 0)
      continue;
    const std::int64_t chi = std::int64_t(comp.vertices) - comp.edges + comp.faces;
    if(sums[c] != n * chi)
      throw Invalid_input(Error_code::solver_failure,
                          "the singularities read off the smoothest field of component " + std::to_string(c) +
                            " sum to " + std::to_string(sums[c]) + "/" + std::to_string(n) + " instead of its Euler "
                            "characteristic " + std::to_string(chi) + " (rounding error up to " +
                            std::to_string(result.max_rounding) + " of a unit: the field is numerically degenerate)",
                          c);
  }
  return result;
}

/*
  Combines an automatic placement `automatic` (n times the indices per vertex) with what the user prescribes: fixed
  singularities (`fixed`, `fixed_k`) and the index sums some components must have (`target`, n times the sum per
  component, from prescribed boundary indices; empty: the automatic placement's sum, chi on a closed component).
  On the fixed vertices the fixed index is taken; then the automatic singularities nearest (graph distance) to the
  sources give way, one unit of 1/n at a time, until each component's sum is its target. The sources are the fixed
  vertices and the boundary vertices of the components with a target: the singularities nearest to a hole whose
  index is prescribed are the ones that were standing for it. When no automatic singularity of the needed sign is
  left, units of the other sign are added at free interior vertices: nearest to the sources on a bordered
  component with a target, farthest from every singularity on a closed one. Counts the units removed and added.
*/
template <class TriangleMesh>
std::vector<std::int64_t> combine_with_prescribed(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& g,
                                                  const Mesh_topology& t, const std::vector<std::int64_t>& automatic,
                                                  const std::vector<std::int64_t>& fixed_k, const std::vector<char>& fixed,
                                                  const std::vector<std::optional<std::int64_t>>& target,
                                                  std::size_t& removed, std::size_t& added)
{
  std::vector<std::int64_t> k(automatic);
  const std::size_t nc = t.components.size();
  std::vector<std::int64_t> excess(nc, 0);
  auto component_of = [&](int v) { return t.component_of_node[t.node_of_vertex[v]]; };
  for(int v = 0; v < m.nv; ++v) {
    if(m.faces_at_vertex[v] == 0)
      continue;
    if(fixed[v])
      k[v] = fixed_k[v];
    excess[component_of(v)] += k[v] - automatic[v];
  }
  for(std::size_t c = 0; c < nc; ++c)
    if(target[c]) {
      std::int64_t sum = 0;
      for(int v = 0; v < m.nv; ++v)
        if(m.faces_at_vertex[v] > 0 && component_of(v) == int(c))
          sum += k[v];
      excess[c] = sum - *target[c];
    }
  removed = added = 0;
  if(std::all_of(excess.begin(), excess.end(), [](std::int64_t e) { return e == 0; }))
    return k;

  std::vector<std::vector<int>> neighbours(std::size_t(m.nv));
  for(int i = 0; i < 3 * m.nf; ++i) {
    neighbours[m.source_of(i)].push_back(m.target_of(i));
    neighbours[m.target_of(i)].push_back(m.source_of(i));
  }
  auto distances_from = [&](const std::vector<int>& sources) {
    std::vector<int> distance(std::size_t(m.nv), -1);
    std::deque<int> queue;
    for(int s : sources) {
      distance[s] = 0;
      queue.push_back(s);
    }
    while(!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      for(int w : neighbours[v])
        if(distance[w] < 0) {
          distance[w] = distance[v] + 1;
          queue.push_back(w);
        }
    }
    return distance;
  };
  std::vector<int> sources;
  for(int v = 0; v < m.nv; ++v)
    if(m.faces_at_vertex[v] > 0 && (fixed[v] || (g.on_boundary[v] && target[component_of(v)])))
      sources.push_back(v);
  const std::vector<int> near = distances_from(sources);
  // unreached vertices (a component without sources) last
  auto nearer = [&](int a, int b) {
    return (near[a] < 0 ? INT_MAX : near[a]) < (near[b] < 0 ? INT_MAX : near[b]);
  };
  std::vector<int> by_distance;
  for(int v = 0; v < m.nv; ++v)
    if(!fixed[v] && k[v] != 0)
      by_distance.push_back(v);
  std::stable_sort(by_distance.begin(), by_distance.end(), nearer);
  for(int v : by_distance) {
    const int c = component_of(v);
    while(excess[c] != 0 && k[v] != 0 && (k[v] > 0) == (excess[c] > 0)) {
      const std::int64_t s = excess[c] > 0 ? 1 : -1;
      k[v] -= s;
      excess[c] -= s;
      ++removed;
    }
  }
  // what removal could not balance: units of the missing sign
  std::vector<int> singular;
  for(int v = 0; v < m.nv; ++v)
    if(k[v] != 0)
      singular.push_back(v);
  const std::vector<int> far = distances_from(singular);
  std::vector<int> candidates;
  for(int v = 0; v < m.nv; ++v)
    if(m.faces_at_vertex[v] > 0 && !g.on_boundary[v] && !fixed[v] && k[v] == 0)
      candidates.push_back(v);
  std::vector<int> closest(candidates), farthest(candidates);
  std::stable_sort(closest.begin(), closest.end(), nearer);
  std::stable_sort(farthest.begin(), farthest.end(), [&](int a, int b) { return far[a] > far[b]; });
  for(int pass = 0; pass < 2; ++pass)
    for(int v : pass == 0 ? farthest : closest) {
      const int c = component_of(v);
      const bool bordered = t.components[c].boundary_loops > 0;
      if(excess[c] == 0 || k[v] != 0 || bordered != (pass == 1) || (bordered && !target[c]))
        continue;
      const std::int64_t s = excess[c] > 0 ? 1 : -1;
      k[v] = -s;
      excess[c] -= s;
      ++added;
    }
  for(std::size_t c = 0; c < nc; ++c)
    if(excess[c] != 0 && (t.components[c].boundary_loops == 0 || target[c]))
      throw Invalid_input(Error_code::poincare_hopf_violated,
                          "the prescribed singularities and boundary indices of component " + std::to_string(c) +
                            " cannot be completed to satisfy Poincare-Hopf (not enough free interior vertices)", c);
  return k;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_FIELD_SINGULARITIES_H
