// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Feature pins (issue 37, item 2): what pinning the faces beside the sharp edges costs, against the same mesh
// without pins measured in the same run, in the library and in the program as a whole process.
//
//   trivial_connections_feature_pins_benchmark [--benchmark_filter=REGEX]
//   trivial_connections_feature_pins_benchmark --write-pins MESH OUT.txt [features|band|50k]   (the pins only)
//
// Meshes: CGAL's fandisk (13k faces), fandisk_large (32k) and fandisk_large split 1-to-4 by edge midpoints once
// (mid1, 127k) and twice (mid2, 507k); the splits are made on first use in the benchmark mesh cache
// (TC_BENCH_MESH_CACHE, as benchmark_meshes.h does for the Loop subdivisions), with an OFF copy of every mesh
// for the program. n = 4 throughout.
// Pins (`f x y z`, also written to the cache as MESH.PINS.constraints.txt for the program's --constraints):
//   features  CGAL::Trivial_connections::feature_aligned_faces(mesh, 30 degrees, symmetry_order(4)): the faces
//             beside the sharp feature curves, with the curve's fitted direction
//   band      the feature faces and the faces within r vertex rings of them, r the smallest giving >= 5 % of the
//             faces, the last ring cut at 10 % (in the order of the breadth-first growth); a band face takes the
//             direction of the face it was reached from, projected to its plane
//   50k       (mid2 only) the first 50,000 faces of the same breadth-first growth
// Benchmarks:
//   library/MESH/PINS  solver without pins: constructor, place_singularities(), solve(); then a new solver with
//     the pins as constrained_faces with their face_directions and symmetry_order (so that touching pins that
//     disagree go to the lattice): constructor, place_singularities(face_directions), solve(face_directions).
//     Counters: t_build0, t_place0, t_solve0, t_build, t_place, t_solve, r_build = t_build / t_build0,
//     r_total = (t_build + t_place + t_solve) / (t_build0 + t_place0 + t_solve0), peak0_bytes, peak_bytes
//     (VmHWM above the resident size before each solver), r_peak; energy0, energy (Solve_report::energy),
//     proven (integers_proven_optimal), lower_bound (energy_lower_bound), links (Solve_report::constraints),
//     decided (links whose faces touch: share a vertex), links_one_edge (length 1), pins, pin_fraction,
//     disagreeing_pairs / neighbouring_pairs (feature_aligned_faces' report), t_reference (the suite's reference
//     factorization of the same mesh's Laplacian), r_build_reference = t_build / t_reference.
//   set_constraints/MESH/PINS  a solver built without pins (t_build0), then set_constraints(constrained_faces)
//     (t_set), place_singularities(face_directions) (t_place), solve (t_solve): r_set_solve = (t_set + t_solve) /
//     t_build0, peak over the three above the solver without pins (r_peak = peak / peak of the constructor;
//     peak_set_bytes, r_peak_set: up to the end of set_constraints()).
//   program/MESH/PINS  `trivial_connections MESH.off --n 4 --auto --no-refine` (the placement, what the pins cost
//     it; --auto alone also refines) without and with `--constraints`, each a child
//     process (fork + exec, wait4: wall time and its own maximum resident size): t_program0, t_program,
//     r_program, rss0_bytes, rss_bytes, r_rss, program_energy0, program_energy (parsed from its output).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/feature_alignment.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/singularity_placement.h>

#include "benchmark_meshes.h"
#include "benchmark_support.h"

#include <benchmark/benchmark.h>

#include <CGAL/boost/graph/IO/OFF.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <fcntl.h>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
namespace P = TC::parameters;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Vertex = Mesh::Vertex_index;
using Face = Mesh::Face_index;
using Singularities = std::vector<std::pair<Vertex, TC::Singularity_index>>;

