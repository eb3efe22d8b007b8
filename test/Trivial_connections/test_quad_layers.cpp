// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// The first three layers of quad meshing (issue 43), internal/quad/: the cut graph with the matching and the
// combing of a cross field, the seamless parametrisation and its integer rounding. Every property is checked from its definition,
// recomputed here from the positions, the solver's connection and field (Mesh_view, test_support): the cut
// surface's Euler characteristic and connectedness, the matching by transport and rotation, the holonomy
// against the prescribed indices, the transitions corner by corner, the optimality along feasible directions,
// the exact answer on a flat square, and independence from the numbering.

#include "test_support.h"

#include <CGAL/Trivial_connections/internal/quad/cut_graph.h>
#include <CGAL/Trivial_connections/internal/quad/integer_rounding.h>
#include <CGAL/Trivial_connections/internal/quad/kept_factor_fixing.h>
#include <CGAL/Trivial_connections/internal/quad/map_untangling.h>
#include <CGAL/Trivial_connections/internal/quad/quad_mesh_pipeline.h>
#include <CGAL/Trivial_connections/internal/quad/quad_extraction.h>
#include <CGAL/Trivial_connections/internal/quad/seamless_parametrization.h>
#include <CGAL/Trivial_connections/feature_alignment.h>
#include <CGAL/Trivial_connections/singularity_placement.h>

#include <chrono>
#include <complex>

namespace {

using namespace tc_test;
namespace TCI = CGAL::Trivial_connections::internal;

// A cross field solved on a mesh with the given singularities, and the two layers built on it.
struct Quad_case
{
  Surface_mesh mesh;
  Mesh_view<Surface_mesh> view;
  Singularities singularities;
  std::vector<double> x;       // per view halfedge
  std::vector<Vector> field;   // per view face
  TCI::Mesh_arrays<Surface_mesh> arrays;
  TCI::Mesh_geometry geometry;
  std::vector<double> angle;   // per face: the field's angle in its frame
  std::vector<double> connection; // per interior edge (Mesh_geometry numbering)
  std::vector<int> matching;
  TCI::Cut_graph cut;

  // align_with_axis: the field turned by one constant angle so that it is along the first edge of face 0 that is
  // along a coordinate axis (on a cube, whose connection is Levi-Civita, along the edges everywhere)
  Quad_case(const Soup& soup, const Singularities& sing, bool align_with_axis = false)
    : mesh(to_surface_mesh(soup)), view(mesh), singularities(sing),
      arrays(mesh, get(CGAL::vertex_point, mesh), K()), geometry(arrays, TC::Weighting::hodge_star)
  {
    TC::Trivial_connection_solver<Surface_mesh> solver(mesh);
    solver.solve(descriptors(view, sing), view.halfedge_map(x), TC::parameters::symmetry_order(4));
    solver.compute_field(view.halfedge_map_const(x), view.face_map(field));
    if(align_with_axis) {
      V3 edge = {{0, 0, 0}};
      for(int k = 0; k < 3; ++k) { // the first edge of face 0 along a coordinate axis
        const V3 e = q_sub(arrays.points[arrays.corner_vertex[(k + 1) % 3]], arrays.points[arrays.corner_vertex[k]]);
        if(int(e[0] == 0) + int(e[1] == 0) + int(e[2] == 0) == 2) {
          edge = e;
          break;
        }
      }
      EXPECT_GT(norm(edge), 0.) << "face 0 has no edge along an axis";
      const double offset = signed_angle(edge, V(0), view.N[0]);
      for(int f = 0; f < arrays.nf; ++f) {
        const V3 turned_field = rotate(V(f), view.N[f], -offset);
        field[f] = Vector(turned_field[0], turned_field[1], turned_field[2]);
      }
    }
    finish();
  }
  // a field designed by the caller: design(mesh, view, singularities, x, field) fills the last three (x per view
  // halfedge, field per view face)
  using Designer = std::function<void(const Surface_mesh&, const Mesh_view<Surface_mesh>&, Singularities&,
                                      std::vector<double>&, std::vector<Vector>&)>;
  Quad_case(Surface_mesh m, const Designer& design)
    : mesh(std::move(m)), view(mesh), arrays(mesh, get(CGAL::vertex_point, mesh), K()),
      geometry(arrays, TC::Weighting::hodge_star)
  {
    design(mesh, view, singularities, x, field);
    finish();
  }
  Quad_case(const Quad_case&) = delete;

  void finish()
  {
    geometry.compute_angles(arrays);
    for(int f = 0; f < arrays.nf; ++f)
      angle.push_back(TCI::angle_in_frame(arrays, f, V(f)));
    for(int i : geometry.edge_corner)
      connection.push_back(x[view.hid.at(arrays.halfedges[i])]);
    matching = TCI::cross_field_matching(arrays, geometry, angle, connection);
    std::vector<int> singular;
    for(const auto& s : singularities)
      singular.push_back(s.first);
    cut = TCI::build_cut_graph(arrays, geometry, matching, singular);
  }

