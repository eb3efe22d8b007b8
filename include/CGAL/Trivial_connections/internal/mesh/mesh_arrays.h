// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_MESH_MESH_ARRAYS_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_MESH_MESH_ARRAYS_H

#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/assertions.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The mesh flattened once into int arrays, so that the numerics never touch descriptors or
  (possibly hashed) property maps. Face f owns the "corner halfedges" 3f, 3f+1, 3f+2:
  3f is halfedge(f), then next, next. Corner halfedge i goes from corner_vertex[i] to
  corner_vertex[next_corner(i)]; opposite_corner[i] is the corner halfedge on the other side, or -1 on a border edge.
*/
// The largest sine of the three corners of triangle (p, q, r), or 0 when a squared length or the normal
// under- or overflows: the faces whose largest sine is below minimum_corner_sine are refused (their normal, from
// the corner of largest sine, has a rounding error of about eps / sine: their plane is rounding noise).
inline constexpr double minimum_corner_sine = 1e-12;

inline double largest_corner_sine(const std::array<double, 3>& p0, const std::array<double, 3>& q0,
                                  const std::array<double, 3>& r0)
{
  double best_sine = 0;
  const std::array<double, 3>* corners[3] = {&p0, &q0, &r0};
  for(int k = 0; k < 3; ++k) {
    const auto& p = *corners[k];
    const auto& q = *corners[(k + 1) % 3];
    const auto& r = *corners[(k + 2) % 3];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if(!std::isnormal(nn) || !std::isnormal(lu) || !std::isnormal(lw)) // squares under- or overflowed
      return 0;
    best_sine = std::max(best_sine, nn / lu / lw);
  }
  return best_sine;
}

template <class TriangleMesh>
struct Mesh_arrays
{
  using GT = boost::graph_traits<TriangleMesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;
  using Vertex_index_map = typename CGAL::GetInitializedVertexIndexMap<TriangleMesh>::const_type;
  using Face_index_map = typename CGAL::GetInitializedFaceIndexMap<TriangleMesh>::const_type;

  static int next_corner(int i) { return i % 3 == 2 ? i - 2 : i + 1; }
  static int prev_corner(int i) { return i % 3 == 0 ? i + 2 : i - 1; }
  static int face_of(int i) { return i / 3; }

  int nv = 0, nf = 0;
  std::vector<vertex_descriptor> vertex_descriptors;   // by index
  std::vector<face_descriptor> face_descriptors;        // by index
  std::vector<halfedge_descriptor> halfedges; // corner halfedge -> descriptor
  std::vector<int> corner_vertex;
  std::vector<int> opposite_corner;
  std::vector<int> faces_at_vertex;          // number of corners at each vertex (0: isolated)
  std::vector<std::array<double, 3>> points;
  Vertex_index_map vertex_index;
  Face_index_map face_index;

  int source_of(int i) const { return corner_vertex[i]; }
  int target_of(int i) const { return corner_vertex[next_corner(i)]; }
  bool is_border_edge(int i) const { return opposite_corner[i] < 0; }

  // Corner halfedge of a descriptor; -1 for a border halfedge.
  int corner_of(halfedge_descriptor h, const TriangleMesh& tm) const
  {
    const face_descriptor f = face(h, tm);
    if(f == GT::null_face())
      return -1;
    const int fi = int(get(face_index, f));
    for(int k = 0; k < 3; ++k)
      if(halfedges[3 * fi + k] == h)
        return 3 * fi + k;
    return -1;
  }

  // Corner halfedge of an edge: one of its halfedges with a face.
  template <class Edge>
  int corner_of_edge(Edge e, const TriangleMesh& tm) const
  {
    const int i = corner_of(halfedge(e, tm), tm);
    return i >= 0 ? i : corner_of(opposite(halfedge(e, tm), tm), tm);
  }

  template <class VertexPointMap, class Traits>
  Mesh_arrays(const TriangleMesh& tm, VertexPointMap vpm, const Traits& traits)
    : Mesh_arrays(tm)
  {
    check_and_read_points(vpm, traits);
  }

