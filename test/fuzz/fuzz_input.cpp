// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// libFuzzer harness over the command-line program's input path (examples/Trivial_connections/
// trivial_connections.cpp): mesh bytes + singularity-file bytes -> either a clean error (TC::Invalid_input)
// or a connection and a field that pass the invariant checks below. Anything else is a bug: an exception
// of another type, a crash, a sanitizer report, a hang, or a failed invariant (abort() with a message).
//
// Input format (what test/fuzz/make_seed_corpus.py writes, and what a person can type):
//
//   HEADER '\n' MESH [ '\n' "%%" '\n' SINGULARITIES ]
//
//   HEADER         the bytes before the first '\n' (which must come within the first 16 bytes, else the
//                  input is ignored):
//                    [0] mesh format: 'O' OFF, 'J' OBJ, 'P' PLY, 'S' STL (either case); any other byte b
//                        selects format b % 4 in that order. OFF, OBJ and PLY take the package's
//                        readers (OBJ then CGAL's), STL CGAL's reader.
//                    [1] symmetry order n: '1'..'6', any other byte b gives 1 + b % 6; missing: n = 1.
//                    [2..] flags: 'u' unit weights (default Hodge star), 't' triangulate faces of more than
//                        three vertices (the program's --triangulate); other bytes are ignored.
//   MESH           the mesh file's bytes, written to a temporary file with the format's extension and read
//                  with TC::read_triangle_mesh(path, mesh), as the program does.
//   SINGULARITIES  the singularity file's bytes ("v k" lines), read with TC::read_singularities(); they
//                  start after the first line that is exactly "%%". Without such a line: no singularity.
//
// Example (a tetrahedron, n = 1, two +1 singularities):
//   O1
//   OFF
//   4 4 0
//   ... 4 vertex lines, 4 face lines ...
//   %%
//   0 1
//   1 1
//
// Meshes with more than kMaxElements vertices or faces are skipped after reading (return 0), so that
// every execution stays fast.
//
// Outcomes. TC::Invalid_input: a clean error (the program's exit status 1), return 0. Any other exception
// (CGAL assertion failures are reported with their expression and file), including std::bad_alloc, aborts:
// under ASan a failed allocation is not a std::bad_alloc anyway but a sanitizer report, and libFuzzer stops at
// a single allocation above -malloc_limit_mb (= -rss_limit_mb): an input of a few kilobytes never needs that
// much, so a reader that asks for it trusts a count of the file, which is a finding. After a successful solve
// check_solution() checks the connection (finite, antisymmetric, 0 on border halfedges), the report
// (Poincare-Hopf per component, boundary indices = period / n, residuals), our own vertex holonomy from our own
// corner angles, and the field (finite, unit, tangent, parallel for the connection modulo 2 pi / n across
// every interior edge, by the solver's transport angle in face frames and by our own unfolding). Residuals
// are bounded by 1e-9 times the magnitudes the residual sums (see check_solution()).
//
// Environment: TC_FUZZ_VERBOSE=1 prints how each input ended; TC_FUZZ_RESIDUAL=X replaces the 1e-9 residual
// bound (exploration only); TC_FUZZ_TMPDIR the directory of the temporary mesh file (default /dev/shm).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace {

namespace TC = CGAL::Trivial_connections;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Solver = TC::Trivial_connection_solver<Mesh>;
using vertex_descriptor = Mesh::Vertex_index;
using halfedge_descriptor = Mesh::Halfedge_index;
using face_descriptor = Mesh::Face_index;

constexpr std::size_t kMaxElements = 2000;
constexpr double kPi = 3.14159265358979323846;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// The project's standard residual bound (relative to the magnitudes each residual sums, see check_solution()).
// TC_FUZZ_RESIDUAL=1e-8 (say) changes it for one run, to look past a known excess (never in CI).
double kResidual = 1e-9;

const char* const kExtensions[4] = {"off", "obj", "ply", "stl"};

