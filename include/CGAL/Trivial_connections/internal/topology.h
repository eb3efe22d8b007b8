// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_H

#include <CGAL/Trivial_connections/Solve_report.h>
#include <CGAL/Trivial_connections/internal/mesh_arrays.h>

#include <boost/graph/breadth_first_search.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// Graph on int nodes whose arcs carry an int (a corner halfedge or an edge id).
// 32-bit vertex and arc indices: half the memory of the defaults, which matters on large meshes.
using Labelled_graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, int,
                                                          boost::no_property, std::uint32_t, std::uint32_t>;

// Breadth-first spanning forest of `g`, rooted at the first unvisited node in increasing order.
// Returns the discovery order; arc_to[v] is the label of the tree arc that reached v (-1 at roots).
inline std::vector<int> spanning_forest(const Labelled_graph& g, std::vector<int>& arc_to)
{
  struct Recorder : boost::default_bfs_visitor
  {
    std::vector<int>* order; std::vector<int>* arc_to;
    void discover_vertex(std::uint32_t v, const Labelled_graph&) const { order->push_back(int(v)); }
    void tree_edge(boost::graph_traits<Labelled_graph>::edge_descriptor e, const Labelled_graph& g) const
    {
      (*arc_to)[boost::target(e, g)] = g[e];
    }
  };
  const std::size_t n = boost::num_vertices(g);
  std::vector<int> order;
  order.reserve(n);
  arc_to.assign(n, -1);
  std::vector<boost::default_color_type> color(n, boost::white_color);
  auto color_map = boost::make_iterator_property_map(color.begin(), boost::get(boost::vertex_index, g));
  Recorder rec;
  rec.order = &order; rec.arc_to = &arc_to;
  boost::queue<std::uint32_t> queue;
  for(std::uint32_t s = 0; s < n; ++s)
    if(color[s] == boost::white_color)
      boost::breadth_first_visit(g, s, queue, rec, color_map);
  return order;
}

inline Labelled_graph make_labelled_graph(int n, const std::vector<std::pair<int, int>>& arcs,
                                          const std::vector<int>& labels)
{
  return Labelled_graph(boost::edges_are_unsorted_multi_pass, arcs.begin(), arcs.end(), labels.begin(),
                        std::uint32_t(n));
}

/*
  Tree-cotree decomposition of the "collapsed" surface, where every boundary loop is shrunk to one node:
  then every component is closed, the nodes are its interior vertices plus one node per boundary loop, and
  a node's dual cycle (its star) is exactly the loop of CONVENTIONS.md (for a boundary loop: the open fans
  of its vertices). A dual spanning tree T* on faces, a primal spanning tree T on nodes using only edges
  outside T*, and the 2g remaining edges, each closing one generator loop in T*.
*/
struct Mesh_topology
{
  struct Loop
  {
    Loop_kind kind;
    int component;
    int node;                 // boundary loop: its node; generator: -1
    std::vector<int> crossings; // corner halfedges crossed from their face to the opposite one, in order
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

  int number_of_interior_nodes = 0;
  int number_of_nodes = 0;
  std::vector<int> node_of_vertex;   // -1: isolated vertex
  std::vector<int> component_of_face;
  std::vector<int> component_of_node;
  std::vector<int> face_order;       // breadth-first, components contiguous, each root first
  std::vector<int> parent_corner;    // per face: corner halfedge of the parent crossed to reach it (-1: root)
  std::vector<int> depth;
  std::vector<char> in_dual_tree, in_primal_tree; // per interior edge
  std::vector<Loop> loops;           // per component: its boundary loops, then its generators
  std::vector<Component> components;

