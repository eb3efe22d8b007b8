// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_INDEPENDENT_GEOMETRY_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_INDEPENDENT_GEOMETRY_H

// Test support: geometry and topology recomputed from the positions and the connectivity only (Mesh_view).

#include "mesh_builders.h"

namespace tc_test {

// =====================================================================================================
// (b) Independent geometry and topology, from positions and connectivity only
// =====================================================================================================

using V3 = std::array<double, 3>;
inline V3 operator+(const V3& a, const V3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline V3 operator-(const V3& a, const V3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline V3 operator*(double s, const V3& a) { return {{s * a[0], s * a[1], s * a[2]}}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }
inline V3 unit(const V3& a) { return (1 / norm(a)) * a; }

/// a - (multiple of period) in (-period/2, period/2]
inline double wrap(double a, double period = two_pi)
{
  double r = std::fmod(a, period);
  if(r > period / 2) r -= period;
  if(r <= -period / 2) r += period;
  return r;
}

/// signed angle from u to w about the unit normal N (both tangent)
inline double signed_angle(const V3& u, const V3& w, const V3& N)
{
  return std::atan2(dot(cross(u, w), N), dot(u, w));
}

/// the counter-clockwise rotation of tangent vector u by angle t about the unit normal N
inline V3 rotate(const V3& u, const V3& N, double t) { return std::cos(t) * u + std::sin(t) * cross(N, u); }

/// Key -> Value property map over a std::vector, through a hash map from descriptors to numbers
template <class Key, class Value>
struct Indexed_map
{
  using key_type = Key;
  using value_type = Value;
  using reference = Value&;
  using category = boost::lvalue_property_map_tag;
  const std::unordered_map<Key, int>* index = nullptr;
  std::vector<Value>* values = nullptr;
  Value& operator[](const Key& k) const { return (*values)[index->at(k)]; }
  friend Value& get(const Indexed_map& m, const Key& k) { return m[k]; }
  friend void put(const Indexed_map& m, const Key& k, const Value& v) { m[k] = v; }
};

/*
  The mesh as flat arrays, numbered in the iteration order of vertices(tm), faces(tm), halfedges(tm),
  with every quantity of CONVENTIONS.md recomputed from the positions: corner angles, angle defects,
  unit normals, components, Euler characteristics, boundary loops, Hodge-star weights.
*/
template <class Mesh>
struct Mesh_view
{
  using GT = boost::graph_traits<Mesh>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using edge_descriptor = typename GT::edge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  const Mesh& tm;
  std::vector<vertex_descriptor> vertices;
  std::vector<face_descriptor> faces;
  std::vector<halfedge_descriptor> halfedges;
  std::unordered_map<vertex_descriptor, int> vid;
  std::unordered_map<face_descriptor, int> fid;
  std::unordered_map<halfedge_descriptor, int> hid;

  std::vector<V3> P;                         // per vertex
  std::vector<int> src, tgt, hface, opp, nxt; // per halfedge (hface = -1: border halfedge)
  std::vector<std::array<int, 3>> face_he;    // per face: halfedge(f), next, next
  std::vector<V3> N, bary;                    // per face: unit normal, barycentre
  std::vector<double> angle_sum;              // per vertex
  std::vector<int> faces_at;                  // per vertex
  std::vector<char> on_boundary;              // per vertex
  std::vector<int> interior_halfedges;        // the halfedges of interior edges (both)
  std::vector<int> interior_edges;            // one halfedge per interior edge (the smaller number)

  std::vector<int> comp_of_face, comp_of_vertex; // own component numbering
  int ncomp = 0;
  std::vector<long long> chi;                    // per component
  std::vector<int> boundary_count, genus;        // per component
  struct Boundary_loop { int component; std::vector<int> vertices; double kappa; };
  std::vector<Boundary_loop> boundary_loops;
  std::vector<int> loop_of_vertex;               // -1 for interior vertices

  int nv() const { return int(vertices.size()); }
  int nf() const { return int(faces.size()); }
  int nh() const { return int(halfedges.size()); }
  bool interior_halfedge(int h) const { return hface[h] >= 0 && hface[opp[h]] >= 0; }
  bool interior_vertex(int v) const { return faces_at[v] > 0 && !on_boundary[v]; }
  /// angle defect: 2 pi - angle sum (interior), pi - angle sum (boundary)
  double defect(int v) const { return (on_boundary[v] ? pi : two_pi) - angle_sum[v]; }

  explicit Mesh_view(const Mesh& m) : tm(m)
  {
    for(auto v : CGAL::vertices(tm)) { vid[v] = int(vertices.size()); vertices.push_back(v); }
    for(auto f : CGAL::faces(tm)) { fid[f] = int(faces.size()); faces.push_back(f); }
    for(auto h : CGAL::halfedges(tm)) { hid[h] = int(halfedges.size()); halfedges.push_back(h); }
    auto vpm = get(CGAL::vertex_point, tm);
    for(auto v : vertices) {
      const Point& p = get(vpm, v);
      P.push_back({{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
    }
    const int H = nh();
    src.resize(H); tgt.resize(H); hface.resize(H); opp.resize(H); nxt.resize(H);
    for(int h = 0; h < H; ++h) {
      const halfedge_descriptor d = halfedges[h];
      src[h] = vid.at(source(d, tm));
      tgt[h] = vid.at(target(d, tm));
      hface[h] = is_border(d, tm) ? -1 : fid.at(face(d, tm));
      opp[h] = hid.at(opposite(d, tm));
      nxt[h] = hid.at(next(d, tm));
    }
    angle_sum.assign(nv(), 0.);
    faces_at.assign(nv(), 0);
    on_boundary.assign(nv(), 0);
    for(int f = 0; f < nf(); ++f) {
      const int h0 = hid.at(halfedge(faces[f], tm)), h1 = nxt[h0], h2 = nxt[h1];
      face_he.push_back({{h0, h1, h2}});
      const V3 &a = P[src[h0]], &b = P[src[h1]], &c = P[src[h2]];
      // from the two edges of the largest angle (opposite the longest edge): exact to rounding on needles too
      const double la = dot(c - b, c - b), lb = dot(a - c, a - c), lc = dot(b - a, b - a);
      N.push_back(unit(la >= lb && la >= lc ? cross(b - a, c - a) : lb >= lc ? cross(c - b, a - b) : cross(a - c, b - c)));
      bary.push_back((1. / 3) * (a + b + c));
      for(int k = 0; k < 3; ++k) {
        const int h = face_he[f][k], hp = face_he[f][(k + 2) % 3];
        const V3 u = P[tgt[h]] - P[src[h]], w = P[src[hp]] - P[src[h]]; // the two edges at src(h)
        angle_sum[src[h]] += std::atan2(norm(cross(u, w)), dot(u, w));
        ++faces_at[src[h]];
      }
    }
    for(int h = 0; h < H; ++h) {
      if(hface[h] < 0) { on_boundary[src[h]] = on_boundary[tgt[h]] = 1; continue; }
      if(hface[opp[h]] >= 0) {
        interior_halfedges.push_back(h);
        if(h < opp[h]) interior_edges.push_back(h);
      }
    }
    // components: union-find of faces through interior edges
    std::vector<int> parent(nf());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
    for(int h : interior_edges) parent[find(hface[h])] = find(hface[opp[h]]);
    std::map<int, int> comp_id;
    comp_of_face.assign(nf(), -1);
    for(int f = 0; f < nf(); ++f) {
      const int r = find(f);
      if(!comp_id.count(r)) comp_id[r] = ncomp++;
      comp_of_face[f] = comp_id[r];
    }
    comp_of_vertex.assign(nv(), -1);
    std::vector<long long> V(ncomp, 0), E(ncomp, 0), F(ncomp, 0);
    for(int f = 0; f < nf(); ++f) ++F[comp_of_face[f]];
    for(int h = 0; h < H; ++h) {
      const int f = hface[h] >= 0 ? hface[h] : hface[opp[h]];
      comp_of_vertex[src[h]] = comp_of_face[f];
      if(h < opp[h]) ++E[comp_of_face[f]];
    }
    for(int v = 0; v < nv(); ++v)
      if(faces_at[v] > 0) ++V[comp_of_vertex[v]];
    chi.resize(ncomp);
    for(int c = 0; c < ncomp; ++c) chi[c] = V[c] - E[c] + F[c];
    // boundary loops: cycles of border halfedges through next()
    loop_of_vertex.assign(nv(), -1);
    boundary_count.assign(ncomp, 0);
    std::vector<char> seen(H, 0);
    for(int h = 0; h < H; ++h) {
      if(hface[h] >= 0 || seen[h]) continue;
      Boundary_loop B{comp_of_face[hface[opp[h]]], {}, 0.};
      int c = h;
      do {
        seen[c] = 1;
        B.vertices.push_back(tgt[c]);
        c = nxt[c];
      } while(c != h);
      for(int v : B.vertices) {
        B.kappa += pi - angle_sum[v];
        loop_of_vertex[v] = int(boundary_loops.size());
      }
      ++boundary_count[B.component];
      boundary_loops.push_back(B);
    }
    genus.resize(ncomp);
    for(int c = 0; c < ncomp; ++c) genus[c] = int((2 - chi[c] - boundary_count[c]) / 2);
  }

  /// Hodge-star weight w_e = |e| / |e*|, |e*| = |b_f - m_e| + |m_e - b_g| (barycentres, edge midpoint)
  double hodge_weight(int h) const
  {
    const V3 m = 0.5 * (P[src[h]] + P[tgt[h]]);
    return norm(P[tgt[h]] - P[src[h]]) / (norm(bary[hface[h]] - m) + norm(m - bary[hface[opp[h]]]));
  }
  double weight(int h, TC::Weighting w) const { return w == TC::Weighting::unit ? 1. : hodge_weight(h); }

  /// Levi-Civita transport of tangent vector u of face(h) to face(opposite(h)), by unfolding about the edge
  V3 transport(int h, const V3& u) const
  {
    const V3 e = unit(P[tgt[h]] - P[src[h]]);
    const V3& Nf = N[hface[h]];
    const V3& Ng = N[hface[opp[h]]];
    return dot(u, e) * e + dot(u, cross(Nf, e)) * cross(Ng, e);
  }

  /// direction of halfedge(f): the frame the package documents for face f
  V3 frame(int f) const { const int h = face_he[f][0]; return unit(P[tgt[h]] - P[src[h]]); }

  /// a halfedge property map over a vector indexed by our halfedge numbers
  Indexed_map<halfedge_descriptor, double> halfedge_map(std::vector<double>& values) const
  {
    values.assign(nh(), std::numeric_limits<double>::quiet_NaN());
    return Indexed_map<halfedge_descriptor, double>{&hid, &values};
  }
  /// the same map over values already computed (not reset)
  Indexed_map<halfedge_descriptor, double> halfedge_map_const(std::vector<double>& values) const
  {
    return Indexed_map<halfedge_descriptor, double>{&hid, &values};
  }
  Indexed_map<face_descriptor, Vector> face_map(std::vector<Vector>& values) const
  {
    values.assign(nf(), Vector(0, 0, 0));
    return Indexed_map<face_descriptor, Vector>{&fid, &values};
  }
  /// halfedge from vertex i to vertex j (-1 when none)
  int halfedge_between(int i, int j) const
  {
    auto r = halfedge(vertices[i], vertices[j], tm);
    return r.second ? hid.at(r.first) : -1;
  }
};

template <class Mesh>
std::vector<std::pair<typename boost::graph_traits<Mesh>::vertex_descriptor, Index>>
descriptors(const Mesh_view<Mesh>& view, const Singularities& s)
{
  std::vector<std::pair<typename boost::graph_traits<Mesh>::vertex_descriptor, Index>> r;
  for(const auto& p : s) r.emplace_back(view.vertices[p.first], p.second);
  return r;
}

/// n times the prescribed index of every vertex
inline std::vector<long long> scaled_indices(int nv, const Singularities& s, int n)
{
  std::vector<long long> k(nv, 0);
  for(const auto& p : s) {
    EXPECT_TRUE(p.second.is_multiple_of_one_over(n)) << "test set-up: index " << p.second << " with n = " << n;
    k[p.first] = (long long)p.second.numerator() * (n / p.second.denominator());
  }
  return k;
}

/// Σ over the interior halfedges h with target(h) = v of x(h): the counter-clockwise ring sum at v
template <class Mesh>
std::vector<double> ring_sums(const Mesh_view<Mesh>& view, const std::vector<double>& x)
{
  std::vector<double> S(view.nv(), 0.);
  for(int h : view.interior_halfedges) S[view.tgt[h]] += x[h];
  return S;
}

/// energy Σ_e w_e x_e^2 with our own weights
template <class Mesh>
double energy(const Mesh_view<Mesh>& view, const std::vector<double>& x, TC::Weighting w)
{
  double E = 0;
  for(int h : view.interior_edges) E += view.weight(h, w) * x[h] * x[h];
  return E;
}

/// Transports a vector once around a closed dual loop (halfedge numbers), turning by x at each crossing
/// when `x` is given; returns the angle (about the normal of the first face) from the start vector to the
/// end vector. `closed` receives whether face(opposite(h_i)) == face(h_{i+1}) cyclically. An empty loop
/// (the boundary loop of a component whose boundary vertices have no interior edge, e.g. one triangle)
/// stays in one face: closed, rotation 0.
template <class Mesh>
double loop_rotation(const Mesh_view<Mesh>& view, const std::vector<int>& loop, const std::vector<double>* x,
                     bool& closed)
{
  closed = true;
  if(loop.empty()) return 0;
  for(std::size_t i = 0; i < loop.size() && closed; ++i) {
    const int h = loop[i], h2 = loop[(i + 1) % loop.size()];
    closed = view.interior_halfedge(h) && view.hface[view.opp[h]] == view.hface[h2];
  }
  if(!closed) return std::numeric_limits<double>::quiet_NaN();
  const int f0 = view.hface[loop[0]];
  const V3 u0 = view.frame(f0);
  V3 u = u0;
  for(int h : loop) {
    u = view.transport(h, u);
    if(x) u = rotate(u, view.N[view.hface[view.opp[h]]], (*x)[h]);
    u = unit(u);
  }
  return signed_angle(u0, u, view.N[f0]);
}

} // namespace tc_test

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_INDEPENDENT_GEOMETRY_H
