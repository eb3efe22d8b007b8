// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_TREE_COTREE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_TREE_COTREE_H

#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/dual_tree_paths.h>

#include <boost/pending/disjoint_sets.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Tree-cotree decomposition of the "collapsed" surface, where every boundary loop is shrunk to one node:
  then every component is closed, the nodes are its interior vertices plus one node per boundary loop, and
  a node's dual cycle (its star) is exactly the loop of CONVENTIONS.md (for a boundary loop: the open fans
  of its vertices). A dual spanning tree T* on faces, a primal spanning tree T on nodes using only edges
  outside T*, and the 2g remaining edges, each closing one generator loop in T*.
  Two steps: the constructor finds the boundary loops and numbers the nodes (enough to order the
  constraint system, which may then start on another thread); `build_trees()` does the rest and never
  writes what the constructor computed.
*/
struct Mesh_topology
{
  struct Loop
  {
    Loop_kind kind;
    int component;
    int node;                 // boundary loop: its node; generator: -1
    std::vector<int> crossings; // corner halfedges crossed from their face to the opposite one, in order
    // boundary loop: its border corner halfedges in the order visited, and where the open fan of the source
    // of each starts in `crossings` (that fan goes from the face of border_corners[i] to the face of
    // border_corners[i + 1], cyclically)
    std::vector<int> border_corners, fan_start;
  };

  struct Component
  {
    int root_face = -1;
    int faces = 0, vertices = 0, edges = 0;
    int boundary_loops = 0, generators = 0;
    std::int64_t euler_characteristic = 0, genus = 0;
    int pinned_node = -1;     // the node whose star constraint is implied by all the others
    std::vector<int> loops;   // indices in `loops`
  };

  // constructor
  int number_of_interior_nodes = 0;
  int number_of_nodes = 0;
  std::vector<int> node_of_vertex;   // -1: isolated vertex
  // build_trees()
  std::vector<int> component_of_face;
  std::vector<int> component_of_node;
  std::vector<int> face_order;       // breadth-first, components contiguous, each root first
  std::vector<int> parent_corner;    // per face: corner halfedge of the parent crossed to reach it (-1: root)
  std::vector<Loop> loops;           // per component: its boundary loops, then its generators
  std::vector<Component> components;

  Mesh_topology() = default;

  template <class TriangleMesh>
  explicit Mesh_topology(const Mesh_arrays<TriangleMesh>& m)
  {
    using MA = Mesh_arrays<TriangleMesh>;
    const int nc = 3 * m.nf;
    node_of_vertex.assign(m.nv, -1);
    std::vector<char> visited(nc, 0);
    for(int start = 0; start < nc; ++start) {
      if(m.opposite_corner[start] >= 0 || visited[start])
        continue;
      Loop loop{Loop_kind::boundary, -1, -1, {}, {}, {}};
      int cur = start;
      do {
        visited[cur] = 1;
        loop.border_corners.push_back(cur);
        loop.fan_start.push_back(int(loop.crossings.size()));
        node_of_vertex[m.source_of(cur)] = -2 - int(m_boundary.size()); // provisional: boundary loop id
        // the open fan at source(cur), counter-clockwise, starting at the face of cur
        int j = MA::prev_corner(cur);
        while(m.opposite_corner[j] >= 0) {
          loop.crossings.push_back(j);
          j = MA::prev_corner(m.opposite_corner[j]);
        }
        cur = j;
      } while(cur != start);
      m_boundary.push_back(std::move(loop));
      m_boundary_start.push_back(start);
    }
    // nodes: interior vertices in index order, then boundary loops
    for(int v = 0; v < m.nv; ++v)
      if(node_of_vertex[v] == -1 && m.faces_at_vertex[v] > 0)
        node_of_vertex[v] = number_of_interior_nodes++;
    number_of_nodes = number_of_interior_nodes + int(m_boundary.size());
    for(int v = 0; v < m.nv; ++v)
      if(node_of_vertex[v] <= -2)
        node_of_vertex[v] = number_of_interior_nodes + (-2 - node_of_vertex[v]);
    for(std::size_t b = 0; b < m_boundary.size(); ++b)
      m_boundary[b].node = number_of_interior_nodes + int(b);
  }

