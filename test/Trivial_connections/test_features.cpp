// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// Feature alignment (feature_alignment.h), against answers the geometry fixes: a cube built here, its faces split
// into triangles with their inner vertices jittered in the faces' planes, has twelve curves (its edges), every face
// with an edge on one is pinned along that edge, the pins agree exactly for n = 4, and the trivial connection with
// a +1/4 at each corner follows them at zero energy; a straight crease meshed as a zigzag is one curve whose fitted
// directions agree where each edge's own do not; the result does not depend on the numbering; bad thresholds are
// errors; a smooth mesh gives nothing.

#include "test_support.h"

#include <CGAL/Trivial_connections/feature_alignment.h>

using namespace tc_test;

namespace {

/// The cube [0,1]^3, each face a k x k grid of squares split along a diagonal, the grid's inner vertices moved by
/// up to `jitter` / k inside their face (the vertices on the cube's edges stay on them)
Soup jittered_cube(int k, double jitter, unsigned seed = 1)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-jitter / k, jitter / k);
  Soup s;
  std::map<std::array<int, 3>, int> id;
  auto vertex = [&](const std::array<int, 3>& g, bool inner, int du, int dv) {
    const auto it = id.find(g);
    if(it != id.end())
      return it->second;
    double c[3] = {double(g[0]) / k, double(g[1]) / k, double(g[2]) / k};
    if(inner) {
      c[du] += offset(rng);
      c[dv] += offset(rng);
    }
    id[g] = int(s.points.size());
    s.points.push_back(Point(c[0], c[1], c[2]));
    return int(s.points.size()) - 1;
  };
  for(int d = 0; d < 3; ++d)
    for(int side = 0; side < 2; ++side) {
      // (u, v) with u x v the outward normal
      int du = (d + 1) % 3, dv = (d + 2) % 3;
      if(side == 0)
        std::swap(du, dv);
      auto at = [&](int a, int b) {
        std::array<int, 3> g{};
        g[d] = side * k;
        g[du] = a;
        g[dv] = b;
        return vertex(g, a > 0 && a < k && b > 0 && b < k, du, dv);
      };
      for(int a = 0; a < k; ++a)
        for(int b = 0; b < k; ++b) {
          const int p00 = at(a, b), p10 = at(a + 1, b), p11 = at(a + 1, b + 1), p01 = at(a, b + 1);
          s.faces.push_back({{p00, p10, p11}});
          s.faces.push_back({{p00, p11, p01}});
        }
    }
  return s;
}

/// A roof: two planes z = -|y| meeting at a right angle along the x axis, x in [0, L h], y in [-J h, J h], on a grid
/// of squares of side h split along alternating diagonals, with the vertices of the crease row moved to y = +-delta
/// in turn (and onto the roof): the crease is a zigzag of edges.
Soup zigzag_roof(int L, int J, double delta)
{
  const double h = 1;
  Soup s;
  auto index = [&](int i, int j) { return i * (2 * J + 1) + (j + J); };
  for(int i = 0; i <= L; ++i)
    for(int j = -J; j <= J; ++j) {
      const double y = j * h + (j == 0 ? (i % 2 == 0 ? delta : -delta) : 0.);
      s.points.push_back(Point(i * h, y, -std::abs(y)));
    }
  for(int i = 0; i < L; ++i)
    for(int j = -J; j < J; ++j) {
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      if((i + j) % 2 == 0) {
        s.faces.push_back({{a, b, c}});
        s.faces.push_back({{a, c, d}});
      } else {
        s.faces.push_back({{a, b, d}});
        s.faces.push_back({{b, c, d}});
      }
    }
  return s;
}

struct Pins
{
  TC::Feature_alignment_report report;
  std::vector<Surface_mesh::Face_index> faces;
  std::map<Surface_mesh::Face_index, V3> direction;
};

template <class NP>
Pins pins_of(const Surface_mesh& m, double threshold, const NP& np)
{
  Pins p;
  std::map<Surface_mesh::Face_index, Vector> d;
  p.report = TC::feature_aligned_faces(m, threshold, std::back_inserter(p.faces), boost::make_assoc_property_map(d), np);
  for(const auto& [f, v] : d)
    p.direction[f] = {{v.x(), v.y(), v.z()}};
  return p;
}

V3 point_of(const Surface_mesh& m, Surface_mesh::Vertex_index v)
{
  const Point& p = m.point(v);
  return {{p.x(), p.y(), p.z()}};
}

V3 normal_of(const Surface_mesh& m, Surface_mesh::Face_index f)
{
  const auto h = m.halfedge(f);
  const V3 a = point_of(m, m.source(h)), b = point_of(m, m.target(h)), c = point_of(m, m.target(m.next(h)));
  return unit(cross(b - a, c - a));
}