  // The connectivity alone (checked: triangles, contiguous indices, manifold). check_and_read_points() completes the
  // set-up; the connectivity is all the fill-reducing order needs, so it may start in between.
  explicit Mesh_arrays(const TriangleMesh& tm)
    : vertex_index(CGAL::get_initialized_vertex_index_map(tm)),
      face_index(CGAL::get_initialized_face_index_map(tm))
  {
    // counted by iteration: num_faces() of a Surface_mesh also counts removed faces
    nv = int(std::distance(vertices(tm).begin(), vertices(tm).end()));
    nf = int(std::distance(faces(tm).begin(), faces(tm).end()));
    if(nf == 0)
      throw Invalid_input(Error_code::empty_mesh, "the mesh has no face");

    // indices must be a permutation of 0..n-1 (not so in a Surface_mesh with removed elements)
    const std::string not_contiguous =
      " indices are not 0..n-1 (a Surface_mesh with removed elements? call collect_garbage() first)";
    vertex_descriptors.assign(nv, GT::null_vertex());
    for(vertex_descriptor v : vertices(tm)) {
      const std::size_t i = std::size_t(get(vertex_index, v));
      if(i >= std::size_t(nv) || vertex_descriptors[i] != GT::null_vertex())
        throw Invalid_input(Error_code::invalid_argument, "vertex" + not_contiguous);
      vertex_descriptors[i] = v;
    }
    face_descriptors.assign(nf, GT::null_face());
    for(face_descriptor f : faces(tm)) {
      const std::size_t i = std::size_t(get(face_index, f));
      if(i >= std::size_t(nf) || face_descriptors[i] != GT::null_face())
        throw Invalid_input(Error_code::invalid_argument, "face" + not_contiguous);
      face_descriptors[i] = f;
    }

    halfedges.resize(3 * std::size_t(nf));
    corner_vertex.resize(3 * std::size_t(nf));
    opposite_corner.assign(3 * std::size_t(nf), -1);
    faces_at_vertex.assign(nv, 0);
    for(int f = 0; f < nf; ++f) {
      const halfedge_descriptor h0 = halfedge(face_descriptors[f], tm);
      halfedge_descriptor h = h0;
      int k = 0;
      do {
        if(k == 3)
          break;
        halfedges[3 * f + k] = h;
        ++k;
        h = next(h, tm);
      } while(h != h0);
      if(k != 3 || h != h0)
        throw Invalid_input(Error_code::not_triangle_mesh,
                            "face " + std::to_string(f) + " is not a triangle", std::size_t(f));
      for(int j = 0; j < 3; ++j) {
        // the source of a corner halfedge is the target of the previous one: no opposite() lookup
        const int v = int(get(vertex_index, target(halfedges[3 * f + (j + 2) % 3], tm)));
        corner_vertex[3 * f + j] = v;
        ++faces_at_vertex[v];
      }
    }
    for(int i = 0; i < 3 * nf; ++i) {
      const halfedge_descriptor o = opposite(halfedges[i], tm);
      opposite_corner[i] = corner_of(o, tm);
    }
    check_manifold_vertices(tm);
  }

  // From connectivity validated already, as the soup a mesh is built from (IO/internal/build_mesh.h): vertex i,
  // face f and corner halfedge c of the arrays are vertices[i], faces[f] and corner_halfedges[c] of the mesh,
  // which vertex_index and face_index number i and f. Nothing is read from the mesh, which may still be under
  // construction; check_and_read_points() completes the set-up as above.
  Mesh_arrays(Vertex_index_map vertex_indices, Face_index_map face_indices, std::vector<vertex_descriptor>&& vertices,
              std::vector<face_descriptor>&& faces, std::vector<halfedge_descriptor>&& corner_halfedges,
              std::vector<int>&& corner_vertices, std::vector<int>&& opposite_corners)
    : nv(int(vertices.size())),
      nf(int(faces.size())),
      vertex_descriptors(std::move(vertices)),
      face_descriptors(std::move(faces)),
      halfedges(std::move(corner_halfedges)),
      corner_vertex(std::move(corner_vertices)),
      opposite_corner(std::move(opposite_corners)),
      vertex_index(vertex_indices),
      face_index(face_indices)
  {
    CGAL_precondition(halfedges.size() == 3 * std::size_t(nf) && corner_vertex.size() == halfedges.size() &&
                      opposite_corner.size() == halfedges.size());
    if(nf == 0)
      throw Invalid_input(Error_code::empty_mesh, "the mesh has no face");
    faces_at_vertex.assign(nv, 0);
    for(int v : corner_vertex)
      ++faces_at_vertex[v];
  }

