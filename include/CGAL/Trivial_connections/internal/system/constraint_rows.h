// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_ROWS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_ROWS_H

#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <CGAL/assertions.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The sums the constraints read from a connection: per node its star sum (collapsed for a boundary loop;
// pinned nodes too), per slot the signed sum of its crossings (a boundary loop's is its node's; a link's
// includes its guided ends' slacks).
struct Constraint_sums
{
  std::vector<double> node, loop;
  double energy = 0;          // sum of w_e x_e^2, read on the way
  std::vector<double> slack;  // per guided face, its mismatch d_g
  double guidance_energy = 0; // mu sum_g d_g^2
};

/*
  The rows of the constraint system A x = b and the products with A that never form it. The unknown is x_e
  per interior edge. Rows: one per node of the collapsed surface (interior vertex or boundary loop) except
  the pinned node of each component, whose row follows from the others; then one per generator and per link
  of the directional constraints. "Slots" number everything that carries an integer: the loops of the
  tree-cotree decomposition (boundary loops, whose row is their node's, then generators), then the links.
  A slot's crossings are coded e (x_e) or ~e (-x_e).
  A decided link (between touching pins, see Constraint_links) has its integer chosen by rounding. Across one
  edge it has no row: the rounding fixes x_e there, and that edge leaves the system: its column of A is dropped
  (`inverse_weight` 0), and the fixed x_e moves to the right-hand side. M keeps its pattern (the entries become
  0), so the fill-reducing order of the node rows holds whatever the pins. Through a vertex's fan it is a row
  with a prescribed integer, placed in the factor right after the last of the nodes it touches (a boundary loop's
  node aside: its row is free, last): their columns already join its neighbours, so it adds one short column and
  no fill elsewhere.
  Reads the geometry, the topology and the links it was built from, which must outlive it.
*/
class Constraint_rows
{
public:
  std::vector<int> row_of_node;    // -1: pinned
  std::vector<int> row_of_slot;    // -1: the pinned boundary loop; >= rows: a link outside the factor
  std::vector<int> vertex_of_node; // per interior node
  std::vector<int> free_rows;      // rows with a free integer when the system was built: last in the factor
  std::vector<std::vector<int>> free_slots;  // per component: slots with a row (free integers)
  std::vector<int> slot_edge_start, slot_edges; // per slot (CSR): its coded crossings
  std::vector<int> border_corners;            // corner halfedges on a border edge
  std::vector<double> inverse_weight;         // per interior edge: 1 / w_e, 0 on an edge a decided link fixes
  std::vector<int> decided_slots;             // slots of the decided links (a row only through a fan)
  std::vector<int> decided_row_node_start, decided_row_nodes; // per decided row (CSR, in row order): its nodes
  // per interior edge, the nodes of its canonical corner's source and target (compute_edge_nodes())
  std::vector<std::array<int, 2>> edge_nodes;
  Eigen::Index rows = 0;    // of the factored system
  Eigen::Index outside = 0; // link rows outside the factor (after set_link_rows())

  Constraint_rows() = default;

