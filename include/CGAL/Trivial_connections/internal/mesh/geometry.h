// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_MESH_GEOMETRY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_MESH_GEOMETRY_H

#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/parameters.h>

#include <CGAL/number_type_config.h>

#include <array>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 scaled(const Vec3& a, double s) { return {{a[0] * s, a[1] * s, a[2] * s}}; }

// Angle in (-pi, pi] congruent to a modulo 2 pi. Sums of a few wrapped angles take the branch without fmod.
inline double wrap_angle(double a)
{
  const double two_pi = 2 * CGAL_PI;
  if(a > CGAL_PI && a <= 3 * CGAL_PI) return a - two_pi;
  if(a <= -CGAL_PI && a > -3 * CGAL_PI) return a + two_pi;
  if(a > -CGAL_PI && a <= CGAL_PI) return a;
  double r = std::fmod(a, two_pi);
  if(r > CGAL_PI) r -= two_pi;
  else if(r <= -CGAL_PI) r += two_pi;
  return r;
}

// Unsigned angle between two vectors, accurate for every angle (atan2 of |u x w| and u.w).
inline double angle_between(const Vec3& u, const Vec3& w) { return std::atan2(norm(cross(u, w)), dot(u, w)); }

/*
  Intrinsic quantities of the flattened mesh. Each face f has the frame (e_f, N_f x e_f) with e_f the
  unit direction of its corner halfedge 3f; a tangent direction of f is an angle in that frame.
  Interior edges are numbered in the order of their smaller corner halfedge, which is their "canonical"
  halfedge: x_e = x(canonical halfedge).
  The constructor computes what the constraint system needs (edges, weights); `compute_angles()` what
  only the right-hand sides, loop holonomies and fields need, so that it can run beside the factorization.
*/
struct Mesh_geometry
{
  std::vector<bool> on_boundary;        // per vertex
  std::vector<int> edge_of_corner;      // per corner halfedge: interior edge id, -1 on a border edge
  std::vector<int> edge_corner;         // per interior edge: its canonical corner halfedge
  std::vector<double> weight;           // per interior edge: w_e

  std::vector<double> angle_sum;        // per vertex (compute_angles)
  std::vector<double> transport;        // per interior edge: rho of its canonical halfedge (compute_angles)

  int number_of_interior_edges() const { return int(edge_corner.size()); }

  // x(i) for corner halfedge i of an interior edge, given x per interior edge
  template <class Values>
  double oriented(const Values& per_edge, int i) const
  {
    const int e = edge_of_corner[i];
    return edge_corner[e] == i ? per_edge[e] : -per_edge[e];
  }

  // rho(i): the angle a direction gains in frame coordinates when moved by Levi-Civita transport from
  // face(i) to the face of opposite(i). The edge keeps its direction while the frames change.
  double transport_angle(int i) const { return oriented(transport, i); }

  // the frame (e_f, N_f x e_f) of face f, recomputed when needed rather than stored (fresh memory is
  // what large meshes pay for)
  template <class TriangleMesh>
  static void frame(const Mesh_arrays<TriangleMesh>& m, int f, Vec3& ex, Vec3& ey)
  {
    const Vec3* p[3] = {&m.points[m.corner_vertex[3 * f]], &m.points[m.corner_vertex[3 * f + 1]],
                        &m.points[m.corner_vertex[3 * f + 2]]};
    const Vec3 e01 = sub(*p[1], *p[0]);
    // the normal from the two edges of the largest angle (the corner opposite the longest edge): at a needle's
    // sharp corner the two edges are nearly parallel and their cross product loses its digits
    int k = 0;
    double longest = -1;
    for(int i = 0; i < 3; ++i) {
      const double l = dot(sub(*p[(i + 2) % 3], *p[(i + 1) % 3]), sub(*p[(i + 2) % 3], *p[(i + 1) % 3]));
      if(l > longest) {
        longest = l;
        k = i;
      }
    }
    const Vec3 n = cross(sub(*p[(k + 1) % 3], *p[k]), sub(*p[(k + 2) % 3], *p[k]));
    ex = scaled(e01, 1 / norm(e01));
    ey = cross(scaled(n, 1 / norm(n)), ex);
  }

  double angle_defect(int v) const { return (on_boundary[v] ? CGAL_PI : 2 * CGAL_PI) - angle_sum[v]; }

  Mesh_geometry() = default;