/// the angle between two tangent directions of a face modulo 2 pi / n, in [0, pi / n]
double angle_mod(const V3& u, const V3& w, int n)
{
  const double period = two_pi / n;
  double a = std::fmod(std::abs(std::atan2(norm(cross(u, w)), dot(u, w))), period);
  return std::min(a, period - a);
}

/// the cube edge an edge of the grid lies on: both ends have the same two coordinates in {0, 1}
bool on_cube_edge(const V3& a, const V3& b)
{
  int shared = 0;
  for(int i = 0; i < 3; ++i)
    shared += a[i] == b[i] && (a[i] == 0 || a[i] == 1);
  return shared >= 2;
}

template <class F>
void expect_invalid_argument(F&& f, const std::string& fragment)
{
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch(const TC::Invalid_input& e) {
    EXPECT_EQ(e.code(), TC::Error_code::invalid_argument) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

} // namespace

TEST(Feature_alignment, jittered_cube_twelve_curves_pins_along_the_edges)
{
  const int k = 5;
  const Surface_mesh m = to_surface_mesh(jittered_cube(k, 0.3));
  const TC::Feature_curves<Surface_mesh> curves = TC::feature_curves(m);
  ASSERT_EQ(curves.curves.size(), 12u);
  EXPECT_EQ(curves.number_of_sharp_edges, 12u * k);
  EXPECT_EQ(curves.dropped_curves, 0u);
  for(const auto& c : curves.curves) {
    EXPECT_EQ(c.halfedges.size(), std::size_t(k));
    EXPECT_NEAR(c.length, 1., 1e-12);
  }
  for(int n : {1, 2, 4}) {
    const Pins p = pins_of(m, TC::default_feature_angle_degrees, TC::parameters::symmetry_order(n));
    std::size_t expected = 0;
    for(auto f : faces(m)) {
      std::vector<V3> along; // the cube edges the face has
      for(auto h : CGAL::halfedges_around_face(m.halfedge(f), m)) {
        const V3 a = point_of(m, m.source(h)), b = point_of(m, m.target(h));
        if(on_cube_edge(a, b))
          along.push_back(unit(b - a));
      }
      if(along.empty()) {
        EXPECT_EQ(p.direction.count(f), 0u) << "face " << f;
        continue;
      }
      ++expected;
      ASSERT_EQ(p.direction.count(f), 1u) << "face " << f;
      const V3 d = p.direction.at(f);
      EXPECT_NEAR(norm(d), 1., 1e-12);
      double best = 1;
      for(const V3& e : along) {
        best = std::min(best, norm(cross(d, e)));
        if(n == 4) { // a cross along one cube edge is along the other
          EXPECT_LT(std::min(norm(cross(d, e)), std::abs(dot(d, e))), 1e-12) << "face " << f;
        }
      }
      if(along.size() == 1 || n != 1) // n = 1: the mean of two perpendicular unit vectors is their bisector
        EXPECT_LT(best, 1e-12) << "face " << f << " n = " << n;
      else
        EXPECT_NEAR(std::abs(dot(d, along[0])), std::sqrt(0.5), 1e-12) << "face " << f;
    }
    EXPECT_EQ(p.faces.size(), expected);
    EXPECT_EQ(p.report.number_of_pinned_faces, expected);
    EXPECT_EQ(p.report.number_of_curves, 12u);
    // per cube face, the triangles of the two corner cells the diagonal does not cut: two cube edges each
    EXPECT_EQ(p.report.faces_with_several_edges, 12u);
    EXPECT_GT(p.report.neighbouring_pairs, 0u);
    if(n == 4) {
      EXPECT_EQ(p.report.disagreeing_pairs, 0u);
      EXPECT_LT(p.report.max_disagreement_degrees, 1e-9);
    }
  }
}

TEST(Feature_alignment, cube_field_follows_the_pins_at_zero_energy)
{
  const Surface_mesh m = to_surface_mesh(jittered_cube(4, 0.3, 7));
  std::vector<Surface_mesh::Face_index> pinned;
  std::map<Surface_mesh::Face_index, Vector> d;
  auto map = boost::make_assoc_property_map(d);
  TC::feature_aligned_faces(m, 30., std::back_inserter(pinned), map, TC::parameters::symmetry_order(4));
  TC::Trivial_connection_solver<Surface_mesh> solver(m, TC::parameters::constrained_faces(pinned));
  std::vector<std::pair<Surface_mesh::Vertex_index, TC::Singularity_index>> corners;
  for(auto v : vertices(m)) {
    const Point& p = m.point(v);
    if((p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1) && (p.z() == 0 || p.z() == 1))
      corners.emplace_back(v, TC::Singularity_index(1, 4));
  }
  ASSERT_EQ(corners.size(), 8u);
  Surface_mesh copy = m;
  auto x = copy.add_property_map<Surface_mesh::Halfedge_index, double>("h:x", 0.).first;
  auto field = copy.add_property_map<Surface_mesh::Face_index, Vector>("f:field").first;
  const auto np = TC::parameters::symmetry_order(4, TC::parameters::face_directions(map));
  const TC::Solve_report r = solver.solve(corners, x, np);
  EXPECT_LT(r.energy, 1e-20);
  EXPECT_LT(r.max_constraint_residual, 1e-9);
  solver.compute_field(x, field, np);
  for(auto f : pinned) {
    const V3 u = {{field[f].x(), field[f].y(), field[f].z()}};
    const V3 t = {{d[f].x(), d[f].y(), d[f].z()}};
    EXPECT_LT(angle_mod(u, t, 4), 1e-9) << "face " << f;
  }
}

TEST(Feature_alignment, zigzag_crease_is_one_curve_and_its_fitted_directions_agree)
{
  const Surface_mesh m = to_surface_mesh(zigzag_roof(24, 4, 0.25));
  const TC::Feature_curves<Surface_mesh> curves = TC::feature_curves(m);
  ASSERT_EQ(curves.curves.size(), 1u);
  EXPECT_GE(curves.number_of_sharp_edges, 24u);
  const Pins naive = pins_of(m, 30., TC::parameters::symmetry_order(4, TC::parameters::feature_smoothing(0)));
  const Pins fitted = pins_of(m, 30., TC::parameters::symmetry_order(4));
  ASSERT_EQ(naive.faces, fitted.faces);
  ASSERT_GT(fitted.faces.size(), 40u);
  // the naive pins follow each edge of the zigzag (atan(0.5) = 26.6 degrees off the crease); the fitted ones follow
  // the crease, the x axis, within a few degrees except near its two ends
  double worst_naive = 0, worst_fitted = 0;
  for(auto f : fitted.faces) {
    const V3 N = normal_of(m, f);
    const V3 x = unit(V3{{1., 0., 0.}} - dot(V3{{1., 0., 0.}}, N) * N); // the crease's direction in the face
    bool middle = true;
    for(auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      middle = middle && m.point(v).x() >= 3 && m.point(v).x() <= 21;
    if(!middle)
      continue;
    worst_naive = std::max(worst_naive, angle_mod(naive.direction.at(f), x, 4));
    worst_fitted = std::max(worst_fitted, angle_mod(fitted.direction.at(f), x, 4));
  }
  EXPECT_GT(worst_naive * 180 / pi, 20.);
  EXPECT_LT(worst_fitted * 180 / pi, 3.);
  EXPECT_GT(naive.report.disagreeing_pairs, fitted.report.disagreeing_pairs);
  EXPECT_GT(naive.report.max_disagreement_degrees, 20.);
  EXPECT_LT(fitted.report.max_disagreement_degrees, 5.);
}

/// A crease that turns back: the plane z = 0 in the wedge |phi| <= 10 degrees (polar angle about the apex at the
/// origin), and z = the distance to the wedge outside it (two planes at 45 degrees beside its rays, a cone behind
/// the apex). A polar mesh of R rings, rays every 20 degrees from 10: the wedge's two rays are chains of sharp edges
/// that leave the apex 20 degrees apart, and the wedge's first face is the apex's sector between them.
Soup turning_back_crease(int R)
{
  Soup s;
  const int rays = 18;
  s.points.push_back(Point(0, 0, 0));
  for(int i = 1; i <= R; ++i)
    for(int j = 0; j < rays; ++j) {
      const double phi = (10. + 20. * j) * pi / 180, off = std::abs(std::remainder(phi, two_pi)) - pi / 18;
      const double z = off <= 0 ? 0. : off <= pi / 2 ? i * std::sin(off) : double(i);
      s.points.push_back(Point(i * std::cos(phi), i * std::sin(phi), z));
    }
  auto at = [&](int i, int j) { return 1 + (i - 1) * rays + (j % rays); };
  for(int j = 0; j < rays; ++j)
    s.faces.push_back({{0, at(1, j), at(1, j + 1)}});
  for(int i = 1; i < R; ++i)
    for(int j = 0; j < rays; ++j) {
      s.faces.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}});
      s.faces.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}});
    }
  return s;
}

