// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FEATURES_FEATURE_CURVES_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FEATURES_FEATURE_CURVES_H

#include <CGAL/Trivial_connections/internal/mesh/geometry.h>
#include <CGAL/Trivial_connections/internal/mesh/mesh_arrays.h>

#include <CGAL/number_type_config.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace features {

/*
  Sharp edges, feature curves and the directions of the faces beside them, on the flat arrays of Mesh_arrays
  (corner halfedges 3f, 3f+1, 3f+2 of face f). Every choice below depends on the geometry only, except where two
  candidates tie exactly (noted): the curves and the directions do not depend on how the mesh is numbered.

  Real creases are often not chains. On a mesh that was not made to follow them (fandisk_large, a scan) a crease
  crosses triangles, and its sharp edges form a band: a zigzag on each side and rungs between them (on
  fandisk_large at 30 degrees, 600 of the 1,600 vertices on sharp edges have three of them and 280 faces have three
  sharp edges). Chains through the vertices of two sharp edges cut such a band into single edges (1,021 of its
  1,303 chains). So the curves are the sharp edges connected through any vertex except the corners, and a corner is
  found from the shape of the sharp edges around a vertex, not from their number: the vertices on the sharp edges
  within corner_hops edges of it are not along one line (the second eigenvalue of their covariance over the first
  exceeds corner_ratio, and that ratio is the largest among its neighbours on sharp edges). A cube's corner
  (three arms) and a turn of 90 degrees are corners; a band along a straight crease is not.
*/

constexpr int corner_hops = 3;
constexpr double corner_ratio = 0.3;

inline Vec3 unit(const Vec3& a)
{
  const double l = norm(a);
  return l > 0 ? scaled(a, 1 / l) : a;
}
inline Vec3 add(const Vec3& a, const Vec3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }

struct Sharp_graph
{
  std::vector<int> edges;                  // per sharp edge: its corner halfedge of smaller index
  std::vector<std::vector<int>> at_vertex; // per vertex: its sharp edges
  std::vector<char> corner;                // per vertex: a corner (where curves meet, or a curve turns)
  std::vector<char> cusp;                  // per vertex: a corner where a crease turns back (see detect_curves())
  double mean_edge_length = 0;
};

// A feature curve: sharp edges connected through vertices that are not corners.
struct Curve
{
  std::vector<int> edges; // sharp edge ids, in breadth-first order
  double length = 0;
};

struct Curve_set
{
  Sharp_graph graph;
  std::vector<Curve> kept;
  std::size_t dropped_curves = 0, dropped_edges = 0;
};

template <class Mesh>
std::vector<Vec3> face_normals(const Mesh& m)
{
  std::vector<Vec3> N(std::size_t(m.nf));
  for(int f = 0; f < m.nf; ++f) {
    const Vec3& a = m.points[m.corner_vertex[3 * f]];
    const Vec3& b = m.points[m.corner_vertex[3 * f + 1]];
    const Vec3& c = m.points[m.corner_vertex[3 * f + 2]];
    N[f] = unit(cross(sub(b, a), sub(c, a)));
  }
  return N;
}

template <class Mesh>
Vec3 edge_vector(const Mesh& m, int corner)
{
  return sub(m.points[m.target_of(corner)], m.points[m.source_of(corner)]);
}

template <class Mesh>
int other_end(const Mesh& m, int corner, int v)
{
  return m.source_of(corner) == v ? m.target_of(corner) : m.source_of(corner);
}

// Along a chain of sharp edges, the vertex after `current` coming from `previous`: -1 unless `current` has exactly
// two sharp edges.
template <class Mesh>
int next_on_chain(const Mesh& m, const std::vector<std::vector<int>>& at_vertex, const std::vector<int>& edges,
                  int current, int previous)
{
  if(at_vertex[current].size() != 2)
    return -1;
  for(int e : at_vertex[current])
    if(other_end(m, edges[e], current) != previous)
      return other_end(m, edges[e], current);
  return -1;
}

