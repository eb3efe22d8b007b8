// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_RIGHT_HAND_SIDE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_RIGHT_HAND_SIDE_H

#include <CGAL/Trivial_connections/Singularity_index.h>
#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/system/constraint_rows.h>

#include <CGAL/number_type_config.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// the symmetry order n of a solve or a field, checked
inline int checked_symmetry_order(int n)
{
  if(n < 1)
    throw Invalid_input(Error_code::invalid_symmetry_order,
                        "the symmetry order n must be at least 1 (got " + std::to_string(n) + ")");
  return n;
}

/*
  The bound of the integers that set holonomies: |n k_v| of a vertex index k_v, and |period| of a loop (holonomy
  2 pi period / n), at most 2^10 full turns (n 2^10) and never more than 2^30. A solve's right-hand side holds
  2 pi k, and the residuals it reaches are rounding relative to it: about 4e-11 rad at 2^10 turns (6.4e3 rad), well
  below the 1e-9 a solve is held to, but 2.7e-9 at 2^16 turns on a small torus, and 1e-6 at 10^9 turns, silently.
  No design needs more than a few turns. 2^30 keeps the sums over any mesh far from overflow.
*/
inline std::int64_t max_scaled_index(int n)
{
  return (std::min)(std::int64_t(1) << 30, (std::int64_t(1) << 10) * std::int64_t(n));
}

// whether n index is within max_scaled_index(n), for an index that is a multiple of 1/n (n index itself may
// overflow: it is not computed)
inline bool index_in_range(const Singularity_index& index, int n)
{
  return std::abs(index.numerator()) <= max_scaled_index(n) / (n / index.denominator());
}

// what a message says of the bound: "1024" (turns)
inline std::string max_index_text(int n)
{
  return Singularity_index(max_scaled_index(n), n).to_string();
}

/*
  The singularities as n times their index per vertex, checked: vertices of the mesh with a face, listed
  once, interior, multiples of 1/n, bounded (max_scaled_index()), and
  Poincare-Hopf on every closed component, exactly. Writes each component's index sum into `components`.
*/
template <class TriangleMesh, class SingularityRange>
std::vector<std::int64_t> checked_vertex_indices(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& geometry,
                                                 const Mesh_topology& topology, const SingularityRange& singularities,
                                                 int n, std::vector<Component_report>& components)
{
  std::vector<std::int64_t> k(m.nv, 0);
  std::vector<char> listed(m.nv, 0);
  std::vector<std::int64_t> sums(components.size(), 0); // n times the index sums
  for(const auto& s : singularities) {
    const typename boost::graph_traits<TriangleMesh>::vertex_descriptor vd = s.first;
    const Singularity_index& index = s.second;
    const std::size_t v = std::size_t(get(m.vertex_index, vd));
    if(v >= std::size_t(m.nv) || m.vertex_descriptors[v] != vd)
      throw Invalid_input(Error_code::invalid_vertex, "a singularity is placed on a vertex that is not in the mesh");
    if(m.faces_at_vertex[v] == 0)
      throw Invalid_input(Error_code::invalid_vertex,
                          "vertex " + std::to_string(v) + " carries a singularity but belongs to no face", v);
    if(listed[v])
      throw Invalid_input(Error_code::duplicate_singularity, "vertex " + std::to_string(v) + " is given a singularity twice", v);
    listed[v] = 1;
    if(geometry.on_boundary[v])
      throw Invalid_input(Error_code::singularity_on_boundary,
                          "vertex " + std::to_string(v) + " is on the boundary: singularities must be interior "
                          "(boundary loops get their index from the solver or from loop_periods)", v);
    if(!index.is_multiple_of_one_over(n))
      throw Invalid_input(Error_code::index_not_multiple,
                          "the index " + index.to_string() + " of vertex " + std::to_string(v) +
                            " is not a multiple of 1/" + std::to_string(n), v);
    if(!index_in_range(index, n))
      throw Invalid_input(Error_code::invalid_index,
                          "the index " + index.to_string() + " of vertex " + std::to_string(v) +
                            " is too large (at most " + max_index_text(n) + " in absolute value)", v);
    k[v] = index.times(n);
    sums[topology.component_of_node[topology.node_of_vertex[v]]] += k[v];
  }
  std::string violations;
  std::size_t first_bad = Invalid_input::no_location, bad = 0;
  for(std::size_t c = 0; c < components.size(); ++c) {
    const Singularity_index sum(sums[c], n);
    components[c].vertex_index_sum = sum;
    if(components[c].number_of_boundary_loops == 0 && sums[c] != n * components[c].euler_characteristic && ++bad <= 5) {
      violations += (violations.empty() ? "" : "; ") + std::string("component ") + std::to_string(c) +
                    " (closed, genus " + std::to_string(components[c].genus) + "): indices sum to " +
                    sum.to_string() + ", expected " + std::to_string(components[c].euler_characteristic);
      if(first_bad == Invalid_input::no_location)
        first_bad = c;
    }
  }
  if(bad > 5)
    violations += "; and " + std::to_string(bad - 5) + " more components";
  if(!violations.empty())
    throw Invalid_input(Error_code::poincare_hopf_violated, "Poincare-Hopf violated: " + violations, first_bad);
  return k;
}

// n times the index sum of each component's vertices, from the `vertex_index_sum` that checked_vertex_indices()
// wrote (exact: its denominator divides n)
inline std::vector<std::int64_t> scaled_vertex_index_sums(const std::vector<Component_report>& components, int n)
{
  std::vector<std::int64_t> sums(components.size(), 0);
  for(std::size_t c = 0; c < components.size(); ++c)
    sums[c] = components[c].vertex_index_sum.times(n);
  return sums;
}