  TCI::Vec3 V(int f) const { return {{field[f].x(), field[f].y(), field[f].z()}}; }
  static V3 q_sub(const TCI::Vec3& a, const TCI::Vec3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
  // view halfedge of corner halfedge i, and back
  int halfedge(int i) const { return view.hid.at(arrays.halfedges[i]); }
  int corner(int h) const { return arrays.corner_of(view.halfedges[h], mesh); }
  bool cut_halfedge(int h) const
  {
    const int i = view.hface[h] >= 0 ? corner(h) : corner(view.opp[h]);
    return cut.is_cut[cut.edge_of_corner[i]];
  }
};

// The number of quarter turns r (0..3) with: transport of face(h)'s vector to the other face, turned by x(h)
// and then by r quarter turns about the arrival normal, is the other face's vector. Our definition, our transport.
int independent_matching(const Quad_case& q, int h, double* error = nullptr)
{
  const int f = q.view.hface[h], g = q.view.hface[q.view.opp[h]];
  const V3 u = rotate(q.view.transport(h, q.V(f)), q.view.N[g], q.x[h]);
  int best = -1;
  double best_error = 10;
  for(int r = 0; r < 4; ++r) {
    const double d = std::abs(signed_angle(rotate(u, q.view.N[g], r * pi / 2), q.V(g), q.view.N[g]));
    if(d < best_error) {
      best_error = d;
      best = r;
    }
  }
  if(error)
    *error = best_error;
  return best;
}

// the matching, then the combing: r(h) + c_g - c_f is 0 off the cut; the holonomy counter-clockwise around every
// interior vertex is -4 k_v modulo 4
void check_matching_and_combing(const Quad_case& q)
{
  const std::vector<long long> k4 = scaled_indices(q.view.nv(), q.singularities, 4);
  std::vector<long long> ring(q.view.nv(), 0);
  double worst = 0;
  int mismatches = 0, combing_failures = 0;
  for(int h : q.view.interior_halfedges) {
    double error = 0;
    const int r = independent_matching(q, h, &error);
    worst = std::max(worst, error);
    const int i = q.corner(h);
    mismatches += TCI::matching_across(q.geometry, q.matching, i) != r;
    ring[q.view.tgt[h]] += r;
    const int f = q.view.hface[h], g = q.view.hface[q.view.opp[h]];
    const int combed = ((r + q.cut.combing[g] - q.cut.combing[f]) % 4 + 4) % 4;
    if(!q.cut_halfedge(h))
      combing_failures += combed != 0;
    EXPECT_EQ(combed, TCI::matching_across(q.geometry, q.cut.combed_matching, i));
  }
  EXPECT_LT(worst, 1e-8) << "the field is not a cross field parallel for the connection";
  EXPECT_EQ(mismatches, 0) << "matchings that differ from the definition";
  EXPECT_EQ(combing_failures, 0) << "edges off the cut with a non-zero combed matching";
  for(int v = 0; v < q.view.nv(); ++v) {
    if(!q.view.interior_vertex(v))
      continue;
    EXPECT_EQ(((ring[v] + k4[v]) % 4 + 4) % 4, 0) << "vertex " << v << ": holonomy " << ring[v] << ", 4k = " << k4[v];
    EXPECT_EQ(q.cut.holonomy[v], ((-k4[v]) % 4 + 4) % 4) << "vertex " << v;
  }
}

// The surface cut along the cut graph, per component: connected, and V - E + F = 1 (a disk); every singular
// vertex on the cut. Corners (face, vertex) are glued across the edges off the cut, faces too.
void check_cut_is_disk(const Quad_case& q)
{
  const Mesh_view<Surface_mesh>& view = q.view;
  std::map<std::pair<int, int>, int> corner_id;
  for(int h = 0; h < view.nh(); ++h)
    if(view.hface[h] >= 0)
      corner_id.emplace(std::make_pair(view.hface[h], view.tgt[h]), int(corner_id.size()));
  std::vector<int> parent(corner_id.size() + view.nf());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int a) { return parent[a] == a ? a : parent[a] = find(parent[a]); };
  auto join = [&](int a, int b) { parent[find(a)] = find(b); };
  const int face_base = int(corner_id.size());
  std::vector<long long> E(view.ncomp, 0), F(view.ncomp, 0), V(view.ncomp, 0), pieces(view.ncomp, 0);
  for(int h = 0; h < view.nh(); ++h) {
    if(h > view.opp[h])
      continue; // each edge once
    const int f = view.hface[h] >= 0 ? view.hface[h] : view.hface[view.opp[h]];
    const int c = view.comp_of_face[f];
    if(view.hface[h] < 0 || view.hface[view.opp[h]] < 0) {
      E[c] += 1;
      continue;
    }
    if(q.cut_halfedge(h)) {
      E[c] += 2;
      continue;
    }
    E[c] += 1;
    const int g = view.hface[view.opp[h]];
    join(face_base + f, face_base + g);
    for(int v : {view.src[h], view.tgt[h]})
      join(corner_id.at({f, v}), corner_id.at({g, v}));
  }
  for(const auto& c : corner_id)
    if(find(c.second) == c.second)
      ++V[view.comp_of_face[c.first.first]];
  for(int f = 0; f < view.nf(); ++f) {
    ++F[view.comp_of_face[f]];
    if(find(face_base + f) == face_base + f)
      ++pieces[view.comp_of_face[f]];
  }
  for(int c = 0; c < view.ncomp; ++c) {
    EXPECT_EQ(pieces[c], 1) << "component " << c << " falls apart along the cut";
    EXPECT_EQ(V[c] - E[c] + F[c], 1) << "component " << c << " cut open is not a disk";
  }
  for(const auto& s : q.singularities) {
    bool on_cut = false;
    for(int h = 0; h < view.nh(); ++h)
      on_cut = on_cut || (view.tgt[h] == s.first && view.hface[h] >= 0 && q.cut_halfedge(h));
    EXPECT_TRUE(on_cut) << "singular vertex " << s.first << " is not on the cut";
  }
  // the arcs: chains of cut edges, each joined to the next at a vertex, the combed matching constant
  for(const TCI::Cut_graph::Arc& arc : q.cut.arcs) {
    for(std::size_t j = 0; j + 1 < arc.left_corners.size(); ++j)
      EXPECT_EQ(q.arrays.target_of(arc.left_corners[j]), q.arrays.source_of(arc.left_corners[j + 1]));
    for(int l : arc.left_corners)
      EXPECT_EQ(TCI::matching_across(q.geometry, q.cut.combed_matching, l), arc.matching);
  }
}

// (u, v) turned by q quarter turns counter-clockwise
std::array<double, 2> turned(const std::array<double, 2>& w, int q)
{
  switch(((q % 4) + 4) % 4) {
    case 0: return w;
    case 1: return {{-w[1], w[0]}};
    case 2: return {{-w[0], -w[1]}};
    default: return {{w[1], -w[0]}};
  }
}

// corner of face(i) at vertex v (header numbering)
int corner_at(const Quad_case& q, int f, int v)
{
  for(int c = 3 * f; c < 3 * f + 3; ++c)
    if(q.arrays.corner_vertex[c] == v)
      return c;
  ADD_FAILURE() << "no corner of face " << f << " at vertex " << v;
  return 3 * f;
}

// Across every interior edge, at both ends: off the cut the two faces agree; on arc a, right = R^q left + t_a
// with q = -(r + c_right - c_left) from our matching. Returns the largest error.
double transition_error(const Quad_case& q, const TCI::Seamless_parametrization::Map& map)
{
  double worst = 0;
  std::vector<int> arc_of_left(3 * q.arrays.nf, -1);
  for(std::size_t a = 0; a < q.cut.arcs.size(); ++a)
    for(int l : q.cut.arcs[a].left_corners)
      arc_of_left[l] = int(a);
  for(int h : q.view.interior_halfedges) {
    const int i = q.corner(h);
    const int f = q.view.hface[h], g = q.view.hface[q.view.opp[h]];
    int turns = 0;
    std::array<double, 2> t = {{0, 0}};
    if(q.cut_halfedge(h)) {
      if(arc_of_left[i] < 0)
        continue; // the other halfedge is the left one
      const int r = independent_matching(q, h);
      turns = -(r + q.cut.combing[g] - q.cut.combing[f]);
      t = map.translation[arc_of_left[i]];
    } else if(h > q.view.opp[h]) {
      continue;
    }
    for(int v : {q.view.src[h], q.view.tgt[h]}) {
      const auto& left = map.corner_uv[corner_at(q, f, v)];
      const auto& right = map.corner_uv[corner_at(q, g, v)];
      const auto expected = turned(left, turns);
      worst = std::max(worst, std::hypot(right[0] - expected[0] - t[0], right[1] - expected[1] - t[1]));
    }
  }
  return worst;
}

// Our energy sum_f A_f (|grad u - d/H|^2 + |grad v - N x d/H|^2) with d the field turned by the combing, and
// its gradient with respect to the corner values (u, v) (header layout: 2 per corner halfedge)
// scale: empty, or a factor per face of the target (Seamless_parametrization::reduce_curl())
double independent_energy(const Quad_case& q, double H, const std::vector<std::array<double, 2>>& uv,
                          Eigen::VectorXd* gradient = nullptr, const std::vector<double>& scale = {})
{
  if(gradient)
    *gradient = Eigen::VectorXd::Zero(2 * uv.size());
  double E = 0;
  for(int f = 0; f < q.arrays.nf; ++f) {
    const V3& N = q.view.N[f];
    const V3 d = ((scale.empty() ? 1. : scale[f]) / H) * rotate(q.V(f), N, q.cut.combing[f] * pi / 2);
    const V3 dperp = cross(N, d);
    int c[3];
    V3 P[3];
    for(int k = 0; k < 3; ++k) {
      c[k] = 3 * f + k;
      P[k] = q.view.P[q.arrays.corner_vertex[c[k]]];
    }
    const double A = norm(cross(P[1] - P[0], P[2] - P[0])) / 2;
    V3 hat[3]; // gradients of the hat functions: N x (edge opposite k) / 2A
    for(int k = 0; k < 3; ++k)
      hat[k] = (1 / (2 * A)) * cross(N, P[(k + 2) % 3] - P[(k + 1) % 3]);
    V3 gu = {{0, 0, 0}}, gv = {{0, 0, 0}};
    for(int k = 0; k < 3; ++k) {
      gu = gu + uv[c[k]][0] * hat[k];
      gv = gv + uv[c[k]][1] * hat[k];
    }
    const V3 ru = gu - d, rv = gv - dperp;
    E += A * (dot(ru, ru) + dot(rv, rv));
    if(gradient)
      for(int k = 0; k < 3; ++k) {
        (*gradient)[2 * c[k]] += 2 * A * dot(ru, hat[k]);
        (*gradient)[2 * c[k] + 1] += 2 * A * dot(rv, hat[k]);
      }
  }
  return E;
}

std::vector<std::array<double, 2>> scaled_uv(const std::vector<std::array<double, 2>>& uv, double s)
{
  std::vector<std::array<double, 2>> r(uv);
  for(auto& w : r)
    w = {{s * w[0], s * w[1]}};
  return r;
}

// The parametrisation of a case: transitions, energy, optimality (normal equations, and the gradient of our
// energy orthogonal to every feasible map: the basis, the minimiser itself, the minimiser for another H and
// for the field turned by a constant angle)
TCI::Seamless_parametrization::Map check_parametrization(const Quad_case& q, double H)
{
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
  const TCI::Seamless_parametrization::Map map = param.solve();
  double scale = 0;
  for(const auto& w : map.corner_uv)
    scale = std::max({scale, std::abs(w[0]), std::abs(w[1])});
  EXPECT_GT(scale, 1.) << "H is meant to give (u, v) of a few units";
  EXPECT_LT(transition_error(q, map), 1e-9) << "a transition does not hold";
  Eigen::VectorXd gradient;
  const double E = independent_energy(q, H, map.corner_uv, &gradient);
  EXPECT_NEAR(E, map.energy, 1e-9 * (1 + E));
  // optimality: the normal equations, then our gradient against feasible directions
  const Eigen::VectorXd residual = param.normal_matrix() * param.reduced_solution() - param.normal_rhs();
  EXPECT_LT(residual.norm(), 1e-10 * param.normal_rhs().norm());
  Eigen::VectorXd gradient_at_zero;
  std::vector<std::array<double, 2>> zero(map.corner_uv.size(), {{0., 0.}});
  independent_energy(q, H, zero, &gradient_at_zero);
  const double reference = (param.corner_basis().transpose() * gradient_at_zero).norm();
  EXPECT_GT(reference, 0.);
  EXPECT_LT((param.corner_basis().transpose() * gradient).norm(), 1e-9 * reference);
  auto along = [&](const std::vector<std::array<double, 2>>& direction) {
    double s = 0, n = 0;
    for(std::size_t c = 0; c < direction.size(); ++c) {
      s += gradient[2 * c] * direction[c][0] + gradient[2 * c + 1] * direction[c][1];
      n += gradient_at_zero[2 * c] * direction[c][0] + gradient_at_zero[2 * c + 1] * direction[c][1];
    }
    return std::abs(s) / std::max(std::abs(n), 1e-300);
  };
  EXPECT_LT(along(map.corner_uv), 1e-9);
  // E(s w) = E(w) + (s-1) g.w + (s-1)^2 q(w): with g.w = 0, E(2w) - E(w) = E(0) - E(w)
  EXPECT_NEAR(independent_energy(q, H, scaled_uv(map.corner_uv, 2)) - E, independent_energy(q, H, zero) - E,
              1e-8 * independent_energy(q, H, zero));
  TCI::Seamless_parametrization other_h(q.arrays, q.cut, q.angle, 2.7 * H);
  EXPECT_LT(along(other_h.solve().corner_uv), 1e-9);
  std::vector<double> turned_angle(q.angle);
  for(double& a : turned_angle)
    a += 0.4;
  TCI::Seamless_parametrization other_angle(q.arrays, q.cut, turned_angle, H);
  const TCI::Seamless_parametrization::Map turned_map = other_angle.solve();
  EXPECT_LT(along(turned_map.corner_uv), 1e-9);
  // a field turned by a constant angle has the same optimal energy: the map turns with it
  EXPECT_NEAR(turned_map.energy, map.energy, 1e-9 * (1 + map.energy));
  return map;
}

Singularities quarters(const std::vector<int>& vertices, int sign = 1)
{
  Singularities s;
  for(int v : vertices)
    s.emplace_back(v, Index(sign, 4));
  return s;
}

// eight -1/4 spread over genus2_soup()'s vertices (index sum -2 = chi)
Singularities genus_two_singularities(const Soup& soup)
{
  const int nv = int(soup.points.size());
  std::vector<int> v;
  for(int j = 0; j < 8; ++j)
    v.push_back(j * nv / 8 + 3);
  return quarters(v, -1);
}

// eight +1/4 on each sphere of two_spheres_soup(2)
Singularities two_spheres_singularities()
{
  const int first = int(icosphere_soup(2).points.size());
  std::vector<int> v = {0, 1, 2, 3, 4, 5, 6, 7};
  for(int j = 0; j < 8; ++j)
    v.push_back(first + j);
  return quarters(v);
}

// A warped sphere with eight +1/4, and the same surface with its vertices renumbered, faces shuffled and corners
// rotated (the singularities follow their vertices).
struct Sphere_and_renumbered
{
  Soup soup, renamed;
  Singularities sing, renamed_sing;
};

Sphere_and_renumbered sphere_and_renumbered()
{
  Sphere_and_renumbered r;
  r.soup = warped(icosphere_soup(2));
  r.sing = quarters({0, 1, 2, 3, 4, 5, 6, 7});
  std::vector<int> perm;
  r.renamed = renumbered(r.soup, 11, &perm, true);
  for(const auto& s : r.sing)
    r.renamed_sing.emplace_back(perm[s.first], s.second);
  return r;
}

void check_all(const Quad_case& q, double H)
{
  {
    SCOPED_TRACE("matching and combing");
    check_matching_and_combing(q);
  }
  {
    SCOPED_TRACE("cut");
    check_cut_is_disk(q);
  }
  {
    SCOPED_TRACE("parametrisation");
    check_parametrization(q, H);
  }
}

TEST(QuadLayers, SphereWithEightQuarters)
{
  const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
  check_all(q, 0.15);
}

TEST(QuadLayers, SphereWithHalvesAndOnes)
{
  // index 1/2: the transitions turn by a half turn around them; index 1: no turn at all, still on the cut
  Singularities s = {{0, Index(1, 2)}, {3, Index(1, 2)}, {5, Index(1, 2)}, {9, Index(1, 2)}};
  const Quad_case halves(warped(icosphere_soup(2)), s);
  check_all(halves, 0.15);
  const Quad_case ones(warped(icosphere_soup(2)), {{0, Index(1)}, {3, Index(1)}});
  check_all(ones, 0.15);
}

TEST(QuadLayers, TorusWithoutAndWithSingularities)
{
  const Quad_case plain(torus_soup(3, 1, 24, 12), {});
  // two generator loops: a figure eight (2 arcs) or a theta (3 arcs)
  EXPECT_TRUE(plain.cut.arcs.size() == 2u || plain.cut.arcs.size() == 3u) << plain.cut.arcs.size() << " arcs";
  check_all(plain, 0.3);
  const Quad_case pair(warped(torus_soup(3, 1, 24, 12)), {{5, Index(1, 4)}, {150, Index(-1, 4)}});
  check_all(pair, 0.3);
}

// Curl reduction (Seamless_parametrization::reduce_curl()): a target scaled per face, e^{s_f} d_f / H, with s
// fitted with the map. On a torus of revolution the unit field along the parallels is not a gradient (the angle
// about the axis has |grad| = 1 / rho, rho the distance to the axis), the field scaled by c / rho is (conformal
// coordinates): the scaled target must be closer to a gradient (a lower least-squares residual, the energy of the
// definition recomputed here), its scale must follow 1 / rho, and the mean quad size must stay H.
TEST(QuadLayers, CurlReductionScalesTowardsAGradient)
{
  // the field along the parallels (z x centroid), its connection the angle from the transported vector to it
  const Quad_case torus(to_surface_mesh(torus_soup(3, 1, 48, 24)),
                        [](const Surface_mesh&, const Mesh_view<Surface_mesh>& view, Singularities&,
                           std::vector<double>& x, std::vector<Vector>& field) {
                          std::vector<V3> d(view.nf());
                          for(int f = 0; f < view.nf(); ++f) {
                            V3 c = {{0, 0, 0}};
                            for(int h : view.face_he[f])
                              c = c + (1. / 3) * view.P[view.src[h]];
                            const V3 parallel = {{-c[1], c[0], 0}};
                            d[f] = unit(parallel - dot(parallel, view.N[f]) * view.N[f]);
                            field.emplace_back(d[f][0], d[f][1], d[f][2]);
                          }
                          x.assign(view.nh(), 0.);
                          for(int h = 0; h < view.nh(); ++h)
                            if(view.hface[h] >= 0 && view.hface[view.opp[h]] >= 0)
                              x[h] = signed_angle(view.transport(h, d[view.hface[h]]), d[view.hface[view.opp[h]]],
                                                  view.N[view.hface[view.opp[h]]]);
                        });
  const double H = 0.3;
  TCI::Seamless_parametrization plain(torus.arrays, torus.cut, torus.angle, H);
  const TCI::Seamless_parametrization::Map unscaled = plain.solve();
  TCI::Seamless_parametrization param(torus.arrays, torus.cut, torus.angle, H);
  const std::vector<double> scale = param.reduce_curl(0.1);
  const TCI::Seamless_parametrization::Map map = param.solve();
  ASSERT_EQ(scale.size(), std::size_t(torus.arrays.nf));
  EXPECT_NEAR(independent_energy(torus, H, map.corner_uv, nullptr, scale), map.energy, 1e-9 * (1 + map.energy));
  EXPECT_NEAR(independent_energy(torus, H, unscaled.corner_uv), unscaled.energy, 1e-9 * (1 + unscaled.energy));
  double area = 0, scaled_area = 0;
  std::vector<double> log_scale, log_rho;
  for(int f = 0; f < torus.arrays.nf; ++f) {
    V3 c = {{0, 0, 0}};
    V3 P[3];
    for(int k = 0; k < 3; ++k) {
      P[k] = torus.view.P[torus.arrays.corner_vertex[3 * f + k]];
      c = c + (1. / 3) * P[k];
    }
    const double A = norm(cross(P[1] - P[0], P[2] - P[0])) / 2;
    EXPECT_GT(scale[f], 0.);
    area += A;
    scaled_area += A * scale[f] * scale[f];
    log_scale.push_back(std::log(scale[f]));
    log_rho.push_back(std::log(std::hypot(c[0], c[1])));
  }
  EXPECT_NEAR(scaled_area, area, 1e-9 * area); // the mean quad size stays H
  EXPECT_LT(map.energy, 0.25 * unscaled.energy) << map.energy << " against " << unscaled.energy;
  // log scale against log rho: a line of slope -1 (scale = c / rho), up to the discretisation and the smoothing
  const int n = int(log_scale.size());
  double ms = 0, mr = 0;
  for(int f = 0; f < n; ++f) {
    ms += log_scale[f] / n;
    mr += log_rho[f] / n;
  }
  double sr = 0, ss = 0, rr = 0;
  for(int f = 0; f < n; ++f) {
    sr += (log_scale[f] - ms) * (log_rho[f] - mr);
    ss += (log_scale[f] - ms) * (log_scale[f] - ms);
    rr += (log_rho[f] - mr) * (log_rho[f] - mr);
  }
  const double slope = sr / rr, correlation = sr / std::sqrt(ss * rr);
  EXPECT_LT(correlation, -0.95);
  EXPECT_NEAR(slope, -1, 0.2);
  std::cout << "torus: E " << unscaled.energy << " -> " << map.energy << ", log scale against log rho: slope " << slope
            << ", correlation " << correlation << std::endl;
}

TEST(QuadLayers, GenusTwo)
{
  const Soup soup = genus2_soup(3);
  const Quad_case q(soup, genus_two_singularities(soup));
  check_all(q, 0.2);
}

// a warped grid on [0, 4]^2 with two square holes
Soup grid_with_holes(int n)
{
  Soup s;
  for(int i = 0; i <= n; ++i)
    for(int j = 0; j <= n; ++j)
      s.points.emplace_back(4. * i / n, 4. * j / n, 0.);
  auto id = [&](int i, int j) { return i * (n + 1) + j; };
  auto in_hole = [&](int i, int j) {
    const double x = (i + 0.5) * 4 / n, y = (j + 0.5) * 4 / n;
    return (x > 0.8 && x < 1.6 && y > 0.8 && y < 3.2) || (x > 2.4 && x < 3.2 && y > 1.2 && y < 2.4);
  };
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j)
      if(!in_hole(i, j)) {
        s.faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
        s.faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
      }
  // drop the vertices no face uses
  std::vector<int> used(s.points.size(), -1);
  Soup r;
  for(Tri& t : s.faces)
    for(int& c : t) {
      if(used[c] < 0) {
        used[c] = int(r.points.size());
        r.points.push_back(s.points[c]);
      }
      c = used[c];
    }
  r.faces = s.faces;
  for(Point& p : r.points) // a bump, so that the surface is curved
    p = Point(p.x(), p.y(), 0.3 * std::sin(p.x()) * std::cos(0.7 * p.y()));
  return r;
}

