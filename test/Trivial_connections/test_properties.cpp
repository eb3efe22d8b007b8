// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

/*
  Property-based tests: random valid meshes (closed surfaces of random genus, random holes, several
  components, random positions and numbering) x random valid singularity sets (indices in (1/n)Z,
  Poincare-Hopf on every closed component, boundary indices free or prescribed with `loop_periods`),
  every answer checked by the independent code of test_support.h (CONVENTIONS.md from first principles):

    - holonomy K_v + sum x = 2 pi k_v at every interior vertex, and a multiple of 2 pi / n around every
      boundary loop and generator, recomputed by our own transport (residual < 1e-9);
    - Poincare-Hopf per component, exactly, in units of 1/n;
    - optimality: the weighted divergence sum_{h of f} w_e x(h) vanishes on every face (every cycle is
      constrained), the reported energy is ours, and no +-1 move of a free loop integer lowers it;
    - the field: unit, tangent, parallel across every interior edge modulo 2 pi / n;
    - independence of the vertex and face numbering (same x per geometric edge, same energy, same index
      of every hole);
    - invariance under scaling the coordinates by 1e-6 and 1e6 and translating them by 1e6.

  Then meshes that are valid but hard: needle and cap triangles (aspect ratios 1e4 to 1e9) against the
  well-shaped mesh of the same connectivity and the known flat answers, a vertex of valence 256 at a sharp
  cone (K > pi) and at saddles (K = -20 and about -400) against the closed-form answer, genus 6 and 8, a
  sheet with 150 holes (150 free integers, known optimum), 60 components of eight kinds.

  These tests found that on needles of aspect ratio above about 1e6 the holonomy residual exceeded 1e-9, and
  that from about 1e9 on the solve threw solver_failure on a valid mesh; the solver now refines x itself
  (Needle_residual, at the end of the needle tests, keeps the minimal cases).

  Every random case draws from std::mt19937 seeded by the case's own seed, which every failure message
  shows (SCOPED_TRACE): to run that case alone, set TC_PROPERTY_SEED=seed in the environment and filter the
  test (--gtest_filter). The distributions are those of the standard library the tests were built with
  (libstdc++): the same seed gives the same case there.
*/

#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace tc_test;
using TC::Weighting;

template <class Mesh>
using Solver = TC::Trivial_connection_solver<Mesh>;
using Periods = std::vector<std::optional<std::int64_t>>;

// =====================================================================================================
// Random numbers
// =====================================================================================================

struct Random
{
  std::mt19937 engine;
  explicit Random(unsigned seed) : engine(seed) {}
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine); } // [lo, hi]
  double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine); }
  bool coin(double p = 0.5) { return real(0, 1) < p; }
  unsigned seed() { return unsigned(engine()); }
  V3 in_ball()
  {
    for(;;) {
      const V3 v{{real(-1, 1), real(-1, 1), real(-1, 1)}};
      if(dot(v, v) <= 1) return v;
    }
  }
};

/// runs `body(seed, random)` for `count` cases with seeds base, base + 1, ..., each under a SCOPED_TRACE
/// naming its seed; stops at the first case with a fatal failure. With the environment variable
/// TC_PROPERTY_SEED set, only the case of that seed runs (to reproduce one failure alone).
template <class Body>
void for_each_case(unsigned base, int count, Body body)
{
  const char* only = std::getenv("TC_PROPERTY_SEED");
  for(int i = 0; i < count; ++i) {
    const unsigned seed = base + unsigned(i);
    if(only != nullptr && std::strtoul(only, nullptr, 10) != seed) continue;
    SCOPED_TRACE("case seed " + std::to_string(seed));
    Random random(seed);
    body(seed, random);
    if(::testing::Test::HasFatalFailure()) return;
  }
}

// =====================================================================================================
// Soups: validity, transformations, surgery
// =====================================================================================================

V3 v3(const Point& p) { return {{p.x(), p.y(), p.z()}}; }
Point point(const V3& v) { return Point(v[0], v[1], v[2]); }
V3 face_cross(const Soup& s, const Tri& t)
{
  const V3 a = v3(s.points[t[0]]), b = v3(s.points[t[1]]), c = v3(s.points[t[2]]);
  return cross(b - a, c - a);
}

/// "" when the soup is an oriented 2-manifold (with or without boundary) that a CGAL user can load:
/// every point used, no face with a repeated corner or zero area, every directed edge at most once
/// (consistent orientation, at most two faces per edge), the faces at every vertex one fan
std::string soup_problem(const Soup& s)
{
  const int np = int(s.points.size());
  std::set<std::pair<int, int>> directed;
  std::vector<std::vector<int>> at(np);
  for(std::size_t f = 0; f < s.faces.size(); ++f) {
    const Tri& t = s.faces[f];
    for(int k = 0; k < 3; ++k) {
      if(t[k] < 0 || t[k] >= np || t[k] == t[(k + 1) % 3]) return "face " + std::to_string(f) + " is not a triangle";
      if(!directed.insert({t[k], t[(k + 1) % 3]}).second)
        return "directed edge " + std::to_string(t[k]) + "->" + std::to_string(t[(k + 1) % 3]) + " twice";
      at[t[k]].push_back(int(f));
    }
    if(!(norm(face_cross(s, t)) > 0)) return "face " + std::to_string(f) + " has zero area";
  }
  for(int v = 0; v < np; ++v) {
    if(at[v].empty()) return "point " + std::to_string(v) + " is in no face";
    std::map<int, int> out, in;
    for(int f : at[v]) {
      Tri t = s.faces[f];
      while(t[0] != v) std::rotate(t.begin(), t.begin() + 1, t.end());
      out[t[1]] = t[2];
      in[t[2]] = t[1];
    }
    int start = -1;
    for(const auto& kv : out)
      if(!in.count(kv.first)) {
        if(start >= 0) return "the faces at vertex " + std::to_string(v) + " form several fans";
        start = kv.first;
      }
    if(start < 0) start = out.begin()->first;
    std::size_t steps = 0;
    for(int c = start; out.count(c) && steps <= at[v].size();) {
      c = out[c];
      ++steps;
      if(c == start) break;
    }
    if(steps != at[v].size()) return "the faces at vertex " + std::to_string(v) + " form several fans";
  }
  return "";
}

/// the soup without its unused points (the others keep their order, faces renumbered)
Soup compacted(const Soup& s)
{
  std::vector<int> id(s.points.size(), -1);
  for(const Tri& t : s.faces)
    for(int v : t) id[v] = 0;
  Soup r;
  for(std::size_t i = 0; i < s.points.size(); ++i)
    if(id[i] == 0) { id[i] = int(r.points.size()); r.points.push_back(s.points[i]); }
  for(const Tri& t : s.faces) r.faces.push_back({{id[t[0]], id[t[1]], id[t[2]]}});
  return r;
}

Soup transformed(Soup s, double scale, const V3& shift = {{0, 0, 0}})
{
  for(Point& p : s.points) p = point(scale * v3(p) + shift);
  return s;
}

/// coordinates rounded to multiples of 2^-30: a translation by up to 2^20 (e.g. 1e6) is then exact
Soup snapped(Soup s)
{
  const double q = std::ldexp(1., 30);
  for(Point& p : s.points) p = Point(std::round(p.x() * q) / q, std::round(p.y() * q) / q, std::round(p.z() * q) / q);
  return s;
}

/// a random smooth deformation p + A sin(k.p + phase) per coordinate with |gradient| <= 0.25: a
/// diffeomorphism of space (I + J, |J| < 1), so the surface stays embedded and oriented
Soup randomly_warped(Soup s, Random& random, double amplitude)
{
  std::array<V3, 3> k;
  std::array<double, 3> phase;
  for(int c = 0; c < 3; ++c) {
    k[c] = {{random.real(-1, 1), random.real(-1, 1), random.real(-1, 1)}};
    k[c] = (random.real(0.5, 1.5) / norm(k[c])) * k[c];
    phase[c] = random.real(0, two_pi);
  }
  const double A = std::min(amplitude, 0.25 / 1.5 / std::sqrt(3.));
  for(Point& p : s.points) {
    V3 q = v3(p);
    const V3 o = q;
    for(int c = 0; c < 3; ++c) q[c] += A * std::sin(dot(k[c], o) + phase[c]);
    p = point(q);
  }
  return s;
}

