// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_LINKS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_LINKS_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/topology/dual_tree_paths.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <CGAL/assertions.h>
#include <CGAL/number_type_config.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// A signed reference to element i is coded i (+1) or ~i (-1): a loop's crossings (x_e or -x_e), the links at a
// guided face. Decoded without branches, whose sign pattern is random.
inline int index_of_code(int code) { return code ^ (code >> 31); }
inline double sign_of_code(int code) { return double(1 | (code >> 31)); }

// A range of face descriptors given by the user, as face indices (checked: faces of the mesh, once each).
// `what` names the set in the messages ("constrained", "guided").
template <class TriangleMesh, class FaceRange>
std::vector<int> checked_face_indices(const Mesh_arrays<TriangleMesh>& m, const FaceRange& range, const std::string& what)
{
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  std::vector<int> faces;
  std::vector<char> listed(std::size_t(m.nf), 0);
  for(const face_descriptor f : range) {
    const std::size_t i = f == boost::graph_traits<TriangleMesh>::null_face() ? std::size_t(m.nf)
                                                                              : std::size_t(get(m.face_index, f));
    if(i >= std::size_t(m.nf) || m.face_descriptors[i] != f)
      throw Invalid_input(Error_code::invalid_constraint, "a " + what + " face is not a face of the mesh");
    if(listed[i])
      throw Invalid_input(Error_code::invalid_constraint, "face " + std::to_string(i) + " is " + what + " twice", i);
    listed[i] = 1;
    faces.push_back(int(i));
  }
  return faces;
}

// no face both constrained and guided
inline void check_disjoint_face_sets(int nf, const std::vector<int>& constrained_faces, const std::vector<int>& guided)
{
  std::vector<char> constrained(std::size_t(nf), 0);
  for(int f : constrained_faces)
    constrained[f] = 1;
  for(int f : guided)
    if(constrained[f])
      throw Invalid_input(Error_code::invalid_constraint, "face " + std::to_string(f) + " is both constrained and guided",
                          std::size_t(f));
}

/*
  The directional constraints as links between faces. Per component, the constrained faces are chained and
  each link is a dual path, whose row says that the connection carries the target of one end to the target
  of the other, up to a free multiple of 2 pi / n. With the boundary aligned, the boundary faces of each loop
  are chained along the loop, each link being the open fan of the boundary vertex between them; the chains
  and the faces the user constrains are then linked by short dual paths between neighbours (see
  link_groups_by_shortest_paths()). The links of a component form a tree on its constrained faces, so their
  rows are independent of each other and of the cycle rows.
  Guided faces (soft guidance) are linked like constrained ones; each has a slack, its mismatch d_g, which
  enters its links' rows with weight 1 / mu (see the user manual).
  Pins that touch (user targets on faces sharing an edge or a vertex) are linked first, by a spanning forest of
  the clusters they form: first across their shared edges, then through the fan of a shared vertex (the faces
  between them around it). The integer of such a link is decided by rounding (`decided`): a link across one
  edge fixes x_e, and the edge leaves the system; a fan link is a row with a prescribed integer, ordered in the
  factor right after its vertex's rows (see Constraint_rows). Only one face of each cluster is then chained with
  the others: the free integers grow with the clusters (feature curves, parts of them), not with the pins.
*/
struct Constraint_links
{
  struct Constrained_face
  {
    int face;
    int border_corner; // the border corner halfedge it follows with the boundary aligned; -1: a user target
    bool soft;         // a guided face (its target is a guide)
  };
  struct Link
  {
    int from, to;      // in `faces`
    int component;
    std::vector<int> crossings; // corner halfedges, as a loop's (released once the rows have coded them)
    std::size_t length = 0;
    bool decided = false;       // between touching pins (one edge, or a vertex's fan): the integer is rounded
  };