  // Releases the links' crossings once coded.
  template <class TriangleMesh>
  Constraint_rows(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& geometry, const Mesh_topology& topology,
                  Constraint_links& links)
    : m_geometry(&geometry), m_topology(&topology), m_links(&links)
  {
    const Mesh_topology& t = topology;
    row_of_node.assign(t.number_of_nodes, -1);
    int count = 0;
    std::vector<char> pinned(t.number_of_nodes, 0);
    for(const auto& c : t.components)
      pinned[c.pinned_node] = 1;
    for(int node = 0; node < t.number_of_nodes; ++node)
      if(!pinned[node])
        row_of_node[node] = count++;
    const std::size_t nl = t.loops.size(), slots = nl + links.links.size();
    row_of_slot.assign(slots, -1);
    free_slots.assign(t.components.size(), {});
    for(std::size_t l = 0; l < slots; ++l) {
      const int component = l < nl ? t.loops[l].component : links.links[l - nl].component;
      if(l >= nl && links.links[l - nl].decided) {
        decided_slots.push_back(int(l));
        if(links.links[l - nl].crossings.size() > 1)
          row_of_slot[l] = count++;
        continue;
      }
      row_of_slot[l] = l < nl && t.loops[l].kind == Loop_kind::boundary ? row_of_node[t.loops[l].node] : count++;
      if(row_of_slot[l] >= 0) {
        free_slots[component].push_back(int(l));
        free_rows.push_back(row_of_slot[l]);
      }
    }
    for(int i = 0; i < 3 * m.nf; ++i)
      if(m.opposite_corner[i] < 0)
        border_corners.push_back(i);
    vertex_of_node.assign(t.number_of_interior_nodes, -1);
    for(int v = 0; v < m.nv; ++v) {
      const int node = t.node_of_vertex[v];
      if(node >= 0 && node < t.number_of_interior_nodes)
        vertex_of_node[node] = v;
    }
    auto crossings_of = [&](std::size_t l) -> const std::vector<int>& {
      return l < nl ? t.loops[l].crossings : links.links[l - nl].crossings;
    };
    slot_edge_start.assign(slots + 1, 0);
    for(std::size_t l = 0; l < slots; ++l)
      slot_edge_start[l + 1] = slot_edge_start[l] + int(crossings_of(l).size());
    slot_edges.resize(std::size_t(slot_edge_start.back()));
    for(std::size_t l = 0; l < slots; ++l) {
      int* out = slot_edges.data() + slot_edge_start[l];
      for(int i : crossings_of(l))
        *out++ = coded_crossing(i);
    }
    decided_row_node_start.assign(1, 0);
    for(int l : decided_slots)
      if(row_of_slot[std::size_t(l)] >= 0) {
        for(int i : crossings_of(std::size_t(l)))
          for(int v : {m.source_of(i), m.target_of(i)})
            decided_row_nodes.push_back(t.node_of_vertex[v]);
        decided_row_node_start.push_back(int(decided_row_nodes.size()));
      }
    links.release_crossings();
    rows = count;
    inverse_weight.resize(std::size_t(geometry.number_of_interior_edges()));
    for(std::size_t e = 0; e < inverse_weight.size(); ++e)
      inverse_weight[e] = 1 / geometry.weight[e];
    for(int l : decided_slots)
      if(row_of_slot[std::size_t(l)] < 0)
        inverse_weight[std::size_t(index_of_code(slot_edges[std::size_t(slot_edge_start[l])]))] = 0;
  }

  // after the links changed (set_constraints() on a kept factorization): `row_of_link[j]` is link j's row, in
  // the factor or >= rows outside it; `outside` rows lie outside. Releases the links' crossings once coded.
  void set_link_rows(Constraint_links& links, const std::vector<int>& row_of_link, Eigen::Index outside_rows)
  {
    CGAL_precondition(!links.has_decided_links() && decided_slots.empty());
    m_links = &links;
    const Mesh_topology& t = *m_topology;
    const std::size_t nl = t.loops.size();
    row_of_slot.resize(nl + links.links.size());
    for(std::size_t j = 0; j < links.links.size(); ++j)
      row_of_slot[nl + j] = row_of_link[j];
    outside = outside_rows;
    free_slots.assign(t.components.size(), {});
    for(std::size_t l = 0; l < row_of_slot.size(); ++l)
      if(row_of_slot[l] >= 0)
        free_slots[l < nl ? std::size_t(t.loops[l].component) : std::size_t(links.links[l - nl].component)].push_back(int(l));
    slot_edge_start.resize(nl + 1);
    slot_edges.resize(std::size_t(slot_edge_start[nl]));
    for(const auto& link : links.links) {
      for(int i : link.crossings)
        slot_edges.push_back(coded_crossing(i));
      slot_edge_start.push_back(int(slot_edges.size()));
    }
    links.release_crossings();
  }