/// every vertex moved at random by up to `amount` times its shortest incident edge (in the plane z = const
/// when `planar`), one vertex at a time, a move undone when it would turn a face by more than 60 degrees or
/// shrink it below a quarter of its area
Soup jittered(Soup s, Random& random, double amount, bool planar = false)
{
  const int np = int(s.points.size());
  std::vector<std::vector<int>> at(np);
  std::vector<double> shortest(np, std::numeric_limits<double>::infinity());
  for(std::size_t f = 0; f < s.faces.size(); ++f)
    for(int k = 0; k < 3; ++k) {
      const int a = s.faces[f][k], b = s.faces[f][(k + 1) % 3];
      at[a].push_back(int(f));
      const double l = norm(v3(s.points[a]) - v3(s.points[b]));
      shortest[a] = std::min(shortest[a], l);
      shortest[b] = std::min(shortest[b], l);
    }
  for(int v = 0; v < np; ++v) {
    if(at[v].empty()) continue;
    V3 d = random.in_ball();
    if(planar) d[2] = 0;
    const Point old = s.points[v];
    std::vector<V3> before;
    for(int f : at[v]) before.push_back(face_cross(s, s.faces[f]));
    s.points[v] = point(v3(old) + (amount * shortest[v]) * d);
    for(std::size_t i = 0; i < at[v].size(); ++i) {
      const V3 after = face_cross(s, s.faces[at[v][i]]);
      if(dot(after, before[i]) < 0.5 * norm(after) * norm(before[i]) || norm(after) < 0.25 * norm(before[i])) {
        s.points[v] = old;
        break;
      }
    }
  }
  return s;
}

/*
  Removes `holes` random disks of up to `max_faces` faces (grown face by face from a random face), each
  removal kept only when the surface stays a 2-manifold and none of its faces had a boundary vertex (so a
  hole never touches another hole or the boundary, and no vertex loses all its faces). A disk that encloses
  part of a thin handle may still cut it: the topology is read from the result, never assumed.
*/
Soup with_holes(const Soup& s, Random& random, int holes, int max_faces)
{
  const int nf = int(s.faces.size());
  std::map<std::pair<int, int>, int> face_of;
  std::vector<std::vector<int>> at(s.points.size());
  for(int f = 0; f < nf; ++f)
    for(int k = 0; k < 3; ++k) {
      face_of[{s.faces[f][k], s.faces[f][(k + 1) % 3]}] = f;
      at[s.faces[f][k]].push_back(f);
    }
  std::vector<char> alive(nf, 1);
  auto neighbours = [&](int f) {
    std::vector<int> r;
    for(int k = 0; k < 3; ++k) {
      auto it = face_of.find({s.faces[f][(k + 1) % 3], s.faces[f][k]});
      if(it != face_of.end() && alive[it->second]) r.push_back(it->second);
    }
    return r;
  };
  auto on_boundary = [&](int v) {
    for(int f : at[v])
      if(alive[f])
        for(int k = 0; k < 3; ++k)
          if(s.faces[f][k] == v) {
            auto it = face_of.find({s.faces[f][(k + 1) % 3], v});
            if(it == face_of.end() || !alive[it->second]) return true;
          }
    return false;
  };
  // the alive faces at v form one fan (or none)
  auto one_fan = [&](int v) {
    std::map<int, int> out, in;
    std::size_t count = 0;
    for(int f : at[v])
      if(alive[f]) {
        Tri t = s.faces[f];
        while(t[0] != v) std::rotate(t.begin(), t.begin() + 1, t.end());
        out[t[1]] = t[2];
        in[t[2]] = t[1];
        ++count;
      }
    if(count == 0) return false;
    int start = -1, starts = 0;
    for(const auto& kv : out)
      if(!in.count(kv.first)) { start = kv.first; ++starts; }
    if(starts > 1) return false;
    if(start < 0) start = out.begin()->first;
    std::size_t steps = 0;
    for(int c = start; out.count(c) && steps <= count;) {
      c = out[c];
      ++steps;
      if(c == start) break;
    }
    return steps == count;
  };
  for(int h = 0, attempts = 0; h < holes && attempts < 20 * holes; ++attempts) {
    const int seed = random.integer(0, nf - 1);
    if(!alive[seed]) continue;
    std::vector<int> disk = {seed};
    std::set<int> in_disk = {seed};
    const int size = random.integer(1, max_faces);
    for(std::size_t i = 0; i < disk.size() && int(disk.size()) < size; ++i)
      for(int g : neighbours(disk[i]))
        if(int(disk.size()) < size && in_disk.insert(g).second) disk.push_back(g);
    std::set<int> touched;
    for(int f : disk)
      for(int v : s.faces[f]) touched.insert(v);
    bool ok = true;
    for(int v : touched) ok = ok && !on_boundary(v);
    if(!ok) continue;
    for(int f : disk) alive[f] = 0;
    for(int v : touched) ok = ok && one_fan(v);
    if(!ok) {
      for(int f : disk) alive[f] = 1;
      continue;
    }
    ++h;
  }
  Soup r;
  r.points = s.points;
  for(int f = 0; f < nf; ++f)
    if(alive[f]) r.faces.push_back(s.faces[f]);
  return compacted(r);
}

// =====================================================================================================
// Random surfaces
// =====================================================================================================

/// boundary of a one-cube-thick slab of (2p+1) x (2q+1) cubes with `genus` one-cube holes at odd positions
/// (holes share no vertex: the surface is a manifold of that genus), cube faces cut into s x s squares
Soup slab_soup(Random& random, int genus, int s, std::string& what)
{
  const int p = random.integer(1, 3);
  const int q = std::max(1, (genus + p - 1) / p) + random.integer(0, 1);
  std::vector<std::array<int, 3>> slots;
  for(int i = 0; i < p; ++i)
    for(int j = 0; j < q; ++j) slots.push_back({{2 * i + 1, 2 * j + 1, 0}});
  std::shuffle(slots.begin(), slots.end(), random.engine);
  const std::set<std::array<int, 3>> hole(slots.begin(), slots.begin() + genus);
  std::set<std::array<int, 3>> cells;
  for(int i = 0; i <= 2 * p; ++i)
    for(int j = 0; j <= 2 * q; ++j)
      if(!hole.count({{i, j, 0}})) cells.insert({{i, j, 0}});
  Soup soup = voxel_surface_soup(cells, s);
  const double a = random.real(0.7, 1.3), b = random.real(0.7, 1.3), c = random.real(0.5, 1.5);
  for(Point& pt : soup.points) pt = Point(a * pt.x(), b * pt.y(), c * pt.z());
  what = "slab " + std::to_string(2 * p + 1) + "x" + std::to_string(2 * q + 1) + ", genus " + std::to_string(genus) +
         ", s = " + std::to_string(s);
  return soup;
}