// Per slot, H with H + sum x = 2 pi period / n: the loops' Levi-Civita holonomy, and for a link the
// transport along it plus the target angle it leaves minus the one it reaches (wrapped).
inline std::vector<double> slot_holonomies(const Constraint_rows& rows, const std::vector<double>& loop_holonomy,
                                           const std::vector<double>& target)
{
  const Constraint_links& links = rows.links();
  std::vector<double> holonomy(loop_holonomy);
  holonomy.resize(rows.number_of_slots(), 0.);
  for(std::size_t j = 0; j < links.links.size(); ++j) {
    const std::size_t l = loop_holonomy.size() + j;
    double h = target[links.links[j].from] - target[links.links[j].to];
    for(int p = rows.slot_edge_start[l]; p < rows.slot_edge_start[l + 1]; ++p)
      h += sign_of_code(rows.slot_edges[p]) * rows.geometry().transport[index_of_code(rows.slot_edges[p])];
    holonomy[l] = wrap_angle(h);
  }
  return holonomy;
}

/*
  Per component, the share of its Gauss-Bonnet rounding that each of its node rows takes. The rows of all the
  nodes of a component, the pinned one included, sum to 2 pi chi - sum_v K_v - sum_L H_L, which is 0 in exact
  arithmetic (the integers add up to n chi). In double the angle defects' rounding adds up, about 1e-16 per vertex
  and linearly (6e-10 on a 4.8M-face sphere, 1e-9 near 8M faces), and as the pinned node's row is implied by the
  others all of it would land on the pinned node's residual. Subtracting the component's sum divided by its number
  of nodes from each of its node rows leaves that share on every node instead. A sum that is not rounding (beyond
  1e-13 per node) is left alone (share 0), to show in the pinned node's residual. Depends on the mesh only:
  computed once per solver. `loop_holonomy`: per loop, H_L.
*/
inline std::vector<double> gauss_bonnet_rounding_shares(const Constraint_rows& rows,
                                                        const std::vector<double>& loop_holonomy)
{
  const Mesh_topology& t = rows.topology();
  const std::size_t nc = t.components.size();
  // compensated (Neumaier) sums: the plain sum's own rounding would be of the size being removed
  std::vector<double> sum(nc, 0.), compensation(nc, 0.);
  std::vector<double> nodes(nc, 0.);
  auto add = [&](std::size_t c, double value) {
    const double s = sum[c] + value;
    compensation[c] += std::abs(sum[c]) >= std::abs(value) ? (sum[c] - s) + value : (value - s) + sum[c];
    sum[c] = s;
  };
  for(std::size_t c = 0; c < nc; ++c)
    add(c, 2 * CGAL_PI * double(t.components[c].euler_characteristic));
  for(std::size_t node = 0; node < rows.vertex_of_node.size(); ++node) {
    const std::size_t c = std::size_t(t.component_of_node[node]);
    add(c, -rows.geometry().angle_defect(rows.vertex_of_node[node]));
    nodes[c] += 1;
  }
  for(std::size_t l = 0; l < t.loops.size(); ++l)
    if(t.loops[l].kind == Loop_kind::boundary) {
      const std::size_t c = std::size_t(t.loops[l].component);
      add(c, -loop_holonomy[l]);
      nodes[c] += 1;
    }
  std::vector<double> share(nc, 0.);
  for(std::size_t c = 0; c < nc; ++c) {
    const double rounding = sum[c] + compensation[c];
    if(nodes[c] > 0 && std::abs(rounding) <= 1e-13 * nodes[c])
      share[c] = rounding / nodes[c];
  }
  return share;
}

// b of A x = b: per node row 2 pi k_v / n - K_v, per slot row 2 pi period / n - H; then each node row less its
// component's share of the Gauss-Bonnet rounding (`shares`, from gauss_bonnet_rounding_shares()).
inline Eigen::VectorXd right_hand_side(const Constraint_rows& rows, const std::vector<std::int64_t>& k,
                                       const std::vector<std::int64_t>& periods, const std::vector<double>& holonomy,
                                       int n, const std::vector<double>& shares)
{
  const double unit = 2 * CGAL_PI / n;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(rows.size());
  for(std::size_t node = 0; node < rows.vertex_of_node.size(); ++node) {
    const int r = rows.row_of_node[node];
    if(r >= 0) {
      const int v = rows.vertex_of_node[node];
      b[r] = unit * double(k[v]) - rows.geometry().angle_defect(v);
    }
  }
  for(std::size_t l = 0; l < holonomy.size(); ++l)
    if(rows.row_of_slot[l] >= 0)
      b[rows.row_of_slot[l]] = unit * double(periods[l]) - holonomy[l];
  const Mesh_topology& t = rows.topology();
  for(int node = 0; node < t.number_of_nodes; ++node)
    if(rows.row_of_node[node] >= 0)
      b[rows.row_of_node[node]] -= shares[std::size_t(t.component_of_node[node])];
  return b;
}

// b for the chosen integers of the free slots not prescribed, from b for the integers 0 there
inline void add_chosen_periods(const Constraint_rows& rows, const std::vector<std::int64_t>& periods,
                               const std::vector<char>& prescribed, double unit, Eigen::VectorXd& b)
{
  for(const std::vector<int>& free : rows.free_slots)
    for(int l : free)
      if(!prescribed[l])
        b[rows.row_of_slot[l]] += unit * double(periods[l]);
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_RIGHT_HAND_SIDE_H