namespace {

using tc_bench::Clock;
using tc_bench::seconds_since;

constexpr int symmetry = 4;
constexpr double feature_angle = 30;
constexpr double band_fraction = 0.05, band_cap = 0.10;
constexpr std::size_t many_pins = 50000;

struct Spec
{
  std::string name;
  int splits; // 1-to-4 midpoint splits of fandisk_large (-1: fandisk itself)
};

const std::vector<Spec>& specs()
{
  static const std::vector<Spec> s = {
    {"fandisk", -1}, {"fandisk_large", 0}, {"fandisk_large_mid1", 1}, {"fandisk_large_mid2", 2}};
  return s;
}

// 1-to-4 split by edge midpoints (the shape, and its sharp edges, unchanged)
Mesh midpoint_split(const Mesh& m)
{
  Mesh out;
  std::vector<Vertex> old(num_vertices(m));
  for(Vertex v : vertices(m))
    old[std::size_t(v)] = out.add_vertex(m.point(v));
  std::vector<Vertex> mid(num_edges(m));
  for(auto e : edges(m)) {
    const auto h = halfedge(e, m);
    mid[std::size_t(e)] = out.add_vertex(CGAL::midpoint(m.point(source(h, m)), m.point(target(h, m))));
  }
  for(Face f : faces(m)) {
    const auto h0 = halfedge(f, m), h1 = next(h0, m), h2 = next(h1, m);
    const Vertex a = old[std::size_t(source(h0, m))], b = old[std::size_t(source(h1, m))],
                 c = old[std::size_t(source(h2, m))];
    const Vertex ab = mid[std::size_t(edge(h0, m))], bc = mid[std::size_t(edge(h1, m))],
                 ca = mid[std::size_t(edge(h2, m))];
    out.add_face(a, ab, ca);
    out.add_face(ab, b, bc);
    out.add_face(ca, bc, c);
    out.add_face(ab, bc, ca);
  }
  return out;
}

bool write_off(const Mesh& mesh, const std::string& path)
{
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp);
    if(!out || !CGAL::IO::write_OFF(out, mesh, CGAL::parameters::stream_precision(17))) {
      std::remove(tmp.c_str());
      return false;
    }
  }
  return std::rename(tmp.c_str(), path.c_str()) == 0;
}

// the mesh, and its OFF file in the cache (for the program); the splits are made on first use
std::string load(const Spec& spec, Mesh& mesh, std::string& off)
{
  const std::string dir = tc_bench::mesh_cache_dir();
  ::mkdir(dir.c_str(), 0755);
  off = dir + "/" + spec.name + ".off";
  if(tc_bench::file_exists(off) && CGAL::IO::read_polygon_mesh(off, mesh) && num_faces(mesh) > 0)
    return "";
  mesh.clear();
  const std::string source = std::string(TC_CGAL_DATA_DIR) + (spec.splits < 0 ? "/fandisk.off" : "/fandisk_large.off");
  if(!CGAL::IO::read_polygon_mesh(source, mesh))
    return "cannot read " + source + " (run scripts/fetch_cgal_data.sh)";
  for(int i = 0; i < spec.splits; ++i)
    mesh = midpoint_split(mesh);
  if(!write_off(mesh, off))
    return "cannot write " + off;
  mesh.clear();
  // read back, so that the library and the program see the same coordinates and numbering
  return CGAL::IO::read_polygon_mesh(off, mesh) ? "" : "cannot read back " + off;
}

struct Pins
{
  std::vector<Face> faces; // increasing index
  std::vector<K::Vector_3> directions; // per face of the mesh (zero where not pinned)
  TC::Feature_alignment_report features;
  int rings = 0;
};

K::Vector_3 face_normal(const Mesh& m, Face f)
{
  const auto h = halfedge(f, m);
  const K::Point_3 &a = m.point(source(h, m)), &b = m.point(target(h, m)), &c = m.point(target(next(h, m), m));
  const K::Vector_3 n = CGAL::cross_product(b - a, c - a);
  return n / std::sqrt(n.squared_length());
}

struct Direction_writer
{
  using key_type = Face;
  using value_type = K::Vector_3;
  using reference = K::Vector_3&;
  using category = boost::writable_property_map_tag;
  std::vector<K::Vector_3>* d;
  friend void put(const Direction_writer& m, Face f, const K::Vector_3& v) { (*m.d)[std::size_t(f)] = v; }
};