  template <class TriangleMesh>
  Mesh_topology(const Mesh_arrays<TriangleMesh>& m, const std::vector<int>& edge_of_corner,
                const std::vector<int>& edge_corner)
  {
    using MA = Mesh_arrays<TriangleMesh>;
    const int nc = 3 * m.nf;
    const int ne = int(edge_corner.size());

    // dual spanning forest: components and T*
    {
      std::vector<std::pair<int, int>> arcs;
      std::vector<int> labels;
      arcs.reserve(2 * std::size_t(ne)); labels.reserve(2 * std::size_t(ne));
      for(int i = 0; i < nc; ++i)
        if(m.opposite_corner[i] >= 0) {
          arcs.emplace_back(MA::face_of(i), MA::face_of(m.opposite_corner[i]));
          labels.push_back(i);
        }
      face_order = spanning_forest(make_labelled_graph(m.nf, arcs, labels), parent_corner);
    }
    component_of_face.assign(m.nf, -1);
    depth.assign(m.nf, 0);
    in_dual_tree.assign(ne, 0);
    for(int f : face_order) {
      const int i = parent_corner[f];
      if(i < 0) {
        components.emplace_back();
        components.back().root_face = f;
        component_of_face[f] = int(components.size()) - 1;
      } else {
        const int parent = MA::face_of(i);
        component_of_face[f] = component_of_face[parent];
        depth[f] = depth[parent] + 1;
        in_dual_tree[edge_of_corner[i]] = 1;
      }
      ++components[component_of_face[f]].faces;
    }

    // boundary loops, each collapsed to one node
    node_of_vertex.assign(m.nv, -1);
    std::vector<Loop> boundary;
    {
      std::vector<char> visited(nc, 0);
      for(int start = 0; start < nc; ++start) {
        if(m.opposite_corner[start] >= 0 || visited[start])
          continue;
        Loop loop{Loop_kind::boundary, component_of_face[MA::face_of(start)], -1, {}};
        std::vector<int> loop_vertices;
        int cur = start;
        do {
          visited[cur] = 1;
          loop_vertices.push_back(m.source_of(cur));
          // the open fan at source(cur), counter-clockwise, starting at the face of cur
          int j = MA::prev_corner(cur);
          while(m.opposite_corner[j] >= 0) {
            loop.crossings.push_back(j);
            j = MA::prev_corner(m.opposite_corner[j]);
          }
          cur = j;
        } while(cur != start);
        boundary.push_back(std::move(loop));
        for(int v : loop_vertices)
          node_of_vertex[v] = -2 - int(boundary.size() - 1); // provisional: boundary loop id
      }
    }
    // nodes: interior vertices in index order, then boundary loops
    for(int v = 0; v < m.nv; ++v)
      if(node_of_vertex[v] == -1 && m.faces_at_vertex[v] > 0)
        node_of_vertex[v] = number_of_interior_nodes++;
    number_of_nodes = number_of_interior_nodes + int(boundary.size());
    for(int v = 0; v < m.nv; ++v)
      if(node_of_vertex[v] <= -2)
        node_of_vertex[v] = number_of_interior_nodes + (-2 - node_of_vertex[v]);
    for(std::size_t b = 0; b < boundary.size(); ++b)
      boundary[b].node = number_of_interior_nodes + int(b);

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
    for(const Loop& b : boundary)
      ++components[b.component].boundary_loops;

    // primal spanning forest on nodes, with the edges outside T*
    {
      std::vector<std::pair<int, int>> arcs;
      std::vector<int> labels;
      for(int e = 0; e < ne; ++e) {
        if(in_dual_tree[e])
          continue;
        const int a = node_of_vertex[m.source_of(edge_corner[e])], b = node_of_vertex[m.target_of(edge_corner[e])];
        if(a == b)
          continue;
        arcs.emplace_back(a, b); labels.push_back(e);
        arcs.emplace_back(b, a); labels.push_back(e);
      }
      std::vector<int> arc_to;
      spanning_forest(make_labelled_graph(number_of_nodes, arcs, labels), arc_to);
      in_primal_tree.assign(ne, 0);
      for(int label : arc_to)
        if(label >= 0)
          in_primal_tree[label] = 1;
    }

    // generators: one per edge in neither tree
    std::vector<Loop> generators;
    for(int e = 0; e < ne; ++e) {
      if(in_dual_tree[e] || in_primal_tree[e])
        continue;
      const int i = edge_corner[e];
      Loop loop{Loop_kind::generator, component_of_face[MA::face_of(i)], -1, {}};
      // from the face across i up to the common ancestor, down to face(i), then across i
      int a = MA::face_of(m.opposite_corner[i]), b = MA::face_of(i);
      std::vector<int> down;
      while(a != b) {
        if(depth[a] >= depth[b]) {
          loop.crossings.push_back(m.opposite_corner[parent_corner[a]]);
          a = MA::face_of(parent_corner[a]);
        } else {
          down.push_back(parent_corner[b]);
          b = MA::face_of(parent_corner[b]);
        }
      }
      loop.crossings.insert(loop.crossings.end(), down.rbegin(), down.rend());
      loop.crossings.push_back(i);
      generators.push_back(std::move(loop));
    }

    for(Loop& b : boundary)
      loops.push_back(std::move(b));
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

};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_H