// ---------------------------------------------------------------------------------------------------
// Temporary mesh files: one name per extension and process, written and removed by each execution (libFuzzer
// ends with _Exit(), which runs no atexit() handler).

std::string temp_path(int format)
{
  static const std::string base = [] {
    const char* dir = std::getenv("TC_FUZZ_TMPDIR");
    std::string d = dir != nullptr && *dir != '\0' ? dir : (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp");
    return d + "/tc_fuzz_input_" + std::to_string(long(getpid())) + ".";
  }();
  return base + kExtensions[format];
}

void write_file(const std::string& path, const char* data, std::size_t size)
{
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if(file == nullptr) {
    std::perror(path.c_str());
    std::abort(); // the harness cannot do its work: not a finding, but never silent
  }
  if(size > 0 && std::fwrite(data, 1, size, file) != size) {
    std::perror(path.c_str());
    std::abort();
  }
  std::fclose(file);
}

// ---------------------------------------------------------------------------------------------------
// Invariant failures

std::string g_input_summary; // what this execution is about, printed with a failure
bool g_verbose = false;       // TC_FUZZ_VERBOSE=1: one line per input saying how it ended (for the seeds)

[[noreturn]] void fail(const std::string& what)
{
  std::fprintf(stderr, "\n==tc_fuzz== INVARIANT VIOLATED: %s\n==tc_fuzz== input: %s\n", what.c_str(),
               g_input_summary.c_str());
  std::fflush(stderr);
  std::abort();
}

std::string num(double x)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", x);
  return buffer;
}

// ---------------------------------------------------------------------------------------------------
// Small independent geometry (from the vertex positions only)