  std::vector<Constrained_face> faces; // aligned boundary faces, then user targets, then guided faces
  std::vector<Link> links;
  std::vector<int> seed_constraint;    // per component: the constrained face the field starts from, or -1
  bool has_user_constraints = false;   // user targets or guides (read from face_directions)
  int first_guided = 0;                // the guided faces are the last of `faces`
  double guidance_weight = 1;          // mu
  // per guided face (CSR): the links at it, j when it is their `from` end (+1), ~j when their `to` end (-1)
  std::vector<int> slack_start, slack_links;

  Constraint_links() = default;

  // `user_angles` (optional, per user face): their targets' angles in their frames when known as the solver is
  // built (NaN: not known); then touching pins whose targets disagree by more than a quarter of 2 pi / n along their link are
  // not linked by rounding (the lattice chooses between them). `boundary_turn_order`: with the boundary aligned, the
  // n for which a fan between two boundary faces is decided by rounding when its turn is within a quarter of
  // 2 pi / n of a multiple (0: every turn is a free integer)
  template <class TriangleMesh>
  Constraint_links(const Mesh_arrays<TriangleMesh>& m, const Mesh_topology& t, const std::vector<int>& user_faces,
                   const std::vector<int>& guided, bool align, double mu,
                   const std::vector<double>& user_angles = std::vector<double>(), int n = 1,
                   int boundary_turn_order = 0)
    : guidance_weight(mu)
  {
    using Mesh = Mesh_arrays<TriangleMesh>;
    std::vector<int> constraint_of_face(std::size_t(m.nf), -1);
    std::vector<int> chain_head; // per aligned boundary face, the first face of its loop's chain
    std::vector<std::vector<int>> units(t.components.size()); // per component: a constrained face of each chain
    auto add_face = [&](int f, int border_corner, bool soft = false) {
      CGAL_assertion(constraint_of_face[f] < 0);
      constraint_of_face[f] = int(faces.size());
      faces.push_back({f, border_corner, soft});
      return int(faces.size()) - 1;
    };
    auto border_length = [&](int i) { return norm(sub(m.points[m.target_of(i)], m.points[m.source_of(i)])); };
    if(align) {
      for(const Mesh_topology::Loop& loop : t.loops) {
        if(loop.kind != Loop_kind::boundary)
          continue;
        const std::vector<int>& corners = loop.border_corners;
        const int count = int(corners.size());
        // start where the face changes, so that a face with two border edges is one link of the chain
        int start = 0;
        while(start < count && Mesh::face_of(corners[start]) == Mesh::face_of(corners[(start + count - 1) % count]))
          ++start;
        start %= count;
        int previous = -1;
        for(int a = 0; a < count; ++a) {
          const int i = (start + a) % count, corner = corners[i], f = Mesh::face_of(corner);
          if(previous >= 0 && faces[previous].face == f) {
            // the same face again (two border edges): it follows the longer one
            if(border_length(corner) > border_length(faces[previous].border_corner))
              faces[previous].border_corner = corner;
          } else {
            const int current = add_face(f, corner);
            chain_head.push_back(previous >= 0 ? chain_head[std::size_t(previous)] : current);
            if(previous >= 0) {
              // the fan of the vertex between them: from the previous border corner's face to this one
              const int j = (i + count - 1) % count;
              const int end = j + 1 < count ? loop.fan_start[j + 1] : int(loop.crossings.size());
              links.push_back({previous, current, loop.component,
                               std::vector<int>(loop.crossings.begin() + loop.fan_start[j],
                                                loop.crossings.begin() + end)});
            } else {
              units[loop.component].push_back(current);
            }
            previous = current;
          }
        }
      }
    }
    if(align && boundary_turn_order > 0)
      decide_clear_boundary_turns(m, boundary_turn_order);
    // user targets, then guides: each face a chain of its own
    auto add_user_faces = [&](const std::vector<int>& user, bool soft) {
      for(int f : user) {
        if(constraint_of_face[f] >= 0)
          throw Invalid_input(Error_code::invalid_constraint,
                              "face " + std::to_string(f) + " is on the boundary, which the field is aligned with: " +
                                (soft ? "it cannot be guided too" : "it cannot have a target too"),
                              std::size_t(f));
        units[t.component_of_face[f]].push_back(add_face(f, -1, soft));
      }
    };
    const int first_user = int(faces.size());
    add_user_faces(user_faces, false);
    link_touching_pins(m, t, first_user, constraint_of_face, user_angles, n);
    first_guided = int(faces.size());
    add_user_faces(guided, true);
    has_user_constraints = !user_faces.empty() || !guided.empty();
    seed_constraint.assign(t.components.size(), -1);
    if(faces.empty())
      return;

    const Dual_tree_order tree(t.parent_corner, t.face_order);
    // per constrained face, the unit (chain or cluster) it belongs to, as an index from 0
    std::vector<int> group_of_unit(faces.size(), -1);
    std::size_t units_kept = 0;
    for(std::size_t a = cluster_parent.size(); a < faces.size(); ++a) // guided faces: clusters of their own
      cluster_parent.push_back(int(a));
    cluster_seen.assign(faces.size(), 0);
    for(std::size_t c = 0; c < units.size(); ++c) {
      std::vector<int>& u = units[c];
      if(u.empty())
        continue;
      std::sort(u.begin(), u.end(),
                [&](int a, int b) { return tree.preorder[faces[a].face] < tree.preorder[faces[b].face]; });
      // one face per cluster of touching pins (the first in preorder): the others are linked to it already
      u.erase(std::remove_if(u.begin(), u.end(),
                             [&](int a) {
                               const int root = cluster_root(a);
                               if(cluster_seen[std::size_t(root)])
                                 return true;
                               cluster_seen[std::size_t(root)] = 1;
                               return false;
                             }),
              u.end());
      // the field starts from a constrained face (its target is exact); a component with guided faces only
      // is rotated towards its guides
      for(int a : u)
        if(!faces[a].soft) {
          seed_constraint[c] = a;
          break;
        }
      for(std::size_t k = 0; k < u.size(); ++k)
        group_of_unit[std::size_t(u[k])] = int(units_kept++);
    }
    link_groups_by_shortest_paths(m, t, chain_head, group_of_unit, units_kept);
    for(Link& link : decided_links)
      links.push_back(std::move(link));
    std::vector<Link>().swap(decided_links);
    std::vector<int>().swap(cluster_parent);
    std::vector<char>().swap(cluster_seen);
    // per guided face, the links at it: the slack s_g enters +1 in a link from it, -1 in a link to it
    slack_start.assign(faces.size() - std::size_t(first_guided) + 1, 0);
    for(const Link& link : links)
      for(int end : {link.from, link.to})
        if(faces[end].soft)
          ++slack_start[std::size_t(end - first_guided) + 1];
    for(std::size_t g = 1; g < slack_start.size(); ++g)
      slack_start[g] += slack_start[g - 1];
    slack_links.resize(std::size_t(slack_start.back()));
    std::vector<int> next(slack_start.begin(), slack_start.end() - 1);
    for(std::size_t j = 0; j < links.size(); ++j)
      for(int end : {links[j].from, links[j].to})
        if(faces[end].soft)
          slack_links[std::size_t(next[std::size_t(end - first_guided)]++)] = end == links[j].from ? int(j) : ~int(j);
  }

