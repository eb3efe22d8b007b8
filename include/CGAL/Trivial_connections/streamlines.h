// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_STREAMLINES_H
#define CGAL_TRIVIAL_CONNECTIONS_STREAMLINES_H

#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <unordered_set>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
An integral curve of a direction field: a polyline whose segment `i` (from `points[i]` to `points[i+1]`) lies
in face `faces[i]` along one of the field's directions there.
*/
template <class TriangleMesh>
struct Streamline
{
  std::vector<std::array<double, 3>> points; ///< the polyline's points, on the surface
  /// `faces[i]` holds the segment from `points[i]` to `points[i+1]` (one fewer than `points`)
  std::vector<typename boost::graph_traits<TriangleMesh>::face_descriptor> faces;
};

namespace internal {

using Vec = Vec3;
inline Vec unit3(const Vec& a)
{
  const double l = std::sqrt(dot(a, a));
  return l > 0 ? Vec{{a[0] / l, a[1] / l, a[2] / l}} : a;
}
inline Vec combine(double s, const Vec& a, double t, const Vec& b)
{
  return {{s * a[0] + t * b[0], s * a[1] + t * b[1], s * a[2] + t * b[2]}};
}

} // namespace internal

/*!
\ingroup PkgTrivialConnectionsRef
Traces the streamlines of an n-direction field from the barycentre of each seed face (a seed face with a
singular vertex gives no line), along every direction
of the field there (both ways: a line of a cross field through a seed is two of its four rays, joined). In each
face a streamline goes straight along one of the field's directions (the field is constant per face) to the
edge it meets; it then crosses into the neighbouring face with the connection (Levi-Civita transport followed
by the rotation `x(h)`), which brings its direction exactly onto one of the field's directions there when the
field is parallel for `x` (the one nearest is taken). A ray stops at a boundary edge, on entering a face that
has a singular vertex, when it enters a face along a direction it already followed there (a closed or
recurrent curve), or after `maximum_faces_per_ray` faces (default: n times the number of faces of the
mesh, which only a recurrent curve can reach). A ray that meets an edge within
`1e-9` of its length from a vertex crosses it that far from the vertex instead, and the steps of less than
`1e-8` of an edge that such a pass makes are merged into the segment before.
\param tm the triangle mesh the connection and the field were computed on
\param x the connection (from `solve()`)
\param field the field (from `compute_field()` with the same connection)
\param singularities a range of pairs whose `first` is a singular `vertex_descriptor` (as given to `solve()`)
\param seeds a range of `face_descriptor`
\param np an optional sequence of named parameters among the ones listed below
\returns the streamlines, seed after seed in the order of `seeds`: per seed face (none for one with a singular
         vertex) one line per pair of opposite directions for even n (n/2 lines), one per direction for odd n
         (n lines), in counter-clockwise order from `get(field, f)`; a line of fewer than two points is dropped
\cgalNamedParamsBegin
  \cgalParamNBegin{vertex_point_map} \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, tm)`} \cgalParamNEnd
  \cgalParamNBegin{symmetry_order} \cgalParamType{`int`} \cgalParamDefault{1} \cgalParamNEnd
  \cgalParamNBegin{maximum_faces_per_ray} \cgalParamType{`std::size_t`} \cgalParamDefault{n times the number of faces} \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class TriangleMesh, class HalfedgeAngleMap, class FaceVectorMap, class SingularityRange, class FaceRange,
          class NamedParameters = parameters::Default_named_parameters>
std::vector<Streamline<TriangleMesh>> trace_streamlines(const TriangleMesh& tm, HalfedgeAngleMap x, FaceVectorMap field,
                                                        const SingularityRange& singularities, const FaceRange& seeds,
                                                        const NamedParameters& np = parameters::default_values())
{
  using GT = boost::graph_traits<TriangleMesh>;
  using face_descriptor = typename GT::face_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using internal::Vec;
  const auto vpm = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                                      get_const_property_map(CGAL::vertex_point, tm));
  const int n = (std::max)(1, CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tc_np::symmetry_order), 1));
  const double unit = 2 * CGAL_PI / n;
  auto point = [&](vertex_descriptor v) {
    const auto& p = get(vpm, v);
    return Vec{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
  };
  auto normal = [&](face_descriptor f) {
    const halfedge_descriptor h = halfedge(f, tm);
    const Vec a = point(source(h, tm)), b = point(target(h, tm)), c = point(target(next(h, tm), tm));
    return internal::unit3(internal::cross(internal::sub(b, a), internal::sub(c, a)));
  };
  auto field_at = [&](face_descriptor f) {
    const auto v = get(field, f);
    return internal::unit3(Vec{{CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z())}});
  };
  auto turned = [&](const Vec& v, const Vec& N, double angle) {
    return internal::combine(std::cos(angle), v, std::sin(angle), internal::cross(N, v));
  };
  std::unordered_set<vertex_descriptor> singular;
  for(const auto& s : singularities)
    singular.insert(s.first);
  auto touches_singularity = [&](face_descriptor f) {
    for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, tm), tm))
      if(singular.count(target(h, tm)))
        return true;
    return false;
  };
  const std::size_t maximum_faces = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, tc_np::maximum_faces_per_ray), std::size_t(num_faces(tm)) * std::size_t(n) + 1);

  // one ray from point p of face f along direction d, one of the n directions of sign * field there (a ray
  // backwards along a vector field follows minus the field): the points after p
  auto ray = [&](face_descriptor f, Vec p, Vec d, double sign, std::vector<Vec>& points,
                 std::vector<face_descriptor>& faces) {
    std::vector<std::unordered_set<face_descriptor>> followed(static_cast<std::size_t>(n)); // per direction index
    for(std::size_t step = 0; step < maximum_faces; ++step) {
      const Vec N = normal(f);
      // the direction's index among the field's n directions here, for the recurrence test
      const Vec base = internal::combine(sign, field_at(f), 0, field_at(f));
      const double angle = std::atan2(internal::dot(internal::cross(base, d), N), internal::dot(base, d));
      const int k = int(std::lround(angle / unit)) % n;
      if(!followed[std::size_t((k + n) % n)].insert(f).second)
        return;
      // the edge met: p + t d = a + s (b - a), t > 0, s in [0, 1] (in the plane of f)
      halfedge_descriptor exit = GT::null_halfedge();
      double best_t = 0;
      Vec best_q = p;
      for(halfedge_descriptor h : CGAL::halfedges_around_face(halfedge(f, tm), tm)) {
        const Vec a = point(source(h, tm)), b = point(target(h, tm));
        const Vec e = internal::sub(b, a), ap = internal::sub(a, p);
        const double denominator = internal::dot(internal::cross(d, e), N);
        if(!(std::abs(denominator) > 1e-14 * std::sqrt(internal::dot(e, e))))
          continue; // parallel to this edge
        const double t = internal::dot(internal::cross(ap, e), N) / denominator;
        const double s = internal::dot(internal::cross(ap, d), N) / denominator;
        if(t > 1e-12 * std::sqrt(internal::dot(e, e)) && s >= -1e-12 && s <= 1 + 1e-12 &&
           (exit == GT::null_halfedge() || t < best_t)) {
          exit = h;
          best_t = t;
          // through a vertex (or nearly): a point of the edge 1e-9 of its length away from it, so that the
          // next face is the one across the edge
          const double on_edge = (std::min)((std::max)(s, 1e-9), 1 - 1e-9);
          best_q = internal::combine(1, a, on_edge, e);
        }
      }
      if(exit == GT::null_halfedge())
        return; // numerically stuck (at a vertex)
      const Vec moved_by = internal::sub(best_q, p);
      const Vec edge = internal::sub(point(target(exit, tm)), point(source(exit, tm)));
      if(!points.empty() && internal::dot(moved_by, moved_by) < 1e-16 * internal::dot(edge, edge)) {
        points.back() = best_q; // a pass by a vertex: no segment of its own
      } else {
        points.push_back(best_q);
        faces.push_back(f);
      }
      const halfedge_descriptor across = opposite(exit, tm);
      if(is_border(across, tm))
        return;
      const face_descriptor g = face(across, tm);
      // Levi-Civita transport about the edge, then the connection's rotation x(exit) about g's normal
      const Vec e = internal::unit3(internal::sub(point(target(exit, tm)), point(source(exit, tm))));
      const Vec Ng = normal(g);
      Vec moved = internal::combine(internal::dot(d, e), e, internal::dot(d, internal::cross(N, e)),
                                    internal::cross(Ng, e));
      moved = turned(moved, Ng, get(x, exit));
      // the field's direction nearest to it
      const Vec g0 = internal::combine(sign, field_at(g), 0, field_at(g));
      const double a = std::atan2(internal::dot(internal::cross(g0, moved), Ng), internal::dot(g0, moved));
      d = internal::unit3(turned(g0, Ng, unit * std::round(a / unit)));
      p = best_q;
      f = g;
      if(touches_singularity(f))
        return;
    }
  };

  std::vector<Streamline<TriangleMesh>> lines;
  for(face_descriptor f : seeds) {
    if(touches_singularity(f))
      continue;
    const halfedge_descriptor h = halfedge(f, tm);
    const Vec a = point(source(h, tm)), b = point(target(h, tm)), c = point(target(next(h, tm), tm));
    const Vec center = {{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3}};
    const Vec N = normal(f), v = field_at(f);
    // the lines through the seed: for even n, n/2 of them (direction k and its opposite, direction k + n/2);
    // for odd n, one per direction and its opposite
    const int lines_here = n % 2 == 0 ? n / 2 : n;
    for(int k = 0; k < lines_here; ++k) {
      const Vec forward = turned(v, N, unit * k), backward = {{-forward[0], -forward[1], -forward[2]}};
      std::vector<Vec> back_points, front_points;
      std::vector<face_descriptor> back_faces, front_faces;
      ray(f, center, backward, -1, back_points, back_faces);
      ray(f, center, forward, 1, front_points, front_faces);
      Streamline<TriangleMesh> line;
      // backward ray reversed, then the forward ray: segment i lies in faces[i]
      for(std::size_t i = back_points.size(); i-- > 0;) {
        line.points.push_back(back_points[i]);
        line.faces.push_back(back_faces[i]);
      }
      line.points.push_back(center);
      for(std::size_t i = 0; i < front_points.size(); ++i) {
        line.faces.push_back(front_faces[i]);
        line.points.push_back(front_points[i]);
      }
      if(line.points.size() >= 2)
        lines.push_back(std::move(line));
    }
  }
  return lines;
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_STREAMLINES_H