using V3 = std::array<double, 3>;
V3 operator-(const V3& a, const V3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
V3 operator+(const V3& a, const V3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
V3 operator*(double s, const V3& a) { return {{s * a[0], s * a[1], s * a[2]}}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross(const V3& a, const V3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
double norm(const V3& a) { return std::sqrt(dot(a, a)); }
V3 unit(const V3& a) { return (1 / norm(a)) * a; }
bool finite(const V3& a) { return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]); }

// a - (multiple of period) in (-period/2, period/2]
double wrap(double a, double period)
{
  double r = std::fmod(a, period);
  if(r > period / 2) r -= period;
  if(r <= -period / 2) r += period;
  return r;
}

double angle_between(const V3& u, const V3& w) { return std::atan2(norm(cross(u, w)), dot(u, w)); }

struct Face_frame
{
  V3 ex, ey, normal; // the documented frame of face f: direction of halfedge(f), N x ex; unit normal
  // |a||b| / |a x b| at the corner the normal is computed from: the normal's rounding error is about eps times
  // this (1 / sin of that corner's angle)
  double conditioning = 1;
};

V3 point(const Mesh& mesh, vertex_descriptor v)
{
  const Kernel::Point_3& p = mesh.point(v);
  return {{p.x(), p.y(), p.z()}};
}

Face_frame frame_of(const Mesh& mesh, face_descriptor f)
{
  const halfedge_descriptor h = mesh.halfedge(f);
  const V3 p[3] = {point(mesh, mesh.source(h)), point(mesh, mesh.target(h)), point(mesh, mesh.target(mesh.next(h)))};
  // the normal from the best-conditioned corner (at a needle's sharp corner the two edges are nearly parallel
  // and their cross product loses its digits); every corner gives the same orientation
  Face_frame fr;
  fr.conditioning = std::numeric_limits<double>::infinity();
  V3 best = {{0, 0, 0}};
  for(int k = 0; k < 3; ++k) {
    const V3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k], n = cross(a, b);
    const double c = norm(a) * norm(b) / norm(n);
    if(!(c >= fr.conditioning)) {
      fr.conditioning = c;
      best = n;
    }
  }
  fr.ex = unit(p[1] - p[0]);
  fr.normal = unit(best);
  fr.ey = cross(fr.normal, fr.ex);
  return fr;
}

// Levi-Civita transport by unfolding about the edge of h (conventions.md), then the rotation by t about
// the arrival normal
V3 transport(const Mesh& mesh, halfedge_descriptor h, const Face_frame& from, const Face_frame& to, const V3& u,
             double t)
{
  const V3 e = unit(point(mesh, mesh.target(h)) - point(mesh, mesh.source(h)));
  const V3 v = dot(u, e) * e + dot(u, cross(from.normal, e)) * cross(to.normal, e);
  return std::cos(t) * v + std::sin(t) * cross(to.normal, v);
}

double angle_in_frame(const Face_frame& fr, const V3& v) { return std::atan2(dot(v, fr.ey), dot(v, fr.ex)); }

// ---------------------------------------------------------------------------------------------------
// The checks of a successful solve

void check_solution(const Mesh& mesh, const Solver& solver, const TC::Solve_report& report,
                    const std::vector<std::pair<vertex_descriptor, TC::Singularity_index>>& singularities, int n,
                    Mesh::Property_map<halfedge_descriptor, double> x,
                    Mesh::Property_map<face_descriptor, Kernel::Vector_3> field)
{
  const double unit_angle = 2 * kPi / n;

  // x: finite, antisymmetric, 0 on border halfedges
  double max_x = 0;
  for(halfedge_descriptor h : mesh.halfedges()) {
    const double xh = x[h];
    if(!std::isfinite(xh))
      fail("connection angle not finite at halfedge " + std::to_string(std::size_t(h)));
    if(mesh.is_border(mesh.edge(h))) {
      if(xh != 0)
        fail("connection angle " + num(xh) + " on a border halfedge " + std::to_string(std::size_t(h)));
    } else if(x[mesh.opposite(h)] != -xh) {
      fail("connection not antisymmetric at halfedge " + std::to_string(std::size_t(h)));
    }
    max_x = (std::max)(max_x, std::abs(xh));
  }

  // the report: finite residuals, Poincare-Hopf per component in units of 1/n
  if(!std::isfinite(report.energy) || !(report.energy >= 0))
    fail("energy " + num(report.energy));
  if(!std::isfinite(report.max_vertex_residual) || !std::isfinite(report.max_loop_residual))
    fail("non-finite residual in the report");
  std::vector<std::int64_t> sum_in_units(report.components.size(), 0);
  for(const TC::Loop_report& l : report.loops) {
    if(l.component >= report.components.size())
      fail("loop of a component that does not exist");
    if(l.kind == TC::Loop_kind::boundary) {
      if(!l.index.is_multiple_of_one_over(n) || l.index.times(n) != l.period)
        fail("boundary loop index " + l.index.to_string() + " is not period / n = " + std::to_string(l.period) +
             "/" + std::to_string(n));
      sum_in_units[l.component] += l.period;
    }
  }
  for(std::size_t c = 0; c < report.components.size(); ++c) {
    const TC::Component_report& r = report.components[c];
    if(!r.vertex_index_sum.is_multiple_of_one_over(n))
      fail("vertex index sum of component " + std::to_string(c) + " is not a multiple of 1/n");
    const std::int64_t total = sum_in_units[c] + r.vertex_index_sum.times(n);
    if(total != n * r.euler_characteristic)
      fail("Poincare-Hopf violated on component " + std::to_string(c) + ": indices sum to " + std::to_string(total) +
           "/" + std::to_string(n) + ", chi = " + std::to_string(r.euler_characteristic));
  }

  // our own vertex holonomy: K_v + sum over the ring of x = 2 pi k_v, bounded relative to the magnitudes summed
  std::vector<double> k(mesh.number_of_vertices(), 0.);
  for(const auto& s : singularities)
    k[std::size_t(s.first)] = unit_angle * double(s.second.times(n));
  std::vector<double> angle_sum(mesh.number_of_vertices(), 0.), ring(mesh.number_of_vertices(), 0.),
    ring_abs(mesh.number_of_vertices(), 0.);
  std::vector<char> on_border(mesh.number_of_vertices(), 0);
  for(face_descriptor f : mesh.faces()) {
    const halfedge_descriptor h0 = mesh.halfedge(f);
    const halfedge_descriptor hs[3] = {h0, mesh.next(h0), mesh.next(mesh.next(h0))};
    for(int j = 0; j < 3; ++j) {
      const vertex_descriptor v = mesh.target(hs[j]);
      const V3 a = point(mesh, mesh.source(hs[j])) - point(mesh, v);
      const V3 b = point(mesh, mesh.target(hs[(j + 1) % 3])) - point(mesh, v);
      angle_sum[std::size_t(v)] += angle_between(a, b);
    }
  }
  for(halfedge_descriptor h : mesh.halfedges()) {
    if(mesh.is_border(h)) {
      on_border[std::size_t(mesh.target(h))] = 1;
      on_border[std::size_t(mesh.source(h))] = 1;
      continue;
    }
    if(mesh.is_border(mesh.opposite(h)))
      continue;
    ring[std::size_t(mesh.target(h))] += x[h];
    ring_abs[std::size_t(mesh.target(h))] += std::abs(x[h]);
  }
  // per interior vertex: |K_v + ring sum - 2 pi k_v| <= kResidual * (1 + |K_v| + |2 pi k_v| + sum |x| of the ring):
  // the rounding of the sum itself grows with the magnitudes summed, whatever the solver does
  double worst_ratio = 0, worst_value = 0, vertex_scale = 1, total_residual = 0;
  std::size_t worst_v = 0;
  for(vertex_descriptor v : mesh.vertices()) {
    const std::size_t i = std::size_t(v);
    if(mesh.is_isolated(v) || on_border[i])
      continue;
    const double K = 2 * kPi - angle_sum[i];
    const double r = std::abs(K + ring[i] - k[i]);
    const double scale = 1 + std::abs(K) + std::abs(k[i]) + ring_abs[i];
    vertex_scale = (std::max)(vertex_scale, scale);
    total_residual += r;
    if(!(r / scale <= worst_ratio)) {
      worst_ratio = r / scale;
      worst_value = r;
      worst_v = i;
    }
  }
  if(!(worst_ratio <= kResidual))
    fail("vertex holonomy (own corner angles) |K_v + sum x - 2 pi k_v| = " + num(worst_value) + " at vertex " +
         std::to_string(worst_v) + ": " + num(worst_ratio) + " times its scale, bound " + num(kResidual) +
         " (the solver's K_v differs from ours by " +
         num(std::abs(solver.angle_defect(vertex_descriptor(Mesh::size_type(worst_v))) -
                      (2 * kPi - angle_sum[worst_v]))) +
         "; report.max_vertex_residual " + num(report.max_vertex_residual) + ")");

  // the report's residuals, with the same kind of scale
  if(!(report.max_vertex_residual <= kResidual * vertex_scale))
    fail("report.max_vertex_residual = " + num(report.max_vertex_residual) + " > " + num(kResidual) + " * scale " +
         num(vertex_scale));
  if(report.loops.size() != solver.loops().size())
    fail("the report has " + std::to_string(report.loops.size()) + " loops, the solver " +
         std::to_string(solver.loops().size()));
  double max_loop = 0;
  for(std::size_t l = 0; l < report.loops.size(); ++l) {
    // a loop's sum reads every halfedge it crosses (a boundary loop: the open fans of its vertices)
    double crossed = 0;
    for(halfedge_descriptor h : solver.loops()[l].halfedges)
      crossed += std::abs(x[h]);
    const double H = solver.levi_civita_holonomy(l);
    const double scale = 1 + std::abs(H) + std::abs(unit_angle * double(report.loops[l].period)) + crossed;
    const double r = report.loops[l].residual;
    if(!(r <= kResidual * scale))
      fail("loop " + std::to_string(l) + (report.loops[l].kind == TC::Loop_kind::boundary ? " (boundary)" : " (generator)") +
           ": residual " + num(r) + " > " + num(kResidual) + " * scale " + num(scale));
    max_loop = (std::max)(max_loop, r);
    total_residual += r;
  }
  if(report.max_loop_residual != max_loop)
    fail("report.max_loop_residual = " + num(report.max_loop_residual) + " is not the largest loop residual " +
         num(max_loop));

  // the field: finite, unit, tangent, parallel for the connection modulo 2 pi / n across every interior edge
  std::vector<Face_frame> frames(mesh.number_of_faces());
  std::vector<double> angle(mesh.number_of_faces(), 0.);
  for(face_descriptor f : mesh.faces()) {
    const std::size_t i = std::size_t(f);
    const Kernel::Vector_3& w = field[f];
    const V3 v = {{w.x(), w.y(), w.z()}};
    if(!finite(v))
      fail("field vector not finite on face " + std::to_string(i));
    frames[i] = frame_of(mesh, f);
    const Face_frame& fr = frames[i];
    // rounding of the normal (and so of the frame the field is built in) grows like eps / sin(corner angle)
    const double geometric = 64 * kEps * fr.conditioning;
    if(!(std::abs(norm(v) - 1) <= 1e-12 + geometric))
      fail("field vector on face " + std::to_string(i) + " has length " + num(norm(v)));
    if(!(std::abs(dot(v, fr.normal)) <= 1e-12 + geometric))
      fail("field vector on face " + std::to_string(i) + " is not tangent: |v.N| = " + num(std::abs(dot(v, fr.normal))) +
           " (conditioning " + num(fr.conditioning) + ")");
    angle[i] = angle_in_frame(fr, v);
  }
  for(Mesh::Edge_index e : mesh.edges()) {
    if(mesh.is_border(e))
      continue;
    const halfedge_descriptor h = mesh.halfedge(e);
    const std::size_t f = std::size_t(mesh.face(h)), g = std::size_t(mesh.face(mesh.opposite(h)));
    // (1) in face frames with the solver's transport angle: angle_g = angle_f + rho(h) + x(h) (mod 2 pi / n)
    const double rho = solver.transport_angle(h);
    if(!std::isfinite(rho) || !(std::abs(rho) <= kPi + 1e-12))
      fail("transport_angle " + num(rho) + " at halfedge " + std::to_string(std::size_t(h)));
    // the field is propagated along a tree: across any other edge it is off by the holonomy of the cycle the edge
    // closes, a sum of vertex and loop residuals (checked above), plus the rounding of the propagation
    // and the angles are read in our frames, whose normals may differ from the solver's by their rounding
    // (the library refuses faces whose plane is rounding noise: conditioning above 1e12)
    const double frame_rounding = 64 * kEps * (frames[f].conditioning + frames[g].conditioning) * (1 + max_x);
    const double tol = kResidual * (1 + max_x) + total_residual + frame_rounding;
    const double d = std::abs(wrap(angle[g] - angle[f] - rho - x[h], unit_angle));
    // our own transport angle (unfolding of the frame vector of f), for the messages
    auto own_rho = [&] {
      return angle_in_frame(frames[g], transport(mesh, h, frames[f], frames[g], frames[f].ex, 0.));
    };
    if(!(d <= tol))
      fail("field not parallel (mod 2pi/" + std::to_string(n) + ") across edge " +
           std::to_string(std::size_t(mesh.source(h))) + "-" + std::to_string(std::size_t(mesh.target(h))) +
           ": mismatch " + num(d) + " > " + num(tol) + " (faces " + std::to_string(f) + ", " + std::to_string(g) +
           "; sum of the vertex and loop residuals " + num(total_residual) + ", largest |x| " + num(max_x) +
           ", report residuals " + num(report.max_vertex_residual) + " " + num(report.max_loop_residual) +
           "; transport_angle " + num(rho) + ", ours " + num(own_rho()) + ", conditioning of the faces " +
           num(frames[f].conditioning) + " " + num(frames[g].conditioning) + ")");
    // (2) independently, by our own unfolding of the field vector of f (rounding of the normals grows with
    // the faces' conditioning)
    const Kernel::Vector_3& wf = field[mesh.face(h)];
    const Kernel::Vector_3& wg = field[mesh.face(mesh.opposite(h))];
    const V3 u = transport(mesh, h, frames[f], frames[g], V3{{wf.x(), wf.y(), wf.z()}}, x[h]);
    const V3 vg = {{wg.x(), wg.y(), wg.z()}};
    const double d2 =
      std::abs(wrap(std::atan2(dot(cross(u, vg), frames[g].normal), dot(u, vg)), unit_angle));
    const double tol2 = tol;
    if(!(d2 <= tol2))
      fail("field not parallel by our own Levi-Civita unfolding across edge " +
           std::to_string(std::size_t(mesh.source(h))) + "-" + std::to_string(std::size_t(mesh.target(h))) +
           ": mismatch " + num(d2) + " > " + num(tol2));
  }
}

// ---------------------------------------------------------------------------------------------------

struct Input
{
  int format = 0;
  int n = 1;
  bool unit_weights = false;
  bool triangulate = false;
  std::string mesh, singularities;
};

bool split_input(const uint8_t* data, std::size_t size, Input& in)
{
  const char* p = reinterpret_cast<const char*>(data);
  std::size_t eol = 0;
  while(eol < size && eol < 16 && p[eol] != '\n')
    ++eol;
  if(eol >= size || p[eol] != '\n')
    return false;
  if(eol >= 1) {
    const unsigned char c = static_cast<unsigned char>(p[0]);
    switch(c) {
      case 'O': case 'o': in.format = 0; break;
      case 'J': case 'j': in.format = 1; break;
      case 'P': case 'p': in.format = 2; break;
      case 'S': case 's': in.format = 3; break;
      default: in.format = c % 4;
    }
  }
  if(eol >= 2) {
    const unsigned char c = static_cast<unsigned char>(p[1]);
    in.n = (c >= '1' && c <= '6') ? c - '0' : 1 + c % 6;
  }
  for(std::size_t i = 2; i < eol; ++i) {
    in.unit_weights = in.unit_weights || p[i] == 'u';
    in.triangulate = in.triangulate || p[i] == 't';
  }
  const std::string rest(p + eol + 1, size - eol - 1);
  // the singularities start after the first line that is exactly "%%"
  std::size_t sep = std::string::npos;
  if(rest.compare(0, 3, "%%\n") == 0)
    sep = 0;
  else {
    const std::size_t at = rest.find("\n%%\n");
    if(at != std::string::npos)
      sep = at + 1;
  }
  if(sep == std::string::npos) {
    in.mesh = rest;
  } else {
    in.mesh = rest.substr(0, sep);
    in.singularities = rest.substr(sep + 3);
  }
  return true;
}

int run(const Input& in)
{
  const std::string path = temp_path(in.format);
  write_file(path, in.mesh.data(), in.mesh.size());
  struct Remove_file
  {
    const std::string& path;
    ~Remove_file() { std::remove(path.c_str()); }
  } remove_file{path};

  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order =
    TC::read_triangle_mesh(path, mesh, TC::parameters::triangulate(in.triangulate));
  if(order.vertices.size() > kMaxElements || order.faces.size() > kMaxElements) {
    if(g_verbose)
      std::fprintf(stderr, "tc_fuzz: skipped (%zu vertices, %zu faces)\n", order.vertices.size(), order.faces.size());
    return 0;
  }

  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> singularities;
  {
    std::istringstream is(in.singularities);
    for(const auto& s : TC::read_singularities(is, "singularities", order.vertices.size()))
      singularities.emplace_back(order.vertices[s.first], s.second);
  }

  Solver solver(mesh, TC::parameters::weighting(in.unit_weights ? TC::Weighting::unit : TC::Weighting::hodge_star));
  Mesh::Property_map<halfedge_descriptor, double> x =
    mesh.add_property_map<halfedge_descriptor, double>("h:tc_connection", 0.).first;
  Mesh::Property_map<face_descriptor, Kernel::Vector_3> field =
    mesh.add_property_map<face_descriptor, Kernel::Vector_3>("f:tc_field", CGAL::NULL_VECTOR).first;
  const TC::Solve_report report = solver.solve(singularities, x, TC::parameters::symmetry_order(in.n));
  solver.compute_field(x, field);
  check_solution(mesh, solver, report, singularities, in.n, x, field);
  if(g_verbose)
    std::fprintf(stderr, "tc_fuzz: solved and checked (%zu vertices, %zu faces, %zu loops, residuals %.2e %.2e)\n",
                 order.vertices.size(), order.faces.size(), report.loops.size(), report.max_vertex_residual,
                 report.max_loop_residual);
  return 0;
}

} // namespace

