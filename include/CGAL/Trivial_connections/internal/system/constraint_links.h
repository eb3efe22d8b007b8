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
  and the faces the user constrains are then linked in the order of a depth-first traversal of the dual
  spanning tree, by their paths in that tree. The links of a component form a tree on its constrained
  faces, so their rows are independent of each other and of the cycle rows.
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
  // not linked by rounding (the lattice chooses between them)
  template <class TriangleMesh>
  Constraint_links(const Mesh_arrays<TriangleMesh>& m, const Mesh_topology& t, const std::vector<int>& user_faces,
                   const std::vector<int>& guided, bool align, double mu,
                   const std::vector<double>& user_angles = std::vector<double>(), int n = 1)
    : guidance_weight(mu)
  {
    using Mesh = Mesh_arrays<TriangleMesh>;
    std::vector<int> constraint_of_face(std::size_t(m.nf), -1);
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
      for(std::size_t k = 1; k < u.size(); ++k) {
        std::vector<int> crossings;
        append_dual_tree_path(m.opposite_corner, t.parent_corner, tree.depth, faces[u[k - 1]].face, faces[u[k]].face,
                              crossings);
        links.push_back({u[k - 1], u[k], int(c), std::move(crossings)});
      }
    }
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
    // with the targets known: whether the link a -> b across `crossings` turns by less than a quarter of 2 pi / n
    // (H = theta_a - theta_b + the transport along it, as the link's row reads it), so that rounding is safe
    auto direction = [&](int i) {
      return angle_in_frame(m, Mesh::face_of(i), sub(m.points[m.target_of(i)], m.points[m.source_of(i)]));
    };
    auto agree = [&](int a, int b, const std::vector<int>& crossings) {
      if(user_angles.empty())
        return true;
      double h = user_angles[std::size_t(a - first_user)] - user_angles[std::size_t(b - first_user)];
      if(std::isnan(h)) // a target not known yet
        return true;
      for(int i : crossings)
        h += direction(m.opposite_corner[i]) + CGAL_PI - direction(i);
      const double turns = h * n / (2 * CGAL_PI);
      return std::abs(turns - std::round(turns)) <= 0.25;
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
