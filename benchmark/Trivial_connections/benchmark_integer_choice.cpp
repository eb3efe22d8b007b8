// The choice of the free integers (one per homology generator, boundary loop and constraint link) against
// their number k, from about 10 to 2,000, through the public API only. The solver reduces the lattice of the
// integers once, in its constructor (phase loop_metric: the metric read from the factorization, then LLL with
// deep insertions), and every solve() chooses them by nearest plane, greedy descent and a budgeted
// Schnorr-Euchner enumeration (phase loop_integers). This benchmark says how both costs grow with k, and how
// good the choice is where the enumeration cannot finish: the gap to the solve's own lower bound.
//
//   trivial_connections_integer_benchmark [--benchmark_filter=REGEX] [--benchmark_format=json]
//
// Benchmarks are named integers/CASE/n:N/set:S (N = 1 or 4, two singularity sets S = 0, 1). The solver of a
// case is built once, before its first benchmark, and kept for the others of the case; each benchmark times
// solve() only (manual time: the whole solve), the same solve in every iteration.
//
// Cases (the annuli and squares are made here; CGAL's meshes come from TC_CGAL_DATA_DIR, skipped if missing):
//   annulus_mM   planar annulus (radii 1 and 1.5), M vertices on each boundary circle, rings of near-square
//                cells, interior vertices jittered; align_with_boundary(true): a constraint link per boundary
//                vertex but one, k = 1 loop + 2M - 1 links.
//   holes_pP     gently curved square (a bump of height 0.15 over the unit square) with P x P square holes,
//                interior vertices jittered; align_with_boundary(true), k = P^2 loops + the boundary
//                vertices - 1 links.
//   cheese       cheese.off, genus 133 (266 generator integers), no alignment.
//   elephant-with-holes, elephant-with-holes_aligned   elephant-with-holes.off (111 free loop integers
//                without alignment; 111 + 1,217 links with it).
// Singularities: on a closed component |chi| n vertices of index sign(chi) / n (Poincare-Hopf), set 1 at
// shifted positions with an extra +1/n, -1/n pair; on a bordered one 5 vertices of index 1/n (set 0), or
// 3 of +1/n and 2 of -1/n elsewhere (set 1); the boundary loops take the rest.
//
// Environment: TC_BENCH_MARKDOWN=FILE also writes the markdown table of the run to FILE (one row per case and
// n, the two singularity sets pooled), which `scripts/run_benchmarks.sh --integers` appends to RESULTS.md.
//
// Counters (seconds unless noted): faces, n, k = free_loops (the loops not prescribed, but one boundary loop
// per bordered component, which Poincare-Hopf fixes) + links (the rows of
// Solve_report::constraints); t_build (the constructor, measured directly) and t_loop_metric (its
// loop_metric phase: metric + lattice reduction, from the progress callback); t_integers and t_integers_max
// (median and largest over the iterations of the loop_integers phase), t_solve (median of the whole solve());
// energy, guidance_energy, energy_lower_bound, rounding_energy of the Solve_report; proven
// (integers_proven_optimal, 0/1); rel_gap = (energy + guidance - bound) / (energy + guidance), 0 when proven;
// rounding_excess = (rounding_energy - energy - guidance) / (energy + guidance), what rounding the integers
// one by one would have cost more.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include "benchmark_support.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Vertex = Mesh::Vertex_index;
using Singularities = std::vector<std::pair<Vertex, TC::Singularity_index>>;
using Solver = TC::Trivial_connection_solver<Mesh>;
using Clock = tc_bench::Clock;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr int iterations = 9; // solves timed per benchmark (the medians are over them)

using tc_bench::seconds_since;
using tc_bench::Phase_times;

double median(std::vector<double> v)
{
  if(v.empty())
    return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

// ---------------------------------------------------------------------------------------------------------
// Generated meshes. The jitter comes from a fixed-seed linear congruential generator (the same meshes on
// every platform).

struct Jitter
{
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  double operator()() // uniform in [-1, 1)
  {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) * (2.0 / 9007199254740992.0) - 1;
  }
};

// quad (a, b, c, d) counter-clockwise, split along a-c or b-d
bool add_quad(Mesh& mesh, Vertex a, Vertex b, Vertex c, Vertex d, bool other_diagonal)
{
  if(other_diagonal)
    return mesh.add_face(a, b, d) != Mesh::null_face() && mesh.add_face(b, c, d) != Mesh::null_face();
  return mesh.add_face(a, b, c) != Mesh::null_face() && mesh.add_face(a, c, d) != Mesh::null_face();
}