// The sector rule at a cusp: the two rays are two curves (the apex is a corner, though its sharp edges lie along
// one line to a covariance), and for n = 4 the apex's sector face is pinned half way along the turn of 90 - 20
// degrees that puts one quad corner in the sector (35 degrees from each ray's cross), not along the short way (10
// degrees from each, the bisector), which n = 2 keeps.
TEST(Feature_alignment, crease_turning_back_is_a_corner_with_a_quad_corner_in_its_sector)
{
  const Surface_mesh m = to_surface_mesh(turning_back_crease(6));
  const TC::Feature_curves<Surface_mesh> curves = TC::feature_curves(m);
  ASSERT_EQ(curves.number_of_sharp_edges, 12u);
  ASSERT_EQ(curves.curves.size(), 2u);
  EXPECT_EQ(curves.curves[0].halfedges.size(), 6u);
  const V3 ray_a{{std::cos(pi / 18), std::sin(pi / 18), 0.}}, ray_b{{std::cos(pi / 18), -std::sin(pi / 18), 0.}};
  Surface_mesh::Face_index tip;
  for(auto f : faces(m)) {
    bool at_apex = false, beside_wedge = true;
    for(auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      at_apex = at_apex || v == Surface_mesh::Vertex_index(0);
      beside_wedge = beside_wedge && std::abs(m.point(v).z()) < 1e-12;
    }
    if(at_apex && beside_wedge)
      tip = f;
  }
  ASSERT_NE(tip, Surface_mesh::null_face());
  const Pins cross = pins_of(m, 30., TC::parameters::symmetry_order(4));
  ASSERT_EQ(cross.direction.count(tip), 1u);
  EXPECT_NEAR(angle_mod(cross.direction.at(tip), ray_a, 4) * 180 / pi, 35., 1e-6);
  EXPECT_NEAR(angle_mod(cross.direction.at(tip), ray_b, 4) * 180 / pi, 35., 1e-6);
  // the faces beside one ray follow it
  for(auto f : cross.faces) {
    if(f == tip)
      continue;
    double best = pi;
    for(const V3& ray : {ray_a, ray_b}) {
      const V3 N = normal_of(m, f), t = unit(ray - dot(ray, N) * N);
      best = std::min(best, angle_mod(cross.direction.at(f), t, 4));
    }
    EXPECT_LT(best * 180 / pi, 1e-6) << "face " << f;
  }
  const Pins line = pins_of(m, 30., TC::parameters::symmetry_order(2));
  EXPECT_NEAR(angle_mod(line.direction.at(tip), ray_a, 2) * 180 / pi, 10., 1e-6);
  EXPECT_NEAR(angle_mod(line.direction.at(tip), ray_b, 2) * 180 / pi, 10., 1e-6);
}