/// a torus of revolution with ring angles `us` (around z) and `vs` (around the tube), faces outward
Soup torus_from_angles(double R, double r, const std::vector<double>& us, const std::vector<double>& vs)
{
  Soup s;
  const int m = int(us.size()), n = int(vs.size());
  for(int i = 0; i < m; ++i)
    for(int j = 0; j < n; ++j)
      s.points.emplace_back((R + r * std::cos(vs[j])) * std::cos(us[i]), (R + r * std::cos(vs[j])) * std::sin(us[i]),
                            r * std::sin(vs[j]));
  auto id = [&](int i, int j) { return (i % m) * n + j % n; };
  for(int i = 0; i < m; ++i)
    for(int j = 0; j < n; ++j) {
      s.faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      s.faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  return s;
}

/// a closed surface of the given genus with random shape, size and positions
Soup random_closed_soup(Random& random, int genus, std::string& what)
{
  Soup s;
  if(genus == 0 && random.coin(0.6)) {
    const int level = random.integer(1, 2);
    s = icosphere_soup(level);
    const double a = random.real(0.6, 1.4), b = random.real(0.6, 1.4), c = random.real(0.6, 1.4);
    for(Point& p : s.points) p = Point(a * p.x(), b * p.y(), c * p.z());
    what = "ellipsoid (icosphere " + std::to_string(level) + ")";
  } else if(genus == 1 && random.coin(0.6)) {
    const double R = random.real(1.5, 3), r = random.real(0.3, 0.9);
    const int m = random.integer(9, 22), n = random.integer(6, 12);
    s = torus_soup(R, r, m, n);
    what = "torus " + std::to_string(m) + "x" + std::to_string(n);
  } else {
    s = slab_soup(random, genus, genus <= 2 ? random.integer(1, 2) : 1, what);
  }
  s = randomly_warped(s, random, random.real(0.02, 0.12));
  return jittered(s, random, random.real(0, 0.2));
}

/// a surface with boundary: a closed one with random holes, or a jittered flat disk or annulus (bumped)
Soup random_bordered_soup(Random& random, std::string& what)
{
  if(random.coin(0.2)) {
    const bool disk = random.coin();
    Soup s = disk ? disk_soup(random.integer(2, 6), random.integer(6, 20))
                  : annulus_soup(random.real(0.2, 0.6), 1, random.integer(1, 5), random.integer(8, 24));
    what = disk ? "disk" : "annulus";
    s = jittered(s, random, random.real(0, 0.2), true);
    if(random.coin()) { // a bump: no longer flat
      const double h = random.real(0.1, 0.5);
      for(Point& p : s.points) p = Point(p.x(), p.y(), h * std::exp(-2 * (p.x() * p.x() + p.y() * p.y())));
      what += " bumped";
    }
    return s;
  }
  const int genus = random.integer(0, 3);
  Soup s = random_closed_soup(random, genus, what);
  const int holes = random.integer(1, 6);
  s = with_holes(s, random, holes, random.integer(1, 8));
  what += " with up to " + std::to_string(holes) + " holes";
  return s;
}

/// 2 to 4 pieces, closed or bordered, side by side
Soup random_multi_soup(Random& random, std::string& what)
{
  const int pieces = random.integer(2, 4);
  Soup s;
  what = std::to_string(pieces) + " pieces:";
  for(int i = 0; i < pieces; ++i) {
    std::string w;
    Soup piece = random.coin() ? random_closed_soup(random, random.integer(0, 2), w) : random_bordered_soup(random, w);
    what += " [" + w + "]";
    s = concatenate(s, transformed(piece, 1, {{8. * i, 0, 0}}));
  }
  return s;
}

enum class Kind { closed, bordered, multi, any };

/// a random valid mesh, randomly renumbered (vertices, faces, corners of each face), snapped (see `snapped`)
Soup random_soup(Random& random, Kind kind, std::string& what)
{
  if(kind == Kind::any) kind = Kind(random.integer(0, 2));
  Soup s;
  if(kind == Kind::closed) s = random_closed_soup(random, random.integer(0, 4), what);
  else if(kind == Kind::bordered) s = random_bordered_soup(random, what);
  else s = random_multi_soup(random, what);
  return snapped(renumbered(s, random.seed(), nullptr, true));
}

// =====================================================================================================
// Random singularities and loop integers
// =====================================================================================================

/*
  Random interior vertices with random indices in (1/n)Z (zero included: a regular vertex may be listed):
  on a closed component 1 to 6 of them whose indices sum to chi (Poincare-Hopf), on a bordered one 0 to 5
  with any indices (the boundary loops take the rest).
*/
template <class Mesh>
Singularities random_singularities(const Mesh_view<Mesh>& view, int n, Random& random)
{
  Singularities s;
  for(int c = 0; c < view.ncomp; ++c) {
    std::vector<int> interior;
    for(int v = 0; v < view.nv(); ++v)
      if(view.comp_of_vertex[v] == c && view.interior_vertex(v)) interior.push_back(v);
    std::shuffle(interior.begin(), interior.end(), random.engine);
    const bool closed = view.boundary_count[c] == 0;
    const int available = int(interior.size());
    const int count = closed ? random.integer(1, std::min(6, available)) : random.integer(0, std::min(5, available));
    long long sum = 0;
    for(int i = 0; i < count; ++i) {
      long long units = random.integer(-2 * n, 2 * n);
      if(closed && i == count - 1) units = n * view.chi[c] - sum;
      sum += units;
      s.emplace_back(interior[i], Index(units, n));
    }
  }
  return s;
}

/*
  Random `loop_periods`: on each bordered component, with probability 1/2, all its boundary loops get random
  integers whose sum makes Poincare-Hopf hold (the others are chosen by the solver); with `generators`,
  each generator with probability 1/4 a random integer. Empty when nothing is prescribed.
*/
template <class Mesh>
Periods random_periods(const Mesh_view<Mesh>& view, const Solver<Mesh>& solver, const Singularities& sing, int n,
                       Random& random, bool generators)
{
  const auto& loops = solver.loops();
  const std::vector<int> mine = our_components(view, solver);
  const std::vector<long long> k = scaled_indices(view.nv(), sing, n);
  std::vector<long long> vertex_sum(view.ncomp, 0);
  for(int v = 0; v < view.nv(); ++v)
    if(k[v] != 0) vertex_sum[view.comp_of_vertex[v]] += k[v];
  Periods given(loops.size());
  bool any = false;
  for(std::size_t c = 0; c < solver.components().size(); ++c) {
    std::vector<std::size_t> boundary;
    for(std::size_t l = 0; l < loops.size(); ++l)
      if(loops[l].component == c && loops[l].kind == TC::Loop_kind::boundary) boundary.push_back(l);
    if(boundary.empty() || random.coin()) continue;
    long long rest = n * view.chi[mine[c]] - vertex_sum[mine[c]];
    for(std::size_t i = 0; i + 1 < boundary.size(); ++i) {
      const long long p = random.integer(-2 * n, 2 * n);
      given[boundary[i]] = p;
      rest -= p;
    }
    given[boundary.back()] = rest;
    any = true;
  }
  if(generators)
    for(std::size_t l = 0; l < loops.size(); ++l)
      if(loops[l].kind == TC::Loop_kind::generator && random.coin(0.25)) {
        given[l] = random.integer(-n, n);
        any = true;
      }
  return any ? given : Periods();
}

/// a number for messages (std::to_string prints 1e-7 as 0.000000)
std::string num(double t)
{
  std::ostringstream o;
  o << t;
  return o.str();
}

std::string describe(const Singularities& sing, const Periods& given)
{
  std::ostringstream o;
  o << sing.size() << " singularities:";
  for(std::size_t i = 0; i < sing.size() && i < 12; ++i) o << " " << sing[i].first << ":" << sing[i].second;
  if(sing.size() > 12) o << " ...";
  o << "; loop_periods:";
  if(given.empty()) o << " none";
  for(const auto& p : given) o << " " << (p ? std::to_string(*p) : std::string("-"));
  return o.str();
}

// =====================================================================================================
// Solve and check everything
// =====================================================================================================

template <class Mesh>
struct Checked
{
  std::vector<double> x;
  TC::Solve_report report;
};

/*
  Solves (with `given` as loop_periods unless empty), then check_connection (holonomy at every interior
  vertex and around every loop by our own transport, boundary indices, Poincare-Hopf, face optimality,
  energy, integers no worse than rounding), the prescribed integers kept and the others marked chosen, and
  (with_field) check_field on the field seeded at face nf/2.
*/
template <class Mesh, class S>
Checked<Mesh> solve_checked(const Mesh_view<Mesh>& view, S& solver, const Singularities& sing, int n,
                            const Periods& given, bool with_field = true, const Tolerances& tol = Tolerances())
{
  Checked<Mesh> r;
  if(given.empty())
    r.report = solver.solve(descriptors(view, sing), view.halfedge_map(r.x), TC::parameters::symmetry_order(n));
  else
    r.report = solver.solve(descriptors(view, sing), view.halfedge_map(r.x),
                            TC::parameters::loop_periods(given, TC::parameters::symmetry_order(n)));
  check_connection(view, solver, sing, n, r.x, r.report, true, tol);
  for(std::size_t l = 0; l < r.report.loops.size(); ++l) {
    const bool is_given = !given.empty() && given[l].has_value();
    EXPECT_EQ(r.report.loops[l].prescribed, is_given) << "loop " << l;
    if(is_given) {
      EXPECT_EQ(r.report.loops[l].period, *given[l]) << "loop " << l << ": prescribed integer not kept";
    }
  }
  if(with_field) {
    std::vector<Vector> field;
    const int seed = view.nf() / 2;
    solver.compute_field(view.halfedge_map_const(r.x), view.face_map(field),
                         TC::parameters::seed_angle(0.3, TC::parameters::seed_face(view.faces[seed])));
    check_field(view, r.x, field, n, seed, 0.3, tol.holonomy);
  }
  return r;
}

/// index of the solver loop of every boundary vertex (numbered in `view`), -1 for interior vertices
template <class Mesh, class S>
std::vector<int> loop_at_vertex(const Mesh_view<Mesh>& view, const S& solver)
{
  std::vector<int> r(view.nv(), -1);
  for(int v = 0; v < view.nv(); ++v)
    if(view.faces_at[v] > 0 && view.on_boundary[v]) {
      const std::optional<std::size_t> l = solver.boundary_loop_of(view.vertices[v]);
      EXPECT_TRUE(l.has_value()) << "boundary vertex " << v << " has no boundary loop";
      if(l) r[v] = int(*l);
    }
  return r;
}

/// the boundary-loop entries of `given` (solver A's loops) as loop_periods of solver B, through the
/// vertices: vertex v of A is vertex `to_b[v]` of B; generator entries are not carried over
template <class MA, class SA, class MB, class SB>
Periods carried_periods(const Periods& given, const Mesh_view<MA>& va, const SA& sa, const Mesh_view<MB>& vb,
                        const SB& sb, const std::vector<int>& to_b)
{
  if(given.empty()) return given;
  const std::vector<int> la = loop_at_vertex(va, sa), lb = loop_at_vertex(vb, sb);
  Periods r(sb.loops().size());
  bool any = false;
  for(int v = 0; v < va.nv(); ++v)
    if(la[v] >= 0 && given[la[v]] && lb[to_b[v]] >= 0) {
      r[lb[to_b[v]]] = given[la[v]];
      any = true;
    }
  return any ? r : Periods();
}

/// the boundary index (period) each boundary vertex's loop got, per vertex, -1e18 elsewhere
template <class Mesh, class S>
std::vector<long long> hole_periods(const Mesh_view<Mesh>& view, const S& solver, const TC::Solve_report& report)
{
  const std::vector<int> l = loop_at_vertex(view, solver);
  std::vector<long long> r(view.nv(), -1000000000000000000LL);
  for(int v = 0; v < view.nv(); ++v)
    if(l[v] >= 0) r[v] = report.loops[l[v]].period;
  return r;
}

/// largest |a - b| over the edges of `a` (both must have the same edges), and where
double largest_difference(const std::map<std::pair<int, int>, double>& a, const std::map<std::pair<int, int>, double>& b,
                          std::pair<int, int>& at)
{
  EXPECT_EQ(a.size(), b.size()) << "number of interior edges";
  double worst = 0;
  for(const auto& kv : a) {
    auto it = b.find(kv.first);
    if(it == b.end()) {
      ADD_FAILURE() << "edge " << kv.first.first << "-" << kv.first.second << " missing";
      return std::numeric_limits<double>::infinity();
    }
    const double d = std::abs(kv.second - it->second);
    if(!(d <= worst)) { worst = d; at = kv.first; }
  }
  return worst;
}

double max_abs(const std::vector<double>& x)
{
  double m = 0;
  for(double t : x)
    if(std::isfinite(t)) m = std::max(m, std::abs(t));
  return m;
}

int random_order(Random& random)
{
  static const int orders[] = {1, 2, 3, 4, 6};
  return orders[random.integer(0, 4)];
}

/// the identity numbering 0 .. n-1
std::vector<int> identity(int n)
{
  std::vector<int> r(n);
  std::iota(r.begin(), r.end(), 0);
  return r;
}

/*
  The full set of checks on one case: the solver's geometry and loops (check_solver_geometry, check_loops),
  then solve_checked and local optimality of the chosen integers. Returns the solution.
*/
template <class Mesh>
Checked<Mesh> check_case(const Mesh_view<Mesh>& view, Solver<Mesh>& solver, const Singularities& sing, int n,
                         const Periods& given, bool geometry = true)
{
  if(geometry) {
    SCOPED_TRACE("solver geometry and loops");
    check_solver_geometry(view, solver);
    check_loops(view, solver);
  }
  Checked<Mesh> r = solve_checked(view, solver, sing, n, given);
  {
    SCOPED_TRACE("local optimality of the integers");
    check_integers_locally_optimal(view, solver, sing, n, r.report, given);
  }
  return r;
}

// =====================================================================================================
// Random valid meshes x random valid singularities: every invariant holds
// =====================================================================================================

void random_property(unsigned base, int count, Kind kind, bool prescribe)
{
  for_each_case(base, count, [&](unsigned, Random& random) {
    std::string what;
    const Soup soup = random_soup(random, kind, what);
    SCOPED_TRACE(what);
    ASSERT_EQ(soup_problem(soup), "") << "test set-up: the generated mesh is not valid";
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    const int n = random_order(random);
    const Weighting w = random.coin(0.7) ? Weighting::hodge_star : Weighting::unit;
    Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
    const Singularities sing = random_singularities(view, n, random);
    const Periods given = prescribe ? random_periods(view, solver, sing, n, random, true) : Periods();
    SCOPED_TRACE("n = " + std::to_string(n) + (w == Weighting::unit ? ", unit weights, " : ", hodge weights, ") +
                 std::to_string(view.nf()) + " faces, " + std::to_string(view.ncomp) + " components; " +
                 describe(sing, given));
    check_case(view, solver, sing, n, given);
  });
}

TEST(Property_random_closed, every_invariant_holds_at_random_genus_and_singularities)
{
  random_property(1000, 50, Kind::closed, false);
}

TEST(Property_random_bordered, every_invariant_holds_with_boundary_indices_free_or_prescribed)
{
  random_property(2000, 50, Kind::bordered, true);
}

TEST(Property_random_components, every_invariant_holds_on_several_components)
{
  random_property(3000, 40, Kind::multi, true);
}

/// a random mesh of any kind with random n, weighting, singularities and prescribed loops, solved and checked
struct Solved_case
{
  const Soup& soup;
  int n;
  const Mesh_view<Surface_mesh>& view;
  Solver<Surface_mesh>& solver;
  const Singularities& sing;
  const Periods& given;
  const Checked<Surface_mesh>& result;
};

/// `check(case, random)` on `count` random solved cases from `first_seed` on (traces say which case failed)
template <class F>
void for_each_solved_case(unsigned first_seed, int count, F check)
{
  for_each_case(first_seed, count, [&](unsigned, Random& random) {
    std::string what;
    const Soup soup = random_soup(random, Kind::any, what);
    SCOPED_TRACE(what);
    ASSERT_EQ(soup_problem(soup), "");
    const int n = random_order(random);
    const Weighting w = random.coin(0.7) ? Weighting::hodge_star : Weighting::unit;
    const Surface_mesh mesh = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(mesh);
    Solver<Surface_mesh> solver(mesh, TC::parameters::weighting(w));
    const Singularities sing = random_singularities(view, n, random);
    const Periods given = random_periods(view, solver, sing, n, random, false);
    SCOPED_TRACE("n = " + std::to_string(n) + "; " + describe(sing, given));
    const Checked<Surface_mesh> result = solve_checked(view, solver, sing, n, given, false);
    check(Solved_case{soup, n, view, solver, sing, given, result}, random);
  });
}

// -----------------------------------------------------------------------------------------------------
// Independence of the numbering: the same mesh with shuffled vertices, faces and corners gives the same x
// per geometric edge, the same energy and the same index of every hole
// -----------------------------------------------------------------------------------------------------

TEST(Property_numbering, same_answer_for_shuffled_vertices_and_faces)
{
  for_each_solved_case(4000, 40, [&](const Solved_case& c, Random& random) {
    const auto& [a, n, va, sa, sing, given, ra] = c;
    const Weighting w = sa.weighting();

    std::vector<int> perm;
    const Soup b = renumbered(a, random.seed(), &perm, true);
    const Surface_mesh mb = to_surface_mesh(b);
    const Mesh_view<Surface_mesh> vb(mb);
    Solver<Surface_mesh> sb(mb, TC::parameters::weighting(w));
    Singularities moved;
    for(const auto& p : sing) moved.emplace_back(perm[p.first], p.second);
    const Periods given_b = carried_periods(given, va, sa, vb, sb, perm);
    const Checked<Surface_mesh> rb = solve_checked(vb, sb, moved, n, given_b, false);

    EXPECT_NEAR(rb.report.energy, ra.report.energy, 1e-9 * std::max(1., ra.report.energy));
    std::vector<int> back(perm.size());
    for(std::size_t i = 0; i < perm.size(); ++i) back[perm[i]] = int(i);
    std::pair<int, int> at{-1, -1};
    const double d =
      largest_difference(x_by_vertex_pair(va, ra.x, identity(va.nv())), x_by_vertex_pair(vb, rb.x, back), at);
    EXPECT_LT(d, 1e-9 * std::max(1., max_abs(ra.x))) << "x differs at edge " << at.first << "-" << at.second;
    const std::vector<long long> ha = hole_periods(va, sa, ra.report), hb = hole_periods(vb, sb, rb.report);
    for(int v = 0; v < va.nv(); ++v)
      EXPECT_EQ(ha[v], hb[perm[v]]) << "index of the hole at vertex " << v;
  });
}

// -----------------------------------------------------------------------------------------------------
// Scale and translation invariance: angles and Hodge weights |e| / |e*| do not change when the mesh is
// scaled, so x does not either. The coordinates are multiples of 2^-30 (`snapped`): adding 1e6 to them is
// exact, so a translated mesh has exactly the same edge vectors.
// -----------------------------------------------------------------------------------------------------

template <class Mesh>
void expect_same_x_after(const Soup& soup, const Mesh_view<Mesh>& va, Solver<Mesh>& sa, const Checked<Mesh>& ra,
                         const Singularities& sing, int n, const Periods& given, double scale, const V3& shift,
                         double tolerance, bool with_field = true)
{
  SCOPED_TRACE("coordinates times " + num(scale) + " plus (" + num(shift[0]) + ", " + num(shift[1]) + ", " + num(shift[2]) + ")");
  const Soup t = transformed(soup, scale, shift);
  const Surface_mesh mb = to_surface_mesh(t);
  const Mesh_view<Surface_mesh> vb(mb);
  Solver<Surface_mesh> sb(mb, TC::parameters::weighting(sa.weighting()));
  // the same soup order gives the same halfedge numbers: when the solver built the same loops (the trees do
  // not depend on the coordinates), every prescribed integer carries over; otherwise only the holes' ones
  bool same_loops = sa.loops().size() == sb.loops().size();
  for(std::size_t l = 0; same_loops && l < sa.loops().size(); ++l) {
    same_loops = sa.loops()[l].kind == sb.loops()[l].kind && sa.loops()[l].halfedges.size() == sb.loops()[l].halfedges.size();
    for(std::size_t i = 0; same_loops && i < sa.loops()[l].halfedges.size(); ++i)
      same_loops = va.hid.at(sa.loops()[l].halfedges[i]) == vb.hid.at(sb.loops()[l].halfedges[i]);
  }
  Periods given_b = given;
  if(!same_loops) {
    for(std::size_t l = 0; l < given.size(); ++l)
      ASSERT_FALSE(given[l] && sa.loops()[l].kind == TC::Loop_kind::generator)
        << "test set-up: the loops changed with the coordinates, a prescribed generator cannot be carried over";
    given_b = carried_periods(given, va, sa, vb, sb, identity(va.nv()));
  }
  const Checked<Surface_mesh> rb = solve_checked(vb, sb, sing, n, given_b, with_field);
  double worst = 0;
  int worst_h = -1;
  for(int h : va.interior_halfedges) // same soup order: same vertex, face and halfedge numbers
    if(!(std::abs(ra.x[h] - rb.x[h]) <= worst)) { worst = std::abs(ra.x[h] - rb.x[h]); worst_h = h; }
  EXPECT_LT(worst, tolerance * std::max(1., max_abs(ra.x)))
    << "x changes by " << worst << " at edge "
    << (worst_h >= 0 ? std::to_string(va.src[worst_h]) + "-" + std::to_string(va.tgt[worst_h]) : std::string());
  EXPECT_NEAR(rb.report.energy, ra.report.energy, tolerance * std::max(1., ra.report.energy));
  const std::vector<long long> ha = hole_periods(va, sa, ra.report), hb = hole_periods(vb, sb, rb.report);
  EXPECT_EQ(ha, hb) << "the holes' indices change";
}

TEST(Property_scale, same_answer_after_scaling_by_1e_minus_6_and_1e6_and_translating_by_1e6)
{
  for_each_solved_case(5000, 40, [&](const Solved_case& c, Random&) {
    const auto& [soup, n, va, sa, sing, given, ra] = c;
    expect_same_x_after(soup, va, sa, ra, sing, n, given, 1e-6, {{0, 0, 0}}, 1e-9, false);
    expect_same_x_after(soup, va, sa, ra, sing, n, given, 1e6, {{0, 0, 0}}, 1e-9, false);
    expect_same_x_after(soup, va, sa, ra, sing, n, given, 1, {{1e6, -1e6, 1e6}}, 1e-9, false);
  });
}

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// the same answers with CHOLMOD as with the default SimplicialLDLT
TEST(Property_backends, cholmod_gives_the_same_answer_as_the_default_backend)
{
  for_each_case(6000, 20, [&](unsigned, Random& random) {
    std::string what;
    const Soup soup = random_soup(random, Kind::any, what);
    SCOPED_TRACE(what);
    const int n = random_order(random);
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    Solver<Surface_mesh> sa(sm);
    TC::Trivial_connection_solver<Surface_mesh, CGAL::Default, TC::Cholmod_solver_traits> sb(sm);
    const Singularities sing = random_singularities(view, n, random);
    const Periods given = random_periods(view, sa, sing, n, random, true);
    SCOPED_TRACE(describe(sing, given));
    const Checked<Surface_mesh> ra = solve_checked(view, sa, sing, n, given, false);
    const Checked<Surface_mesh> rb = solve_checked(view, sb, sing, n, given, false);
    EXPECT_NEAR(ra.report.energy, rb.report.energy, 1e-9 * std::max(1., ra.report.energy));
    double worst = 0;
    for(int h : view.interior_halfedges) worst = std::max(worst, std::abs(ra.x[h] - rb.x[h]));
    EXPECT_LT(worst, 1e-9 * std::max(1., max_abs(ra.x)));
  });
}
#endif

// =====================================================================================================
// Valid but hard meshes
// =====================================================================================================

/// a flat G x G grid of unit squares in z = 0, vertex (i, j) = i (G + 1) + j at (x_i, y_j), each square
/// (i, j) cut along its diagonal from (i, j) to (i + 1, j + 1); squares in `removed` are left out
Soup grid_soup(const std::vector<double>& xs, const std::vector<double>& ys, const std::set<std::pair<int, int>>& removed = {})
{
  const int G = int(xs.size()) - 1;
  Soup s;
  for(int i = 0; i <= G; ++i)
    for(int j = 0; j <= G; ++j) s.points.emplace_back(xs[i], ys[j], 0);
  auto id = [&](int i, int j) { return i * (G + 1) + j; };
  for(int i = 0; i < G; ++i)
    for(int j = 0; j < G; ++j) {
      if(removed.count({i, j})) continue;
      s.faces.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
      s.faces.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
    }
  return compacted(s);
}

/*
  The needle grid: a 24 x 24 grid whose columns 6 and 15 are moved to within eps of columns 5 and 14, and
  row 10 to within eps of row 9 (needles eps x 1, and eps x eps squares where they cross), and six vertices
  (i, j) moved to eps from the segment (i-1, j)-(i, j+1) (caps: an angle pi - O(eps)). Four squares are
  removed (holes). The well-shaped grid has the same connectivity and numbering (eps = 0 moves nothing).
*/
Soup needle_grid(double eps, bool needles)
{
  const int G = 24;
  std::vector<double> xs(G + 1), ys(G + 1);
  for(int i = 0; i <= G; ++i) xs[i] = ys[i] = i;
  if(needles) {
    xs[6] = 5 + eps;
    xs[15] = 14 + eps;
    ys[10] = 9 + eps;
  }
  const std::set<std::pair<int, int>> holes = {{2, 7}, {9, 20}, {19, 13}, {20, 3}};
  Soup s;
  // the points first (compacted keeps them when every point is used; no hole removes a whole vertex star)
  s = grid_soup(xs, ys, holes);
  if(needles) {
    const std::vector<std::pair<int, int>> caps = {{3, 3}, {3, 18}, {20, 6}, {20, 20}, {11, 15}, {11, 3}};
    for(const auto& c : caps) {
      const int v = c.first * (G + 1) + c.second;
      s.points[v] = Point(c.first - 0.5 + eps, c.second + 0.5 - eps, 0);
    }
  }
  return snapped(s);
}

/*
  On needles the unit normal of a face is only determined to about 1e-16 / sin(smallest angle) by the cross
  product of the two edges at the sharp corner; the library's frames and test_support's normals use the two
  edges of the largest angle, so the field is checked (tangent to 1e-12, parallel) at every aspect ratio.
  (With the sharp corner's edges the tangency failed from aspect ratios of about 1e5 on: 8.8e-12 at 1e6.)
*/
bool field_checkable(double) { return true; }

TEST(Hard_needles, grid_with_needles_and_caps_has_the_flat_answers_and_the_well_shaped_grids_integers)
{
  const Soup plain = needle_grid(0, false);
  ASSERT_EQ(soup_problem(plain), "");
  for(double eps : {1e-4, 1e-5, 1e-6, 1e-9}) {
    SCOPED_TRACE("eps = " + num(eps));
    const Soup needle = needle_grid(eps, true);
    ASSERT_EQ(soup_problem(needle), "");
    ASSERT_EQ(needle.faces, plain.faces);
    const Surface_mesh mp = to_surface_mesh(plain), mn = to_surface_mesh(needle);
    const Mesh_view<Surface_mesh> vp(mp), vn(mn);
    ASSERT_EQ(vn.boundary_loops.size(), 5u);
    {
      // smallest area relative to the square of the longest edge: the needles are really there
      double worst = 1;
      for(int f = 0; f < vn.nf(); ++f) {
        const auto& h = vn.face_he[f];
        const V3 &a = vn.P[vn.src[h[0]]], &b = vn.P[vn.src[h[1]]], &c = vn.P[vn.src[h[2]]];
        const double l = std::max({norm(b - a), norm(c - b), norm(a - c)});
        worst = std::min(worst, 0.5 * norm(cross(b - a, c - a)) / (l * l));
      }
      EXPECT_LT(worst, 2 * eps);
    }
    const bool field = field_checkable(eps);
    // (1) flat, no singularity, Hodge weights: x = 0 is feasible with the outer loop at +1 and every hole
    //     at -1, and has energy 0: it is the unique optimum, whatever the shape of the triangles
    {
      SCOPED_TRACE("flat, no singularity, Hodge weights");
      Solver<Surface_mesh> solver(mn);
      const Checked<Surface_mesh> r = solve_checked(vn, solver, {}, 4, {}, field);
      EXPECT_LT(max_abs(r.x), 1e-9);
      EXPECT_LT(r.report.energy, 1e-15);
      for(std::size_t l = 0; l < r.report.loops.size(); ++l) {
        const int b = boundary_loop_of(vn, solver, l);
        ASSERT_GE(b, 0);
        const bool outer = std::find(vn.boundary_loops[b].vertices.begin(), vn.boundary_loops[b].vertices.end(), 0) !=
                           vn.boundary_loops[b].vertices.end();
        EXPECT_EQ(r.report.loops[l].index, Index(outer ? 1 : -1)) << "loop " << l;
      }
      expect_same_x_after(needle, vn, solver, r, {}, 4, {}, 1e-6, {{0, 0, 0}}, 1e-9, field);
      expect_same_x_after(needle, vn, solver, r, {}, 4, {}, 1e6, {{0, 0, 0}}, 1e-9, field);
    }
    // (2) unit weights: x depends only on the connectivity, the indices and the angle defects (all 0 inside,
    //     and 2 pi or -2 pi around each boundary loop of a flat domain): the needle grid gives the well-shaped
    //     grid's x, energy and integers, whatever the singularities
    for_each_case(7000, 6, [&](unsigned, Random& random) {
      const int n = random_order(random);
      const Singularities sing = random_singularities(vp, n, random);
      SCOPED_TRACE("unit weights, n = " + std::to_string(n) + "; " + describe(sing, {}));
      Solver<Surface_mesh> sp(mp, TC::parameters::weighting(Weighting::unit));
      Solver<Surface_mesh> sn(mn, TC::parameters::weighting(Weighting::unit));
      const Checked<Surface_mesh> rp = solve_checked(vp, sp, sing, n, {});
      const Checked<Surface_mesh> rn = solve_checked(vn, sn, sing, n, {}, field);
      double worst = 0;
      for(int h : vp.interior_halfedges) worst = std::max(worst, std::abs(rp.x[h] - rn.x[h]));
      EXPECT_LT(worst, 1e-9 * std::max(1., max_abs(rp.x))) << "needles change x";
      EXPECT_NEAR(rn.report.energy, rp.report.energy, 1e-9 * std::max(1., rp.report.energy));
      EXPECT_EQ(hole_periods(vp, sp, rp.report), hole_periods(vn, sn, rn.report));
      check_integers_locally_optimal(vn, sn, sing, n, rn.report, {});
    });
    // (3) Hodge weights with singularities: every invariant, and scale invariance. Weights down to 1.5 eps
    for_each_case(7100, 4, [&](unsigned, Random& random) {
      const int n = random_order(random);
      const Singularities sing = random_singularities(vn, n, random);
      Solver<Surface_mesh> solver(mn);
      const Periods given = random_periods(vn, solver, sing, n, random, false);
      SCOPED_TRACE("Hodge weights, n = " + std::to_string(n) + "; " + describe(sing, given));
      const Checked<Surface_mesh> r = solve_checked(vn, solver, sing, n, given, field);
      check_integers_locally_optimal(vn, solver, sing, n, r.report, given);
      // scaling by 1e-6 or 1e6 is not exact in binary: the eps-long edges, hence their weights, change by
      // ~1e-16 / eps relatively, and so may x (at eps = 1e-9: 1e-7; x changed by 6e-8 relatively)
      const double tolerance = std::max(1e-9, 1e-15 / eps);
      expect_same_x_after(needle, vn, solver, r, sing, n, given, 1e-6, {{0, 0, 0}}, tolerance, field);
      expect_same_x_after(needle, vn, solver, r, sing, n, given, 1e6, {{0, 0, 0}}, tolerance, field);
    });
  }
}

TEST(Hard_needles, curved_needles_on_a_torus)
{
  // a torus whose ring 5 is eps from ring 4 around z and whose ring 3 is eps from ring 2 around the tube
  // (needles, and eps x eps squares where the two bands cross); aspect ratios 1e4 to 1e7
  for(double eps : {1e-4, 1e-5, 1e-7}) {
    SCOPED_TRACE("eps = " + num(eps));
    const int m = 20, k = 10;
    std::vector<double> us(m), vs(k);
    for(int i = 0; i < m; ++i) us[i] = two_pi * i / m;
    for(int j = 0; j < k; ++j) vs[j] = two_pi * j / k;
    us[5] = us[4] + eps;
    vs[3] = vs[2] + eps;
    const Soup soup = snapped(torus_from_angles(2, 0.7, us, vs));
    ASSERT_EQ(soup_problem(soup), "");
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    for(Weighting w : {Weighting::hodge_star, Weighting::unit})
      for_each_case(7200, 3, [&](unsigned, Random& random) {
        const int n = random_order(random);
        Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
        const Singularities sing = random_singularities(view, n, random);
        SCOPED_TRACE(std::string(w == Weighting::unit ? "unit" : "Hodge") + " weights, n = " + std::to_string(n) +
                     "; " + describe(sing, {}));
        const Checked<Surface_mesh> r = solve_checked(view, solver, sing, n, {}, field_checkable(eps));
        check_integers_locally_optimal(view, solver, sing, n, r.report, {});
        expect_same_x_after(soup, view, solver, r, sing, n, {}, 1e-6, {{0, 0, 0}}, 1e-9, field_checkable(eps));
        expect_same_x_after(soup, view, solver, r, sing, n, {}, 1e6, {{0, 0, 0}}, 1e-9, field_checkable(eps));
      });
  }
}

/*
  Needle residuals. On needle triangles the Hodge weights of the eps-long edges are 1.5 eps, and computing
  x = W^-1 A^T lambda divides differences of multipliers lambda (of size ~1, rounded to ~1e-16) by them: the
  residual is ~1e-16 |lambda| / (1.5 eps) whatever the accuracy of lambda. The solver used to refine lambda
  and compute x from it again, which cannot go below that: the residual exceeded 1e-9 from aspect ratios of
  about 1e6 on (the 24 x 24 needle grid of Hard_needles, eps = 1e-6, Hodge weights: 2.3e-9 at case seed
  7100), and the solve threw solver_failure on a valid mesh from about 1e9 on. It now refines x itself,
  x += W^-1 A^T M^-1 (b - A x). Minimal cases: a 3 x 3 grid of unit squares (16 vertices, 18 triangles,
  Hodge weights) whose column of vertices 2 is moved to x = 1 + eps, one singularity; the first test also
  checks, with its own assembly of M = A W^-1 A^T, that one refinement of x reaches ~1e-15.
*/
struct Needle_case { double eps; int vertex; int index; };

Soup three_by_three_needle_grid(double eps)
{
  std::vector<double> xs = {0, 1, 1 + eps, 3};
  return grid_soup(xs, {0, 1, 2, 3});
}

/// the residual after one step of refinement of x itself (x += W^-1 A^T M^-1 r), on a mesh with one
/// component and one boundary loop (its row dropped: the rows are the interior vertices)
double residual_after_refining_x(const Mesh_view<Surface_mesh>& view, std::vector<double> x, const Singularities& sing)
{
  const std::vector<long long> k = scaled_indices(view.nv(), sing, 1);
  auto residuals = [&](const std::vector<double>& y) {
    const std::vector<double> S = ring_sums(view, y);
    std::vector<double> r(view.nv(), 0.);
    for(int v = 0; v < view.nv(); ++v)
      if(view.interior_vertex(v)) r[v] = two_pi * double(k[v]) - view.defect(v) - S[v];
    return r;
  };
  std::vector<int> row(view.nv(), -1);
  int rows = 0;
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v)) row[v] = rows++;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(rows, rows);
  for(int h : view.interior_edges) { // x(h) enters tgt(h)'s ring with +, src(h)'s with -
    const double w = view.hodge_weight(h);
    const int a = row[view.src[h]], b = row[view.tgt[h]];
    if(a >= 0) M(a, a) += 1 / w;
    if(b >= 0) M(b, b) += 1 / w;
    if(a >= 0 && b >= 0) { M(a, b) -= 1 / w; M(b, a) -= 1 / w; }
  }
  const std::vector<double> r = residuals(x);
  Eigen::VectorXd rhs(rows);
  for(int v = 0; v < view.nv(); ++v)
    if(row[v] >= 0) rhs[row[v]] = r[v];
  const Eigen::VectorXd d = M.ldlt().solve(rhs);
  for(int h : view.interior_edges) {
    const int a = row[view.src[h]], b = row[view.tgt[h]];
    const double dx = ((b >= 0 ? d[b] : 0.) - (a >= 0 ? d[a] : 0.)) / view.hodge_weight(h);
    x[h] += dx;
    x[view.opp[h]] -= dx;
  }
  double worst = 0;
  for(double t : residuals(x)) worst = std::max(worst, std::abs(t));
  return worst;
}