// planar annulus between radii 1 and 1.5 with m vertices on each circle
std::string make_annulus(int m, Mesh& mesh)
{
  const double r0 = 1, r1 = 1.5;
  const double h = 2 * pi * 0.5 * (r0 + r1) / m;                  // cell width along the circles
  const int rings = (std::max)(2, int(std::lround((r1 - r0) / h))); // near-square cells
  Jitter jitter;
  std::vector<Vertex> v(std::size_t(rings + 1) * std::size_t(m));
  for(int i = 0; i <= rings; ++i)
    for(int j = 0; j < m; ++j) {
      const bool interior = i > 0 && i < rings;
      const double rho = r0 + (r1 - r0) * (double(i) + (interior ? 0.2 * jitter() : 0)) / rings;
      const double theta = 2 * pi * (double(j) + 0.2 * jitter()) / m;
      v[std::size_t(i) * m + j] = mesh.add_vertex(Point(rho * std::cos(theta), rho * std::sin(theta), 0));
    }
  for(int i = 0; i < rings; ++i)
    for(int j = 0; j < m; ++j) {
      const int jn = (j + 1) % m;
      if(!add_quad(mesh, v[std::size_t(i) * m + j], v[std::size_t(i + 1) * m + j], v[std::size_t(i + 1) * m + jn],
                   v[std::size_t(i) * m + jn], (i + j) % 2 == 1))
        return "annulus: a face could not be added";
    }
  return "";
}

// the unit square as an N x N grid of cells with p x p holes of s x s cells, g cells apart (N = p s + (p + 1) g),
// on the bump z = 0.15 sin(pi x) sin(pi y)
std::string make_square_with_holes(int p, int s, int g, int subdivision, Mesh& mesh)
{
  s *= subdivision;
  g *= subdivision;
  const int N = p * s + (p + 1) * g;
  auto in_hole = [&](int i, int j) { // cell (i, j); false outside the square
    if(i < 0 || j < 0 || i >= N - g || j >= N - g)
      return false;
    return i % (s + g) >= g && j % (s + g) >= g;
  };
  std::vector<char> used(std::size_t(N + 1) * (N + 1), 0);
  for(int i = 0; i < N; ++i)
    for(int j = 0; j < N; ++j)
      if(!in_hole(i, j))
        for(int di = 0; di < 2; ++di)
          for(int dj = 0; dj < 2; ++dj)
            used[std::size_t(i + di) * (N + 1) + j + dj] = 1;
  Jitter jitter;
  std::vector<Vertex> v(used.size());
  const double h = 1.0 / N;
  for(int i = 0; i <= N; ++i)
    for(int j = 0; j <= N; ++j) {
      if(!used[std::size_t(i) * (N + 1) + j])
        continue;
      // the vertices of the outer square and of the holes stay in place (square holes), the others move
      bool fixed = i == 0 || j == 0 || i == N || j == N;
      for(int ci = i - 1; ci <= i; ++ci)
        for(int cj = j - 1; cj <= j; ++cj)
          fixed = fixed || in_hole(ci, cj);
      const double x = (i + (fixed ? 0 : 0.2 * jitter())) * h;
      const double y = (j + (fixed ? 0 : 0.2 * jitter())) * h;
      v[std::size_t(i) * (N + 1) + j] = mesh.add_vertex(Point(x, y, 0.15 * std::sin(pi * x) * std::sin(pi * y)));
    }
  auto at = [&](int i, int j) { return v[std::size_t(i) * (N + 1) + j]; };
  for(int i = 0; i < N; ++i)
    for(int j = 0; j < N; ++j)
      if(!in_hole(i, j) &&
         !add_quad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), (i + j) % 2 == 1))
        return "square with holes: a face could not be added";
  return "";
}

// ---------------------------------------------------------------------------------------------------------
// Cases

enum class Source { annulus, holes, file };

struct Case_spec
{
  std::string name;
  Source source;
  int a = 0, b = 0, c = 0, d = 1; // annulus: a = M; holes: p, s, g, subdivision
  std::string file;               // in TC_CGAL_DATA_DIR
  bool align = false;
};

const std::vector<Case_spec>& case_specs()
{
  static const std::vector<Case_spec> specs = [] {
    std::vector<Case_spec> s;
    for(int m : {4, 14, 49, 149, 499, 999})
      s.push_back({"annulus_m" + std::to_string(m), Source::annulus, m, 0, 0, 1, "", true});
    // p x p holes of 2 x 2 cells, 2 cells apart, the cells split in 2 x 2
    for(int p : {1, 2, 4, 6, 8, 10})
      s.push_back({"holes_p" + std::to_string(p), Source::holes, p, 2, 2, 2, "", true});
    s.push_back({"cheese", Source::file, 0, 0, 0, 1, "cheese.off", false});
    s.push_back({"elephant-with-holes", Source::file, 0, 0, 0, 1, "elephant-with-holes.off", false});
    s.push_back({"elephant-with-holes_aligned", Source::file, 0, 0, 0, 1, "elephant-with-holes.off", true});
    return s;
  }();
  return specs;
}