// kind: "features", "band" or "50k"
Pins make_pins(const Mesh& mesh, const std::string& kind)
{
  Pins p;
  p.directions.assign(num_faces(mesh), K::Vector_3(0, 0, 0));
  std::vector<Face> feature;
  p.features = TC::feature_aligned_faces(mesh, feature_angle, std::back_inserter(feature), Direction_writer{&p.directions},
                                         P::symmetry_order(symmetry));
  if(kind == "features") {
    p.faces = feature;
    return p;
  }
  // breadth-first growth through shared vertices, ring by ring
  const std::size_t nf = num_faces(mesh);
  const std::size_t wanted = kind == "50k" ? many_pins : std::size_t(std::ceil(band_fraction * double(nf)));
  // the last ring is cut where the band reaches `cap` faces (in the order of the growth)
  const std::size_t cap = kind == "50k" ? many_pins : std::size_t(band_cap * double(nf));
  std::vector<char> in(nf, 0);
  std::vector<Face> order = feature;
  for(Face f : feature)
    in[std::size_t(f)] = 1;
  std::vector<Face> ring = feature;
  while(order.size() < wanted && !ring.empty()) {
    std::vector<Face> next_ring;
    ++p.rings;
    for(std::size_t i = 0; i < ring.size() && order.size() < cap; ++i) {
      const Face f = ring[i];
      for(Vertex v : vertices_around_face(halfedge(f, mesh), mesh))
        for(Face g : faces_around_target(halfedge(v, mesh), mesh)) {
          if(g == Mesh::null_face() || in[std::size_t(g)] || order.size() >= cap)
            continue;
          in[std::size_t(g)] = 1;
          const K::Vector_3 n = face_normal(mesh, g);
          K::Vector_3 d = p.directions[std::size_t(f)];
          d = d - (d * n) * n;
          if(d.squared_length() < 1e-6) { // along the normal: the face's first edge
            const auto h = halfedge(g, mesh);
            d = mesh.point(target(h, mesh)) - mesh.point(source(h, mesh));
          }
          p.directions[std::size_t(g)] = d / std::sqrt(d.squared_length());
          next_ring.push_back(g);
          order.push_back(g);
        }
    }
    ring.swap(next_ring);
  }
  p.faces = order;
  std::sort(p.faces.begin(), p.faces.end());
  return p;
}

std::string write_pins(const Mesh& mesh, const Pins& p, const std::string& path)
{
  std::ofstream out(path);
  out.precision(17);
  for(Face f : p.faces) {
    const K::Vector_3& d = p.directions[std::size_t(f)];
    out << std::size_t(f) << ' ' << d.x() << ' ' << d.y() << ' ' << d.z() << '\n';
  }
  (void)mesh;
  return out ? "" : "cannot write " + path;
}

struct Direction_map
{
  using key_type = Face;
  using value_type = K::Vector_3;
  using reference = const K::Vector_3&;
  using category = boost::readable_property_map_tag;
  const std::vector<K::Vector_3>* d;
  friend reference get(const Direction_map& m, Face f) { return (*m.d)[std::size_t(f)]; }
};

struct Link_counts
{
  std::size_t links = 0, decided = 0, one_edge = 0;
};

Link_counts count_links(const Mesh& mesh, const TC::Solve_report& r)
{
  Link_counts c;
  c.links = r.constraints.size();
  for(const auto& l : r.constraints) {
    if(l.length == 1)
      ++c.one_edge;
    std::set<Vertex> a;
    for(Vertex v : vertices_around_face(halfedge(Face(Mesh::size_type(l.from_face)), mesh), mesh))
      a.insert(v);
    for(Vertex v : vertices_around_face(halfedge(Face(Mesh::size_type(l.to_face)), mesh), mesh))
      if(a.count(v)) {
        ++c.decided;
        break;
      }
  }
  return c;
}