TEST(Needle_residual, holonomy_residual_below_1e_minus_9_at_aspect_ratios_1e7_and_1e8)
{
  // before the solver refined x itself (Eigen's SimplicialLDLT): residual 5.3e-9 (aspect 1e7), 1.1e-8 (1e8)
  for(const Needle_case& c : {Needle_case{1e-7, 6, 5}, Needle_case{1e-8, 5, 1}}) {
    SCOPED_TRACE("3 x 3 grid, column 2 at x = 1 + " + num(c.eps) + ", index " + std::to_string(c.index) +
                 " at vertex " + std::to_string(c.vertex));
    const Soup soup = three_by_three_needle_grid(c.eps);
    ASSERT_EQ(soup_problem(soup), "");
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    Solver<Surface_mesh> solver(sm);
    const Singularities sing = {{c.vertex, Index(c.index)}};
    std::vector<double> x;
    const TC::Solve_report r = solver.solve(descriptors(view, sing), view.halfedge_map(x));
    check_connection(view, solver, sing, 1, x, r);
    EXPECT_LT(residual_after_refining_x(view, x, sing), 1e-12) << "one more refinement of x by the test";
  }
}

TEST(Needle_residual, valid_mesh_of_aspect_ratio_1e9_is_solved)
{
  // used to throw Invalid_input(solver_failure, "the linear solve is inaccurate (residual 0.000000)") on this
  // valid mesh (no zero-area face)
  const Soup soup = three_by_three_needle_grid(1e-9);
  ASSERT_EQ(soup_problem(soup), "");
  const Surface_mesh sm = to_surface_mesh(soup);
  const Mesh_view<Surface_mesh> view(sm);
  Solver<Surface_mesh> solver(sm);
  const Singularities sing = {{9, Index(1)}};
  std::vector<double> x;
  try {
    const TC::Solve_report r = solver.solve(descriptors(view, sing), view.halfedge_map(x));
    check_connection(view, solver, sing, 1, x, r);
  } catch(const TC::Invalid_input& e) {
    ADD_FAILURE() << "valid mesh rejected: " << e.what();
  }
}