// One case at a time: its mesh and solver, built on first use and kept for the case's other benchmarks.
struct Case_state
{
  std::string name;
  Mesh mesh;
  std::unique_ptr<Solver> solver;
  Mesh::Property_map<Mesh::Halfedge_index, double> x;
  std::string error;
  double t_build = 0, t_loop_metric = 0;
};

Case_state& case_state(const Case_spec& spec)
{
  static std::unique_ptr<Case_state> current;
  if(current && current->name == spec.name)
    return *current;
  current.reset(); // the previous solver and mesh are gone before the next are made
  current = std::make_unique<Case_state>();
  Case_state& c = *current;
  c.name = spec.name;
  switch(spec.source) {
  case Source::annulus: c.error = make_annulus(spec.a, c.mesh); break;
  case Source::holes: c.error = make_square_with_holes(spec.a, spec.b, spec.c, spec.d, c.mesh); break;
  case Source::file: {
    const std::string path = std::string(TC_CGAL_DATA_DIR) + "/" + spec.file;
    if(!CGAL::IO::read_polygon_mesh(path, c.mesh))
      c.error = "cannot read " + path + " (run scripts/fetch_cgal_data.sh)";
    break;
  }
  }
  if(!c.error.empty())
    return c;
  c.x = c.mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  Phase_times build;
  try {
    const auto t0 = Clock::now();
    c.solver = std::make_unique<Solver>(
      c.mesh, TC::parameters::align_with_boundary(spec.align, TC::parameters::progress(build.callback())));
    c.t_build = seconds_since(t0);
  } catch(const std::exception& e) {
    c.error = std::string("the solver's constructor failed: ") + e.what();
    return c;
  }
  c.t_loop_metric = build[TC::Phase::loop_metric];
  return c;
}

// see the header comment
Singularities singularities_for(const Mesh& mesh, const Solver& solver, int n, int set)
{
  const std::size_t nc = solver.components().size();
  const std::vector<std::vector<Vertex>> interior = tc_bench::interior_vertices_by_component(mesh, solver);

  Singularities s;
  for(std::size_t c = 0; c < nc; ++c) {
    const auto& report = solver.components()[c];
    const std::size_t count = interior[c].size();
    std::vector<int> signs; // of the indices +-1/n
    if(report.number_of_boundary_loops == 0) {
      const std::int64_t chi = report.euler_characteristic;
      signs.assign(std::size_t(chi < 0 ? -chi : chi) * std::size_t(n), chi < 0 ? -1 : 1);
      if(set == 1 && signs.size() + 3 <= count) {
        signs.push_back(1);
        signs.push_back(-1);
      }
    } else if(set == 0)
      signs = {1, 1, 1, 1, 1};
    else
      signs = {1, -1, 1, -1, 1};
    if(signs.empty() || signs.size() + 1 > count)
      continue;
    const std::size_t stride = count / (signs.size() + 1);
    const std::size_t offset = set == 1 ? stride / 2 + 1 : stride / 3;
    for(std::size_t i = 0; i < signs.size(); ++i)
      s.emplace_back(interior[c][(offset + i * stride) % count], TC::Singularity_index(signs[i], n));
  }
  return s;
}

// ---------------------------------------------------------------------------------------------------------
// The markdown table (TC_BENCH_MARKDOWN): one row per case and n, the two sets pooled.

struct Row
{
  std::string case_name;
  int n = 1;
  double faces = 0, k = 0, t_loop_metric = 0;
  std::vector<double> t_integers, t_solve; // every iteration of both sets
  double gap = 0, rounding_excess = 0;     // the larger of the sets
  int proven = 0, sets = 0;
};

std::vector<Row>& rows()
{
  static std::vector<Row> r;
  return r;
}

std::string format_time(double t)
{
  char buffer[32];
  if(t <= 0)
    return "–";
  if(t < 1e-3)
    std::snprintf(buffer, sizeof buffer, "%.3g µs", t * 1e6);
  else if(t < 1)
    std::snprintf(buffer, sizeof buffer, "%.3g ms", t * 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%.3g s", t);
  return buffer;
}

std::string format_ratio(double r)
{
  if(!(r > 1e-9)) // rounding noise of a zero
    return "0";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, r >= 10 ? "%.0f" : "%.2g", r);
  return buffer;
}