  template <class TriangleMesh>
  Mesh_geometry(const Mesh_arrays<TriangleMesh>& m, Weighting weighting)
  {
    const int nc = 3 * m.nf;
    on_boundary.assign(m.nv, false);
    edge_of_corner.assign(nc, -1);
    int ne = 0;
    for(int i = 0; i < nc; ++i) {
      const int o = m.opposite_corner[i];
      if(o < 0) {
        on_boundary[m.source_of(i)] = true;
        on_boundary[m.target_of(i)] = true;
      } else if(i < o) {
        edge_of_corner[i] = edge_of_corner[o] = ne++;
      }
    }
    edge_corner.resize(ne);
    for(int i = 0; i < nc; ++i)
      if(edge_of_corner[i] >= 0 && i < m.opposite_corner[i])
        edge_corner[edge_of_corner[i]] = i;

    if(weighting == Weighting::unit) {
      weight.assign(ne, 1.);
      return;
    }
    // w_e = |e| / |e*| with |e*| the sum over the two faces of |barycenter - midpoint of e|, which is a
    // third of the median from the opposite corner: accumulated face by face, each face read once
    weight.assign(ne, 0.);
    for(int f = 0; f < m.nf; ++f) {
      const Vec3* p[3] = {&m.points[m.corner_vertex[3 * f]], &m.points[m.corner_vertex[3 * f + 1]],
                          &m.points[m.corner_vertex[3 * f + 2]]};
      for(int k = 0; k < 3; ++k) {
        const int e = edge_of_corner[3 * f + k];
        if(e < 0)
          continue;
        const Vec3& a = *p[k];
        const Vec3& b = *p[(k + 1) % 3];
        const Vec3& c = *p[(k + 2) % 3];
        const Vec3 median = {{(a[0] + b[0]) / 2 - c[0], (a[1] + b[1]) / 2 - c[1], (a[2] + b[2]) / 2 - c[2]}};
        weight[e] += norm(median) / 3;
      }
    }
    for(int e = 0; e < ne; ++e) {
      const int i = edge_corner[e];
      weight[e] = norm(sub(m.points[m.target_of(i)], m.points[m.source_of(i)])) / weight[e];
    }
  }

  // Corner angles (their sums per vertex) and the transport angle of every interior edge. It runs beside
  // the factorization, whose memory is the peak: nothing per corner is stored.
  template <class TriangleMesh>
  void compute_angles(const Mesh_arrays<TriangleMesh>& m)
  {
    angle_sum.assign(m.nv, 0.);
    // transport(e) = direction(o) + pi - direction(i) for e's canonical corner halfedge i and its opposite
    // o, where a corner halfedge's direction is its angle in the frame of its face: summed face by face
    transport.assign(edge_corner.size(), CGAL_PI);
    for(int f = 0; f < m.nf; ++f) {
      const Vec3& p0 = m.points[m.corner_vertex[3 * f]];
      const Vec3& p1 = m.points[m.corner_vertex[3 * f + 1]];
      const Vec3& p2 = m.points[m.corner_vertex[3 * f + 2]];
      const Vec3 e01 = sub(p1, p0), e12 = sub(p2, p1), e20 = sub(p0, p2);
      const double a0 = angle_between(e01, scaled(e20, -1));
      const double a1 = angle_between(e12, scaled(e01, -1));
      const double a2 = angle_between(e20, scaled(e12, -1));
      angle_sum[m.corner_vertex[3 * f]] += a0;
      angle_sum[m.corner_vertex[3 * f + 1]] += a1;
      angle_sum[m.corner_vertex[3 * f + 2]] += a2;
      // the edges of a counter-clockwise triangle turn by the exterior angles: e12 is at pi - a1 from
      // e01, and e20 at a0 - pi (both in (-pi, pi]); no further atan2 needed
      const double direction[3] = {0., CGAL_PI - a1, a0 - CGAL_PI};
      for(int j = 0; j < 3; ++j) {
        const int i = 3 * f + j, e = edge_of_corner[i];
        if(e >= 0)
          transport[e] += edge_corner[e] == i ? -direction[j] : direction[j];
      }
    }
    for(double& t : transport)
      t = wrap_angle(t);
  }
};

// angle of a vector in the frame of face f (counter-clockwise from the direction of its corner halfedge 3f)
template <class TriangleMesh>
double angle_in_frame(const Mesh_arrays<TriangleMesh>& m, int f, const Vec3& v)
{
  Vec3 ex, ey;
  Mesh_geometry::frame(m, f, ex, ey);
  return std::atan2(dot(v, ey), dot(v, ex));
}

// angle of corner halfedge i's edge (source to target) in the frame of its face
template <class TriangleMesh>
double edge_angle_in_frame(const Mesh_arrays<TriangleMesh>& m, int i)
{
  return angle_in_frame(m, Mesh_arrays<TriangleMesh>::face_of(i), sub(m.points[m.target_of(i)], m.points[m.source_of(i)]));
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_MESH_GEOMETRY_H