  // The pattern of the node adjacency (two nodes are adjacent when an interior edge joins them), both
  // triangles and the diagonal, compressed columns sorted: the pattern of the node rows of the
  // constraint system.
  template <class TriangleMesh>
  void node_adjacency(const Mesh_arrays<TriangleMesh>& m, std::vector<int>& column_start,
                      std::vector<int>& rows) const
  {
    const int nc = 3 * m.nf;
    auto for_each_arc = [&](auto&& visit) {
      for(int i = 0; i < nc; ++i)
        if(i < m.opposite_corner[i]) {
          const int a = node_of_vertex[m.source_of(i)], b = node_of_vertex[m.target_of(i)];
          if(a != b) {
            visit(a, b);
            visit(b, a);
          }
        }
    };
    std::vector<int> start(std::size_t(number_of_nodes) + 1, 0);
    for(int c = 0; c < number_of_nodes; ++c)
      start[std::size_t(c) + 1] = 1; // the diagonal
    for_each_arc([&](int c, int) { ++start[std::size_t(c) + 1]; });
    for(int c = 0; c < number_of_nodes; ++c)
      start[c + 1] += start[c];
    rows.assign(std::size_t(start[number_of_nodes]), 0);
    {
      std::vector<int> next(start.begin(), start.end() - 1);
      for(int c = 0; c < number_of_nodes; ++c)
        rows[next[c]++] = c;
      for_each_arc([&](int c, int r) { rows[next[c]++] = r; });
    }
    // sorted, without the repeats of boundary nodes (compacted in place)
    column_start.assign(std::size_t(number_of_nodes) + 1, 0);
    int out = 0;
    for(int c = 0; c < number_of_nodes; ++c) {
      std::sort(rows.begin() + start[c], rows.begin() + start[c + 1]);
      for(int p = start[c]; p < start[c + 1]; ++p)
        if(p == start[c] || rows[p] != rows[p - 1])
          rows[out++] = rows[p];
      column_start[c + 1] = out;
    }
    rows.resize(std::size_t(out));
  }