  std::size_t number_of_guided_faces() const { return faces.size() - std::size_t(first_guided); }

  bool has_decided_links() const
  {
    return std::any_of(links.begin(), links.end(), [](const Link& link) { return link.decided; });
  }

  // For link j, calls visit(link, value) for the entries of C C^T / mu in its row: C has one column per
  // guided face, +1 in the links from it and -1 in the links to it
  template <class Visit>
  void for_each_slack_coupling(int j, Visit visit) const
  {
    for(int end : {links[j].from, links[j].to}) {
      if(!faces[end].soft)
        continue;
      const double sign = end == links[j].from ? 1. : -1.;
      const std::size_t g = std::size_t(end - first_guided);
      for(int p = slack_start[g]; p < slack_start[g + 1]; ++p) {
        const int code = slack_links[p];
        visit(index_of_code(code), sign * sign_of_code(code) / guidance_weight);
      }
    }
  }

private:
  // whether the link a -> b across `crossings` turns by at most a quarter of 2 pi / n away from a multiple of it
  // (H = theta_a - theta_b + the transport along it, as the link's row reads it), so that rounding is safe
  template <class TriangleMesh>
  static bool turns_clearly(const Mesh_arrays<TriangleMesh>& m, double theta_a, double theta_b,
                            const std::vector<int>& crossings, int n)
  {
    double h = theta_a - theta_b;
    for(int i : crossings)
      h += edge_angle_in_frame(m, m.opposite_corner[i]) + CGAL_PI - edge_angle_in_frame(m, i);
    const double turns = h * n / (2 * CGAL_PI);
    return std::abs(turns - std::round(turns)) <= 0.25;
  }