/// a fan: centre (0, 0, apex) and `valence` rim vertices (cos t_i, sin t_i, rim(i)), faces (c, v_i, v_i+1)
Soup fan_soup(int valence, double apex, const std::function<double(int)>& rim)
{
  Soup s;
  s.points.emplace_back(0, 0, apex);
  for(int i = 0; i < valence; ++i)
    s.points.emplace_back(std::cos(two_pi * i / valence), std::sin(two_pi * i / valence), rim(i));
  for(int i = 0; i < valence; ++i) s.faces.push_back({{0, 1 + i, 1 + (i + 1) % valence}});
  return s;
}

/*
  A vertex of valence 256 with one ring: a sharp cone (K close to 2 pi), a flat fan (K = 0) and saddles
  whose rim goes up and down (K = -20 and far below). Every face is congruent (the saddle's alternate
  mirror images) and every spoke has the same weight, and the only constraint is the centre's, so the
  answer is known in closed form: every spoke carries (2 pi k - K) / 256 (into the centre), for both
  weightings, and the boundary loop gets index 1 - k.
*/
TEST(Hard_valence, cone_and_saddle_of_valence_256_have_the_closed_form_answer)
{
  const int valence = 256;
  struct Shape { std::string name; double apex; std::function<double(int)> rim; };
  const std::vector<Shape> shapes = {
    {"sharp cone", 8., [](int) { return 0.; }},
    {"flat fan", 0., [](int) { return 0.; }},
    {"saddle 0.05", 0., [](int i) { return i % 2 ? 0.05 : -0.05; }},
    {"saddle 1", 0., [](int i) { return i % 2 ? 1. : -1.; }},
  };
  for(const Shape& shape : shapes) {
    SCOPED_TRACE(shape.name);
    const Soup soup = fan_soup(valence, shape.apex, shape.rim);
    ASSERT_EQ(soup_problem(soup), "");
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    const double K = view.defect(0);
    if(shape.name == "sharp cone") {
      EXPECT_GT(K, pi);
    } else if(shape.name == "saddle 0.05") {
      EXPECT_LT(K, -6 * pi);
    } else if(shape.name == "saddle 1") {
      EXPECT_LT(K, -100 * pi);
    }
    for(Weighting w : {Weighting::hodge_star, Weighting::unit}) {
      Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
      check_solver_geometry(view, solver);
      for(int n : {1, 4})
        for(const Index k : {Index(0), Index(1, n), Index(1), Index(-1), Index(3)}) {
          SCOPED_TRACE("n = " + std::to_string(n) + ", k = " + k.to_string() + ", K = " + num(K));
          const Singularities sing = {{0, k}};
          const Checked<Surface_mesh> r = solve_checked(view, solver, sing, n, {});
          const double expected = (two_pi * double(k.numerator()) / double(k.denominator()) - K) / valence;
          double worst = 0;
          for(int h : view.interior_halfedges)
            if(view.tgt[h] == 0) worst = std::max(worst, std::abs(r.x[h] - expected));
          EXPECT_LT(worst, 1e-9 * std::max(1., std::abs(expected))) << "spoke angle, expected " << expected;
          ASSERT_EQ(r.report.loops.size(), 1u);
          EXPECT_EQ(r.report.loops[0].index, Index(1) - k);
          expect_same_x_after(soup, view, solver, r, sing, n, {}, 1e-6, {{0, 0, 0}}, 1e-9, false);
          expect_same_x_after(soup, view, solver, r, sing, n, {}, 1e6, {{0, 0, 0}}, 1e-9, false);
        }
    }
  }
}