TEST(QuadLayers, DiskWithTwoHoles)
{
  const Quad_case q(grid_with_holes(20), {});
  ASSERT_EQ(q.view.boundary_loops.size(), 3u);
  check_all(q, 0.2);
  const Soup soup = grid_with_holes(20);
  auto vertex_at = [&](double x, double y) {
    for(std::size_t v = 0; v < soup.points.size(); ++v)
      if(std::abs(soup.points[v].x() - x) < 1e-9 && std::abs(soup.points[v].y() - y) < 1e-9)
        return int(v);
    ADD_FAILURE() << "no vertex at " << x << ", " << y;
    return 0;
  };
  const Quad_case with_singularities(soup, {{vertex_at(0.4, 2.0), Index(1, 4)}, {vertex_at(3.6, 0.6), Index(-1, 4)}});
  check_all(with_singularities, 0.2);
}

TEST(QuadLayers, TwoComponents)
{
  const Soup soup = two_spheres_soup(2);
  const Quad_case q(soup, two_spheres_singularities());
  ASSERT_EQ(q.view.ncomp, 2);
  check_all(q, 0.15);
}

// the unit square, n x n squares of two triangles, interior vertices jittered by up to `amplitude` / n
Soup unit_square(int n, double amplitude = 0.25, unsigned seed = 3)
{
  Soup s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-amplitude / n, amplitude / n);
  for(int i = 0; i <= n; ++i)
    for(int j = 0; j <= n; ++j) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      s.points.emplace_back(double(i) / n + (border ? 0 : jitter(rng)), double(j) / n + (border ? 0 : jitter(rng)), 0.);
    }
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = (i + 1) * (n + 1) + j;
      s.faces.push_back({{a, b, b + 1}});
      s.faces.push_back({{a, b + 1, a + 1}});
    }
  return s;
}

// A flat square with a constant field: the map is exactly affine, its gradient the field and its quarter turn
// divided by H, at zero energy (the cut is the border only).
TEST(QuadLayers, FlatSquareIsAffine)
{
  const Surface_mesh mesh = to_surface_mesh(unit_square(8, 0.3, 7));
  TCI::Mesh_arrays<Surface_mesh> arrays(mesh, get(CGAL::vertex_point, mesh), K());
  TCI::Mesh_geometry geometry(arrays, TC::Weighting::hodge_star);
  geometry.compute_angles(arrays);
  const double alpha = 0.37, H = 0.1;
  const TCI::Vec3 d = {{std::cos(alpha), std::sin(alpha), 0.}}, dperp = {{-std::sin(alpha), std::cos(alpha), 0.}};
  std::vector<double> angle;
  for(int f = 0; f < arrays.nf; ++f)
    angle.push_back(TCI::angle_in_frame(arrays, f, d) + (f % 4) * pi / 2); // any of the four directions
  const std::vector<int> matching = TCI::cross_field_matching(arrays, geometry, angle, {});
  const TCI::Cut_graph cut = TCI::build_cut_graph(arrays, geometry, matching, {});
  EXPECT_TRUE(cut.arcs.empty());
  TCI::Seamless_parametrization param(arrays, cut, angle, H);
  const TCI::Seamless_parametrization::Map map = param.solve();
  EXPECT_LT(map.energy, 1e-20);
  const TCI::Vec3& p0 = arrays.points[arrays.corner_vertex[0]];
  const auto& w0 = map.corner_uv[0];
  double worst = 0;
  for(int c = 0; c < 3 * arrays.nf; ++c) {
    const TCI::Vec3 dp = TCI::sub(arrays.points[arrays.corner_vertex[c]], p0);
    worst = std::max({worst, std::abs(map.corner_uv[c][0] - w0[0] - TCI::dot(d, dp) / H),
                      std::abs(map.corner_uv[c][1] - w0[1] - TCI::dot(dperp, dp) / H)});
  }
  // up to a quarter turn of the whole map (the combing picks one of the four directions)
  if(worst > 1e-9) {
    for(int turn = 1; turn < 4 && worst > 1e-9; ++turn) {
      worst = 0;
      for(int c = 0; c < 3 * arrays.nf; ++c) {
        const TCI::Vec3 dp = TCI::sub(arrays.points[arrays.corner_vertex[c]], p0);
        const auto e = turned({{TCI::dot(d, dp) / H, TCI::dot(dperp, dp) / H}}, turn);
        worst = std::max({worst, std::abs(map.corner_uv[c][0] - w0[0] - e[0]), std::abs(map.corner_uv[c][1] - w0[1] - e[1])});
      }
    }
  }
  EXPECT_LT(worst, 1e-10) << "the map is not the affine map of gradient (d, J d) / H";
}

// Renumbered vertices, shuffled faces, rotated corners: the same surface and singularities give the same cut
// topology and the same optimal energy.
TEST(QuadLayers, IndependentOfNumbering)
{
  const Sphere_and_renumbered s = sphere_and_renumbered();
  const Quad_case a(s.soup, s.sing), b(s.renamed, s.renamed_sing);
  check_cut_is_disk(b);
  check_matching_and_combing(b);
  const double H = 0.15;
  TCI::Seamless_parametrization pa(a.arrays, a.cut, a.angle, H), pb(b.arrays, b.cut, b.angle, H);
  const double ea = pa.solve().energy, eb = pb.solve().energy;
  EXPECT_GT(ea, 0.);
  EXPECT_NEAR(ea, eb, 1e-8 * ea);
}

// What the next layer needs: a singular vertex's root and an arc's translation fixed to given values, the
// transitions still exact and the energy not lower; contradictory values are refused.
TEST(QuadLayers, FixedValues)
{
  const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
  const double H = 0.15;
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
  const double free_energy = param.solve().energy;
  param.fix(param.root_variable(3), 3.);
  param.fix(param.root_variable(3) + 1, -2.);
  param.fix(param.translation_variable(0), 1.);
  const TCI::Seamless_parametrization::Map map = param.solve();
  EXPECT_NEAR(map.root_uv[3][0], 3., 1e-12);
  EXPECT_NEAR(map.root_uv[3][1], -2., 1e-12);
  EXPECT_NEAR(map.translation[0][0], 1., 1e-12);
  EXPECT_LT(transition_error(q, map), 1e-9);
  EXPECT_GE(map.energy, free_energy * (1 - 1e-12));
  // the corners at vertex 3 are its root seen from each side: one of them is the root itself
  bool root_seen = false;
  for(int c = 0; c < 3 * q.arrays.nf; ++c)
    root_seen = root_seen || (q.arrays.corner_vertex[c] == 3 && std::abs(map.corner_uv[c][0] - 3) < 1e-12 &&
                              std::abs(map.corner_uv[c][1] + 2) < 1e-12);
  EXPECT_TRUE(root_seen);
  param.fix(param.root_variable(3), 4.);
  EXPECT_THROW(param.solve(), TC::Invalid_input);
}

// A field whose matching turns around a vertex not declared singular is refused.
TEST(QuadLayers, UndeclaredSingularityIsRefused)
{
  const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_THROW(TCI::build_cut_graph(q.arrays, q.geometry, q.matching, {0, 1, 2, 3, 4, 5, 6}), TC::Invalid_input);
}

// ---- Layer 3: the integer rounding ----

// Checked from the corners alone: every corner at a singular vertex (declared, or with a turning matching) is an
// integer point, and across every interior cut edge, at both ends, right - R^q left is the same integer vector
// (q from our matching): the transitions are grid automorphisms. Returns the largest distance to an integer.
double integer_grid_error(const Quad_case& q, const TCI::Seamless_parametrization::Map& map)
{
  auto off = [](double x) { return std::abs(x - std::round(x)); };
  double worst = 0;
  std::vector<char> singular(q.arrays.nv, 0);
  for(const auto& s : q.singularities)
    singular[s.first] = 1;
  int singular_corners = 0;
  for(int c = 0; c < 3 * q.arrays.nf; ++c) {
    const int v = q.arrays.corner_vertex[c];
    if(singular[v] || q.cut.holonomy[v] != 0) {
      worst = std::max({worst, off(map.corner_uv[c][0]), off(map.corner_uv[c][1])});
      ++singular_corners;
    }
  }
  EXPECT_EQ(singular_corners > 0, !q.singularities.empty());
  for(int h : q.view.interior_halfedges) {
    if(!q.cut_halfedge(h))
      continue;
    const int f = q.view.hface[h], g = q.view.hface[q.view.opp[h]];
    const int turns = -(independent_matching(q, h) + q.cut.combing[g] - q.cut.combing[f]);
    std::array<double, 2> first = {{0, 0}};
    for(int end = 0; end < 2; ++end) {
      const int v = end == 0 ? q.view.src[h] : q.view.tgt[h];
      const auto expected = turned(map.corner_uv[corner_at(q, f, v)], turns);
      const auto& right = map.corner_uv[corner_at(q, g, v)];
      const std::array<double, 2> t = {{right[0] - expected[0], right[1] - expected[1]}};
      worst = std::max({worst, off(t[0]), off(t[1])});
      if(end == 0)
        first = t;
      else
        worst = std::max(worst, std::hypot(t[0] - first[0], t[1] - first[1]));
    }
  }
  return worst;
}

// The greedy rounding on the kept factor against the same greedy rounding with a factorization per solve
// (max_block 0, the scheme before the kept factor): the same integers, the same energy (the integers are chosen
// from minimisers that agree to rounding: a tie within it could differ, none is expected on these meshes)
void expect_kept_factor_rounding_is_from_scratch_one(TCI::Integer_rounding& rounding,
                                                     const TCI::Integer_rounding_result& kept, const std::string& name,
                                                     double batch_distance = 0)
{
  const TCI::Integer_rounding_result scratch =
    rounding.round(TCI::Rounding_scheme::greedy, TCI::Rounding_order::roots_first, batch_distance, 5, 0);
  EXPECT_EQ(scratch.solves, kept.solves) << name;
  EXPECT_EQ(scratch.factorizations, scratch.solves) << name << ": a factorization per solve";
  EXPECT_LE(kept.factorizations, scratch.factorizations) << name;
  EXPECT_EQ(scratch.shifted_unknowns, kept.shifted_unknowns) << name;
  EXPECT_NEAR(kept.map.energy, scratch.map.energy, 1e-8 * (1 + scratch.map.energy)) << name;
  int different = 0;
  for(std::size_t v = 0; v < kept.map.root_uv.size(); ++v)
    for(int k = 0; k < 2; ++k)
      different += std::abs(kept.map.root_uv[v][k] - scratch.map.root_uv[v][k]) > 1e-6;
  for(std::size_t a = 0; a < kept.map.translation.size(); ++a)
    for(int k = 0; k < 2; ++k)
      different += std::abs(kept.map.translation[a][k] - scratch.map.translation[a][k]) > 1e-6;
  EXPECT_EQ(different, 0) << name << ": roots or translations differ";
}

struct Rounding_energies
{
  double continuous = 0, greedy = 0, naive = 0;
  bool naive_feasible = true;
  int integer_unknowns = 0, greedy_solves = 0;
};

// Greedy and naive rounding of a case, both checked as integer-grid maps; the energies checked against our own
// energy and the relaxation bound.
Rounding_energies check_rounding(const Quad_case& q, double H, const std::string& name)
{
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
  TCI::Integer_rounding rounding(param, q.cut);
  Rounding_energies e;
  const TCI::Integer_rounding_result greedy = rounding.round(TCI::Rounding_scheme::greedy);
  e.continuous = greedy.continuous_energy;
  e.greedy = greedy.map.energy;
  e.integer_unknowns = greedy.integer_unknowns;
  e.greedy_solves = greedy.solves;
  EXPECT_EQ(greedy.fixed_unknowns + greedy.implied_unknowns, greedy.integer_unknowns);
  EXPECT_LT(integer_grid_error(q, greedy.map), 1e-9) << name << ": greedy";
  EXPECT_LT(transition_error(q, greedy.map), 1e-9) << name << ": greedy";
  EXPECT_NEAR(independent_energy(q, H, greedy.map.corner_uv), e.greedy, 1e-9 * (1 + e.greedy));
  EXPECT_GE(e.greedy, e.continuous * (1 - 1e-12) - 1e-12) << name << ": below the relaxation";
  expect_kept_factor_rounding_is_from_scratch_one(rounding, greedy, name);
  try {
    const TCI::Integer_rounding_result naive = rounding.round(TCI::Rounding_scheme::naive);
    e.naive = naive.map.energy;
    EXPECT_NEAR(naive.continuous_energy, e.continuous, 1e-12 * (1 + e.continuous));
    EXPECT_EQ(naive.solves, naive.fixed_unknowns > 0 ? 2 : 1);
    EXPECT_LT(integer_grid_error(q, naive.map), 1e-9) << name << ": naive";
    EXPECT_LT(transition_error(q, naive.map), 1e-9) << name << ": naive";
    EXPECT_GE(e.naive, e.continuous * (1 - 1e-12) - 1e-12) << name << ": below the relaxation";
  } catch(const TC::Invalid_input& error) {
    e.naive_feasible = false;
    std::cout << name << ": naive rounding infeasible: " << error.what() << "\n";
  }
  std::cout << name << ": " << e.integer_unknowns << " integer unknowns, energy continuous " << e.continuous
            << ", greedy " << e.greedy << " (" << e.greedy_solves << " solves), naive "
            << (e.naive_feasible ? std::to_string(e.naive) : std::string("infeasible")) << "\n";
  return e;
}

