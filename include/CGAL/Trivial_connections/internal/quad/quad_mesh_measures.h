// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_MESH_MEASURES_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_MESH_MEASURES_H

#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/quad/quad_extraction.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  What compute_quad_mesh() reports about its quads, measured on the quads and the input (not taken from the
  layers' own bookkeeping): the quads whose triangles point against the input surface, and the two one-sided
  Hausdorff distances between the quads (each split into two triangles along its first diagonal) and the input.
*/
namespace quad_measures_impl {

using SC = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<SC::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<SC, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<SC, Primitive>>;

inline SC::Point_3 point(const Vec3& p) { return SC::Point_3(p[0], p[1], p[2]); }

// The largest distance from the samples of `from` to the triangles of `to` (exact point-triangle distances, AABB
// tree): on each triangle the points of the barycentric grid of k x k cells, k = ceil(longest edge / spacing)
// within [2, max_cells]. A lower bound of the one-sided Hausdorff distance, within about one grid cell of it.
inline double one_sided_distance(const Triangles& from, const Triangles& to, double spacing, int max_cells = 32)
{
  if(from.empty())
    return 0;
  if(to.empty())
    return std::numeric_limits<double>::infinity();
  Tree tree(to.begin(), to.end());
  tree.accelerate_distance_queries();
  double worst = 0;
  for(const SC::Triangle_3& t : from) {
    const SC::Point_3 &a = t[0], &b = t[1], &c = t[2];
    const double longest = std::sqrt((std::max)({CGAL::squared_distance(a, b), CGAL::squared_distance(b, c),
                                                 CGAL::squared_distance(c, a)}));
    const int k = int((std::min)(double(max_cells), (std::max)(2., std::ceil(longest / spacing))));
    for(int i = 0; i <= k; ++i)
      for(int j = 0; i + j <= k; ++j) {
        const double s = double(i) / k, r = double(j) / k;
        const SC::Point_3 p(a.x() + s * (b.x() - a.x()) + r * (c.x() - a.x()),
                            a.y() + s * (b.y() - a.y()) + r * (c.y() - a.y()),
                            a.z() + s * (b.z() - a.z()) + r * (c.z() - a.z()));
        worst = (std::max)(worst, tree.squared_distance(p));
      }
  }
  return std::sqrt(worst);
}

} // namespace quad_measures_impl

struct Quad_measures
{
  int flipped_quads = 0;
  int concave_quads = 0;
  double hausdorff_quads_to_input = 0; // the largest distance from a point of the quads to the input
  double hausdorff_input_to_quads = 0; // the largest distance from a point of the input to the quads
};

// The quad's triangles (a, b, c) and (a, c, d)
inline std::array<std::array<int, 3>, 2> quad_triangles(const std::array<int, 4>& q)
{
  return {{{{q[0], q[1], q[2]}}, {{q[0], q[2], q[3]}}}};
}

/*
  A quad is flipped when its vector area (half the sum of p_j x p_j+1, the normal of a planar quad times its area)
  points against the sum of the input's normals at its four vertices (a negative scalar product); it is concave
  when one of its corners (the triangle previous, vertex, next) does. A concave quad is a valid cell of a
  fold-free map (its iso-lines bend inside the triangles); a flipped one is not. The input's normal at a quad
  vertex: at a mesh vertex the angle-weighted mean of the unit normals of its faces, inside an edge the sum of its
  two faces' unit normals, inside a face the face's. `spacing`: the sampling step of the distances (see
  one_sided_distance()).
*/
template <class TriangleMesh>
Quad_measures measure_quad_mesh(const Mesh_arrays<TriangleMesh>& m, const Quad_mesh& quads, double spacing)
{
  using MA = Mesh_arrays<TriangleMesh>;
  using namespace quad_measures_impl;
  std::vector<Vec3> face_normal(m.nf), vertex_normal(m.nv, Vec3{{0, 0, 0}});
  for(int f = 0; f < m.nf; ++f) {
    const Vec3 n = cross(sub(m.points[m.corner_vertex[3 * f + 1]], m.points[m.corner_vertex[3 * f]]),
                         sub(m.points[m.corner_vertex[3 * f + 2]], m.points[m.corner_vertex[3 * f]]));
    face_normal[f] = scaled(n, 1 / norm(n));
    for(int k = 0; k < 3; ++k) {
      const int c = 3 * f + k;
      const Vec3 p = m.points[m.corner_vertex[c]];
      const double corner = angle_between(sub(m.points[m.target_of(c)], p),
                                          sub(m.points[m.source_of(MA::prev_corner(c))], p));
      for(int x = 0; x < 3; ++x)
        vertex_normal[m.corner_vertex[c]][x] += corner * face_normal[f][x];
    }
  }
  auto location_normal = [&](const Quad_mesh::Location& l) {
    if(l.mesh_vertex >= 0)
      return vertex_normal[l.mesh_vertex];
    for(int j = 0; j < 3; ++j)
      if(l.barycentric[j] == 0) { // on the edge opposite corner j: the corner halfedge from j + 1 to j + 2
        const int o = m.opposite_corner[3 * l.face + (j + 1) % 3];
        Vec3 n = face_normal[l.face];
        if(o >= 0)
          for(int x = 0; x < 3; ++x)
            n[x] += face_normal[MA::face_of(o)][x];
        return n;
      }
    return face_normal[l.face];
  };

  Quad_measures result;
  Triangles quad_triangles_3, input_triangles;
  for(const std::array<int, 4>& q : quads.faces) {
    Vec3 reference = {{0, 0, 0}}, area = {{0, 0, 0}}; // the input's normals at the 4 vertices; the vector area
    for(int j = 0; j < 4; ++j) {
      const Vec3 n = location_normal(quads.locations[q[j]]);
      const Vec3 c = cross(quads.points[q[j]], quads.points[q[(j + 1) % 4]]);
      for(int x = 0; x < 3; ++x) {
        reference[x] += n[x];
        area[x] += c[x] / 2;
      }
    }
    result.flipped_quads += dot(area, reference) < 0;
    // a corner turning the wrong way: the triangle (previous, vertex, next) against the input's normals
    bool concave = false;
    for(int j = 0; j < 4; ++j) {
      const Vec3& p = quads.points[q[j]];
      const Vec3 corner = cross(sub(quads.points[q[(j + 1) % 4]], p), sub(quads.points[q[(j + 3) % 4]], p));
      concave = concave || dot(corner, reference) < 0;
    }
    result.concave_quads += concave;
    for(const std::array<int, 3>& t : quad_triangles(q)) {
      const Vec3 n = cross(sub(quads.points[t[1]], quads.points[t[0]]), sub(quads.points[t[2]], quads.points[t[0]]));
      if(norm(n) > 0) // a degenerate one (a quad folded onto a diagonal) has no plane: its points are its neighbours'
        quad_triangles_3.emplace_back(point(quads.points[t[0]]), point(quads.points[t[1]]), point(quads.points[t[2]]));
    }
  }
  for(int f = 0; f < m.nf; ++f)
    input_triangles.emplace_back(point(m.points[m.corner_vertex[3 * f]]), point(m.points[m.corner_vertex[3 * f + 1]]),
                                 point(m.points[m.corner_vertex[3 * f + 2]]));
  result.hausdorff_quads_to_input = one_sided_distance(quad_triangles_3, input_triangles, spacing);
  result.hausdorff_input_to_quads = one_sided_distance(input_triangles, quad_triangles_3, spacing);
  return result;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_QUAD_QUAD_MESH_MEASURES_H
