// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FIELD_FIELD_PROPAGATION_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FIELD_FIELD_PROPAGATION_H

#include <CGAL/Trivial_connections/exceptions.h>
#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>
#include <CGAL/Trivial_connections/internal/system/constraint_links.h>
#include <CGAL/Trivial_connections/internal/system/right_hand_side.h>
#include <CGAL/Trivial_connections/internal/topology/tree_cotree.h>

#include <CGAL/number_type_config.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// the index of the seed face of compute_field(), checked
template <class TriangleMesh>
int checked_seed_face(const Mesh_arrays<TriangleMesh>& m,
                      typename boost::graph_traits<TriangleMesh>::face_descriptor f)
{
  const int seed = f == boost::graph_traits<TriangleMesh>::null_face() ? -1 : int(get(m.face_index, f));
  if(seed < 0 || seed >= m.nf || m.face_descriptors[seed] != f)
    throw Invalid_input(Error_code::invalid_argument, "the seed face is not a face of the mesh");
  return seed;
}

// The phi minimising sum_g (phi + o_g)^2 with each phi + o_g reduced to (-period/2, period/2]: the values
// -o_g reduced to [0, period) are sorted; an optimal choice of representatives takes them as they are from
// some point on and one period higher before it (a contiguous arc), and phi is their mean.
inline double best_rotation(const std::vector<double>& offsets, double period)
{
  std::vector<double> u;
  u.reserve(offsets.size());
  for(double o : offsets) {
    double r = std::fmod(-o, period);
    if(r < 0)
      r += period;
    u.push_back(r);
  }
  std::sort(u.begin(), u.end());
  const double count = double(u.size());
  double s1 = 0, s2 = 0;
  for(double v : u) {
    s1 += v;
    s2 += v * v;
  }
  double best = s2 - s1 * s1 / count, phi = s1 / count;
  for(double v : u) { // move v up by a period
    s2 += 2 * period * v + period * period;
    s1 += period;
    const double cost = s2 - s1 * s1 / count;
    if(cost < best) {
      best = cost;
      phi = s1 / count;
    }
  }
  return phi;
}

/*
  The direction field of a connection as an angle per face in its frame (Mesh_geometry::frame()): a
  direction is moved along the breadth-first dual spanning tree of each component by Levi-Civita transport
  followed by the rotation x(h) (a readable halfedge -> double map). Then each component is rotated: onto the
  target of its first constrained face (`target`: per constrained face of `links`, its target angle; the
  connection carries it to the others), or, with guided faces only, to minimise sum_g d_g^2 (the mismatches
  modulo 2 pi / n: `n` is then required), or onto `seed_angle` in face `seed` (-1: none). Other components
  start with angle 0 at their root face.
*/
template <class TriangleMesh, class HalfedgeAngleMap>
std::vector<double> field_angles(const Mesh_arrays<TriangleMesh>& m, const Mesh_geometry& geometry,
                                 const Mesh_topology& topology, const Constraint_links& links, HalfedgeAngleMap x,
                                 const std::vector<double>& target, const std::optional<int>& n, int seed,
                                 double seed_angle)
{
  std::vector<double> angle(m.nf, 0.);
  for(int f : topology.face_order) {
    const int i = topology.parent_corner[f];
    if(i >= 0)
      angle[f] = wrap_angle(angle[Mesh_arrays<TriangleMesh>::face_of(i)] + geometry.transport_angle(i) +
                            get(x, m.halfedges[i]));
  }
  const std::size_t components = topology.components.size();
  std::vector<double> shift(components, 0.);
  std::vector<char> shifted(components, 0);
  if(!links.faces.empty()) {
    for(std::size_t c = 0; c < components; ++c)
      if(links.seed_constraint[c] >= 0) {
        shift[c] = target[links.seed_constraint[c]] - angle[links.faces[links.seed_constraint[c]].face];
        shifted[c] = 1;
      }
    // a component with guided faces only: the rotation minimising sum_g d_g^2, the mismatches d_g wrapped to
    // a period of the n-field
    std::vector<std::vector<double>> offsets(components);
    for(std::size_t a = std::size_t(links.first_guided); a < links.faces.size(); ++a) {
      const int f = links.faces[a].face, c = topology.component_of_face[f];
      if(links.seed_constraint[c] < 0)
        offsets[c].push_back(angle[f] - target[a]);
    }
    const bool has_guided_only =
      std::any_of(offsets.begin(), offsets.end(), [](const std::vector<double>& o) { return !o.empty(); });
    if(has_guided_only) {
      if(!n)
        throw Invalid_input(Error_code::invalid_argument,
                            "a component has guided faces only: compute_field() needs the symmetry_order of the "
                            "solve to rotate the field towards the guides");
      const int order = checked_symmetry_order(*n);
      for(std::size_t c = 0; c < components; ++c)
        if(!offsets[c].empty()) {
          shift[c] = best_rotation(offsets[c], 2 * CGAL_PI / order);
          shifted[c] = 1;
        }
    }
  }
  if(seed >= 0) {
    const int c = topology.component_of_face[seed];
    if(shifted[c])
      throw Invalid_input(Error_code::invalid_argument,
                          "the seed face is in a component with constrained or guided faces, which set the field there",
                          std::size_t(seed));
    shift[c] = seed_angle - angle[seed];
    shifted[c] = 1;
  }
  for(int f = 0; f < m.nf; ++f)
    if(shifted[topology.component_of_face[f]])
      angle[f] = wrap_angle(angle[f] + shift[topology.component_of_face[f]]);
  return angle;
}

// The unit vectors of angles per face in their frames, into `field` (a writable face -> Vector_3 map).
template <class TriangleMesh, class GeomTraits, class FaceVectorMap>
void write_field(const Mesh_arrays<TriangleMesh>& m, const std::vector<double>& angle, const GeomTraits& traits,
                 FaceVectorMap field)
{
  typename GeomTraits::Construct_vector_3 vector = traits.construct_vector_3_object();
  for(int f = 0; f < m.nf; ++f) {
    const double c = std::cos(angle[f]), s = std::sin(angle[f]);
    Vec3 ex, ey;
    Mesh_geometry::frame(m, f, ex, ey);
    put(field, m.face_descriptors[f], vector(c * ex[0] + s * ey[0], c * ex[1] + s * ey[1], c * ex[2] + s * ey[2]));
  }
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FIELD_FIELD_PROPAGATION_H