// The meshes of the layers' tests: every rounding an integer-grid map above the relaxation bound; greedy against
// naive reported, not asserted case by case (greedy is a heuristic: nothing guarantees it beats naive on one
// mesh), but over the set it must win at least as often as it loses.
TEST(QuadRounding, MeshesOfTheLayers)
{
  std::vector<Rounding_energies> all;
  {
    const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
    all.push_back(check_rounding(q, 0.15, "sphere, eight +1/4"));
  }
  {
    const Quad_case q(warped(icosphere_soup(2)), {{0, Index(1, 2)}, {3, Index(1, 2)}, {5, Index(1, 2)}, {9, Index(1, 2)}});
    all.push_back(check_rounding(q, 0.15, "sphere, four +1/2"));
  }
  {
    const Quad_case q(warped(icosphere_soup(2)), {{0, Index(1)}, {3, Index(1)}});
    all.push_back(check_rounding(q, 0.15, "sphere, two +1"));
  }
  {
    const Quad_case q(torus_soup(3, 1, 24, 12), {});
    all.push_back(check_rounding(q, 0.3, "torus"));
  }
  {
    const Quad_case q(warped(torus_soup(3, 1, 24, 12)), {{5, Index(1, 4)}, {150, Index(-1, 4)}});
    all.push_back(check_rounding(q, 0.3, "warped torus, +1/4 and -1/4"));
  }
  {
    const Soup soup = genus2_soup(3);
    const Quad_case q(soup, genus_two_singularities(soup));
    all.push_back(check_rounding(q, 0.2, "genus 2, eight -1/4"));
  }
  {
    const Soup soup = two_spheres_soup(2);
    const Quad_case q(soup, two_spheres_singularities());
    all.push_back(check_rounding(q, 0.15, "two spheres"));
  }
  {
    const Quad_case q(grid_with_holes(20), {});
    all.push_back(check_rounding(q, 0.2, "disk with two holes"));
  }
  int wins = 0, losses = 0;
  for(const Rounding_energies& e : all)
    if(e.naive_feasible) {
      wins += e.greedy < e.naive * (1 - 1e-9);
      losses += e.greedy > e.naive * (1 + 1e-9);
    }
  std::cout << "greedy below naive on " << wins << " meshes, above on " << losses << "\n";
  EXPECT_GE(wins, losses);
}

// A unit cube (6 x 6 squares per face) with its eight +1/4 corners and the field along the edges: the connection
// is Levi-Civita (the corners' defects are exactly pi/2), the continuous map is the cube's development at zero
// energy. For H = 1/3 it is already an integer-grid map (corners 3 cells apart): every rounding keeps energy 0.
// For H = 0.3 (10/3 cells per edge) the corners cannot all be integer points at zero energy.
TEST(QuadRounding, CubeKnownAnswers)
{
  const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, 6);
  std::vector<int> corners;
  for(int v = 0; v < int(soup.points.size()); ++v) {
    const Point& p = soup.points[v];
    if((p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1) && (p.z() == 0 || p.z() == 1))
      corners.push_back(v);
  }
  ASSERT_EQ(corners.size(), 8u);
  const Quad_case cube(soup, quarters(corners), true);
  const Rounding_energies exact = check_rounding(cube, 1. / 3, "cube, H = 1/3");
  EXPECT_LT(exact.continuous, 1e-20);
  EXPECT_LT(exact.greedy, 1e-20);
  EXPECT_LT(exact.naive, 1e-20);
  EXPECT_LE(exact.greedy_solves, 3) << "every unknown is an integer already: one solve per kind at most";
  const Rounding_energies off_grid = check_rounding(cube, 0.3, "cube, H = 0.3");
  EXPECT_LT(off_grid.continuous, 1e-20);
  EXPECT_GT(off_grid.greedy, 1e-3);
  EXPECT_TRUE(off_grid.naive_feasible);
  EXPECT_GT(off_grid.naive, 1e-3);
}

// The same surface and singularities renumbered: the continuous energy is the same (layer 2's test), the rounded
// one need not be: the integer unknowns are the translations of the arcs of a cut graph, which depends on the
// numbering (breadth-first tree, shortest-path ties), and greedy rounds them one by one in a cut-dependent order.
// The set of integer-grid maps is the same for every cut, so only the path of the heuristic differs: both
// results are checked as integer-grid maps above the same bound, their energies reported, not compared
// (measured: 22.243 and 22.098 greedy, 22.61 and 40.50 naive, for a continuous 20.264).
TEST(QuadRounding, RenumberedSphere)
{
  const Sphere_and_renumbered s = sphere_and_renumbered();
  const Quad_case a(s.soup, s.sing), b(s.renamed, s.renamed_sing);
  const Rounding_energies ea = check_rounding(a, 0.15, "sphere"), eb = check_rounding(b, 0.15, "sphere renumbered");
  EXPECT_NEAR(ea.continuous, eb.continuous, 1e-8 * ea.continuous);
  std::cout << "greedy energies " << ea.greedy << " and " << eb.greedy << " (relative difference "
            << std::abs(ea.greedy - eb.greedy) / ea.greedy << ")\n";
}

// The plain literature order (closest to an integer first, translations and roots alike) on the sphere with
// eight +1/4: naive rounding in it fixes translations that determine singular roots, and the rounding must then
// refuse with the name of the unknown, never return a map that is not integer. Greedy in that order: either a
// checked integer-grid map or the same refusal.
TEST(QuadRounding, InfeasibleRoundingIsRefused)
{
  const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
  const double H = 0.15;
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
  TCI::Integer_rounding rounding(param, q.cut);
  try { // the plain scheme: the nearest integer only
    rounding.round(TCI::Rounding_scheme::naive, TCI::Rounding_order::closest_first, 0, 1);
    ADD_FAILURE() << "naive rounding in the closest-first order is expected to be infeasible here";
  } catch(const TC::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("infeasible"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("singular vertex"), std::string::npos) << e.what();
  }
  try { // with the next integers tried where the nearest determines a non-integer: a map, or the same refusal
    const TCI::Integer_rounding_result naive = rounding.round(TCI::Rounding_scheme::naive, TCI::Rounding_order::closest_first);
    EXPECT_LT(integer_grid_error(q, naive.map), 1e-9);
    std::cout << "naive, closest first, 5 candidates: energy " << naive.map.energy << " (" << naive.shifted_unknowns
              << " unknowns not at their nearest integer)\n";
  } catch(const TC::Invalid_input& e) {
    std::cout << "naive, closest first, 5 candidates: " << e.what() << "\n";
  }
  try {
    const TCI::Integer_rounding_result greedy = rounding.round(TCI::Rounding_scheme::greedy, TCI::Rounding_order::closest_first);
    EXPECT_LT(integer_grid_error(q, greedy.map), 1e-9);
    std::cout << "greedy, closest first: energy " << greedy.map.energy << "\n";
  } catch(const TC::Invalid_input& e) {
    std::cout << "greedy, closest first: " << e.what() << "\n";
  }
  // and the default order after a refusal: the rounding starts again from the continuous map
  const TCI::Integer_rounding_result fine = rounding.round(TCI::Rounding_scheme::greedy);
  EXPECT_LT(integer_grid_error(q, fine.map), 1e-9);
}

// the value of kept unknown j (a root coordinate or a translation) in a map
double integer_of_map(const TCI::Seamless_parametrization& param, const TCI::Seamless_parametrization::Map& map, int j)
{
  const int t = param.translation_variable(0);
  return j < t ? map.root_uv[std::size_t(j / 2)][j % 2] : map.translation[std::size_t((j - t) / 2)][j % 2];
}

// The kept factor (Kept_factor_fixing) against from-scratch solves with the same unknowns fixed, on a genus-2
// surface with eight singularities: the integers of a greedy rounding fixed one by one (consistent values: a
// feasible integer-grid map has them), after each fix the watched values equal those of a new parametrisation
// solved with the same values fixed, and the kept minimiser is optimal for it: our energy's gradient is orthogonal
// to every feasible direction of the fixed problem (its corner basis), and its energy is the fixed problem's.
// With a block of 5 (refactored along the way) and one never refactored.
TEST(QuadRounding, KeptFactorMinimisersAreTheFromScratchOnes)
{
  const Soup soup = genus2_soup(3);
  const Quad_case q(soup, genus_two_singularities(soup));
  const double H = 0.2;
  TCI::Seamless_parametrization reference(q.arrays, q.cut, q.angle, H);
  TCI::Integer_rounding rounding(reference, q.cut);
  const TCI::Integer_rounding_result rounded = rounding.round(TCI::Rounding_scheme::greedy);
  const std::vector<int> z = rounding.integer_variables();
  ASSERT_GT(z.size(), 20u);
  auto integer_of = [&](int j) { return integer_of_map(reference, rounded.map, j); };
  for(int block : {5, 100000}) {
    TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
    param.solve();
    TCI::Kept_factor_fixing kept(param, z, block, true);
    TCI::Seamless_parametrization scratch(q.arrays, q.cut, q.angle, H);
    double moved = 0;
    for(std::size_t i = 0; i < z.size(); ++i) {
      const double value = std::round(integer_of(z[i]));
      moved = std::max(moved, std::abs(value - kept.values()[Eigen::Index(i)]));
      kept.fix(int(i), value);
      scratch.fix(z[i], value);
      if(i % 3 != 2 && i + 1 != z.size())
        continue; // checked every third fix: several fixes between two reads, as the batches do
      const Eigen::VectorXd& values = kept.values();
      const TCI::Seamless_parametrization::Map expected = scratch.solve();
      for(std::size_t j = 0; j < z.size(); ++j)
        EXPECT_NEAR(values[Eigen::Index(j)], integer_of_map(reference, expected, z[j]), 1e-9)
          << "block " << block << ", " << i + 1 << " fixed, unknown " << z[j];
      // the whole kept minimiser: feasible for the fixed problem and optimal there
      const TCI::Seamless_parametrization::Map map = kept.map();
      for(std::size_t j = 0; j <= i; ++j)
        EXPECT_NEAR(integer_of_map(reference, map, z[j]), std::round(integer_of(z[j])), 1e-9);
      EXPECT_LT(transition_error(q, map), 1e-9);
      Eigen::VectorXd gradient, gradient_at_zero;
      const double E = independent_energy(q, H, map.corner_uv, &gradient);
      independent_energy(q, H, std::vector<std::array<double, 2>>(map.corner_uv.size(), {{0., 0.}}), &gradient_at_zero);
      EXPECT_NEAR(E, expected.energy, 1e-9 * (1 + E));
      EXPECT_LT((scratch.corner_basis().transpose() * gradient).norm(),
                1e-9 * (scratch.corner_basis().transpose() * gradient_at_zero).norm())
        << "block " << block << ", " << i + 1 << " fixed";
    }
    EXPECT_GT(moved, 0.1) << "the fixes move the minimiser";
    // unbounded, every fix is tried on the factor (those the fixed ones determine, which the rounding itself never
    // fixes, are then refactored: the parametrisation checks them); the block of 5 is kept to 5
    if(block == 5)
      EXPECT_EQ(kept.largest_block(), 5);
    else
      EXPECT_EQ(kept.back_substitutions(), int(z.size()));
    std::cout << "block " << block << ": " << z.size() << " fixes, " << kept.factorizations() << " factorizations, "
              << kept.back_substitutions() << " back-substitutions, largest block " << kept.largest_block() << "\n";
  }
}

// Several unknowns fixed per solve (batch_distance): fewer solves, still an integer-grid map above the bound.
TEST(QuadRounding, BatchedGreedy)
{
  const Soup soup = genus2_soup(3);
  const Quad_case q(soup, genus_two_singularities(soup));
  const double H = 0.2;
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
  TCI::Integer_rounding rounding(param, q.cut);
  const TCI::Integer_rounding_result one = rounding.round(TCI::Rounding_scheme::greedy);
  const TCI::Integer_rounding_result batched =
    rounding.round(TCI::Rounding_scheme::greedy, TCI::Rounding_order::roots_first, 0.25);
  EXPECT_LT(batched.solves, one.solves);
  expect_kept_factor_rounding_is_from_scratch_one(rounding, batched, "genus 2, batched", 0.25);
  EXPECT_LT(integer_grid_error(q, batched.map), 1e-9);
  EXPECT_GE(batched.map.energy, batched.continuous_energy * (1 - 1e-12));
  std::cout << "genus 2: greedy " << one.map.energy << " in " << one.solves << " solves, batched (0.25) "
            << batched.map.energy << " in " << batched.solves << " solves\n";
}

// ---- Layer 4: the quad mesh of the integer-grid map ----

struct Extraction_counts
{
  int quads = 0, non_quads = 0, folds = 0, valence_3 = 0, valence_5 = 0, other_valence = 0;
  std::array<int, 6> border_valence = {{0, 0, 0, 0, 0, 0}}; // border quad vertices by valence (5: 5 or more)
  int border_vertices = 0, features = 0, features_not_followed = 0, corners_on_features = 0;
  int quad_edges = 0;
  std::vector<int> along_count; // per input edge: the quad edges that run along it
};

// distance from p to the segment [a, b]
double segment_distance(const V3& p, const V3& a, const V3& b)
{
  const V3 d = b - a;
  const double t = std::max(0., std::min(1., dot(p - a, d) / dot(d, d)));
  return norm(p - (a + t * d));
}