// The vertices on sharp edges within `hops` sharp edges of `seeds` (the seeds included), not going on through a
// corner when `stop_at_corners`. `mark` is all 0 on entry and on exit.
template <class Mesh>
void vertices_within(const Mesh& m, const Sharp_graph& g, std::vector<int> seeds, int hops, bool stop_at_corners,
                     std::vector<char>& mark, std::vector<int>& out)
{
  out.clear();
  for(int v : seeds)
    if(!mark[v]) {
      mark[v] = 1;
      out.push_back(v);
    }
  std::size_t begin = 0;
  for(int h = 0; h < hops; ++h) {
    const std::size_t end = out.size();
    for(std::size_t i = begin; i < end; ++i) {
      const int v = out[i];
      if(stop_at_corners && g.corner[v])
        continue;
      for(int e : g.at_vertex[v]) {
        const int w = other_end(m, g.edges[e], v);
        if(!mark[w]) {
          mark[w] = 1;
          out.push_back(w);
        }
      }
    }
    begin = end;
  }
  for(int v : out)
    mark[v] = 0;
}

// The principal axis of points (unit) and the ratio of the second eigenvalue of their covariance to the first
template <class Mesh>
std::pair<Vec3, double> principal_axis(const Mesh& m, const std::vector<int>& vertices)
{
  Vec3 c{{0., 0., 0.}};
  for(int v : vertices)
    c = add(c, m.points[v]);
  c = scaled(c, 1. / double(vertices.size()));
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  for(int v : vertices) {
    const Vec3 d = sub(m.points[v], c);
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 3; ++j)
        A(i, j) += d[i] * d[j];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(A);
  const Eigen::Vector3d lambda = eigen.eigenvalues(); // increasing
  const Eigen::Vector3d axis = eigen.eigenvectors().col(2);
  return {{{axis(0), axis(1), axis(2)}}, lambda(2) > 0 ? lambda(1) / lambda(2) : 0.};
}