void library_run(benchmark::State& state, const Spec& spec, const std::string& kind)
{
  using Solver = TC::Trivial_connection_solver<Mesh>;
  Mesh mesh;
  std::string off;
  const std::string error = load(spec, mesh, off);
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const Pins pins = make_pins(mesh, kind);
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  const Direction_map directions{&pins.directions};
  double t_build0 = 0, t_place0 = 0, t_solve0 = 0, t_build = 0, t_place = 0, t_solve = 0, peak0 = -1, peak = -1;
  TC::Solve_report r0, r;
  TC::Placement_report p0, p;
  tc_bench::Reference_result ref;
  for(auto _ : state) {
    std::vector<tc_bench::Weighted_edge> edges;
    try {
      {
        const double base = tc_bench::reset_peak_memory() ? tc_bench::status_bytes("VmRSS") : -1;
        auto t0 = Clock::now();
        Solver solver(mesh);
        t_build0 = seconds_since(t0);
        Singularities placed;
        t0 = Clock::now();
        p0 = TC::place_singularities(solver, std::back_inserter(placed), P::symmetry_order(symmetry));
        t_place0 = seconds_since(t0);
        t0 = Clock::now();
        r0 = solver.solve(placed, x, P::symmetry_order(symmetry));
        t_solve0 = seconds_since(t0);
        peak0 = base >= 0 ? tc_bench::status_bytes("VmHWM") - base : -1;
        edges = tc_bench::laplacian_edges(mesh, solver);
      }
      {
        const double base = tc_bench::reset_peak_memory() ? tc_bench::status_bytes("VmRSS") : -1;
        auto t0 = Clock::now();
        // the targets given at construction: touching pins that disagree go to the lattice (not rounded)
        Solver solver(mesh, P::constrained_faces(pins.faces, P::face_directions(directions, P::symmetry_order(symmetry))));
        t_build = seconds_since(t0);
        Singularities placed;
        t0 = Clock::now();
        p = TC::place_singularities(solver, std::back_inserter(placed),
                                    P::face_directions(directions, P::symmetry_order(symmetry)));
        t_place = seconds_since(t0);
        t0 = Clock::now();
        r = solver.solve(placed, x, P::face_directions(directions, P::symmetry_order(symmetry)));
        t_solve = seconds_since(t0);
        peak = base >= 0 ? tc_bench::status_bytes("VmHWM") - base : -1;
      }
    } catch(const std::exception& e) {
      state.SkipWithError((spec.name + ": " + e.what()).c_str());
      break;
    }
    ref = tc_bench::reference_factorization<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(num_vertices(mesh),
                                                                                                 edges);
    state.SetIterationTime(t_build + t_place + t_solve);
  }
  const Link_counts links = count_links(mesh, r);
  auto& k = state.counters;
  k["faces"] = double(num_faces(mesh));
  k["pins"] = double(pins.faces.size());
  k["pin_fraction"] = double(pins.faces.size()) / double(num_faces(mesh));
  k["rings"] = pins.rings;
  k["sharp_edges"] = double(pins.features.number_of_sharp_edges);
  k["neighbouring_pairs"] = double(pins.features.neighbouring_pairs);
  k["disagreeing_pairs"] = double(pins.features.disagreeing_pairs);
  k["t_build0"] = t_build0;
  k["t_place0"] = t_place0;
  k["t_solve0"] = t_solve0;
  k["t_build"] = t_build;
  k["t_place"] = t_place;
  k["t_solve"] = t_solve;
  k["r_build"] = t_build / t_build0;
  k["r_total"] = (t_build + t_place + t_solve) / (t_build0 + t_place0 + t_solve0);
  k["peak0_bytes"] = peak0;
  k["peak_bytes"] = peak;
  k["r_peak"] = peak0 > 0 ? peak / peak0 : -1;
  k["energy0"] = r0.energy;
  k["energy"] = r.energy;
  k["field_energy"] = p.field_energy;
  k["singularities0"] = double(p0.number_of_singularities);
  k["singularities"] = double(p.number_of_singularities);
  k["proven0"] = r0.integers_proven_optimal;
  k["proven"] = r.integers_proven_optimal;
  k["lower_bound"] = r.energy_lower_bound;
  k["links"] = double(links.links);
  k["decided"] = double(links.decided);
  k["links_one_edge"] = double(links.one_edge);
  k["max_constraint_residual"] = r.max_constraint_residual;
  k["t_reference"] = ref.seconds;
  k["r_build_reference"] = t_build / ref.seconds;
}