// The feature edges followed by quad edges, from the definitions: each flagged input edge lies on an integer
// iso-line of the map (in the chart of a face beside it, one coordinate equal and an integer at both ends), and
// is run along by a quad edge (two where a quad vertex is inside it); every quad edge that runs along input edges runs along a path of them
// from its first vertex (on the first edge) to its second (on the last). Returns the flagged edges not followed.
int check_features_followed(const Quad_case& q, const TCI::Seamless_parametrization::Map& map,
                            const TCI::Quad_mesh& quad, const std::vector<char>& features, const std::string& name,
                            std::vector<int>& along_count)
{
  const TCI::Mesh_arrays<Surface_mesh>& m = q.arrays;
  const int ne = int(q.cut.edge_corner.size());
  along_count.assign(ne, 0);
  for(std::size_t e = 0; e < quad.edges.size(); ++e) {
    const std::vector<int>& along = quad.edge_along[e];
    for(int x : along)
      ++along_count[x];
    if(along.empty())
      continue;
    auto ends = [&](int x) {
      const int i = q.cut.edge_corner[x];
      return std::make_pair(m.source_of(i), m.target_of(i));
    };
    for(std::size_t j = 0; j + 1 < along.size(); ++j) {
      const auto a = ends(along[j]), b = ends(along[j + 1]);
      EXPECT_TRUE(a.first == b.first || a.first == b.second || a.second == b.first || a.second == b.second)
        << name << ": quad edge " << e << " runs along input edges that do not touch";
    }
    for(int end = 0; end < 2; ++end) {
      const auto x = ends(end == 0 ? along.front() : along.back());
      const double d = segment_distance(V3(quad.points[quad.edges[e][end]]), V3(m.points[x.first]), V3(m.points[x.second]));
      EXPECT_LT(d, 1e-9) << name << ": quad edge " << e << " does not start on the input edge it runs along";
    }
  }
  int not_followed = 0;
  for(int e = 0; e < ne; ++e) {
    if(features.empty() || !features[e])
      continue;
    const int i = q.cut.edge_corner[e];
    const auto& a = map.corner_uv[i];
    const auto& b = map.corner_uv[TCI::Mesh_arrays<Surface_mesh>::next_corner(i)];
    bool on_line = false;
    for(int k = 0; k < 2; ++k)
      on_line = on_line || (std::abs(a[k] - b[k]) < 1e-9 && std::abs(a[k] - std::round(a[k])) < 1e-9);
    if(!on_line || along_count[e] < 1) // (two quad edges where a quad vertex splits it)
      ++not_followed;
    EXPECT_TRUE(on_line) << name << ": feature edge " << e << " (vertices " << m.source_of(i) << ", " << m.target_of(i)
                         << ") is not on an integer iso-line: (" << a[0] << ", " << a[1] << ") to (" << b[0] << ", "
                         << b[1] << ")";
  }
  return not_followed;
}

// The quad mesh of the greedy integer-grid map of a case (with feature edges flagged, border edges included),
// checked from its definition:
// - every quad vertex is on the input: barycentric coordinates in its face in [0, 1] summing to 1, its position
//   their combination of the face's corners, and the map interpolated there an integer point;
// - the faces are quads of 4 distinct vertices, each directed edge in at most one face;
// - the feature edges on integer iso-lines, each followed by one quad edge (check_features_followed);
// and, where the map has no folded or degenerate triangle: no polygon rejected, every edge in exactly two faces
// with opposite directions but along the border (one face), every interior vertex a single fan of quads (its
// link one cycle) and every border vertex a single open fan (its link one path), the Euler characteristic the
// input's, valence 4 everywhere inside but at the singular vertices, which have 4 - 4k, and on the border the
// rule of quad_extraction.h: valence = the quads at the vertex + 1.
Extraction_counts check_quad_mesh(const Quad_case& q, double H, const std::string& name,
                                  const std::vector<char>& features = {}, TCI::Quad_mesh* out = nullptr,
                                  double batch_distance = 0)
{
  const auto start = std::chrono::steady_clock::now();
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H, features);
  TCI::Integer_rounding rounding(param, q.cut);
  const TCI::Integer_rounding_result rounded =
    rounding.round(TCI::Rounding_scheme::greedy, TCI::Rounding_order::roots_first, batch_distance);
  const TCI::Seamless_parametrization::Map& map = rounded.map;
  const double rounding_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const TCI::Quad_mesh quad = TCI::extract_quad_mesh(q.arrays, q.cut, map);
  const double total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Extraction_counts counts;
  counts.quads = quad.quads;
  counts.non_quads = quad.non_quads;
  counts.folds = quad.folded_triangles + quad.degenerate_triangles;
  counts.quad_edges = quad.quad_edges;
  const int nv = int(quad.points.size());
  EXPECT_EQ(quad.locations.size(), quad.points.size());
  EXPECT_EQ(quad.valence.size(), quad.points.size());
  EXPECT_EQ(quad.on_border.size(), quad.points.size());
  EXPECT_EQ(quad.edges.size(), std::size_t(quad.quad_edges));
  EXPECT_EQ(quad.edge_along.size(), std::size_t(quad.quad_edges));
  double worst_off_surface = 0, worst_off_grid = 0;
  for(int p = 0; p < nv; ++p) {
    const TCI::Quad_mesh::Location& l = quad.locations[p];
    if(!(l.face >= 0 && l.face < q.arrays.nf)) {
      ADD_FAILURE() << name << ": quad vertex " << p << " in no face of the input";
      return counts;
    }
    double sum = 0;
    V3 position = {{0, 0, 0}};
    std::array<double, 2> w = {{0, 0}};
    for(int j = 0; j < 3; ++j) {
      EXPECT_GE(l.barycentric[j], -1e-12);
      EXPECT_LE(l.barycentric[j], 1 + 1e-12);
      sum += l.barycentric[j];
      const int c = 3 * l.face + j;
      position = position + l.barycentric[j] * V3(q.arrays.points[q.arrays.corner_vertex[c]]);
      w = {{w[0] + l.barycentric[j] * map.corner_uv[c][0], w[1] + l.barycentric[j] * map.corner_uv[c][1]}};
    }
    EXPECT_NEAR(sum, 1., 1e-12);
    worst_off_surface = std::max(worst_off_surface, norm(position - V3(quad.points[p])));
    worst_off_grid = std::max({worst_off_grid, std::abs(w[0] - std::round(w[0])), std::abs(w[1] - std::round(w[1]))});
    if(l.mesh_vertex >= 0) {
      EXPECT_EQ(q.arrays.corner_vertex[3 * l.face + (l.barycentric[0] == 1 ? 0 : l.barycentric[1] == 1 ? 1 : 2)], l.mesh_vertex);
    }
  }
  EXPECT_LT(worst_off_surface, 1e-12) << name << ": a quad vertex off its triangle";
  EXPECT_LT(worst_off_grid, 1e-6) << name << ": a quad vertex that is not an integer point of the map";
  std::map<std::pair<int, int>, int> directed;
  for(const auto& f : quad.faces) {
    std::set<int> distinct(f.begin(), f.end());
    EXPECT_EQ(distinct.size(), 4u) << name;
    for(int j = 0; j < 4; ++j) {
      EXPECT_TRUE(f[j] >= 0 && f[j] < nv);
      ++directed[{f[j], f[(j + 1) % 4]}];
    }
  }
  for(const auto& d : directed)
    EXPECT_EQ(d.second, 1) << name << ": directed edge " << d.first.first << " -> " << d.first.second << " in several faces";
  const std::vector<long long> k4 = scaled_indices(q.view.nv(), q.singularities, 4);
  for(int p = 0; p < nv; ++p) {
    const int valence = quad.valence[p];
    if(quad.on_border[p]) {
      ++counts.border_vertices;
      ++counts.border_valence[std::min(valence, 5)];
      continue;
    }
    counts.valence_3 += valence == 3;
    counts.valence_5 += valence == 5;
    counts.other_valence += valence != 3 && valence != 4 && valence != 5;
  }
  for(char f : features)
    counts.features += f != 0;
  counts.features_not_followed = check_features_followed(q, map, quad, features, name, counts.along_count);
  std::cout << name << ": " << nv << " quad vertices (" << counts.border_vertices << " on the border), " << quad.quads
            << " quads, " << quad.non_quads << " other polygons, " << quad.quad_edges << " edges (" << quad.dangling_edges
            << " dangling, " << quad.open_edges << " open, " << quad.border_edges << " on the border), valence 3: "
            << counts.valence_3 << ", 5: " << counts.valence_5 << ", other than 3-5: " << counts.other_valence
            << "; border valence 2: " << counts.border_valence[2] << ", 3: " << counts.border_valence[3]
            << ", 4: " << counts.border_valence[4] << "; " << quad.folded_triangles << " folded and "
            << quad.degenerate_triangles << " degenerate triangles of " << q.arrays.nf << "; feature edges "
            << counts.features << ", not followed " << counts.features_not_followed << "; "
            << param.feature_lines().size() << " feature lines, " << rounded.integer_unknowns << " integer unknowns, "
            << rounded.solves << " solves, energy " << rounded.continuous_energy << " -> " << map.energy
            << "; parametrisation and rounding " << rounding_seconds << " s, with the extraction " << total_seconds
            << " s\n";
  if(out)
    *out = quad;
  if(counts.folds > 0)
    return counts;
  // a fold-free map: a consistently oriented 2-manifold of quads with the input's topology
  EXPECT_EQ(quad.non_quads, 0) << name;
  EXPECT_EQ(quad.dangling_edges, 0) << name;
  EXPECT_EQ(quad.open_edges, 0) << name;
  EXPECT_EQ(counts.features_not_followed, 0) << name;
  int border_directed = 0;
  for(const auto& d : directed)
    if(!directed.count({d.first.second, d.first.first})) {
      ++border_directed;
      EXPECT_TRUE(quad.on_border[d.first.first] && quad.on_border[d.first.second])
        << name << ": edge " << d.first.first << " - " << d.first.second << " in one face, not on the border";
    }
  EXPECT_EQ(border_directed, quad.border_edges) << name;
  // the link of every vertex: one cycle (one path on the border) through as many faces as its valence (minus 1)
  std::vector<std::map<int, int>> link(nv); // next vertex -> previous vertex, around each vertex's faces
  for(const auto& f : quad.faces)
    for(int j = 0; j < 4; ++j)
      link[f[j]][f[(j + 1) % 4]] = f[(j + 3) % 4];
  for(int p = 0; p < nv; ++p) {
    if(link[p].empty()) {
      ADD_FAILURE() << name << ": quad vertex " << p << " in no face";
      continue;
    }
    int start = link[p].begin()->first;
    if(quad.on_border[p]) { // the path starts at the vertex that is no face's previous one
      std::set<int> previous;
      for(const auto& l : link[p])
        previous.insert(l.second);
      int starts = 0;
      for(const auto& l : link[p])
        if(!previous.count(l.first)) {
          start = l.first;
          ++starts;
        }
      EXPECT_EQ(starts, 1) << name << ": border quad vertex " << p << " is not one open fan";
    }
    int steps = 0;
    int x = start;
    do {
      auto it = link[p].find(x);
      if(it == link[p].end())
        break;
      x = it->second;
      ++steps;
    } while(x != start && steps <= int(link[p].size()));
    if(!quad.on_border[p]) {
      EXPECT_EQ(x, start) << name << ": the faces at quad vertex " << p << " are not a fan";
    }
    EXPECT_EQ(steps, int(link[p].size())) << name << ": the faces at quad vertex " << p << " are not one fan";
    EXPECT_EQ(int(link[p].size()) + (quad.on_border[p] ? 1 : 0), quad.valence[p]) << name << ": quad vertex " << p;
  }
  std::set<std::pair<int, int>> undirected;
  for(const auto& d : directed)
    undirected.insert({std::min(d.first.first, d.first.second), std::max(d.first.first, d.first.second)});
  const long long edges = (long long)(undirected.size());
  const long long input_edges = (long long)(q.cut.edge_corner.size());
  EXPECT_EQ(nv - edges + (long long)(quad.faces.size()), q.arrays.nv - input_edges + q.arrays.nf)
    << name << ": Euler characteristic";
  EXPECT_EQ(edges, quad.quad_edges) << name;
  // valence 4 - 4k at singular vertices, 4 everywhere else inside; every singular vertex is a quad vertex
  std::vector<int> seen(q.arrays.nv, 0);
  for(int p = 0; p < nv; ++p) {
    const int v = quad.locations[p].mesh_vertex;
    if(v >= 0)
      ++seen[v];
    if(quad.on_border[p])
      continue;
    const int expected = v >= 0 ? int(4 - k4[v]) : 4;
    EXPECT_EQ(quad.valence[p], expected) << name << ": quad vertex " << p << " (mesh vertex " << v << ")";
  }
  for(const auto& s : q.singularities)
    EXPECT_EQ(seen[s.first], 1) << name << ": singular vertex " << s.first << " is not one quad vertex";
  return counts;
}

std::vector<int> cube_corners(const Soup& soup)
{
  std::vector<int> corners;
  for(int v = 0; v < int(soup.points.size()); ++v) {
    const Point& p = soup.points[v];
    if((p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1) && (p.z() == 0 || p.z() == 1))
      corners.push_back(v);
  }
  return corners;
}

// The unit cube, field along the edges, H = 1/k: 6 k^2 quads, the eight corners of valence 3, 6 k^2 + 2 vertices.
// On the 6 x 6 tessellation the iso-lines run along mesh edges and through mesh vertices (every degenerate case
// of the extraction); on the 5 x 5 one (k = 2, 3) they mostly cross triangles.
TEST(QuadExtraction, CubeKnownAnswers)
{
  for(int s : {6, 5}) {
    const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, s);
    const std::vector<int> corners = cube_corners(soup);
    ASSERT_EQ(corners.size(), 8u);
    const Quad_case cube(soup, quarters(corners), true);
    for(int k : {1, 2, 3}) {
      if(s == 5 && k == 1)
        continue;
      const std::string name = "cube " + std::to_string(s) + "x" + std::to_string(s) + ", H = 1/" + std::to_string(k);
      SCOPED_TRACE(name);
      const Extraction_counts c = check_quad_mesh(cube, 1. / k, name);
      EXPECT_EQ(c.folds, 0);
      EXPECT_EQ(c.quads, 6 * k * k);
      EXPECT_EQ(c.non_quads, 0);
      EXPECT_EQ(c.valence_3, 8);
      EXPECT_EQ(c.valence_5 + c.other_valence, 0);
    }
  }
}

