// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_FACE_CURVATURE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_FACE_CURVATURE_H

#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The shape operator of a face, diagonalised: principal curvatures (|first| >= |second|) and the unit direction
// of the first, a tangent vector of the face.
struct Face_curvature
{
  double first = 0, second = 0;
  Vec3 first_direction = {{0., 0., 0.}};
};

/*
  Per-face shape operator of Rusinkiewicz ("Estimating curvatures and their derivatives on triangle meshes",
  3DPVT 2004): with vertex normals n_v (the faces' normals weighted by their corner angle at v), the symmetric
  2x2 operator S of a face in its frame is the least-squares solution of S e = n_b - n_a over its three edges
  e = b - a (six equations, three unknowns). It needs only the face and its vertices' normals, is exact on a
  sphere (S = I / r) and converges linearly in the edge length on smooth surfaces.
*/
template <class TriangleMesh>
std::vector<Face_curvature> face_curvatures(const Mesh_arrays<TriangleMesh>& m)
{
  std::vector<Vec3> normal(std::size_t(m.nv), Vec3{{0., 0., 0.}});
  for(int f = 0; f < m.nf; ++f) {
    const Vec3* p[3] = {&m.points[m.corner_vertex[3 * f]], &m.points[m.corner_vertex[3 * f + 1]],
                        &m.points[m.corner_vertex[3 * f + 2]]};
    Vec3 n = cross(sub(*p[1], *p[0]), sub(*p[2], *p[0]));
    n = scaled(n, 1 / norm(n));
    for(int k = 0; k < 3; ++k) {
      const double a = angle_between(sub(*p[(k + 1) % 3], *p[k]), sub(*p[(k + 2) % 3], *p[k]));
      Vec3& nv = normal[m.corner_vertex[3 * f + k]];
      for(int j = 0; j < 3; ++j)
        nv[j] += a * n[j];
    }
  }
  for(Vec3& n : normal) {
    const double l = norm(n);
    if(l > 0)
      n = scaled(n, 1 / l);
  }
  std::vector<Face_curvature> result(std::size_t(m.nf));
  for(int f = 0; f < m.nf; ++f) {
    Vec3 ex, ey;
    Mesh_geometry::frame(m, f, ex, ey);
    // normal equations of the six equations in (a, b, c), S = [[a, b], [b, c]]
    double M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, r[3] = {0, 0, 0};
    for(int k = 0; k < 3; ++k) {
      const int a = m.corner_vertex[3 * f + k], b = m.corner_vertex[3 * f + (k + 1) % 3];
      const Vec3 e = sub(m.points[b], m.points[a]);
      const Vec3 dn = sub(normal[b], normal[a]);
      const double ux = dot(e, ex), uy = dot(e, ey), nx = dot(dn, ex), ny = dot(dn, ey);
      // (ux, uy, 0) . (a, b, c) = nx and (0, ux, uy) . (a, b, c) = ny
      const double row1[3] = {ux, uy, 0}, row2[3] = {0, ux, uy};
      for(int i = 0; i < 3; ++i) {
        for(int j = 0; j < 3; ++j)
          M[i][j] += row1[i] * row1[j] + row2[i] * row2[j];
        r[i] += row1[i] * nx + row2[i] * ny;
      }
    }
    // Cramer's rule on the 3x3 system (symmetric positive definite for a non-degenerate face)
    auto det3 = [](const double A[3][3]) {
      return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
             A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    };
    const double d = det3(M);
    double s[3] = {0, 0, 0};
    if(d != 0 && std::isfinite(d))
      for(int j = 0; j < 3; ++j) {
        double Mj[3][3];
        for(int a = 0; a < 3; ++a)
          for(int b = 0; b < 3; ++b)
            Mj[a][b] = b == j ? r[a] : M[a][b];
        s[j] = det3(Mj) / d;
      }
    const double a = s[0], b = s[1], c = s[2];
    // eigenvalues of [[a, b], [b, c]] and the direction of the one of larger magnitude
    const double mean = (a + c) / 2, radius = std::hypot((a - c) / 2, b);
    const double k1 = mean + radius, k2 = mean - radius;
    Face_curvature& fc = result[f];
    const bool first_is_k1 = std::abs(k1) >= std::abs(k2);
    fc.first = first_is_k1 ? k1 : k2;
    fc.second = first_is_k1 ? k2 : k1;
    // eigenvector angle t of the eigenvalue mean + radius: tan(2t) = 2b / (a - c); the other is t + pi/2
    double t = 0.5 * std::atan2(2 * b, a - c);
    if(!first_is_k1)
      t += CGAL_PI / 2;
    for(int j = 0; j < 3; ++j)
      fc.first_direction[j] = std::cos(t) * ex[j] + std::sin(t) * ey[j];
  }
  return result;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_PLACEMENT_FACE_CURVATURE_H