/*
  The sharp edges (interior edges whose faces' normals make an angle over `threshold` radians), the corners, and
  the curves: the isolated short ones (touching no corner, fewer than `min_edges` edges and shorter than
  `min_length_factor` mean edge lengths of the mesh) dropped.
*/
template <class Mesh>
Curve_set detect_curves(const Mesh& m, const std::vector<Vec3>& N, double threshold, int min_edges,
                        double min_length_factor)
{
  Curve_set out;
  Sharp_graph& g = out.graph;
  g.at_vertex.assign(std::size_t(m.nv), {});
  g.corner.assign(std::size_t(m.nv), 0);
  g.cusp.assign(std::size_t(m.nv), 0);
  double total_length = 0;
  std::size_t edges = 0;
  for(int c = 0; c < 3 * m.nf; ++c) {
    const int o = m.opposite_corner[c];
    if(o >= 0 && o < c)
      continue;
    total_length += norm(edge_vector(m, c));
    ++edges;
    if(o < 0 || !(angle_between(N[c / 3], N[o / 3]) > threshold))
      continue;
    g.at_vertex[m.source_of(c)].push_back(int(g.edges.size()));
    g.at_vertex[m.target_of(c)].push_back(int(g.edges.size()));
    g.edges.push_back(c);
  }
  g.mean_edge_length = edges > 0 ? total_length / double(edges) : 0;
  if(g.edges.empty())
    return out;

  // corners: where the sharp edges around a vertex are least like a line, and not like one at all
  std::vector<int> on_sharp, near;
  std::vector<char> mark(std::size_t(m.nv), 0);
  std::vector<double> ratio(std::size_t(m.nv), 0.);
  for(int v = 0; v < m.nv; ++v)
    if(!g.at_vertex[v].empty()) {
      on_sharp.push_back(v);
      vertices_within(m, g, {v}, corner_hops, false, mark, near);
      ratio[v] = principal_axis(m, near).second;
    }
  for(int v : on_sharp) {
    if(!(ratio[v] > corner_ratio))
      continue;
    vertices_within(m, g, {v}, 1, false, mark, near);
    bool maximum = true; // an exact tie goes to the vertex of smaller index
    for(int w : near)
      maximum = maximum && (w == v || ratio[w] < ratio[v] || (ratio[w] == ratio[v] && v < w));
    g.corner[v] = maximum;
  }

  // cusps: a crease that turns back on itself at a vertex lies along one line to the covariance (its two arms
  // leave the vertex in nearly the same direction: fandisk's vertex 112, 19 degrees apart). A vertex of two sharp
  // edges is a corner, and a cusp, when each arm is a smooth chain for corner_hops edges (through vertices of two
  // sharp edges, turning by less than 30 degrees at each) and the arms, the mean offsets of their vertices from
  // it, leave it less than 60 degrees apart. The chains keep out the zigzags of noisy creases (the 30 degree
  // sharp edges of a scan turn back all the time, over an edge or two).
  for(int v : on_sharp) {
    if(g.corner[v] || g.at_vertex[v].size() != 2)
      continue;
    std::array<Vec3, 2> arm;
    bool chains = true;
    for(int side = 0; side < 2 && chains; ++side) {
      int previous = v, current = other_end(m, g.edges[g.at_vertex[v][side]], v);
      Vec3 sum = sub(m.points[current], m.points[v]);
      for(int h = 1; h < corner_hops && chains; ++h) {
        const int next = next_on_chain(m, g.at_vertex, g.edges, current, previous);
        chains = next >= 0 && next != v &&
                 angle_between(sub(m.points[current], m.points[previous]), sub(m.points[next], m.points[current])) <
                   CGAL_PI / 6;
        if(!chains)
          break;
        sum = add(sum, sub(m.points[next], m.points[v]));
        previous = current;
        current = next;
      }
      arm[std::size_t(side)] = unit(sum);
    }
    if(chains && dot(arm[0], arm[1]) > 0.5) {
      g.corner[v] = 1;
      g.cusp[v] = 1;
    }
  }

  // curves: connected through the vertices that are not corners
  std::vector<int> curve_of(g.edges.size(), -1);
  std::vector<Curve> curves;
  std::vector<char> touches_corner;
  for(std::size_t e0 = 0; e0 < g.edges.size(); ++e0) {
    if(curve_of[e0] >= 0)
      continue;
    Curve curve;
    bool cornered = false;
    curve_of[e0] = int(curves.size());
    curve.edges.push_back(int(e0));
    for(std::size_t i = 0; i < curve.edges.size(); ++i) {
      const int c = g.edges[curve.edges[i]];
      curve.length += norm(edge_vector(m, c));
      for(int v : {m.source_of(c), m.target_of(c)}) {
        if(g.corner[v]) {
          cornered = true;
          continue;
        }
        for(int e : g.at_vertex[v])
          if(curve_of[e] < 0) {
            curve_of[e] = int(curves.size());
            curve.edges.push_back(e);
          }
      }
    }
    curves.push_back(std::move(curve));
    touches_corner.push_back(cornered);
  }
  for(std::size_t i = 0; i < curves.size(); ++i) {
    Curve& curve = curves[i];
    if(!touches_corner[i] && int(curve.edges.size()) < min_edges &&
       curve.length < min_length_factor * g.mean_edge_length) {
      ++out.dropped_curves;
      out.dropped_edges += curve.edges.size();
    } else {
      out.kept.push_back(std::move(curve));
    }
  }
  return out;
}

/*
  The tangent of the feature at each sharp edge: the principal axis of the vertices on sharp edges within `window`
  sharp edges of its ends, not going on through corners (a least-squares line through the crease around the edge,
  whether the crease is a chain or a band), oriented along the edge's corner halfedge in Sharp_graph::edges. With
  `window` = 0, or when those vertices are the edge's two ends, it is the edge itself.
*/
template <class Mesh>
std::vector<Vec3> edge_tangents(const Mesh& m, const Sharp_graph& g, int window)
{
  std::vector<Vec3> t(g.edges.size());
  std::vector<char> mark(std::size_t(m.nv), 0);
  std::vector<int> near;
  for(std::size_t e = 0; e < g.edges.size(); ++e) {
    const int c = g.edges[e];
    const Vec3 along = edge_vector(m, c);
    if(window > 0)
      vertices_within(m, g, {m.source_of(c), m.target_of(c)}, window, true, mark, near);
    if(window <= 0 || near.size() <= 2) {
      t[e] = unit(along);
      continue;
    }
    const Vec3 axis = principal_axis(m, near).first;
    t[e] = dot(axis, along) < 0 ? scaled(axis, -1.) : axis;
  }
  return t;
}