TEST(Feature_alignment, independent_of_vertex_and_face_numbering)
{
  for(const Soup& soup : {jittered_cube(4, 0.3, 3), zigzag_roof(16, 3, 0.25)}) {
    const Surface_mesh m = to_surface_mesh(soup);
    const Pins p = pins_of(m, 30., TC::parameters::symmetry_order(4));
    // each face of the original by its sorted vertices, in the renumbered mesh's numbers
    for(unsigned seed : {1u, 2u}) {
      std::vector<int> perm;
      const Soup r = renumbered(soup, seed, &perm, true);
      const Surface_mesh mr = to_surface_mesh(r);
      const Pins q = pins_of(mr, 30., TC::parameters::symmetry_order(4));
      EXPECT_EQ(q.report.number_of_sharp_edges, p.report.number_of_sharp_edges);
      EXPECT_EQ(q.report.number_of_curves, p.report.number_of_curves);
      EXPECT_EQ(q.report.number_of_pinned_faces, p.report.number_of_pinned_faces);
      EXPECT_EQ(q.report.faces_with_several_edges, p.report.faces_with_several_edges);
      EXPECT_EQ(q.report.disagreeing_pairs, p.report.disagreeing_pairs);
      EXPECT_NEAR(q.report.max_disagreement_degrees, p.report.max_disagreement_degrees, 1e-9);
      std::map<std::array<int, 3>, Surface_mesh::Face_index> face_of;
      for(auto f : faces(mr)) {
        std::array<int, 3> key{};
        int i = 0;
        for(auto v : CGAL::vertices_around_face(mr.halfedge(f), mr))
          key[i++] = int(v);
        std::sort(key.begin(), key.end());
        face_of[key] = f;
      }
      for(const auto& [f, d] : p.direction) {
        std::array<int, 3> key{};
        int i = 0;
        for(auto v : CGAL::vertices_around_face(m.halfedge(f), m))
          key[i++] = perm[std::size_t(v)];
        std::sort(key.begin(), key.end());
        ASSERT_EQ(q.direction.count(face_of.at(key)), 1u);
        EXPECT_LT(angle_mod(d, q.direction.at(face_of.at(key)), 4), 1e-9);
      }
    }
  }
}