// UBSan's options unless UBSAN_OPTIONS says otherwise (every check already aborts: -fno-sanitize-recover)
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1"; }

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  const char* verbose = std::getenv("TC_FUZZ_VERBOSE");
  g_verbose = verbose != nullptr && *verbose != '\0' && *verbose != '0';
  if(const char* bound = std::getenv("TC_FUZZ_RESIDUAL")) {
    char* end = nullptr;
    const double b = std::strtod(bound, &end);
    if(end == bound || *end != '\0' || !(b > 0)) {
      std::fprintf(stderr, "tc_fuzz: TC_FUZZ_RESIDUAL must be a positive number, got '%s'\n", bound);
      std::exit(2);
    }
    kResidual = b;
    std::fprintf(stderr, "tc_fuzz: residual bound %g (TC_FUZZ_RESIDUAL) instead of 1e-9\n", b);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  Input in;
  if(!split_input(data, size, in)) {
    if(g_verbose)
      std::fprintf(stderr, "tc_fuzz: ignored (no header line)\n");
    return 0;
  }
  g_input_summary = std::string("format ") + kExtensions[in.format] + ", n = " + std::to_string(in.n) +
                    (in.unit_weights ? ", unit weights" : ", hodge weights") + (in.triangulate ? ", triangulate" : "") +
                    ", " + std::to_string(in.mesh.size()) + " mesh bytes, " + std::to_string(in.singularities.size()) +
                    " singularity bytes";
  try {
    return run(in);
  } catch(const TC::Invalid_input& e) {
    if(g_verbose)
      std::fprintf(stderr, "tc_fuzz: clean error %s: %s\n", TC::error_code_name(e.code()), e.what());
    return 0; // a clean error: what the program reports with exit status 1
  } catch(const CGAL::Failure_exception& e) {
    std::fprintf(stderr,
                 "\n==tc_fuzz== CGAL FAILURE (not Invalid_input): %s: expression '%s' at %s:%d (%s)\n"
                 "==tc_fuzz== input: %s\n",
                 e.library().c_str(), e.expression().c_str(), e.filename().c_str(), e.line_number(),
                 e.message().c_str(), g_input_summary.c_str());
    std::fflush(stderr);
    std::abort();
  } catch(const std::exception& e) {
    std::fprintf(stderr, "\n==tc_fuzz== UNEXPECTED EXCEPTION (not Invalid_input): %s\n==tc_fuzz== input: %s\n",
                 e.what(), g_input_summary.c_str());
    std::fflush(stderr);
    std::abort();
  } catch(...) {
    std::fprintf(stderr, "\n==tc_fuzz== UNEXPECTED EXCEPTION of unknown type\n==tc_fuzz== input: %s\n",
                 g_input_summary.c_str());
    std::fflush(stderr);
    std::abort();
  }
}