  /*
    The fans of a boundary chain (all the links so far) whose turn is clear are decided by rounding, as touching
    pins are: the field turns by the least multiple of 2 pi / n at each boundary vertex, relative to the boundary.
    Another integer would put a whole turn of 2 pi / n in the fan of one vertex (a corner where the boundary has
    none), which solve()'s lower bound covers. Left free, every fan is a row of the dense block of the integers'
    metric: elephant-with-holes, 106 loops and 1,111 fans, a factor of 8.7e5 nonzeros against 1.9e4 without the
    alignment, and a search that cannot prove its integers.
  */
  template <class TriangleMesh>
  void decide_clear_boundary_turns(const Mesh_arrays<TriangleMesh>& m, int n)
  {
    for(Link& link : links) {
      const int a = faces[std::size_t(link.from)].border_corner, b = faces[std::size_t(link.to)].border_corner;
      CGAL_assertion(a >= 0 && b >= 0);
      link.decided = turns_clearly(m, edge_angle_in_frame(m, a), edge_angle_in_frame(m, b), link.crossings, n);
    }
  }

  // A spanning forest of the clusters of touching user targets (from `first_user` on, in `faces`): first the
  // edges two of them share, then the fans of the vertices they share; one decided link per forest edge. The
  // clusters are kept in a union-find (cluster_root()), read again when the clusters are chained.
  template <class TriangleMesh>
  void link_touching_pins(const Mesh_arrays<TriangleMesh>& m, const Mesh_topology& t, int first_user,
                          const std::vector<int>& constraint_of_face, const std::vector<double>& user_angles, int n)
  {
    using Mesh = Mesh_arrays<TriangleMesh>;
    cluster_parent.resize(faces.size());
    for(std::size_t a = 0; a < faces.size(); ++a)
      cluster_parent[a] = int(a);
    // with the targets known: whether the link a -> b across `crossings` turns clearly (turns_clearly())
    auto agree = [&](int a, int b, const std::vector<int>& crossings) {
      if(user_angles.empty())
        return true;
      const double theta_a = user_angles[std::size_t(a - first_user)], theta_b = user_angles[std::size_t(b - first_user)];
      if(std::isnan(theta_a - theta_b)) // a target not known yet
        return true;
      return turns_clearly(m, theta_a, theta_b, crossings, n);
    };
    for(int a = first_user; a < int(faces.size()); ++a) {
      const int f = faces[std::size_t(a)].face;
      for(int i = 3 * f; i < 3 * f + 3; ++i) {
        const int o = m.opposite_corner[i];
        if(o < 0)
          continue;
        const int b = constraint_of_face[Mesh_arrays<TriangleMesh>::face_of(o)];
        if(b < first_user || b <= a) // each shared edge once, from its lower end
          continue;
        const int ra = cluster_root(a), rb = cluster_root(b);
        if(ra == rb || !agree(a, b, {i}))
          continue;
        cluster_parent[std::size_t(rb)] = ra;
        Link link{a, b, t.component_of_face[f], {i}};
        link.decided = true;
        decided_links.push_back(std::move(link));
      }
    }
    // then through vertices: around each vertex of a pin, from one pin to the next of another cluster, crossing
    // the faces between them (the corners entering the vertex, in the order of its fan)
    std::vector<std::pair<int, int>> pinned_corners; // (vertex, a corner entering it in a pin)
    for(int a = first_user; a < int(faces.size()); ++a)
      for(int i = 3 * faces[std::size_t(a)].face; i < 3 * faces[std::size_t(a)].face + 3; ++i)
        pinned_corners.push_back({m.target_of(i), i});
    std::sort(pinned_corners.begin(), pinned_corners.end());
    auto pin_of = [&](int corner) {
      const int a = constraint_of_face[Mesh::face_of(corner)];
      return a >= first_user ? a : -1;
    };
    std::vector<int> fan, crossings;
    for(std::size_t p = 0; p < pinned_corners.size();) {
      std::size_t q = p;
      bool several_clusters = false;
      const int first_root = cluster_root(pin_of(pinned_corners[p].second));
      for(; q < pinned_corners.size() && pinned_corners[q].first == pinned_corners[p].first; ++q)
        several_clusters = several_clusters || cluster_root(pin_of(pinned_corners[q].second)) != first_root;
      const int start = pinned_corners[p].second;
      p = q;
      if(!several_clusters)
        continue;
      // the fan as corners entering the vertex: rewound to its border when it is open, else from the pin
      fan.clear();
      int c = start;
      bool closed = false;
      while(!closed && m.opposite_corner[c] >= 0) {
        c = Mesh::prev_corner(m.opposite_corner[c]);
        closed = c == start;
      }
      const int first = c;
      do {
        fan.push_back(c);
        const int o = m.opposite_corner[Mesh::next_corner(c)];
        if(o < 0)
          break;
        c = o;
      } while(c != first);
      if(closed)
        fan.push_back(first);
      int last = -1;
      crossings.clear();
      for(std::size_t k = 0; k < fan.size(); ++k) {
        const int b = pin_of(fan[k]);
        if(b >= 0) {
          if(last >= 0 && cluster_root(last) != cluster_root(b) && agree(last, b, crossings)) {
            cluster_parent[std::size_t(cluster_root(b))] = cluster_root(last);
            Link link{last, b, t.component_of_face[faces[std::size_t(b)].face], crossings};
            link.decided = true;
            decided_links.push_back(std::move(link));
          }
          last = b;
          crossings.clear();
        }
        crossings.push_back(Mesh::next_corner(fan[k]));
      }
    }
  }