// A torus of revolution without singularity: all valence 4 where the map has no fold (counted otherwise).
TEST(QuadExtraction, TorusAllValenceFour)
{
  const Quad_case q(torus_soup(3, 1, 24, 12), {});
  const Extraction_counts c = check_quad_mesh(q, 0.3, "torus");
  if(c.folds == 0) {
    EXPECT_EQ(c.valence_3 + c.valence_5 + c.other_valence, 0);
  }
  EXPECT_GT(c.quads, 0);
}

// Singular spheres and surfaces: +1/4 -> valence 3, -1/4 -> 5, checked in check_quad_mesh where fold-free.
TEST(QuadExtraction, SingularSurfaces)
{
  {
    const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
    const Extraction_counts c = check_quad_mesh(q, 0.15, "sphere, eight +1/4");
    if(c.folds == 0) {
      EXPECT_EQ(c.valence_3, 8);
    }
  }
  {
    const Quad_case q(icosphere_soup(3), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
    const Extraction_counts c = check_quad_mesh(q, 0.2, "round sphere (level 3), eight +1/4");
    if(c.folds == 0) {
      EXPECT_EQ(c.valence_3, 8);
    }
  }
  {
    const Quad_case q(warped(torus_soup(3, 1, 24, 12)), {{5, Index(1, 4)}, {150, Index(-1, 4)}});
    const Extraction_counts c = check_quad_mesh(q, 0.3, "warped torus, +1/4 and -1/4");
    if(c.folds == 0) {
      EXPECT_EQ(c.valence_3, 1);
      EXPECT_EQ(c.valence_5, 1);
    }
  }
  {
    const Soup soup = genus2_soup(3);
    const Quad_case q(soup, genus_two_singularities(soup));
    const Extraction_counts c = check_quad_mesh(q, 0.2, "genus 2, eight -1/4");
    if(c.folds == 0) {
      EXPECT_EQ(c.valence_5, 8);
    }
  }
}

// Maps that are not integer-grid maps, too many quads and a border are refused with Invalid_input.
TEST(QuadExtraction, BadInputsAreRefused)
{
  const Quad_case q(warped(icosphere_soup(2)), quarters({0, 1, 2, 3, 4, 5, 6, 7}));
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, 0.15);
  const TCI::Seamless_parametrization::Map continuous = param.solve();
  EXPECT_THROW(TCI::extract_quad_mesh(q.arrays, q.cut, continuous), TC::Invalid_input);
  TCI::Integer_rounding rounding(param, q.cut);
  const TCI::Seamless_parametrization::Map map = rounding.round(TCI::Rounding_scheme::greedy).map;
  EXPECT_THROW(TCI::extract_quad_mesh(q.arrays, q.cut, map, 10.), TC::Invalid_input);
  TCI::Seamless_parametrization::Map shifted = map;
  if(!shifted.translation.empty()) {
    shifted.translation[0][0] += 1; // the corners no longer follow the transition
    EXPECT_THROW(TCI::extract_quad_mesh(q.arrays, q.cut, shifted), TC::Invalid_input);
  }
  // a border the field is not aligned with (no feature flags): not on an iso-line, refused
  const Quad_case disk(grid_with_holes(20), {});
  TCI::Seamless_parametrization disk_param(disk.arrays, disk.cut, disk.angle, 0.2);
  try {
    TCI::extract_quad_mesh(disk.arrays, disk.cut, disk_param.solve());
    ADD_FAILURE() << "a border off the iso-lines is expected to be refused";
  } catch(const TC::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("border edge"), std::string::npos) << e.what();
  }
}

// ---- Feature curves and borders on integer iso-lines ----

// the edges of a case (cut graph numbering) whose two ends satisfy `on`
std::vector<char> edges_where(const Quad_case& q, const std::function<bool(const V3&, const V3&)>& on)
{
  std::vector<char> flags(q.cut.edge_corner.size(), 0);
  for(std::size_t e = 0; e < flags.size(); ++e) {
    const int i = q.cut.edge_corner[e];
    flags[e] = on(V3(q.arrays.points[q.arrays.source_of(i)]), V3(q.arrays.points[q.arrays.target_of(i)]));
  }
  return flags;
}

std::vector<char> border_flags(const Quad_case& q)
{
  std::vector<char> flags(q.cut.edge_corner.size(), 0);
  for(std::size_t e = 0; e < flags.size(); ++e)
    flags[e] = q.arrays.opposite_corner[q.cut.edge_corner[e]] < 0;
  return flags;
}

// a field of one direction d (tangent to every face: a flat or developable surface), parallel for x = 0
Quad_case::Designer constant_field(const V3& d)
{
  return [d](const Surface_mesh&, const Mesh_view<Surface_mesh>& view, Singularities&, std::vector<double>& x,
             std::vector<Vector>& field) {
    x.assign(view.nh(), 0.);
    field.assign(view.nf(), Vector(d[0], d[1], d[2]));
  };
}

// A flat unit square, field along x, its border flagged, H = 1/k: exactly k^2 quads; on the border the corners
// have valence 2 (a convex quarter turn), the others 3; inside every vertex valence 4. k = 4, 5 do not divide the
// 6 x 6 tessellation: the iso-lines cross its triangles.
TEST(QuadFeatures, FlatSquareWithBorder)
{
  const Quad_case q(to_surface_mesh(unit_square(6)), constant_field({{1., 0., 0.}}));
  for(int k : {1, 2, 3, 4, 5}) {
    const std::string name = "unit square, H = 1/" + std::to_string(k);
    SCOPED_TRACE(name);
    const Extraction_counts c = check_quad_mesh(q, 1. / k, name, border_flags(q));
    EXPECT_EQ(c.folds, 0);
    EXPECT_EQ(c.quads, k * k);
    EXPECT_EQ(c.non_quads, 0);
    EXPECT_EQ(c.border_valence[2], 4);
    EXPECT_EQ(c.border_valence[3], 4 * (k - 1));
    EXPECT_EQ(c.border_vertices, 4 * k);
    EXPECT_EQ(c.valence_3 + c.valence_5 + c.other_valence, 0);
  }
}

// A flat L (the unit square without its quarter x, y > 1/2), field along x, border flagged, H = 1/k for even k:
// 3 k^2 / 4 quads; on the border five convex corners of valence 2, the concave one of valence 4 (the rule of
// quad_extraction.h: the quads at it plus one), the others 3. The border vertices that were inside the square
// (the two inner sides of the L) are jittered: the border there is a few degrees off the field, which the
// alignment tolerance accepts, and the constraints still put it on iso-lines (at a small energy).
TEST(QuadFeatures, FlatLWithConcaveCorner)
{
  Soup square = unit_square(8);
  Soup l;
  std::vector<int> used(square.points.size(), -1);
  for(const Tri& t : square.faces) {
    double cx = 0, cy = 0;
    for(int c : t) {
      cx += square.points[c].x() / 3;
      cy += square.points[c].y() / 3;
    }
    if(cx > 0.5 && cy > 0.5)
      continue;
    Tri r = t;
    for(int& c : r) {
      if(used[c] < 0) {
        used[c] = int(l.points.size());
        l.points.push_back(square.points[c]);
      }
      c = used[c];
    }
    l.faces.push_back(r);
  }
  const Quad_case q(to_surface_mesh(l), constant_field({{1., 0., 0.}}));
  ASSERT_EQ(q.view.boundary_loops.size(), 1u);
  for(int k : {2, 4, 6}) {
    const std::string name = "flat L, H = 1/" + std::to_string(k);
    SCOPED_TRACE(name);
    const Extraction_counts c = check_quad_mesh(q, 1. / k, name, border_flags(q));
    EXPECT_EQ(c.folds, 0);
    EXPECT_EQ(c.quads, 3 * k * k / 4);
    EXPECT_EQ(c.non_quads, 0);
    EXPECT_EQ(c.border_valence[2], 5);
    EXPECT_EQ(c.border_valence[4], 1);
    EXPECT_EQ(c.border_valence[3], c.border_vertices - 6);
    EXPECT_EQ(c.border_vertices, 4 * k);
    EXPECT_EQ(c.valence_3 + c.valence_5 + c.other_valence, 0);
  }
}

// an open cylinder of radius r and height h around the z axis, nt x nz squares of two triangles, outward
Soup open_cylinder(double r, double h, int nt, int nz)
{
  Soup s;
  for(int i = 0; i < nt; ++i)
    for(int j = 0; j <= nz; ++j) {
      const double t = 2 * pi * i / nt;
      s.points.emplace_back(r * std::cos(t), r * std::sin(t), h * j / nz);
    }
  auto id = [&](int i, int j) { return (i % nt) * (nz + 1) + j; };
  for(int i = 0; i < nt; ++i)
    for(int j = 0; j < nz; ++j) {
      s.faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      s.faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  return s;
}

// An open cylinder, field along the axis, both borders flagged: neither the circumference (16.98 H) nor the
// height (5.41 H) is a whole number of cells. Quads only, both borders on iso-lines, every border vertex of
// valence 3 (the border is straight in the map), every inner one 4: n_u columns of n_v quads, with n_u the
// border vertices of one loop and n_v + 1 vertices per column.
TEST(QuadFeatures, OpenCylinder)
{
  const double r = 1, h = 2, H = 0.37;
  const Quad_case q(to_surface_mesh(open_cylinder(r, h, 48, 12)), constant_field({{0., 0., 1.}}));
  ASSERT_EQ(q.view.boundary_loops.size(), 2u);
  const Extraction_counts c = check_quad_mesh(q, H, "open cylinder", border_flags(q));
  EXPECT_EQ(c.folds, 0);
  EXPECT_EQ(c.non_quads, 0);
  EXPECT_EQ(c.border_valence[3], c.border_vertices);
  EXPECT_EQ(c.valence_3 + c.valence_5 + c.other_valence, 0);
  ASSERT_EQ(c.border_vertices % 2, 0);
  const int columns = c.border_vertices / 2;
  ASSERT_GT(columns, 0);
  const int rows = c.quads / columns;
  EXPECT_EQ(c.quads, columns * rows);
  EXPECT_TRUE(columns == 17 || columns == 16) << columns << " columns for a circumference of " << 2 * pi * r / H << " H";
  EXPECT_TRUE(rows == 5 || rows == 6) << rows << " rows for a height of " << h / H << " H";
  EXPECT_EQ(c.features_not_followed, 0);
}

// the cube's edges (both ends on one edge line of the unit cube: two coordinates 0 or 1 and equal) and, per
// flagged edge, which of the 12 cube edges it is on (axis, and the two fixed coordinates)
int cube_edge_of(const V3& a, const V3& b)
{
  int fixed = 0, axis = -1, code = 0;
  for(int c = 0; c < 3; ++c) {
    if(a[c] == b[c] && (a[c] == 0 || a[c] == 1)) {
      ++fixed;
      code = 2 * code + int(a[c]);
    } else {
      axis = c;
    }
  }
  return fixed == 2 ? 4 * axis + code : -1;
}

// The cube with its 12 edges flagged as features, on a tessellation the grid does not fit: 5 x 5 squares per
// face and H = 0.4 (2.5 cells per edge). The corners are singular (+1/4), so integer points either way; without
// the flags the iso-lines between them need not follow the edges (reported), with them every edge is a chain of
// quad edges: each cube edge followed by the same number of quad edges as its three parallel ones (a, b, c per
// axis), and the quads are 2 (ab + bc + ca); the eight corners are the only vertices of valence other than 4.
TEST(QuadFeatures, CubeEdgesAsFeatures)
{
  const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, 5);
  const std::vector<int> corners = cube_corners(soup);
  ASSERT_EQ(corners.size(), 8u);
  const Quad_case cube(soup, quarters(corners), true);
  const std::vector<char> features = edges_where(cube, [](const V3& a, const V3& b) { return cube_edge_of(a, b) >= 0; });
  EXPECT_EQ(std::count(features.begin(), features.end(), 1), 12 * 5);
  const double H = 0.4;
  {
    // without the constraints, only reported: how many cube edges the quad edges follow
    TCI::Seamless_parametrization param(cube.arrays, cube.cut, cube.angle, H);
    TCI::Integer_rounding rounding(param, cube.cut);
    const TCI::Seamless_parametrization::Map map = rounding.round(TCI::Rounding_scheme::greedy).map;
    const TCI::Quad_mesh quad = TCI::extract_quad_mesh(cube.arrays, cube.cut, map);
    std::vector<int> along(features.size(), 0);
    for(const auto& a : quad.edge_along)
      for(int e : a)
        ++along[e];
    int followed = 0;
    for(std::size_t e = 0; e < features.size(); ++e)
      followed += features[e] && along[e] >= 1;
    std::cout << "cube, H = 0.4, without feature constraints: " << followed << " of 60 cube-edge mesh edges followed\n";
  }
  TCI::Quad_mesh quad;
  const Extraction_counts c = check_quad_mesh(cube, H, "cube, H = 0.4, 12 feature edges", features, &quad);
  EXPECT_EQ(c.folds, 0);
  EXPECT_EQ(c.non_quads, 0);
  EXPECT_EQ(c.features_not_followed, 0);
  EXPECT_EQ(c.valence_3, 8);
  EXPECT_EQ(c.valence_5 + c.other_valence, 0);
  // quad edges per cube edge
  std::vector<std::set<int>> per_cube_edge(12);
  for(std::size_t e = 0; e < quad.edge_along.size(); ++e)
    for(int x : quad.edge_along[e]) {
      const int i = cube.cut.edge_corner[x];
      const int id = cube_edge_of(V3(cube.arrays.points[cube.arrays.source_of(i)]), V3(cube.arrays.points[cube.arrays.target_of(i)]));
      if(id >= 0)
        per_cube_edge[id].insert(int(e));
    }
  std::array<int, 3> cells = {{0, 0, 0}};
  for(int axis = 0; axis < 3; ++axis) {
    cells[axis] = int(per_cube_edge[4 * axis].size());
    EXPECT_TRUE(cells[axis] == 2 || cells[axis] == 3) << cells[axis] << " quad edges along a cube edge of 2.5 H";
    for(int k = 1; k < 4; ++k)
      EXPECT_EQ(int(per_cube_edge[4 * axis + k].size()), cells[axis]) << "axis " << axis;
  }
  EXPECT_EQ(c.quads, 2 * (cells[0] * cells[1] + cells[1] * cells[2] + cells[2] * cells[0]));
  // the corners are quad vertices at the cube's corners
  int corner_vertices = 0;
  for(std::size_t p = 0; p < quad.points.size(); ++p)
    corner_vertices += std::find(corners.begin(), corners.end(), quad.locations[p].mesh_vertex) != corners.end();
  EXPECT_EQ(corner_vertices, 8);
}