// One direction proposed for a face by one curve edge beside it, with the edge's length as its weight.
struct Proposal
{
  Vec3 direction;
  double weight;
};

/*
  The directions a curve edge (corner c, along the curve) gives its two faces f = face(c) and g = face(opposite(c)):
  the tangent t makes the angle phi with the edge, the circular mean of its angles in the two faces' planes
  (atan2(t.(N x e), t.e) with N each face's normal); each face gets the vector at angle phi from e in its own plane,
  cos(phi) e + sin(phi) N x e. Levi-Civita transport across the edge preserves the angle to it, so the two faces
  agree exactly across every curve edge, whatever the dihedral angle.
*/
template <class Mesh>
std::pair<Vec3, Vec3> edge_face_directions(const Mesh& m, const std::vector<Vec3>& N, int c, const Vec3& t)
{
  const Vec3 e = unit(edge_vector(m, c));
  const int f = c / 3, g = m.opposite_corner[c] / 3;
  const Vec3 mf = cross(N[f], e), mg = cross(N[g], e);
  const double te = dot(t, e);
  const double pf = std::atan2(dot(t, mf), te), pg = std::atan2(dot(t, mg), te);
  double phi = std::atan2(std::sin(pf) + std::sin(pg), std::cos(pf) + std::cos(pg));
  if(!std::isfinite(phi) || norm(t) == 0)
    phi = 0;
  const double cs = std::cos(phi), sn = std::sin(phi);
  return {add(scaled(e, cs), scaled(mf, sn)), add(scaled(e, cs), scaled(mg, sn))};
}

/*
  A face beside several curve edges: the weighted mean of exp(i n theta) of their directions (theta measured from
  the direction of the longest edge, which the result is taken nearest to), or the longest edge's direction when
  they cancel (|mean| <= 1e-6 of the total weight). For n = 4, perpendicular edges agree. Equal lengths: the first
  proposal wins (the order of the face's halfedges).
*/
inline Vec3 combine_proposals(const std::vector<Proposal>& p, const Vec3& normal, int n)
{
  std::size_t longest = 0;
  for(std::size_t i = 1; i < p.size(); ++i)
    if(p[i].weight > p[longest].weight)
      longest = i;
  const Vec3 r = unit(p[longest].direction);
  if(p.size() == 1)
    return r;
  const Vec3 s = cross(normal, r);
  std::complex<double> sum(0, 0);
  double total = 0;
  for(const Proposal& q : p) {
    const double theta = std::atan2(dot(q.direction, s), dot(q.direction, r));
    sum += q.weight * std::polar(1., n * theta);
    total += q.weight;
  }
  if(!(std::abs(sum) > 1e-6 * total))
    return r;
  const double theta = std::arg(sum) / n;
  return add(scaled(r, std::cos(theta)), scaled(s, std::sin(theta)));
}

inline Vec3 rotated_about(const Vec3& d, const Vec3& normal, double a)
{
  return add(scaled(d, std::cos(a)), scaled(cross(normal, d), std::sin(a)));
}