/// a closed bipyramid: `valence` equator vertices, apexes at +-height: two vertices of that valence
TEST(Hard_valence, closed_bipyramid_with_two_sharp_apexes_of_valence_256)
{
  const int valence = 256;
  const double height = 6;
  Soup s;
  for(int i = 0; i < valence; ++i) s.points.emplace_back(std::cos(two_pi * i / valence), std::sin(two_pi * i / valence), 0);
  s.points.emplace_back(0, 0, height);
  s.points.emplace_back(0, 0, -height);
  const int top = valence, bottom = valence + 1;
  for(int i = 0; i < valence; ++i) {
    s.faces.push_back({{top, i, (i + 1) % valence}});
    s.faces.push_back({{bottom, (i + 1) % valence, i}});
  }
  ASSERT_EQ(soup_problem(s), "");
  const Surface_mesh sm = to_surface_mesh(s);
  const Mesh_view<Surface_mesh> view(sm);
  ASSERT_EQ(view.chi[0], 2);
  EXPECT_GT(view.defect(top), pi);
  for(Weighting w : {Weighting::hodge_star, Weighting::unit}) {
    Solver<Surface_mesh> solver(sm, TC::parameters::weighting(w));
    check_solver_geometry(view, solver);
    // +1 at each apex: by the rotational symmetry every spoke at an apex carries (2 pi - K) / 256
    {
      const Singularities sing = {{top, Index(1)}, {bottom, Index(1)}};
      const Checked<Surface_mesh> r = solve_checked(view, solver, sing, 1, {});
      for(int apex : {top, bottom}) {
        const double expected = (two_pi - view.defect(apex)) / valence;
        double worst = 0;
        for(int h : view.interior_halfedges)
          if(view.tgt[h] == apex) worst = std::max(worst, std::abs(r.x[h] - expected));
        EXPECT_LT(worst, 1e-9) << "spoke angle at apex " << apex << ", expected " << expected;
      }
      expect_same_x_after(s, view, solver, r, sing, 1, {}, 1e-6, {{0, 0, 0}}, 1e-9);
      expect_same_x_after(s, view, solver, r, sing, 1, {}, 1e6, {{0, 0, 0}}, 1e-9);
    }
    // random singularities, apexes included or not
    for_each_case(7300, 5, [&](unsigned, Random& random) {
      const int n = random_order(random);
      const Singularities sing = random_singularities(view, n, random);
      SCOPED_TRACE("n = " + std::to_string(n) + "; " + describe(sing, {}));
      solve_checked(view, solver, sing, n, {});
    });
  }
}