// A field not aligned with a flagged edge (the cube's field turned by 30 degrees) is refused, naming the edge.
TEST(QuadFeatures, MisalignedFeatureIsRefused)
{
  const Soup soup = voxel_surface_soup({{{0, 0, 0}}}, 3);
  const Quad_case cube(soup, quarters(cube_corners(soup)), true);
  const std::vector<char> features = edges_where(cube, [](const V3& a, const V3& b) { return cube_edge_of(a, b) >= 0; });
  std::vector<double> turned_angle(cube.angle);
  for(double& a : turned_angle)
    a += pi / 6;
  try {
    TCI::Seamless_parametrization param(cube.arrays, cube.cut, turned_angle, 0.25, features);
    ADD_FAILURE() << "a field 30 degrees off the feature edges is expected to be refused";
  } catch(const TC::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("not aligned with the feature edge from vertex"), std::string::npos) << e.what();
  }
  // the same turn within a tolerance of 35 degrees is accepted (the tolerance must stay under 45)
  EXPECT_NO_THROW(TCI::Seamless_parametrization(cube.arrays, cube.cut, turned_angle, 0.25, features, 35 * pi / 180));
  EXPECT_THROW(TCI::Seamless_parametrization(cube.arrays, cube.cut, cube.angle, 0.25, std::vector<char>(3, 1)),
               TC::Invalid_input);
}

// A field pinned along the sharp edges through the library's public calls (feature_aligned_faces() at 30 degrees,
// the faces as constrained_faces, the directions as face_directions), singularities placed automatically
// (place_singularities() under the pins), as the program's --auto --align-features; the sharp edges of the kept
// feature curves flagged.
struct Pinned_design
{
  double threshold = 30;
  int pins = 0;
  double seconds = 0;
  void operator()(const Surface_mesh& mesh, const Mesh_view<Surface_mesh>& view, Singularities& singularities,
                  std::vector<double>& x, std::vector<Vector>& field)
  {
    const auto start = std::chrono::steady_clock::now();
    std::vector<Surface_mesh::Face_index> pinned;
    std::map<Surface_mesh::Face_index, Vector> d;
    auto map = boost::make_assoc_property_map(d);
    TC::feature_aligned_faces(mesh, threshold, std::back_inserter(pinned), map, TC::parameters::symmetry_order(4));
    pins = int(pinned.size());
    TC::Trivial_connection_solver<Surface_mesh> solver(mesh, TC::parameters::constrained_faces(pinned));
    const auto np = TC::parameters::face_directions(map, TC::parameters::symmetry_order(4));
    std::vector<std::pair<Surface_mesh::Vertex_index, TC::Singularity_index>> placed;
    TC::place_singularities(solver, std::back_inserter(placed), np);
    for(const auto& p : placed)
      singularities.emplace_back(view.vid.at(p.first), p.second);
    solver.solve(placed, view.halfedge_map(x), np);
    solver.compute_field(view.halfedge_map_const(x), view.face_map(field), np);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

std::vector<char> sharp_edge_flags(const Quad_case& q, double threshold)
{
  std::vector<char> flags(q.cut.edge_corner.size(), 0);
  for(const auto& curve : TC::feature_curves(q.mesh, threshold).curves)
    for(auto h : curve.halfedges)
      flags[q.cut.edge_of_corner[q.arrays.corner_of_edge(edge(h, q.mesh), q.mesh)]] = 1;
  return flags;
}

// An L-shaped block (three unit cubes, 4 x 4 squares per face): convex and concave sharp edges, the field pinned
// to them and its singularities placed automatically; every sharp edge followed by quad edges where fold-free.
TEST(QuadFeatures, PinnedSharpBlock)
{
  Pinned_design design;
  const Quad_case q(to_surface_mesh(voxel_surface_soup({{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}}, 4)), std::ref(design));
  const std::vector<char> features = sharp_edge_flags(q, design.threshold);
  EXPECT_GT(std::count(features.begin(), features.end(), 1), 0);
  std::cout << "L block: " << q.singularities.size() << " singularities placed, " << design.pins << " pinned faces\n";
  const Extraction_counts c = check_quad_mesh(q, 0.3, "L block, H = 0.3, sharp edges", features);
  EXPECT_GT(c.quads, 0);
  if(c.folds == 0) {
    EXPECT_EQ(c.features_not_followed, 0);
  }
}

// fandisk (CGAL's data set), the same design: a measured run. Every sharp edge must be on an integer iso-line and
// followed by a quad edge where the map is fold-free; folds, valence errors and times are reported.
TEST(QuadFeatures, Fandisk)
{
  Surface_mesh tm;
  TC_READ_CGAL_MESH_OR_SKIP("fandisk.off", tm);
  Pinned_design design;
  const Quad_case q(tm, std::ref(design));
  const std::vector<char> features = sharp_edge_flags(q, design.threshold);
  const int flagged = int(std::count(features.begin(), features.end(), 1));
  V3 lo = V3(q.arrays.points[0]), hi = lo;
  for(const auto& a : q.arrays.points)
    for(int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], a[k]);
      hi[k] = std::max(hi[k], a[k]);
    }
  const double H = norm(hi - lo) / 40;
  std::cout << "fandisk: " << q.arrays.nf << " faces, " << q.singularities.size() << " singularities, " << design.pins
            << " pins, " << flagged << " feature edges, " << q.cut.arcs.size() << " arcs; field (pins, placement, "
            << "solve) " << design.seconds << " s; H = diagonal / 40\n";
  const Extraction_counts c = check_quad_mesh(q, H, "fandisk, sharp edges", features, nullptr, 0.1);
  EXPECT_GT(c.quads, 0);
  // the cost of the constraints: the dense system and the solves, with and without the feature lines
  for(bool with : {false, true}) {
    const auto start = std::chrono::steady_clock::now();
    TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H, with ? features : std::vector<char>());
    const double built = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    param.solve();
    const double solved = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    TCI::Integer_rounding rounding(param, q.cut);
    const TCI::Integer_rounding_result r = rounding.round(TCI::Rounding_scheme::greedy);
    const double rounded = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    expect_kept_factor_rounding_is_from_scratch_one(rounding, r, with ? "fandisk, feature lines" : "fandisk");
    const TCI::Quad_mesh quad = TCI::extract_quad_mesh(q.arrays, q.cut, r.map);
    int followed = 0;
    for(const auto& a : quad.edge_along)
      for(int e : a)
        followed += features[e];
    std::cout << "fandisk " << (with ? "with" : "without") << " the feature lines: " << quad.quads << " quads, "
              << quad.non_quads << " other polygons, " << quad.folded_triangles << " folded and "
              << quad.degenerate_triangles << " degenerate triangles, " << followed << " runs along feature edges; "
              << param.constraint_count()
              << " constraint rows, " << param.feature_lines().size() << " lines; built " << built << " s, solved "
              << solved - built << " s, greedy rounding" << (r.naive_fallback ? " (contradicted: the naive one)" : "")
              << " (" << r.integer_unknowns << " unknowns, " << r.solves
              << " solves on " << r.factorizations << " factorizations, " << r.shifted_unknowns << " shifted) "
              << rounded - solved << " s, energy "
              << r.continuous_energy << " -> " << r.map.energy << "\n";
  }
  EXPECT_GT(flagged, 100);
}


// ---- Between layers 3 and 4: the untangling ----

// The winding around every interior vertex (uv_windings()): the (u, v) angles of its corners, folded triangles
// counted negative, sum to the turning of its link, 2 pi (1 - k) plus whole turns (the quarter turns of the
// transitions around it are -4k modulo 4), unless a degenerate triangle has a zero-length edge. On a closed surface
// the whole turns add up to minus the folded triangles: the angles of all corners sum to pi (F+ - F-), those of
// the indices to pi F (Poincare-Hopf, 3F = 2E), so a fold-free map that winds a turn less around one vertex winds
// a turn more around another. A fold-free map that winds once around every vertex has only quads, of valence
// 4 - 4 k at every integer point (the extraction's definition). Returns the vertices wound otherwise.
int check_winding(const Quad_case& q, const TCI::Seamless_parametrization::Map& map, const TCI::Quad_mesh& quad,
                  const std::string& name)
{
  const std::vector<long long> k4 = scaled_indices(q.view.nv(), q.singularities, 4);
  const std::vector<double> sum = TCI::uv_windings(q.arrays, map).angle_sum;
  int wrong = 0;
  long total_turns = 0;
  bool closed = true;
  for(int v = 0; v < q.arrays.nv; ++v) {
    if(q.geometry.on_boundary[std::size_t(v)]) {
      closed = false;
      continue;
    }
    const double turns = (sum[std::size_t(v)] - 2 * CGAL_PI * (1 - double(k4[std::size_t(v)]) / 4)) / (2 * CGAL_PI);
    if(quad.degenerate_triangles == 0)
      EXPECT_NEAR(turns, std::round(turns), 1e-9) << name << ": vertex " << v;
    wrong += std::lround(turns) != 0;
    total_turns += std::lround(turns);
  }
  if(closed && quad.degenerate_triangles == 0)
    EXPECT_EQ(total_turns, -quad.folded_triangles) << name;
  if(wrong == 0 && quad.folded_triangles + quad.degenerate_triangles == 0) {
    EXPECT_EQ(quad.non_quads, 0) << name;
    for(std::size_t p = 0; p < quad.valence.size(); ++p) {
      const int v = quad.locations[p].mesh_vertex;
      if(!quad.on_border[p])
        EXPECT_EQ(quad.valence[p], 4 - (v >= 0 ? k4[std::size_t(v)] : 0)) << name << ": integer point " << p;
    }
  }
  return wrong;
}

// The untangled map of a greedy rounding, checked from the definitions: the same integers (every singular corner
// the same integer point, the same roots and translations), still an integer-grid map across every cut edge, the
// feature edges still on their iso-lines, no closer to the field than the rounded map (the least-squares minimiser
// over exactly these maps: lower would mean it left them), and fewer folded and degenerate triangles, counted by
// the extraction itself. Returns the quad mesh of the untangled map.
TCI::Quad_mesh check_untangling(const Quad_case& q, double H, const std::string& name,
                                const std::vector<char>& features = {})
{
  TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H, features);
  TCI::Integer_rounding rounding(param, q.cut);
  const TCI::Integer_rounding_result rounded = rounding.round(TCI::Rounding_scheme::greedy);
  const TCI::Quad_mesh before = TCI::extract_quad_mesh(q.arrays, q.cut, rounded.map);
  const TCI::Untangling_result u = TCI::Map_untangling(param).untangle(rounded.map);
  EXPECT_EQ(u.inverted_before, before.folded_triangles + before.degenerate_triangles) << name;
  const TCI::Quad_mesh after = TCI::extract_quad_mesh(q.arrays, q.cut, u.map);
  EXPECT_EQ(u.inverted_after, after.folded_triangles + after.degenerate_triangles) << name;
  std::cout << name << ": " << u.inverted_before << " folded and degenerate triangles -> " << u.inverted_after
            << " (" << u.rounds << " rounds, " << u.iterations << " iterations, " << u.seconds << " s), energy "
            << rounded.map.energy << " -> " << u.map.energy << "; other polygons " << before.non_quads << " -> "
            << after.non_quads << ", open edges " << before.open_edges << " -> " << after.open_edges << "\n";
  std::cout << name << ": vertices wound the wrong number of times: " << check_winding(q, rounded.map, before, name + " (rounded)")
            << " in the rounded map, " << check_winding(q, u.map, after, name) << " in the untangled one\n";
  if(u.inverted_before == 0) {
    EXPECT_FALSE(u.applied) << name;
    return after;
  }
  EXPECT_TRUE(u.applied) << name;
  EXPECT_LT(u.inverted_after, u.inverted_before) << name;
  EXPECT_LT(integer_grid_error(q, u.map), 1e-7) << name;
  EXPECT_LT(transition_error(q, u.map), 1e-7) << name;
  EXPECT_GE(u.map.energy, rounded.map.energy * (1 - 1e-9)) << name;
  EXPECT_NEAR(independent_energy(q, H, u.map.corner_uv), u.map.energy, 1e-9 * (1 + u.map.energy)) << name;
  for(std::size_t v = 0; v < rounded.map.root_uv.size(); ++v)
    if(q.cut.is_singular[v] || q.cut.holonomy[v] != 0)
      for(int k = 0; k < 2; ++k)
        EXPECT_NEAR(u.map.root_uv[v][k], rounded.map.root_uv[v][k], 1e-9) << name << ": root of vertex " << v;
  for(std::size_t a = 0; a < rounded.map.translation.size(); ++a)
    for(int k = 0; k < 2; ++k)
      EXPECT_NEAR(u.map.translation[a][k], rounded.map.translation[a][k], 1e-9) << name << ": arc " << a;
  // each feature edge on an integer iso-line in the chart of one of its faces (the other one inside an acute
  // sector), as in the rounded map
  for(std::size_t e = 0; e < features.size(); ++e) {
    if(!features[e])
      continue;
    bool on_line = false;
    for(int i : {q.cut.edge_corner[e], q.arrays.opposite_corner[q.cut.edge_corner[e]]}) {
      if(i < 0)
        continue;
      const auto& a = u.map.corner_uv[i];
      const auto& b = u.map.corner_uv[TCI::Mesh_arrays<Surface_mesh>::next_corner(i)];
      for(int k = 0; k < 2; ++k)
        on_line = on_line || (std::abs(a[k] - b[k]) < 1e-9 && std::abs(a[k] - std::round(a[k])) < 1e-9);
    }
    EXPECT_TRUE(on_line) << name << ": feature edge " << e << " is not on an integer iso-line";
  }
  return after;
}