  // The points (finite, every vertex's: a point the faces do not use is still a mistake of the caller's, as the
  // file readers take it) and non-degenerate faces. Writes `points` only.
  template <class VertexPointMap, class Traits>
  void check_and_read_points(VertexPointMap vpm, const Traits& traits)
  {
    typename Traits::Compute_x_3 x = traits.compute_x_3_object();
    typename Traits::Compute_y_3 y = traits.compute_y_3_object();
    typename Traits::Compute_z_3 z = traits.compute_z_3_object();
    points.resize(nv);
    for(int v = 0; v < nv; ++v) {
      const auto& p = get(vpm, vertex_descriptors[v]);
      points[v] = {{CGAL::to_double(x(p)), CGAL::to_double(y(p)), CGAL::to_double(z(p))}};
      for(double c : points[v])
        if(!std::isfinite(c)) // as the file readers say it
          throw Invalid_input(Error_code::non_finite_point,
                              "vertex " + std::to_string(v) + ": the coordinate '" +
                                (std::isnan(c) ? "nan" : c > 0 ? "inf" : "-inf") + "' is not a finite number",
                              std::size_t(v));
    }
    check_degenerate_faces(vpm, traits);
  }

private:
  // Every face at v must be reached by turning around v from one of its corners: otherwise v joins several
  // umbrellas (pinched or non-manifold vertex). Walked on the corner arrays (compact ints, where the mesh's
  // circulators chase descriptors through its halfedges); the first vertex that fails is circulated again
  // through the mesh, to say which way it fails. Linear in the mesh size.
  void check_manifold_vertices(const TriangleMesh& tm) const
  {
    std::vector<int> first_corner(nv, -1);
    for(int i = 3 * nf - 1; i >= 0; --i)
      first_corner[corner_vertex[i]] = i;
    for(int v = 0; v < nv; ++v)
      if(faces_at_vertex[v] > 0 && fan_size(first_corner[v], faces_at_vertex[v]) != faces_at_vertex[v])
        throw_non_manifold_vertex(tm, v);
  }

  // the corners of the fan of corner c0 (the corners leaving its source), counted up to limit + 1
  int fan_size(int c0, int limit) const
  {
    int seen = 1;
    // counter-clockwise: the corner across the edge that ends at the source (the previous corner's opposite)
    int c = opposite_corner[prev_corner(c0)];
    while(c >= 0 && c != c0 && seen <= limit) {
      ++seen;
      c = opposite_corner[prev_corner(c)];
    }
    if(c < 0) { // an open fan: clockwise from c0 too
      c = opposite_corner[c0];
      while(c >= 0 && seen <= limit) {
        c = next_corner(c);
        ++seen;
        c = opposite_corner[c];
      }
    }
    return seen;
  }

  [[noreturn]] void throw_non_manifold_vertex(const TriangleMesh& tm, int v) const
  {
    int borders = 0;
    for(halfedge_descriptor h : halfedges_around_target(halfedge(vertex_descriptors[v], tm), tm))
      if(is_border(h, tm))
        ++borders;
    throw Invalid_input(Error_code::non_manifold,
                        "vertex " + std::to_string(v) + " is non-manifold (its faces form " +
                          (borders > 1 ? "a pinched fan" : "more than one fan") + ")",
                        std::size_t(v));
  }

  static constexpr double kMinimumSine = minimum_corner_sine;

  template <class VertexPointMap, class Traits>
  void check_degenerate_faces(VertexPointMap vpm, const Traits& traits) const
  {
    typename Traits::Collinear_3 collinear = traits.collinear_3_object();
    for(int f = 0; f < nf; ++f) {
      const int a = corner_vertex[3 * f], b = corner_vertex[3 * f + 1], c = corner_vertex[3 * f + 2];
      bool bad = (a == b || b == c || c == a);
      for(int v : {a, b, c})
        for(double t : points[v])
          bad = bad || !std::isfinite(t);
      if(!bad)
        bad = collinear(get(vpm, vertex_descriptors[a]), get(vpm, vertex_descriptors[b]), get(vpm, vertex_descriptors[c]));
      if(!bad) {
        // A face that is not collinear exactly can still have a zero or subnormal area in double, or be so
        // nearly collinear that its plane is rounding noise: the normal of the face frames comes from the
        // corner of largest sine, and its rounding error is about eps / sine. Below kMinimumSine the normal
        // (and so the field's plane on that face) could be off by 1e-4 rad or more, or flipped. A shape
        // criterion, so that acceptance does not depend on how the mesh is rotated.
        bad = !(largest_corner_sine(points[a], points[b], points[c]) >= kMinimumSine);
      }
      if(bad)
        throw Invalid_input(Error_code::degenerate_face,
                            "face " + std::to_string(f) +
                              " is degenerate (zero area, or so nearly collinear that its plane is not determined in "
                              "double precision: every angle within 1e-12 rad of 0 or pi)",
                            std::size_t(f));
    }
  }
};

// The array number of a singular vertex, checked as compute_quad_mesh() and move_singularities_off_features() check
// it: a vertex of some face, listed once (`listed`, per vertex, marks those seen).
template <class TriangleMesh, class VertexDescriptor>
std::size_t checked_singular_vertex(const Mesh_arrays<TriangleMesh>& m, VertexDescriptor vertex, std::vector<char>& listed)
{
  const std::size_t v = std::size_t(get(m.vertex_index, vertex));
  if(v >= std::size_t(m.nv) || m.faces_at_vertex[v] == 0)
    throw Invalid_input(Error_code::invalid_vertex, "singular vertex " + std::to_string(v) + " is in no face", v);
  if(listed[v])
    throw Invalid_input(Error_code::duplicate_singularity, "vertex " + std::to_string(v) + " is listed twice", v);
  listed[v] = 1;
  return v;
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_MESH_MESH_ARRAYS_H