/// genus 6 and 8: 12 and 16 free integers
TEST(Hard_genus, genus_6_and_8)
{
  for_each_case(7400, 4, [&](unsigned, Random& random) {
    std::string what;
    const int genus = random.coin() ? 6 : 8;
    Soup soup = slab_soup(random, genus, random.integer(1, 2), what);
    soup = snapped(renumbered(jittered(randomly_warped(soup, random, 0.1), random, 0.15), random.seed(), nullptr, true));
    SCOPED_TRACE(what);
    ASSERT_EQ(soup_problem(soup), "");
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    ASSERT_EQ(view.genus[0], genus);
    const int n = random_order(random);
    Solver<Surface_mesh> solver(sm, TC::parameters::weighting(random.coin() ? Weighting::hodge_star : Weighting::unit));
    const Singularities sing = random_singularities(view, n, random);
    SCOPED_TRACE("n = " + std::to_string(n) + "; " + describe(sing, {}));
    const Checked<Surface_mesh> r = check_case(view, solver, sing, n, {});
    EXPECT_EQ(int(r.report.loops.size()), 2 * genus);
    expect_same_x_after(soup, view, solver, r, sing, n, {}, 1e-6, {{0, 0, 0}}, 1e-9, false);
    expect_same_x_after(soup, view, solver, r, sing, n, {}, 1e6, {{0, 0, 0}}, 1e-9, false);
    expect_same_x_after(soup, view, solver, r, sing, n, {}, 1, {{1e6, 1e6, -1e6}}, 1e-9, false);
  });
}