void set_constraints_run(benchmark::State& state, const Spec& spec, const std::string& kind)
{
  using Solver = TC::Trivial_connection_solver<Mesh>;
  Mesh mesh;
  std::string off;
  const std::string error = load(spec, mesh, off);
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const Pins pins = make_pins(mesh, kind);
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  const Direction_map directions{&pins.directions};
  double t_build0 = 0, t_set = 0, t_place = 0, t_solve = 0, peak0 = -1, peak_set = -1, peak = -1;
  TC::Solve_report r;
  TC::Constraint_update u;
  for(auto _ : state) {
    try {
      const double base = tc_bench::reset_peak_memory() ? tc_bench::status_bytes("VmRSS") : -1;
      auto t0 = Clock::now();
      Solver solver(mesh);
      t_build0 = seconds_since(t0);
      peak0 = base >= 0 ? tc_bench::status_bytes("VmHWM") - base : -1;
      t0 = Clock::now();
      u = solver.set_constraints(
        P::constrained_faces(pins.faces, P::face_directions(directions, P::symmetry_order(symmetry))));
      t_set = seconds_since(t0);
      peak_set = base >= 0 ? tc_bench::status_bytes("VmHWM") - base : -1;
      Singularities placed;
      t0 = Clock::now();
      TC::place_singularities(solver, std::back_inserter(placed),
                              P::face_directions(directions, P::symmetry_order(symmetry)));
      t_place = seconds_since(t0);
      t0 = Clock::now();
      r = solver.solve(placed, x, P::face_directions(directions, P::symmetry_order(symmetry)));
      t_solve = seconds_since(t0);
      peak = base >= 0 ? tc_bench::status_bytes("VmHWM") - base : -1;
    } catch(const std::exception& e) {
      state.SkipWithError((spec.name + ": " + e.what()).c_str());
      break;
    }
    state.SetIterationTime(t_set + t_solve);
  }
  const Link_counts links = count_links(mesh, r);
  auto& k = state.counters;
  k["faces"] = double(num_faces(mesh));
  k["pins"] = double(pins.faces.size());
  k["t_build0"] = t_build0;
  k["t_set"] = t_set;
  k["t_place"] = t_place;
  k["t_solve"] = t_solve;
  k["r_set_solve"] = (t_set + t_solve) / t_build0;
  k["r_set_place_solve"] = (t_set + t_place + t_solve) / t_build0;
  k["peak0_bytes"] = peak0;
  k["peak_set_bytes"] = peak_set;
  k["peak_bytes"] = peak;
  k["r_peak_set"] = peak0 > 0 ? peak_set / peak0 : -1;
  k["r_peak"] = peak0 > 0 ? peak / peak0 : -1;
  k["refactored"] = u.refactored;
  k["energy"] = r.energy;
  k["proven"] = r.integers_proven_optimal;
  k["lower_bound"] = r.energy_lower_bound;
  k["links"] = double(links.links);
  k["decided"] = double(links.decided);
  k["links_one_edge"] = double(links.one_edge);
}

#ifdef TC_PROGRAM_PATH
struct Child
{
  double seconds = 0, rss = -1;
  bool ok = false;
  std::string output;
};