  // The nodes of every interior edge, for the products with A (may run on another thread: reads only).
  template <class TriangleMesh>
  void compute_edge_nodes(const Mesh_arrays<TriangleMesh>& m)
  {
    const Mesh_geometry& g = *m_geometry;
    edge_nodes.resize(std::size_t(g.number_of_interior_edges()));
    for(int e = 0; e < g.number_of_interior_edges(); ++e)
      edge_nodes[e] = nodes_of_edge(m, e);
  }

  // the nodes of interior edge e's canonical corner: x_e enters the star of the second and, reversed, the
  // star of the first; both are the same node when the edge joins two vertices of one boundary loop
  template <class TriangleMesh>
  std::array<int, 2> nodes_of_edge(const Mesh_arrays<TriangleMesh>& m, int e) const
  {
    const int i = m_geometry->edge_corner[e];
    return {m_topology->node_of_vertex[m.source_of(i)], m_topology->node_of_vertex[m.target_of(i)]};
  }

  // rows of the factored system, then those outside it
  Eigen::Index size() const { return rows + outside; }
  std::size_t number_of_slots() const { return row_of_slot.size(); }

  // corner halfedge i of an interior edge e as a crossing: e when i is e's canonical halfedge, else ~e
  int coded_crossing(int i) const
  {
    const int e = m_geometry->edge_of_corner[i];
    return m_geometry->edge_corner[e] == i ? e : ~e;
  }

  // a generator or a link: a row made of its crossings (a boundary loop's row is its node's)
  bool is_crossing_slot(std::size_t l) const
  {
    return l >= m_topology->loops.size() || m_topology->loops[l].kind == Loop_kind::generator;
  }

  // a slot whose row is made of its crossings (a decided link has none)
  bool is_crossing_row(std::size_t l) const { return is_crossing_slot(l) && row_of_slot[l] >= 0; }

  const Mesh_geometry& geometry() const { return *m_geometry; }
  const Mesh_topology& topology() const { return *m_topology; }
  const Constraint_links& links() const { return *m_links; }

  // x = W^-1 A^T lambda, without A: each interior edge gets the multipliers of the stars it enters (+ at its
  // target's node, - at its source's; the difference vanishes when both are one boundary loop) and of the
  // generators and links that cross it.
  Eigen::VectorXd connection_of(const Eigen::VectorXd& lambda) const
  {
    Eigen::VectorXd xe;
    connection_of(lambda, xe);
    return xe;
  }
  // the same into `xe`, whose storage is reused when it has the size already (a solve's vectors are megabytes:
  // allocated afresh, each of their pages is a fault)
  void connection_of(const Eigen::VectorXd& lambda, Eigen::VectorXd& xe) const
  {
    transposed_product(lambda, xe);
    for(Eigen::Index e = 0; e < xe.size(); ++e)
      xe[e] *= inverse_weight[std::size_t(e)];
  }

  // A^T lambda, per interior edge (w_e x_e of x = W^-1 A^T lambda): the decided links, which have no row, left out
  Eigen::VectorXd transposed_product(const Eigen::VectorXd& lambda) const
  {
    Eigen::VectorXd xe;
    transposed_product(lambda, xe);
    return xe;
  }
  void transposed_product(const Eigen::VectorXd& lambda, Eigen::VectorXd& xe) const
  {
    const int ne = m_geometry->number_of_interior_edges();
    xe.setZero(ne); // first the generators' (and links') part, then the stars'
    for(std::size_t l = 0; l < row_of_slot.size(); ++l)
      if(is_crossing_row(l)) {
        const double g = lambda[row_of_slot[l]];
        for(int p = slot_edge_start[l]; p < slot_edge_start[l + 1]; ++p)
          xe[index_of_code(slot_edges[p])] += sign_of_code(slot_edges[p]) * g;
      }
    for(int e = 0; e < ne; ++e) {
      const int a = row_of_node[edge_nodes[e][0]], c = row_of_node[edge_nodes[e][1]];
      xe[e] += (c >= 0 ? lambda[c] : 0.) - (a >= 0 ? lambda[a] : 0.);
    }
  }