/*
  The sector rule at a cusp, for cross fields (n = 4): a crease turning back at vertex v leaves a sector of angle
  theta < 45 degrees between its two arms. A quad mesh that follows both arms puts one quad corner in it (a sector
  of angle theta gets k = max(1, round(theta / 90 degrees)) corners, the sector rule of integer-grid maps at
  feature vertices), so the field turns by theta - 90 degrees across the sector, not by theta (the short way,
  k = 0, which gives both arms the same iso-line and folds the quads between them). Each face of the sector gets
  the direction of that turn at the middle of its angle (linear in the angle from the first arm): with one face,
  half the turn on each of its two arm edges, so that the links on either side take it. So do the faces between
  the arms beside no sharp edge (the tongue, reached from the sector without crossing a sharp edge, within the
  distance from v where the arms are 50 degrees apart: beyond, the short way is the turn), with the turn taken
  linearly in their distances to the two arms: with the sector alone pinned, the tongue's touching pins were
  still linked the short way and the placement undid the cusp's -1/4 with a +1/4 beside it. Appends (face,
  direction) for these faces; returns the number of cusps so treated.
*/
template <class Mesh>
std::size_t cusp_sector_directions(const Mesh& m, const std::vector<Vec3>& N, const Sharp_graph& g,
                                   const std::vector<char>& kept_edge, std::vector<std::pair<int, Vec3>>& out)
{
  std::size_t cusps = 0;
  std::vector<int> sector[2];
  std::vector<double> width[2]; // per corner of sector[s]: its face's angle at v
  double angle[2];
  std::vector<char> sharp_corner(std::size_t(3 * m.nf), 0), in_tongue(std::size_t(m.nf), 0);
  for(int c : g.edges) {
    sharp_corner[std::size_t(c)] = 1;
    sharp_corner[std::size_t(m.opposite_corner[c])] = 1;
  }
  for(int v = 0; v < m.nv; ++v) {
    if(!g.cusp[v] || g.at_vertex[v].size() != 2 || !kept_edge[g.at_vertex[v][0]] || !kept_edge[g.at_vertex[v][1]])
      continue;
    int leaving[2], end[2];
    for(int s = 0; s < 2; ++s) {
      const int c = g.edges[g.at_vertex[v][s]];
      leaving[s] = m.source_of(c) == v ? c : m.opposite_corner[c];
      end[s] = m.target_of(leaving[s]);
    }
    // counter-clockwise from the arm s to the other: the corners entering v, face by face
    bool closed = true;
    for(int s = 0; s < 2 && closed; ++s) {
      sector[s].clear();
      width[s].clear();
      angle[s] = 0;
      int c = Mesh::prev_corner(leaving[s]);
      closed = false;
      for(int guard = 0; guard <= 3 * m.nf; ++guard) {
        sector[s].push_back(c);
        width[s].push_back(angle_between(sub(m.points[m.target_of(Mesh::next_corner(c))], m.points[v]),
                                         sub(m.points[m.source_of(c)], m.points[v])));
        angle[s] += width[s].back();
        if(m.source_of(c) == end[1 - s]) {
          closed = true;
          break;
        }
        if(m.opposite_corner[c] < 0)
          break;
        c = Mesh::prev_corner(m.opposite_corner[c]);
      }
    }
    if(!closed)
      continue;
    const int s = angle[0] <= angle[1] ? 0 : 1;
    const double theta = angle[s];
    if(!(theta < CGAL_PI / 4) || !(theta > 0))
      continue;
    const double turn = theta - CGAL_PI / 2; // over the sector, counter-clockwise from arm s
    ++cusps;
    double position = 0;
    std::vector<int> tongue;
    for(std::size_t j = 0; j < sector[s].size(); ++j) {
      const int c = sector[s][j], f = Mesh::face_of(c);
      const Vec3 first = sub(m.points[m.target_of(Mesh::next_corner(c))], m.points[v]);
      const double middle = position + width[s][j] / 2;
      out.push_back({f, rotated_about(unit(first), N[f], middle * turn / theta - position)});
      in_tongue[std::size_t(f)] = 1;
      tongue.push_back(f);
      position += width[s][j];
    }
    // the arms, as chains from v (s first), while their vertices have two sharp edges
    std::array<std::vector<int>, 2> arm;
    for(int a = 0; a < 2; ++a) {
      const int side = a == 0 ? s : 1 - s;
      arm[a] = {v, end[side]};
      while(arm[a].size() < 65) {
        const int current = arm[a].back(), previous = arm[a][arm[a].size() - 2];
        const int next = g.corner[current] ? -1 : next_on_chain(m, g.at_vertex, g.edges, current, previous);
        if(next < 0 || next == v)
          break;
        arm[a].push_back(next);
      }
    }
    // the tongue: between the arms, from v to where they are 50 degrees apart (the short way gives one quad
    // corner beyond, as the sector rule does)
    std::size_t reach = std::min(arm[0].size(), arm[1].size()) - 1;
    for(std::size_t i = 1; i <= reach; ++i)
      if(angle_between(sub(m.points[arm[0][i]], m.points[arm[0][i - 1]]),
                       sub(m.points[arm[1][i]], m.points[arm[1][i - 1]])) >= 50 * CGAL_PI / 180) {
        reach = i;
        break;
      }
    const double radius = std::min(norm(sub(m.points[arm[0][reach]], m.points[v])),
                                   norm(sub(m.points[arm[1][reach]], m.points[v])));
    auto within = [&](int f) {
      for(int k = 0; k < 3; ++k)
        if(norm(sub(m.points[m.corner_vertex[3 * f + k]], m.points[v])) > radius)
          return false;
      return true;
    };
    // the nearest segment of an arm (up to reach) to a point: its distance and unit direction away from v
    auto nearest = [&](int a, const Vec3& x, double& distance, Vec3& direction) {
      distance = std::numeric_limits<double>::infinity();
      for(std::size_t i = 1; i <= reach && i < arm[a].size(); ++i) {
        const Vec3 p = m.points[arm[a][i - 1]], d = sub(m.points[arm[a][i]], p);
        const double t = std::clamp(dot(sub(x, p), d) / dot(d, d), 0., 1.);
        const double dist = norm(sub(x, add(p, scaled(d, t))));
        if(dist < distance) {
          distance = dist;
          direction = unit(d);
        }
      }
    };
    for(std::size_t q = 0; q < tongue.size(); ++q) {
      const int f = tongue[q];
      if(q >= sector[s].size()) {
        bool beside_arm = false;
        for(int k = 0; k < 3; ++k)
          beside_arm = beside_arm || sharp_corner[std::size_t(3 * f + k)];
        if(!beside_arm) {
          const Vec3 x = scaled(add(add(m.points[m.corner_vertex[3 * f]], m.points[m.corner_vertex[3 * f + 1]]),
                                    m.points[m.corner_vertex[3 * f + 2]]), 1. / 3);
          double dF, dS;
          Vec3 tF, tS;
          nearest(0, x, dF, tF);
          nearest(1, x, dS, tS);
          tF = unit(sub(tF, scaled(N[f], dot(tF, N[f]))));
          tS = unit(sub(tS, scaled(N[f], dot(tS, N[f]))));
          const double alpha = std::atan2(dot(N[f], cross(tF, tS)), dot(tF, tS));
          if(alpha > 0 && alpha < CGAL_PI / 2 && dF + dS > 0)
            out.push_back({f, rotated_about(tF, N[f], dF / (dF + dS) * (alpha - CGAL_PI / 2))});
        }
      }
      for(int k = 0; k < 3; ++k) {
        const int o = m.opposite_corner[3 * f + k];
        if(o < 0 || sharp_corner[std::size_t(3 * f + k)] || in_tongue[std::size_t(Mesh::face_of(o))] ||
           !within(Mesh::face_of(o)))
          continue;
        in_tongue[std::size_t(Mesh::face_of(o))] = 1;
        tongue.push_back(Mesh::face_of(o));
      }
    }
  }
  return cusps;
}

