// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TRIANGULATE_POLYGONS_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TRIANGULATE_POLYGONS_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/IO/internal/triangle_soup.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh/Surface_mesh.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/exceptions.h>
#include <CGAL/boost/graph/iterator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

/*
  Triangulates a polygon of five or more corners: projected onto the plane of its Newell normal, it must be
  simple (no two edges meet except consecutive ones at their common corner; exact predicates on the
  projected points) and within 5% of its size from planar, else false. Its triangles, the faces of the
  constrained Delaunay triangulation of the projected corners inside the polygon (m - 2 of them, no new
  vertex), are appended to `out` as point indices, with the polygon's orientation. We do not call
  PMP::triangulate_face() for these: it asserts, crashes, loops or corrupts its mesh (an endless face cycle)
  on faces it projects differently, which the fuzzer kept finding.
*/
template <class Point>
bool triangulate_simple_polygon(const std::vector<Point>& points, const std::vector<std::size_t>& corners,
                                std::vector<std::array<int, 3>>& out)
{
  using K2 = CGAL::Exact_predicates_inexact_constructions_kernel;
  const std::size_t m = corners.size();
  double n[3] = {0, 0, 0};
  for(std::size_t k = 0; k < m; ++k) {
    const Point& a = points[corners[k]];
    const Point& b = points[corners[(k + 1) % m]];
    const double ax = CGAL::to_double(a.x()), ay = CGAL::to_double(a.y()), az = CGAL::to_double(a.z());
    const double bx = CGAL::to_double(b.x()), by = CGAL::to_double(b.y()), bz = CGAL::to_double(b.z());
    n[0] += (ay - by) * (az + bz);
    n[1] += (az - bz) * (ax + bx);
    n[2] += (ax - bx) * (ay + by);
  }
  const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if(!(length > 0) || !std::isfinite(length))
    return false;
  for(double& c : n)
    c /= length;
  // u: perpendicular to n, along the axis n is furthest from; v = n x u
  double u[3] = {0, 0, 0};
  const int axis = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2]) ? 0
                   : std::abs(n[1]) <= std::abs(n[2])                                   ? 1
                                                                                        : 2;
  u[axis] = 1;
  const double d = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
  for(int i = 0; i < 3; ++i)
    u[i] -= d * n[i];
  const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for(double& c : u)
    c /= lu;
  const double v[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  // far from planar: CGAL's triangulation of such a face can loop forever (found by fuzzing), so a corner
  // more than 5% of the face's size away from its mean plane is refused
  double centre[3] = {0, 0, 0}, size = 0;
  for(std::size_t i : corners) {
    centre[0] += CGAL::to_double(points[i].x()) / double(m);
    centre[1] += CGAL::to_double(points[i].y()) / double(m);
    centre[2] += CGAL::to_double(points[i].z()) / double(m);
  }
  double height = 0;
  for(std::size_t i : corners) {
    const double p[3] = {CGAL::to_double(points[i].x()) - centre[0], CGAL::to_double(points[i].y()) - centre[1],
                         CGAL::to_double(points[i].z()) - centre[2]};
    size = (std::max)(size, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
    height = (std::max)(height, std::abs(p[0] * n[0] + p[1] * n[1] + p[2] * n[2]));
  }
  if(!(height <= 0.05 * size))
    return false;
  std::vector<K2::Point_2> q;
  for(std::size_t i : corners) {
    const double p[3] = {CGAL::to_double(points[i].x()), CGAL::to_double(points[i].y()), CGAL::to_double(points[i].z())};
    q.emplace_back(p[0] * u[0] + p[1] * u[1] + p[2] * u[2], p[0] * v[0] + p[1] * v[1] + p[2] * v[2]);
  }
  for(std::size_t i = 0; i < m; ++i) {
    const K2::Segment_2 s(q[i], q[(i + 1) % m]);
    if(s.is_degenerate())
      return false;
    for(std::size_t j = i + 1; j < m; ++j) {
      const K2::Segment_2 t(q[j], q[(j + 1) % m]);
      const bool next = j == i + 1, previous = (j + 1) % m == i;
      if(next || previous) {
        // consecutive edges share one corner: they must not overlap beyond it
        const K2::Point_2& shared = next ? q[j] : q[i];
        const K2::Point_2& other_s = next ? q[i] : q[(i + 1) % m];
        const K2::Point_2& other_t = next ? q[(j + 1) % m] : q[j];
        if(CGAL::collinear(other_s, shared, other_t) && !CGAL::collinear_are_strictly_ordered_along_line(other_s, shared, other_t))
          return false;
      } else if(CGAL::do_intersect(s, t)) {
        return false;
      }
    }
  }
  // (u, v, n) is right-handed, so the polygon turns counter-clockwise in (u, v), as the faces of the CDT
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K2>;
  using Fb = CGAL::Constrained_triangulation_face_base_2<K2, CGAL::Triangulation_face_base_with_info_2<int, K2>>;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<K2, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                                         CGAL::No_constraint_intersection_tag>;
  CDT cdt;
  std::vector<typename CDT::Vertex_handle> handles;
  for(std::size_t k = 0; k < m; ++k) {
    handles.push_back(cdt.insert(q[k]));
    handles.back()->info() = corners[k];
  }
  if(cdt.number_of_vertices() != m)
    return false;
  for(std::size_t k = 0; k < m; ++k)
    cdt.insert_constraint(handles[k], handles[(k + 1) % m]);
  if(cdt.number_of_vertices() != m) // no Steiner point, but for safety
    return false;
  // inside: reached from the infinite face by crossing an odd number of constraints (exactly one: simple)
  for(auto fh = cdt.all_faces_begin(); fh != cdt.all_faces_end(); ++fh)
    fh->info() = -1;
  std::vector<typename CDT::Face_handle> stack(1, cdt.infinite_face());
  cdt.infinite_face()->info() = 0;
  while(!stack.empty()) {
    const typename CDT::Face_handle fh = stack.back();
    stack.pop_back();
    for(int i = 0; i < 3; ++i) {
      const typename CDT::Face_handle g = fh->neighbor(i);
      if(g->info() != -1)
        continue;
      g->info() = fh->info() + (cdt.is_constrained(typename CDT::Edge(fh, i)) ? 1 : 0);
      stack.push_back(g);
    }
  }
  const std::size_t first = out.size();
  for(auto fh = cdt.finite_faces_begin(); fh != cdt.finite_faces_end(); ++fh)
    if(fh->info() % 2 == 1)
      out.push_back({{int(fh->vertex(0)->info()), int(fh->vertex(1)->info()), int(fh->vertex(2)->info())}});
  if(out.size() - first != m - 2) {
    out.resize(first);
    return false;
  }
  return true;
}

/*
  Splits every polygon of more than three vertices into triangles (a quad along its better diagonal with
  PMP::triangulate_face(), larger polygons by triangulate_simple_polygon(): a constrained Delaunay
  triangulation in their plane), keeping the polygon's orientation and the vertex indices. Triangles of a polygon are consecutive, polygons in order;
  source[t] is the polygon of triangle t. Indices are checked first; polygons of fewer than three vertices are
  left to the validation, which rejects them.
*/
template <class Point, class PolygonRange>
void triangulate_polygons(const std::vector<Point>& points, const PolygonRange& polygons,
                          std::vector<std::array<int, 3>>& triangles, std::vector<std::size_t>& source)
{
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using Patches = CGAL::Surface_mesh<typename Kernel::Point_3>;
  using Patch_vertex = typename Patches::Vertex_index;
  using Patch_face = typename Patches::Face_index;
  const std::size_t nf = polygons.size();
  check_soup_size(points.size(), nf);

  // Each polygon on its own copies of its vertices: one disk per polygon, whatever the soup's connectivity.
  Patches patches;
  auto point_index = patches.template add_property_map<Patch_vertex, int>("v:tc_point", -1).first;
  // by vertex: the faces split_face() creates have no property of their own, their vertices do
  auto polygon_of = patches.template add_property_map<Patch_vertex, std::size_t>("v:tc_polygon", 0).first;
  std::vector<Patch_face> to_split;
  std::vector<std::pair<std::size_t, std::array<int, 3>>> pieces; // (polygon, triangle)
  std::size_t f = 0;
  for(const auto& polygon : polygons) {
    for(const auto& index : polygon)
      if(std::size_t(index) >= points.size())
        throw_vertex_out_of_range(f, std::size_t(index), points.size());
    if(polygon.size() > 3) {
      std::vector<std::size_t> corners(polygon.begin(), polygon.end());
      std::vector<std::size_t> sorted = corners;
      std::sort(sorted.begin(), sorted.end());
      const auto repeated = std::adjacent_find(sorted.begin(), sorted.end());
      if(repeated != sorted.end())
        throw Invalid_input(Error_code::degenerate_face, "face " + std::to_string(f) + " uses vertex " +
                                                          std::to_string(*repeated) + " twice", f);
      if(polygon.size() > 4) {
        std::vector<std::array<int, 3>> split;
        if(!triangulate_simple_polygon(points, corners, split))
          throw Invalid_input(Error_code::degenerate_face,
                              "face " + std::to_string(f) +
                                " cannot be triangulated (it is far from planar, or seen along its normal its boundary"
                                " crosses itself)", f);
        for(const std::array<int, 3>& t : split)
          pieces.emplace_back(f, t);
        ++f;
        continue;
      }
      // a quad: PMP::triangulate_face() splits it along its better diagonal
      std::vector<Patch_vertex> corner_vertices;
      for(std::size_t i : corners) {
        const Point& p = points[i];
        const Patch_vertex v = patches.add_vertex(typename Kernel::Point_3(p.x(), p.y(), p.z()));
        put(point_index, v, int(i));
        put(polygon_of, v, f);
        corner_vertices.push_back(v);
      }
      to_split.push_back(patches.add_face(corner_vertices));
    }
    ++f;
  }
  for(const Patch_face pf : to_split) {
    const std::size_t bad = get(polygon_of, patches.target(patches.halfedge(pf)));
    bool split = false;
    try {
      split = CGAL::Polygon_mesh_processing::triangulate_face(pf, patches);
    } catch(const CGAL::Failure_exception&) {
      // CGAL's triangulation asserts on some faces that are far from planar or have coincident corners
      split = false;
    }
    if(!split)
      throw Invalid_input(Error_code::degenerate_face,
                          "face " + std::to_string(bad) + " cannot be triangulated (it is degenerate, or far from planar)",
                          bad);
  }

  // Triangles of each split polygon, gathered by polygon (new faces are appended, so sort by polygon).
  for(const Patch_face pf : patches.faces()) {
    std::array<int, 3> t;
    std::size_t k = 0;
    for(const Patch_vertex v : CGAL::vertices_around_face(patches.halfedge(pf), patches)) {
      if(k == 3) { // more corners (and no endless walk if the face cycle is broken)
        ++k;
        break;
      }
      t[k++] = get(point_index, v);
    }
    const std::size_t polygon = get(polygon_of, patches.target(patches.halfedge(pf)));
    if(k != 3) // triangulate_face() reported success but left a larger face (non-planar faces, found by fuzzing)
      throw Invalid_input(Error_code::degenerate_face,
                          "face " + std::to_string(polygon) + " cannot be triangulated (it is far from planar)",
                          polygon);
    pieces.emplace_back(polygon, t);
  }
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });

  triangles.clear();
  source.clear();
  auto piece = pieces.begin();
  f = 0;
  for(const auto& polygon : polygons) {
    if(polygon.size() > 3) {
      for(; piece != pieces.end() && piece->first == f; ++piece) {
        triangles.push_back(piece->second);
        source.push_back(f);
      }
    } else if(polygon.size() == 3) {
      std::array<int, 3> t;
      std::size_t k = 0;
      for(const auto& index : polygon)
        t[k++] = int(std::size_t(index));
      triangles.push_back(t);
      source.push_back(f);
    } else {
      throw Invalid_input(Error_code::not_triangle_mesh,
                          "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) + " vertices", f);
    }
    ++f;
  }
}

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_TRIANGULATE_POLYGONS_H