void write_markdown(const std::string& path)
{
  std::ofstream out(path);
  out << "| case | faces | k | n | reduction (constructor) | choice per solve | solve | rel. gap | proven | rounding excess |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for(const Row& r : rows()) {
    char k[32], faces[32];
    std::snprintf(k, sizeof k, "%.0f", r.k);
    std::snprintf(faces, sizeof faces, "%.0f", r.faces);
    out << "| " << r.case_name << " | " << faces << " | " << k << " | " << r.n << " | "
        << format_time(r.t_loop_metric) << " | " << format_time(median(r.t_integers)) << " | "
        << format_time(median(r.t_solve)) << " | " << format_ratio(r.gap) << " | " << r.proven << " of " << r.sets
        << " | " << format_ratio(r.rounding_excess) << " |\n";
  }
}

// ---------------------------------------------------------------------------------------------------------

void integer_choice(benchmark::State& state, const Case_spec& spec, int n, int set)
{
  Case_state& c = case_state(spec);
  if(!c.error.empty()) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  const Singularities sing = singularities_for(c.mesh, *c.solver, n, set);
  std::vector<double> t_integers, t_solve;
  TC::Solve_report report;
  for(auto _ : state) {
    Phase_times phases;
    const auto t0 = Clock::now();
    try {
      report = c.solver->solve(sing, c.x, TC::parameters::symmetry_order(n, TC::parameters::progress(phases.callback())));
    } catch(const std::exception& e) {
      state.SkipWithError((std::string("solve() failed: ") + e.what()).c_str());
      return;
    }
    const double t = seconds_since(t0);
    t_solve.push_back(t);
    t_integers.push_back(phases[TC::Phase::loop_integers]);
    state.SetIterationTime(t);
  }
  // free integers: every loop but one boundary loop per bordered component (Poincare-Hopf fixes its index)
  std::size_t free_loops = 0;
  std::vector<char> bordered(report.components.size(), 0);
  for(const TC::Loop_report& l : report.loops) {
    free_loops += l.prescribed ? 0 : 1;
    if(l.kind == TC::Loop_kind::boundary && !l.prescribed)
      bordered[l.component] = 1;
  }
  for(char b : bordered)
    free_loops -= std::size_t(b);
  const std::size_t k = free_loops + report.constraints.size();
  const double minimised = report.energy + report.guidance_energy;
  const double gap = report.integers_proven_optimal || !(minimised > 0)
                       ? 0
                       : (std::max)(0., (minimised - report.energy_lower_bound) / minimised);
  const double excess = minimised > 0 ? (std::max)(0., (report.rounding_energy - minimised) / minimised) : 0;

  auto& counters = state.counters;
  counters["faces"] = double(num_faces(c.mesh));
  counters["k"] = double(k);
  counters["free_loops"] = double(free_loops);
  counters["links"] = double(report.constraints.size());
  counters["n"] = n;
  counters["t_build"] = c.t_build;
  counters["t_loop_metric"] = c.t_loop_metric;
  counters["t_integers"] = median(t_integers);
  counters["t_integers_max"] = t_integers.empty() ? 0 : *std::max_element(t_integers.begin(), t_integers.end());
  counters["t_solve"] = median(t_solve);
  counters["energy"] = report.energy;
  counters["guidance_energy"] = report.guidance_energy;
  counters["energy_lower_bound"] = report.energy_lower_bound;
  counters["rounding_energy"] = report.rounding_energy;
  counters["proven"] = report.integers_proven_optimal ? 1 : 0;
  counters["rel_gap"] = gap;
  counters["rounding_excess"] = excess;

  std::vector<Row>& r = rows();
  if(r.empty() || r.back().case_name != spec.name || r.back().n != n) {
    r.emplace_back();
    r.back().case_name = spec.name;
    r.back().n = n;
  }
  Row& row = r.back();
  row.faces = double(num_faces(c.mesh));
  row.k = double(k);
  row.t_loop_metric = c.t_loop_metric;
  row.t_integers.insert(row.t_integers.end(), t_integers.begin(), t_integers.end());
  row.t_solve.insert(row.t_solve.end(), t_solve.begin(), t_solve.end());
  row.gap = (std::max)(row.gap, gap);
  row.rounding_excess = (std::max)(row.rounding_excess, excess);
  row.proven += report.integers_proven_optimal ? 1 : 0;
  ++row.sets;
}

} // namespace

int main(int argc, char** argv)
{
  for(const Case_spec& spec : case_specs())
    for(int n : {1, 4})
      for(int set : {0, 1})
        benchmark::RegisterBenchmark(
          ("integers/" + spec.name + "/n:" + std::to_string(n) + "/set:" + std::to_string(set)).c_str(),
          [spec, n, set](benchmark::State& s) { integer_choice(s, spec, n, set); })
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(iterations);
  benchmark::Initialize(&argc, argv);
  if(benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if(const char* markdown = std::getenv("TC_BENCH_MARKDOWN"))
    if(*markdown)
      write_markdown(markdown);
  return 0;
}