/*
  A 48 x 48 sheet with 150 holes (one triangle or one square each, three squares apart: no two share a
  vertex). Flat, without singularities: x = 0 with the outer loop at +1 and every hole at -1 is feasible with
  energy 0, so it is the unique optimum among the 150 free integers. Bent: every invariant, with free and with
  prescribed hole indices.
*/
TEST(Hard_many_holes, sheet_with_150_holes)
{
  const int G = 48;
  std::vector<double> xs(G + 1);
  for(int i = 0; i <= G; ++i) xs[i] = i;
  Soup grid = grid_soup(xs, xs);
  std::set<int> drop;
  int holes = 0;
  std::mt19937 pick(7500);
  std::vector<std::pair<int, int>> spots;
  for(int a = 0; a < 16; ++a)
    for(int b = 0; b < 16; ++b) spots.emplace_back(3 * a + 1, 3 * b + 1);
  std::shuffle(spots.begin(), spots.end(), pick);
  for(const auto& q : spots) {
    if(holes == 150) break;
    const int f = 2 * (q.first * G + q.second); // the faces of square (i, j) are 2 (i G + j) and the next
    drop.insert(f);
    if(holes % 2) drop.insert(f + 1);
    ++holes;
  }
  Soup sheet;
  sheet.points = grid.points;
  for(int f = 0; f < int(grid.faces.size()); ++f)
    if(!drop.count(f)) sheet.faces.push_back(grid.faces[f]);
  sheet = compacted(sheet);
  ASSERT_EQ(soup_problem(sheet), "");
  {
    SCOPED_TRACE("flat, no singularity");
    const Surface_mesh sm = to_surface_mesh(sheet);
    const Mesh_view<Surface_mesh> view(sm);
    ASSERT_EQ(view.boundary_loops.size(), 151u);
    Solver<Surface_mesh> solver(sm);
    const Checked<Surface_mesh> r = solve_checked(view, solver, {}, 4, {});
    EXPECT_LT(max_abs(r.x), 1e-9);
    EXPECT_LT(r.report.energy, 1e-15);
    int outer = 0, inner = 0;
    for(const auto& l : r.report.loops) {
      outer += l.index == Index(1);
      inner += l.index == Index(-1);
    }
    EXPECT_EQ(outer, 1);
    EXPECT_EQ(inner, 150);
  }
  {
    Random random(7501);
    Soup bent = sheet;
    for(Point& p : bent.points)
      p = Point(p.x(), p.y(), 3 * std::sin(p.x() / 7) * std::cos(p.y() / 9) + 0.1 * std::sin(p.x() + 2 * p.y()));
    bent = snapped(renumbered(jittered(bent, random, 0.15), 7502, nullptr, true));
    ASSERT_EQ(soup_problem(bent), "");
    const Surface_mesh sm = to_surface_mesh(bent);
    const Mesh_view<Surface_mesh> view(sm);
    ASSERT_EQ(view.boundary_loops.size(), 151u);
    Solver<Surface_mesh> solver(sm);
    for(int c = 0; c < 3; ++c) {
      const int n = c == 0 ? 1 : 4;
      const Singularities sing = random_singularities(view, n, random);
      const Periods given = c == 2 ? random_periods(view, solver, sing, n, random, false) : Periods();
      SCOPED_TRACE("bent, n = " + std::to_string(n) + (given.empty() ? ", free hole indices" : ", prescribed hole indices"));
      const Checked<Surface_mesh> r = check_case(view, solver, sing, n, given, c == 0);
      if(c == 1) {
        expect_same_x_after(bent, view, solver, r, sing, n, {}, 1e-6, {{0, 0, 0}}, 1e-9, false);
        expect_same_x_after(bent, view, solver, r, sing, n, {}, 1e6, {{0, 0, 0}}, 1e-9, false);
      }
    }
  }
}

/*
  60 components of many kinds: tetrahedra, icosahedra, small tori, fans, annuli, genus-2 slabs, single
  triangles and two-triangle strips (no interior edge at all), each warped and jittered.
*/
TEST(Hard_many_components, sixty_components)
{
  for_each_case(7600, 3, [&](unsigned, Random& random) {
    Soup all;
    for(int i = 0; i < 60; ++i) {
      Soup piece;
      std::string what;
      switch(i % 8) {
        case 0: piece.points = {Point(1, 1, 1), Point(1, -1, -1), Point(-1, 1, -1), Point(-1, -1, 1)};
                piece.faces = {{{0, 1, 2}}, {{0, 2, 3}}, {{0, 3, 1}}, {{1, 3, 2}}}; break;
        case 1: piece = icosphere_soup(0); break;
        case 2: piece = torus_soup(2, 0.7, 6, 4); break;
        case 3: piece = disk_soup(1, 5); break;
        case 4: piece = annulus_soup(0.5, 1, 1, 8); break;
        case 5: piece = slab_soup(random, 2, 1, what); break;
        case 6: piece.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)}; piece.faces = {{{0, 1, 2}}}; break;
        default: piece.points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0.2), Point(0, 1, 0)};
                 piece.faces = {{{0, 1, 2}}, {{0, 2, 3}}}; break;
      }
      piece = jittered(randomly_warped(piece, random, 0.05), random, 0.1);
      all = concatenate(all, transformed(piece, random.real(0.5, 2), {{10. * (i % 8), 10. * (i / 8), 0}}));
    }
    all = snapped(renumbered(all, random.seed(), nullptr, true));
    ASSERT_EQ(soup_problem(all), "");
    const Surface_mesh sm = to_surface_mesh(all);
    const Mesh_view<Surface_mesh> view(sm);
    ASSERT_EQ(view.ncomp, 60);
    const int n = random_order(random);
    Solver<Surface_mesh> solver(sm);
    const Singularities sing = random_singularities(view, n, random);
    const Periods given = random_periods(view, solver, sing, n, random, true);
    SCOPED_TRACE("n = " + std::to_string(n) + "; " + describe(sing, given));
    const Checked<Surface_mesh> r = check_case(view, solver, sing, n, given);
    expect_same_x_after(all, view, solver, r, sing, n, given, 1e-6, {{0, 0, 0}}, 1e-9, false);
    expect_same_x_after(all, view, solver, r, sing, n, given, 1e6, {{0, 0, 0}}, 1e-9, false);
    expect_same_x_after(all, view, solver, r, sing, n, given, 1, {{1e6, 1e6, 1e6}}, 1e-9, false);
  });
}

// -----------------------------------------------------------------------------------------------------
// The generators themselves: valid meshes of the intended kinds (so that the properties above are not
// vacuous)
// -----------------------------------------------------------------------------------------------------

TEST(Property_generators, produce_valid_meshes_of_every_kind)
{
  std::set<int> genera, boundary_counts, component_counts;
  int with_prescribed = 0, total = 0;
  for_each_case(1000, 50, [&](unsigned, Random& random) {
    std::string what;
    const Soup soup = random_soup(random, Kind::closed, what);
    ASSERT_EQ(soup_problem(soup), "") << what;
    const Surface_mesh sm = to_surface_mesh(soup);
    ASSERT_TRUE(CGAL::is_valid_polygon_mesh(sm));
    const Mesh_view<Surface_mesh> view(sm);
    ASSERT_EQ(view.ncomp, 1);
    EXPECT_EQ(view.boundary_count[0], 0);
    genera.insert(view.genus[0]);
  });
  for_each_case(2000, 50, [&](unsigned, Random& random) {
    std::string what;
    const Soup soup = random_soup(random, Kind::bordered, what);
    ASSERT_EQ(soup_problem(soup), "") << what;
    const Surface_mesh sm = to_surface_mesh(soup);
    ASSERT_TRUE(CGAL::is_valid_polygon_mesh(sm));
    const Mesh_view<Surface_mesh> view(sm);
    for(int c = 0; c < view.ncomp; ++c) boundary_counts.insert(view.boundary_count[c]);
    const int n = random_order(random);
    Solver<Surface_mesh> solver(sm);
    const Singularities sing = random_singularities(view, n, random);
    with_prescribed += random_periods(view, solver, sing, n, random, true).empty() ? 0 : 1;
    ++total;
  });
  for_each_case(3000, 40, [&](unsigned, Random& random) {
    std::string what;
    const Soup soup = random_soup(random, Kind::multi, what);
    ASSERT_EQ(soup_problem(soup), "") << what;
    const Surface_mesh sm = to_surface_mesh(soup);
    const Mesh_view<Surface_mesh> view(sm);
    component_counts.insert(view.ncomp);
  });
  EXPECT_EQ(genera, (std::set<int>{0, 1, 2, 3, 4}));
  EXPECT_GE(boundary_counts.size(), 4u);
  EXPECT_GE(*boundary_counts.rbegin(), 5);
  EXPECT_GE(component_counts.size(), 3u);
  EXPECT_GT(with_prescribed, total / 4);
  EXPECT_LT(with_prescribed, total);
}

} // namespace