struct Face_pins
{
  std::vector<int> faces;       // increasing face index
  std::vector<Vec3> directions; // unit, tangent to the face
  std::size_t faces_with_several_edges = 0;
  std::size_t cusps = 0;        // cusps whose sector the sector rule pinned (n = 4)
  std::size_t sector_faces = 0; // faces pinned by the sector rule (a cusp's sector, the inner faces of its tongue)
};

template <class Mesh>
Face_pins pin_faces(const Mesh& m, const std::vector<Vec3>& N, const Sharp_graph& g, const std::vector<Curve>& curves,
                    int window, int n)
{
  std::vector<std::vector<Proposal>> proposals(std::size_t(m.nf));
  // the proposals of a face in the order of its corners, so that ties do not depend on the curves' order
  std::vector<std::array<Vec3, 3>> by_corner(std::size_t(m.nf));
  std::vector<std::array<double, 3>> weight_by_corner(std::size_t(m.nf), {{0., 0., 0.}});
  const std::vector<Vec3> t = edge_tangents(m, g, window);
  for(const Curve& curve : curves)
    for(int e : curve.edges) {
      const int c = g.edges[e], o = m.opposite_corner[c];
      const std::pair<Vec3, Vec3> d = edge_face_directions(m, N, c, t[e]);
      const double length = norm(edge_vector(m, c));
      by_corner[c / 3][c % 3] = d.first;
      weight_by_corner[c / 3][c % 3] = length;
      by_corner[o / 3][o % 3] = d.second;
      weight_by_corner[o / 3][o % 3] = length;
    }
  Face_pins out;
  std::vector<char> in_sector(std::size_t(m.nf), 0);
  std::vector<Vec3> sector_direction(std::size_t(m.nf));
  if(n == 4) {
    std::vector<char> kept_edge(g.edges.size(), 0);
    for(const Curve& curve : curves)
      for(int e : curve.edges)
        kept_edge[std::size_t(e)] = 1;
    std::vector<std::pair<int, Vec3>> sectors;
    out.cusps = cusp_sector_directions(m, N, g, kept_edge, sectors);
    out.sector_faces = sectors.size();
    for(const auto& fd : sectors) {
      in_sector[std::size_t(fd.first)] = 1;
      sector_direction[std::size_t(fd.first)] = fd.second;
    }
  }
  for(int f = 0; f < m.nf; ++f) {
    if(in_sector[std::size_t(f)]) {
      out.faces.push_back(f);
      out.directions.push_back(sector_direction[std::size_t(f)]);
      continue;
    }
    std::vector<Proposal> p;
    for(int k = 0; k < 3; ++k)
      if(weight_by_corner[f][k] > 0)
        p.push_back({by_corner[f][k], weight_by_corner[f][k]});
    if(p.empty())
      continue;
    if(p.size() > 1)
      ++out.faces_with_several_edges;
    out.faces.push_back(f);
    out.directions.push_back(combine_proposals(p, N[f], n));
  }
  return out;
}