// quad_cone_mode_weight (the pipeline's two stages): on the layers' warped torus and genus-2 surface the map of
// the single stage winds a turn less around a -1/4 vertex (the least squares use its harmonic z^(1/4)). With the
// cone modes penalised and the rightly wound one-rings held, every singular vertex is wound as its index asks
// (the (u, v) angles of its corners, uv_windings(), from the definitions) and the map is still an integer-grid map.
// On genus 2 the map is then fold-free and wound once around every vertex (check_winding()). On the warped torus,
// whose triangles are larger than H, the continuous untangling keeps one fold beside vertex 150 that its held
// one-ring blocks (without the hold it unfolds and winds 150 wrongly again): a limit of the stages, printed.
// The one-ring's Fourier coefficients (1 / 2 pi) sum of (w - w_v) e^{-i (j - k) phi} d phi (trapezoidal, each ring
// value divided by (r / mean)^((1 - k) 2 pi / angle sum)), computed here from the corners' (u, v) alone: the ring
// differences of each face brought into the chart of the fan's first face by the quarter turn that matches the two
// copies of the edge it shares with the previous face (the map is seamless: they differ by exactly that).
std::vector<std::complex<double>> independent_cone_coefficients(const Quad_case& q,
                                                                const std::vector<std::array<double, 2>>& uv, int v,
                                                                int k4, const std::vector<int>& harmonics)
{
  using MA = TCI::Mesh_arrays<Surface_mesh>;
  const MA& m = q.arrays;
  int first = -1;
  for(int c = 0; c < 3 * m.nf && first < 0; ++c)
    if(m.source_of(c) == v)
      first = c;
  std::vector<int> fan;
  for(int c = first;;) {
    fan.push_back(c);
    c = m.opposite_corner[MA::prev_corner(c)];
    if(c == first)
      break;
  }
  const auto w = [&](int c) { return std::complex<double>(uv[std::size_t(c)][0], uv[std::size_t(c)][1]); };
  const auto at = [&](int c) { return m.points[m.source_of(c)]; };
  std::vector<std::array<std::complex<double>, 2>> d;
  std::vector<std::array<double, 2>> radius;
  std::vector<double> angle;
  double total = 0, mean = 0;
  std::complex<double> chart(1, 0);
  for(std::size_t t = 0; t < fan.size(); ++t) {
    const int c = fan[t], a = MA::next_corner(c), b = MA::prev_corner(c);
    const V3 ea = Quad_case::q_sub(at(a), at(c)), eb = Quad_case::q_sub(at(b), at(c));
    angle.push_back(std::acos(std::clamp(TCI::dot(ea, eb) / (norm(ea) * norm(eb)), -1., 1.)));
    total += angle.back();
    mean += norm(ea) / double(fan.size());
    radius.push_back({{norm(ea), norm(eb)}});
    if(t > 0) { // this face's copy of the shared edge against the previous face's, both in their own charts
      const std::complex<double> turn = d.back()[1] / (w(a) - w(c));
      const double quarter = std::round(std::arg(turn) / (CGAL_PI / 2));
      EXPECT_NEAR(std::abs(turn - std::polar(1., quarter * CGAL_PI / 2)), 0., 1e-8) << "vertex " << v;
      chart = std::polar(1., quarter * CGAL_PI / 2);
    }
    d.push_back({{chart * (w(a) - w(c)), chart * (w(b) - w(c))}});
  }
  const double k = k4 / 4., exponent = (1 - k) * 2 * CGAL_PI / total;
  std::vector<std::complex<double>> coefficient;
  for(int j : harmonics) {
    std::complex<double> sum = 0;
    double phi = 0;
    for(std::size_t t = 0; t < fan.size(); ++t) {
      const double delta = 2 * CGAL_PI * angle[t] / total;
      for(int s = 0; s < 2; ++s)
        sum += delta / 2 * d[t][std::size_t(s)] * std::polar(1., -(j - k) * (phi + s * delta)) /
               std::pow(radius[t][std::size_t(s)] / mean, exponent);
      phi += delta;
    }
    coefficient.push_back(sum / (2 * CGAL_PI));
  }
  return coefficient;
}

// Seamless_parametrization::cone_harmonic_rows() computes those coefficients (in the root's chart: the same up to
// one quarter turn per vertex), and penalise_cone_modes() lowers the penalised ones as the weight grows (the
// penalty of a weighted least squares never rises with its weight) while the cone's own, j = 1, stays.
TEST(QuadUntangling, ConeHarmonicRows)
{
  const Soup soup = genus2_soup(3);
  const Quad_case q(soup, genus_two_singularities(soup));
  const std::vector<long long> k4 = scaled_indices(q.view.nv(), q.singularities, 4);
  std::vector<std::pair<int, int>> cones;
  for(int v = 0; v < q.arrays.nv; ++v)
    if(k4[std::size_t(v)] != 0)
      cones.emplace_back(v, int(k4[std::size_t(v)]));
  ASSERT_FALSE(cones.empty());
  const double H = 0.2;
  const std::vector<int> harmonics = {1, 0, -1};
  double previous_penalty = std::numeric_limits<double>::infinity(), first_penalty = 0, last_penalty = 0;
  double first_cone = 0;
  for(double weight : {0., 1., 10., 100., 1000.}) {
    TCI::Seamless_parametrization param(q.arrays, q.cut, q.angle, H);
    if(weight > 0)
      param.penalise_cone_modes(q.arrays, cones, weight);
    const TCI::Seamless_parametrization::Map map = param.solve();
    Eigen::VectorXd x(2 * map.corner_uv.size());
    for(std::size_t c = 0; c < map.corner_uv.size(); ++c)
      x.segment<2>(2 * Eigen::Index(c)) = Eigen::Vector2d(map.corner_uv[c][0], map.corner_uv[c][1]);
    double penalty = 0, cone = std::numeric_limits<double>::infinity();
    for(const auto& [v, k] : cones) {
      std::vector<Eigen::Triplet<double>> t;
      param.cone_harmonic_rows(q.arrays, v, k, harmonics, 0, 1., t);
      Eigen::SparseMatrix<double> rows(2 * Eigen::Index(harmonics.size()), x.size());
      rows.setFromTriplets(t.begin(), t.end());
      const Eigen::VectorXd y = rows * x;
      const std::vector<std::complex<double>> expected = independent_cone_coefficients(q, map.corner_uv, v, k, harmonics);
      std::complex<double> chart = 0; // root chart against the fan's first face: one quarter turn for all j
      for(std::size_t h = 0; h < harmonics.size(); ++h) {
        const std::complex<double> got(y[2 * Eigen::Index(h)], y[2 * Eigen::Index(h) + 1]);
        EXPECT_NEAR(std::abs(got), std::abs(expected[h]), 1e-9 * (1 + std::abs(expected[h])))
          << "vertex " << v << ", j = " << harmonics[h] << ", weight " << weight;
        if(std::abs(expected[h]) > 1e-6) {
          if(chart == 0.)
            chart = got / expected[h];
          EXPECT_NEAR(std::abs(got - chart * expected[h]), 0., 1e-9 * (1 + std::abs(got))) << "vertex " << v;
        }
        if(harmonics[h] == 0 || (harmonics[h] == -1 && k < 0))
          penalty += std::norm(expected[h]);
      }
      cone = std::min(cone, std::abs(expected[0]));
    }
    std::cout << "weight " << weight << ": penalised coefficients, sum of squares " << penalty
              << "; smallest cone coefficient (j = 1) " << cone << "\n";
    EXPECT_LE(penalty, previous_penalty * (1 + 1e-9) + 1e-15) << "weight " << weight;
    if(weight == 0) {
      first_penalty = penalty;
      first_cone = cone;
    }
    EXPECT_GT(cone, 0.5 * first_cone) << "weight " << weight << ": the cone's own harmonic stays";
    last_penalty = penalty;
    previous_penalty = penalty;
  }
  EXPECT_LT(last_penalty, 0.01 * first_penalty);
}

TEST(QuadUntangling, ConeModes)
{
  auto run = [](const Quad_case& q, double H, double weight) {
    std::vector<int> singular;
    const std::vector<long long> k4 = scaled_indices(q.view.nv(), q.singularities, 4);
    for(int v = 0; v < q.arrays.nv; ++v)
      if(k4[std::size_t(v)] != 0)
        singular.push_back(v);
    TCI::Quad_field field{q.angle, q.connection};
    return TCI::quad_mesh_pipeline(q.arrays, q.geometry, field, singular, k4, H, TCI::Rounding_scheme::greedy, 1e7,
                                   {}, 0., true, weight);
  };
  const Quad_case torus(warped(torus_soup(3, 1, 24, 12)), {{5, Index(1, 4)}, {150, Index(-1, 4)}});
  const Soup soup = genus2_soup(3);
  const Quad_case genus2(soup, genus_two_singularities(soup));
  for(const auto& [q, H, name] : {std::make_tuple(&torus, 0.3, std::string("warped torus")),
                                  std::make_tuple(&genus2, 0.2, std::string("genus 2"))}) {
    const TCI::Quad_pipeline_result plain = run(*q, H, 0);
    const TCI::Quad_pipeline_result modes = run(*q, H, 30);
    const int wrong_plain = check_winding(*q, plain.untangling.map, plain.mesh, name + " (single stage)");
    const int wrong = check_winding(*q, modes.untangling.map, modes.mesh, name + " (cone modes)");
    std::cout << name << ": wrongly wound vertices " << wrong_plain << " -> " << wrong << ", folded and degenerate "
              << plain.mesh.folded_triangles + plain.mesh.degenerate_triangles << " -> "
              << modes.mesh.folded_triangles + modes.mesh.degenerate_triangles << ", valence errors (non-quads) "
              << plain.mesh.non_quads << " -> " << modes.mesh.non_quads << "\n";
    EXPECT_GT(wrong_plain, 0) << name << ": the case no longer shows what the stages are for";
    const std::vector<long long> k4 = scaled_indices(q->view.nv(), q->singularities, 4);
    const TCI::Uv_windings winding = TCI::uv_windings(q->arrays, modes.untangling.map);
    for(int v = 0; v < q->arrays.nv; ++v)
      if(k4[std::size_t(v)] != 0) {
        const double turns = (winding.angle_sum[std::size_t(v)] - 2 * CGAL_PI * (1 - double(k4[std::size_t(v)]) / 4)) /
                             (2 * CGAL_PI);
        EXPECT_FALSE(winding.beside_inverted[std::size_t(v)]) << name << ": singular vertex " << v;
        EXPECT_NEAR(turns, 0., 1e-9) << name << ": singular vertex " << v;
      }
    if(name == "genus 2") {
      EXPECT_EQ(wrong, 0) << name;
      EXPECT_EQ(modes.mesh.folded_triangles + modes.mesh.degenerate_triangles, 0) << name;
    }
    EXPECT_TRUE(modes.cone_modes) << name;
    EXPECT_LT(integer_grid_error(*q, modes.untangling.map), 1e-7) << name;
    EXPECT_LT(transition_error(*q, modes.untangling.map), 1e-7) << name;
  }
}

// The rounded maps of the layers' meshes that fold (a singular root moved to an integer point drags only its
// nearest triangles along) and fandisk's with its feature lines: fewer folds, the same integer-grid map.
TEST(QuadUntangling, FoldsOfRoundedMaps)
{
  {
    const Quad_case q(warped(torus_soup(3, 1, 24, 12)), {{5, Index(1, 4)}, {150, Index(-1, 4)}});
    const TCI::Quad_mesh quad = check_untangling(q, 0.3, "warped torus, +1/4 and -1/4");
    EXPECT_EQ(quad.folded_triangles + quad.degenerate_triangles, 0);
  }
  {
    const Soup soup = genus2_soup(3);
    const Quad_case q(soup, genus_two_singularities(soup));
    const TCI::Quad_mesh quad = check_untangling(q, 0.2, "genus 2, eight -1/4");
    EXPECT_EQ(quad.folded_triangles + quad.degenerate_triangles, 0);
  }
  {
    Surface_mesh tm;
    TC_READ_CGAL_MESH_OR_SKIP("fandisk.off", tm);
    Pinned_design design;
    const Quad_case q(tm, std::ref(design));
    const std::vector<char> features = sharp_edge_flags(q, design.threshold);
    V3 lo = V3(q.arrays.points[0]), hi = lo;
    for(const auto& a : q.arrays.points)
      for(int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], a[k]);
        hi[k] = std::max(hi[k], a[k]);
      }
    check_untangling(q, norm(hi - lo) / 40, "fandisk, sharp edges", features);
  }
}

} // namespace