  // the slacks s = C^T lambda / mu of the guided faces (their mismatches d_g), from the multipliers
  std::vector<double> slacks(const Eigen::VectorXd& lambda) const
  {
    const Constraint_links& k = *m_links;
    const std::size_t nl = m_topology->loops.size();
    std::vector<double> s(k.number_of_guided_faces(), 0.);
    for(std::size_t g = 0; g < s.size(); ++g)
      for(int p = k.slack_start[g]; p < k.slack_start[g + 1]; ++p) {
        const int code = k.slack_links[p];
        s[g] += sign_of_code(code) * lambda[row_of_slot[nl + std::size_t(index_of_code(code))]];
      }
    for(double& v : s)
      v /= k.guidance_weight;
    return s;
  }

  // The sums the constraints read from a connection x and the guided faces' slacks, and the energies.
  void sums_of(const Eigen::VectorXd& xe, const std::vector<double>& slack, Constraint_sums& sums) const
  {
    const Mesh_topology& t = *m_topology;
    const Constraint_links& k = *m_links;
    const int ne = m_geometry->number_of_interior_edges();
    // x(i) enters target(i)'s star, -x(i) = x(opposite(i)) enters source(i)'s star (in the storage of sums.node:
    // sums kept from solve to solve are not allocated again)
    std::vector<double> node_sum;
    node_sum.swap(sums.node);
    node_sum.assign(std::size_t(t.number_of_nodes), 0.);
    double energy = 0;
    for(int e = 0; e < ne; ++e) {
      const int a = edge_nodes[e][0], c = edge_nodes[e][1];
      const double x = xe[e];
      energy += m_geometry->weight[e] * x * x;
      if(a != c) {
        node_sum[c] += x;
        node_sum[a] -= x;
      }
    }
    sums.energy = energy;
    sums.loop.assign(row_of_slot.size(), 0.);
    for(std::size_t l = 0; l < row_of_slot.size(); ++l) {
      if(!is_crossing_slot(l)) {
        sums.loop[l] = node_sum[t.loops[l].node];
        continue;
      }
      double sum = 0;
      for(int p = slot_edge_start[l]; p < slot_edge_start[l + 1]; ++p)
        sum += sign_of_code(slot_edges[p]) * xe[index_of_code(slot_edges[p])];
      sums.loop[l] = sum;
    }
    sums.node.swap(node_sum);
    // the guided faces' slacks: row j of the links reads sum x + s_from - s_to
    sums.slack = slack;
    sums.guidance_energy = 0;
    for(std::size_t g = 0; g < sums.slack.size(); ++g) {
      sums.guidance_energy += k.guidance_weight * sums.slack[g] * sums.slack[g];
      for(int p = k.slack_start[g]; p < k.slack_start[g + 1]; ++p) {
        const int code = k.slack_links[p];
        sums.loop[t.loops.size() + std::size_t(index_of_code(code))] += sign_of_code(code) * sums.slack[g];
      }
    }
  }

  // A x, from its constraint sums
  Eigen::VectorXd row_sums(const Constraint_sums& sums) const
  {
    Eigen::VectorXd ax;
    row_sums(sums, ax);
    return ax;
  }
  void row_sums(const Constraint_sums& sums, Eigen::VectorXd& ax) const
  {
    ax.setZero(size());
    for(int node = 0; node < m_topology->number_of_nodes; ++node)
      if(row_of_node[node] >= 0)
        ax[row_of_node[node]] = sums.node[node];
    for(std::size_t l = 0; l < row_of_slot.size(); ++l)
      if(row_of_slot[l] >= 0)
        ax[row_of_slot[l]] = sums.loop[l];
  }

private:
  const Mesh_geometry* m_geometry = nullptr;
  const Mesh_topology* m_topology = nullptr;
  const Constraint_links* m_links = nullptr;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_ROWS_H