// runs argv as a child process, stdout and stderr to `log`: wall time and the child's own maximum resident size
Child run_child(const std::vector<std::string>& args, const std::string& log)
{
  Child c;
  std::vector<char*> argv;
  for(const std::string& a : args)
    argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  tc_bench::stop_idle_blas_threads();
  const auto t0 = Clock::now();
  const pid_t pid = ::fork();
  if(pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if(fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage;
  if(pid < 0 || ::wait4(pid, &status, 0, &usage) != pid)
    return c;
  c.seconds = seconds_since(t0);
  c.rss = double(usage.ru_maxrss) * 1024;
  c.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::ifstream in(log);
  c.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return c;
}

double energy_of(const std::string& output)
{
  std::smatch m;
  static const std::regex e("energy: ([-+0-9.eE]+)");
  double last = -1;
  for(auto it = std::sregex_iterator(output.begin(), output.end(), e); it != std::sregex_iterator(); ++it)
    last = std::stod((*it)[1]); // the final solve's (after the placement's)
  return last;
}

void program_run(benchmark::State& state, const Spec& spec, const std::string& kind)
{
  Mesh mesh;
  std::string off;
  const std::string error = load(spec, mesh, off);
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const Pins pins = make_pins(mesh, kind);
  const std::string base = tc_bench::mesh_cache_dir() + "/" + spec.name;
  const std::string constraints = base + "." + kind + ".constraints.txt";
  const std::string written = write_pins(mesh, pins, constraints);
  if(!written.empty()) {
    state.SkipWithError(written.c_str());
    return;
  }
  const std::size_t nf = num_faces(mesh);
  mesh.clear();
  const std::vector<std::string> without = {TC_PROGRAM_PATH, off, "--n", "4", "--auto", "--no-refine"};
  std::vector<std::string> with = without;
  with.push_back("--constraints");
  with.push_back(constraints);
  Child c0, c;
  for(auto _ : state) {
    c0 = run_child(without, base + ".program0.log");
    c = run_child(with, base + "." + kind + ".program.log");
    if(!c0.ok || !c.ok) {
      state.SkipWithError(("the program failed, see " + base + ".*.log").c_str());
      break;
    }
    state.SetIterationTime(c.seconds);
  }
  auto& k = state.counters;
  k["faces"] = double(nf);
  k["pins"] = double(pins.faces.size());
  k["pin_fraction"] = double(pins.faces.size()) / double(nf);
  k["t_program0"] = c0.seconds;
  k["t_program"] = c.seconds;
  k["r_program"] = c.seconds / c0.seconds;
  k["rss0_bytes"] = c0.rss;
  k["rss_bytes"] = c.rss;
  k["r_rss"] = c.rss / c0.rss;
  k["program_energy0"] = energy_of(c0.output);
  k["program_energy"] = energy_of(c.output);
}
#endif

} // namespace

int main(int argc, char** argv)
{
  // the pins of any mesh, for the comparison with Directional (scripts/compare_directional.sh)
  if(argc >= 4 && std::string(argv[1]) == "--write-pins") {
    Mesh mesh;
    if(!CGAL::IO::read_polygon_mesh(argv[2], mesh) || num_faces(mesh) == 0) {
      std::cerr << "cannot read " << argv[2] << "\n";
      return 1;
    }
    const Pins pins = make_pins(mesh, argc >= 5 ? argv[4] : "features");
    const std::string error = write_pins(mesh, pins, argv[3]);
    std::cout << pins.faces.size() << " pins of " << num_faces(mesh) << " faces, " << pins.features.number_of_sharp_edges
              << " sharp edges, " << pins.features.disagreeing_pairs << " of " << pins.features.neighbouring_pairs
              << " neighbouring pairs disagree by more than 5 degrees\n";
    if(!error.empty())
      std::cerr << error << "\n";
    return error.empty() ? 0 : 1;
  }
  for(const Spec& spec : specs()) {
    std::vector<std::string> kinds = {"features", "band"};
    if(spec.splits == 2)
      kinds.push_back("50k");
    for(const std::string& kind : kinds) {
      benchmark::RegisterBenchmark(("library/" + spec.name + "/" + kind).c_str(),
                                   [spec, kind](benchmark::State& s) { library_run(s, spec, kind); })
        ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
#ifdef TC_PROGRAM_PATH
      benchmark::RegisterBenchmark(("program/" + spec.name + "/" + kind).c_str(),
                                   [spec, kind](benchmark::State& s) { program_run(s, spec, kind); })
        ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
#endif
    }
    if(spec.splits == 2)
      benchmark::RegisterBenchmark(("set_constraints/" + spec.name + "/50k").c_str(),
                                   [spec](benchmark::State& s) { set_constraints_run(s, spec, "50k"); })
        ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);
  }
  benchmark::AddCustomContext("mesh_cache", tc_bench::mesh_cache_dir());
  benchmark::AddCustomContext("symmetry_order", std::to_string(symmetry));
  benchmark::AddCustomContext("feature_angle_degrees", std::to_string(feature_angle));
  benchmark::Initialize(&argc, argv);
  if(benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