TEST(Feature_alignment, bad_thresholds_and_parameters_are_errors)
{
  const Surface_mesh m = to_surface_mesh(jittered_cube(2, 0.2));
  std::vector<Surface_mesh::Face_index> out;
  std::map<Surface_mesh::Face_index, Vector> d;
  auto map = boost::make_assoc_property_map(d);
  for(double bad : {-1., -1e-9, 180.5, 1e300, std::numeric_limits<double>::quiet_NaN(),
                    std::numeric_limits<double>::infinity()}) {
    expect_invalid_argument([&] { TC::feature_curves(m, bad); }, "threshold");
    expect_invalid_argument([&] { TC::feature_aligned_faces(m, bad, std::back_inserter(out), map); }, "threshold");
  }
  expect_invalid_argument(
    [&] { TC::feature_aligned_faces(m, 30., std::back_inserter(out), map, TC::parameters::symmetry_order(0)); },
    "symmetry order");
  expect_invalid_argument(
    [&] { TC::feature_aligned_faces(m, 30., std::back_inserter(out), map, TC::parameters::feature_smoothing(-1)); },
    "smoothing");
  EXPECT_TRUE(out.empty());
  // the bounds themselves are fine: every bent edge at 0, none at 180
  EXPECT_EQ(TC::feature_curves(m, 0.).number_of_sharp_edges, 24u);
  EXPECT_EQ(TC::feature_curves(m, 180.).number_of_sharp_edges, 0u);
  EXPECT_EQ(TC::feature_curves(m, 89.9).number_of_sharp_edges, 24u);
  EXPECT_EQ(TC::feature_curves(m, 90.1).number_of_sharp_edges, 0u);
}

TEST(Feature_alignment, no_sharp_edge_gives_an_empty_result)
{
  for(const Surface_mesh& m : {icosphere(3), disk(4, 12)}) {
    std::vector<Surface_mesh::Face_index> out;
    std::map<Surface_mesh::Face_index, Vector> d;
    const TC::Feature_alignment_report r =
      TC::feature_aligned_faces(m, 30., std::back_inserter(out), boost::make_assoc_property_map(d));
    EXPECT_TRUE(out.empty());
    EXPECT_TRUE(d.empty());
    EXPECT_EQ(r.number_of_sharp_edges, 0u);
    EXPECT_EQ(r.number_of_curves, 0u);
    EXPECT_EQ(r.number_of_pinned_faces, 0u);
    EXPECT_EQ(r.neighbouring_pairs, 0u);
    EXPECT_TRUE(TC::feature_curves(m).curves.empty());
  }
}

TEST(Feature_alignment, isolated_short_sharp_edge_is_dropped)
{
  // two triangles folded by 45 degrees along their shared edge: one isolated sharp edge (shorter than three mean edge
  // lengths), dropped; with a cube's twelve curves beside it (another component), those are kept
  Soup fold;
  fold.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0), Point(0.5, -1, 1)};
  fold.faces = {{{0, 1, 2}}, {{1, 0, 3}}};
  const Surface_mesh m = to_surface_mesh(fold);
  const auto curves = TC::feature_curves(m, 30.);
  EXPECT_EQ(curves.number_of_sharp_edges, 1u);
  EXPECT_TRUE(curves.curves.empty());
  EXPECT_EQ(curves.dropped_curves, 1u);
  EXPECT_EQ(curves.dropped_edges, 1u);
  std::vector<Surface_mesh::Face_index> out;
  std::map<Surface_mesh::Face_index, Vector> d;
  const auto r = TC::feature_aligned_faces(m, 30., std::back_inserter(out), boost::make_assoc_property_map(d));
  EXPECT_EQ(r.dropped_curves, 1u);
  EXPECT_EQ(r.number_of_pinned_faces, 0u);
  EXPECT_TRUE(out.empty());
  // at 50 degrees it is not sharp at all
  EXPECT_EQ(TC::feature_curves(m, 50.).number_of_sharp_edges, 0u);
  const Surface_mesh both = to_surface_mesh(concatenate(jittered_cube(3, 0.2), fold));
  const auto c2 = TC::feature_curves(both, 30.);
  EXPECT_EQ(c2.curves.size(), 12u);
  EXPECT_EQ(c2.dropped_curves, 1u);
}