  /*
    Links the units of each component (a loop's chain of boundary faces, a cluster of touching pins, a lone pin or
    guided face) into a tree by short dual paths: a breadth-first search grows from every constrained face at once,
    each edge where two units' regions meet offers the path through it, and the shortest offers that join two
    units not yet joined are taken (Kruskal). A link then runs between neighbouring units, not up and down the
    dual spanning tree towards its root: with curvature guidance (64 guided faces, n = 4) the factor has 1.08e5
    nonzeros instead of 1.13e5 on homer, 1.07e6 instead of 1.09e6 on bunny00.
  */
  template <class TriangleMesh>
  void link_groups_by_shortest_paths(const Mesh_arrays<TriangleMesh>& m, const Mesh_topology& t,
                                     const std::vector<int>& chain_head, const std::vector<int>& group_of_unit,
                                     std::size_t groups)
  {
    using Mesh = Mesh_arrays<TriangleMesh>;
    if(groups < 2)
      return;
    // the unit of every constrained face: its chain's head, or its cluster's face kept in the units
    std::vector<int> group(faces.size(), -1);
    for(std::size_t a = 0; a < faces.size(); ++a) {
      const int head = a < chain_head.size() ? chain_head[a] : -1;
      group[a] = head >= 0 ? group_of_unit[std::size_t(head)] : -1;
    }
    std::vector<int> group_of_root(faces.size(), -1);
    for(std::size_t a = 0; a < faces.size(); ++a)
      if(group_of_unit[a] >= 0)
        group_of_root[std::size_t(cluster_root(int(a)))] = group_of_unit[a];
    for(std::size_t a = chain_head.size(); a < faces.size(); ++a)
      group[a] = group_of_root[std::size_t(cluster_root(int(a)))];
    // breadth-first from all constrained faces: per face, the constrained face it was reached from, its distance
    // and the corner crossed to enter it (in the face it came from)
    std::vector<int> source(std::size_t(m.nf), -1), distance(std::size_t(m.nf), 0), enter(std::size_t(m.nf), -1);
    std::vector<int> queue;
    queue.reserve(std::size_t(m.nf));
    for(std::size_t a = 0; a < faces.size(); ++a) {
      CGAL_assertion(group[a] >= 0);
      source[std::size_t(faces[a].face)] = int(a);
      queue.push_back(faces[a].face);
    }
    for(std::size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      for(int i = 3 * f; i < 3 * f + 3; ++i) {
        const int o = m.opposite_corner[i];
        if(o < 0 || source[std::size_t(Mesh::face_of(o))] >= 0)
          continue;
        const int g = Mesh::face_of(o);
        source[std::size_t(g)] = source[std::size_t(f)];
        distance[std::size_t(g)] = distance[std::size_t(f)] + 1;
        enter[std::size_t(g)] = i;
        queue.push_back(g);
      }
    }
    // the edges where two units' regions meet, shortest path first
    std::vector<std::pair<int, int>> offers; // (length, corner)
    for(int i = 0; i < 3 * m.nf; ++i) {
      const int o = m.opposite_corner[i];
      if(o < i)
        continue;
      const int f = Mesh::face_of(i), g = Mesh::face_of(o);
      if(source[std::size_t(f)] < 0 || source[std::size_t(g)] < 0 ||
         group[std::size_t(source[std::size_t(f)])] == group[std::size_t(source[std::size_t(g)])])
        continue;
      offers.push_back({distance[std::size_t(f)] + distance[std::size_t(g)] + 1, i});
    }
    std::sort(offers.begin(), offers.end());
    std::vector<int> parent(groups);
    for(std::size_t a = 0; a < groups; ++a)
      parent[a] = int(a);
    auto root = [&](int a) {
      while(parent[std::size_t(a)] != a)
        a = parent[std::size_t(a)] = parent[std::size_t(parent[std::size_t(a)])];
      return a;
    };
    std::vector<int> up;
    for(const auto& offer : offers) {
      const int i = offer.second, f = Mesh::face_of(i), g = Mesh::face_of(m.opposite_corner[i]);
      const int from = source[std::size_t(f)], to = source[std::size_t(g)];
      const int a = root(group[std::size_t(from)]), b = root(group[std::size_t(to)]);
      if(a == b)
        continue;
      parent[std::size_t(b)] = a;
      // from `from` down to f, across i, then from g up to `to`
      up.clear();
      for(int h = f; enter[std::size_t(h)] >= 0; h = Mesh::face_of(enter[std::size_t(h)]))
        up.push_back(enter[std::size_t(h)]);
      std::vector<int> crossings(up.rbegin(), up.rend());
      crossings.push_back(i);
      for(int h = g; enter[std::size_t(h)] >= 0; h = Mesh::face_of(enter[std::size_t(h)]))
        crossings.push_back(m.opposite_corner[enter[std::size_t(h)]]);
      links.push_back({from, to, t.component_of_face[std::size_t(faces[std::size_t(from)].face)], std::move(crossings)});
    }
  }

  int cluster_root(int a)
  {
    while(cluster_parent[std::size_t(a)] != a)
      a = cluster_parent[std::size_t(a)] = cluster_parent[std::size_t(cluster_parent[std::size_t(a)])];
    return a;
  }

  std::vector<int> cluster_parent;
  std::vector<char> cluster_seen;
  std::vector<Link> decided_links; // appended to `links` after the chains

public:
  // the crossings are coded by the constraint rows, which keep them: only the lengths stay here
  void release_crossings()
  {
    for(Link& link : links) {
      link.length = link.crossings.size();
      std::vector<int>().swap(link.crossings);
    }
  }
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_SYSTEM_CONSTRAINT_LINKS_H