struct Disagreement
{
  std::size_t pairs = 0, over = 0;
  double max_radians = 0;
};

/*
  For each interior edge between two pinned faces: the angle between the first face's direction moved across the
  edge by Levi-Civita transport (a e + b N_f x e becomes a e + b N_g x e) and the second face's, modulo 2 pi / n,
  in [0, pi / n]; counted over `limit` radians.
*/
template <class Mesh>
Disagreement disagreement(const Mesh& m, const std::vector<Vec3>& N, const std::vector<int>& faces,
                          const std::vector<Vec3>& directions, int n, double limit)
{
  std::vector<int> pin(std::size_t(m.nf), -1);
  for(std::size_t i = 0; i < faces.size(); ++i)
    pin[faces[i]] = int(i);
  const double period = 2 * CGAL_PI / n;
  Disagreement out;
  for(int c = 0; c < 3 * m.nf; ++c) {
    const int o = m.opposite_corner[c];
    if(o < c)
      continue;
    const int f = c / 3, g = o / 3;
    if(pin[f] < 0 || pin[g] < 0)
      continue;
    const Vec3 e = unit(edge_vector(m, c));
    const Vec3& u = directions[pin[f]];
    const Vec3 moved = add(scaled(e, dot(u, e)), scaled(cross(N[g], e), dot(u, cross(N[f], e))));
    const Vec3& w = directions[pin[g]];
    double a = std::fmod(std::abs(std::atan2(dot(N[g], cross(moved, w)), dot(moved, w))), period);
    a = (std::min)(a, period - a);
    ++out.pairs;
    if(a > limit)
      ++out.over;
    out.max_radians = (std::max)(out.max_radians, a);
  }
  return out;
}

} // namespace features
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FEATURES_FEATURE_CURVES_H
