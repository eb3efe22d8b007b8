// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_DUAL_TREE_PATHS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_DUAL_TREE_PATHS_H

#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  Paths in a dual spanning forest given by `parent_corner` (per face, the corner halfedge of its parent
  crossed to reach it; -1 at a root) and `depth` (per face, its depth in the forest). Corner halfedge i
  belongs to face i / 3; `opposite_corner[i]` is the corner halfedge on the other side.
  Appends to `crossings` the corner halfedges crossed from face a to face b of the same tree: up from a to
  the common ancestor, then down to b.
*/
inline void append_dual_tree_path(const std::vector<int>& opposite_corner, const std::vector<int>& parent_corner,
                                  const std::vector<int>& depth, int a, int b, std::vector<int>& crossings)
{
  std::vector<int> down;
  while(a != b) {
    if(depth[a] >= depth[b]) {
      crossings.push_back(opposite_corner[parent_corner[a]]);
      a = parent_corner[a] / 3;
    } else {
      down.push_back(parent_corner[b]);
      b = parent_corner[b] / 3;
    }
  }
  crossings.insert(crossings.end(), down.rbegin(), down.rend());
}

/*
  The depth and a depth-first preorder of every face in the dual spanning forest, from the breadth-first
  `face_order` (parents first) of the tree-cotree decomposition. The tree paths between consecutive faces of
  a depth-first order cross each tree edge at most twice in all, which keeps chains of links short.
*/
struct Dual_tree_order
{
  std::vector<int> depth, preorder;

  Dual_tree_order(const std::vector<int>& parent_corner, const std::vector<int>& face_order)
  {
    const int nf = int(parent_corner.size());
    std::vector<int> child_start(std::size_t(nf) + 1, 0), children(std::size_t(nf), 0);
    depth.assign(std::size_t(nf), 0);
    for(int f = 0; f < nf; ++f)
      if(parent_corner[f] >= 0)
        ++child_start[std::size_t(parent_corner[f] / 3) + 1];
    for(int f = 0; f < nf; ++f)
      child_start[f + 1] += child_start[f];
    {
      std::vector<int> next(child_start.begin(), child_start.end() - 1);
      for(int f : face_order) // parents first
        if(parent_corner[f] >= 0) {
          const int p = parent_corner[f] / 3;
          children[next[p]++] = f;
          depth[f] = depth[p] + 1;
        }
    }
    preorder.assign(std::size_t(nf), 0);
    int count = 0;
    std::vector<int> stack;
    for(int f : face_order)
      if(parent_corner[f] < 0) {
        stack.push_back(f);
        while(!stack.empty()) {
          const int g = stack.back();
          stack.pop_back();
          preorder[g] = count++;
          for(int p = child_start[g + 1]; p-- > child_start[g];)
            stack.push_back(children[p]);
        }
      }
  }
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_TOPOLOGY_DUAL_TREE_PATHS_H