  template <class TriangleMesh>
  void build_trees(const Mesh_arrays<TriangleMesh>& m, const std::vector<int>& edge_of_corner,
                   const std::vector<int>& edge_corner)
  {
    using MA = Mesh_arrays<TriangleMesh>;
    const int nc = 3 * m.nf;
    const int ne = int(edge_corner.size());

    // dual spanning forest T* by breadth-first search over the faces; the corner arrays are the graph
    face_order.clear();
    face_order.reserve(m.nf);
    parent_corner.assign(m.nf, -1);
    component_of_face.assign(m.nf, -1);
    // only needed here: per face its depth in T*, per interior edge whether it is in T* or T
    std::vector<int> depth(std::size_t(m.nf), 0);
    std::vector<char> in_dual_tree(std::size_t(ne), 0), in_primal_tree(std::size_t(ne), 0);
    for(int root = 0; root < m.nf; ++root) {
      if(component_of_face[root] >= 0)
        continue;
      const int c = int(components.size());
      components.emplace_back();
      components.back().root_face = root;
      component_of_face[root] = c;
      const std::size_t first = face_order.size();
      face_order.push_back(root);
      std::size_t head = first;
      for(; head < face_order.size(); ++head) {
        const int f = face_order[head];
        for(int i = 3 * f; i < 3 * f + 3; ++i) {
          const int o = m.opposite_corner[i];
          if(o < 0 || component_of_face[MA::face_of(o)] >= 0)
            continue;
          const int g = MA::face_of(o);
          component_of_face[g] = c;
          parent_corner[g] = i;
          depth[g] = depth[f] + 1;
          in_dual_tree[edge_of_corner[i]] = 1;
          face_order.push_back(g);
        }
      }
      components[c].faces = int(face_order.size() - first);
    }

    for(std::size_t b = 0; b < m_boundary.size(); ++b)
      m_boundary[b].component = component_of_face[MA::face_of(m_boundary_start[b])];
    component_of_node.assign(number_of_nodes, -1);
    for(int i = 0; i < nc; ++i) {
      const int c = component_of_face[MA::face_of(i)];
      component_of_node[node_of_vertex[m.source_of(i)]] = c;
      if(i < m.opposite_corner[i] || m.opposite_corner[i] < 0)
        ++components[c].edges;
    }
    for(int v = 0; v < m.nv; ++v)
      if(m.faces_at_vertex[v] > 0)
        ++components[component_of_node[node_of_vertex[v]]].vertices;
    for(const Loop& b : m_boundary)
      ++components[b.component].boundary_loops;

    // primal spanning forest T on the nodes with the edges outside T*: any spanning forest will do, and
    // union-find needs no graph
    {
      std::vector<int> rank(std::size_t(number_of_nodes), 0);
      std::vector<int> parent(std::size_t(number_of_nodes), 0);
      boost::disjoint_sets<int*, int*> sets(rank.data(), parent.data());
      for(int v = 0; v < number_of_nodes; ++v)
        sets.make_set(v);
      for(int e = 0; e < ne; ++e) {
        if(in_dual_tree[e])
          continue;
        const int a = sets.find_set(node_of_vertex[m.source_of(edge_corner[e])]);
        const int b = sets.find_set(node_of_vertex[m.target_of(edge_corner[e])]);
        if(a != b) {
          sets.link(a, b);
          in_primal_tree[e] = 1;
        }
      }
    }

    // generators: one per edge in neither tree
    std::vector<Loop> generators;
    for(int e = 0; e < ne; ++e) {
      if(in_dual_tree[e] || in_primal_tree[e])
        continue;
      const int i = edge_corner[e];
      Loop loop{Loop_kind::generator, component_of_face[MA::face_of(i)], -1, {}, {}, {}};
      // from the face across i up to the common ancestor, down to face(i), then across i
      append_dual_tree_path(m.opposite_corner, parent_corner, depth, MA::face_of(m.opposite_corner[i]),
                            MA::face_of(i), loop.crossings);
      loop.crossings.push_back(i);
      generators.push_back(std::move(loop));
    }

    loops = std::move(m_boundary); // not read by node_adjacency(), which may be running meanwhile
    for(Loop& g : generators)
      loops.push_back(std::move(g));
    std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
      return a.component < b.component || (a.component == b.component && a.kind == Loop_kind::boundary &&
                                           b.kind == Loop_kind::generator);
    });
    for(std::size_t l = 0; l < loops.size(); ++l) {
      Component& c = components[loops[l].component];
      c.loops.push_back(int(l));
      if(loops[l].kind == Loop_kind::generator)
        ++c.generators;
      else
        c.pinned_node = loops[l].node; // the last boundary loop of the component
    }
    for(int v = 0; v < m.nv; ++v) {
      const int node = node_of_vertex[v];
      if(node >= 0 && node < number_of_interior_nodes) {
        Component& c = components[component_of_node[node]];
        if(c.boundary_loops == 0 && c.pinned_node < 0)
          c.pinned_node = node;
      }
    }
    for(Component& c : components) {
      c.euler_characteristic = std::int64_t(c.vertices) - c.edges + c.faces;
      c.genus = (2 - c.euler_characteristic - c.boundary_loops) / 2;
      CGAL_assertion(c.generators == 2 * c.genus);
      CGAL_assertion(c.pinned_node >= 0);
    }
  }

  // the position in `loops` of the boundary loop of a node, if it is one
  std::optional<std::size_t> boundary_loop_of_node(int node) const
  {
    if(node < number_of_interior_nodes)
      return std::nullopt;
    for(std::size_t l = 0; l < loops.size(); ++l)
      if(loops[l].kind == Loop_kind::boundary && loops[l].node == node)
        return l;
    return std::nullopt;
  }

private:
  std::vector<Loop> m_boundary; // boundary loops in the order found; `component` set by build_trees()
  std::vector<int> m_boundary_start; // a border corner halfedge of each
};

// the topology of each component as the public reports give it (`vertex_index_sum` 0)
inline std::vector<Component_report> component_reports(const Mesh_topology& topology)
{
  std::vector<Component_report> reports(topology.components.size());
  for(std::size_t c = 0; c < reports.size(); ++c) {
    const Mesh_topology::Component& component = topology.components[c];
    reports[c].number_of_faces = std::size_t(component.faces);
    reports[c].euler_characteristic = component.euler_characteristic;
    reports[c].genus = component.genus;
    reports[c].number_of_boundary_loops = std::size_t(component.boundary_loops);
  }
  return reports;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_TREE_COTREE_H
