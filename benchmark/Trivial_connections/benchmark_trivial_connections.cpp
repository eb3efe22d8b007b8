// The trivial-connection pipeline on CGAL's data meshes and on larger meshes made here by Loop subdivision,
// each measured next to the reference timed in the same run: analysis + numeric factorization of the same
// mesh's vertex Laplacian (edge weights 1 / w_e, one vertex pinned per component) with the same sparse
// backend (the method's physical limit).
//
//   trivial_connections_benchmark [--benchmark_filter=REGEX] [--benchmark_repetitions=N] [--benchmark_format=json]
//
// Benchmarks are named BACKEND/MESH (backend `ldlt` = Eigen::SimplicialLDLT, `cholmod` = supernodal CHOLMOD,
// `auto` = Automatic_solver_traits, the program's choice by predicted cost; the last two only when
// CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD is defined).
// Every run also times the floor (fastest_reference(), benchmark_meshes.h): the fastest factorization of the
// same Laplacian this build has (SimplicialLDLT with AMD, with METIS when TC_BENCH_HAVE_METIS, CHOLMOD),
// t_floor, floor_backend (0 SimplicialLDLT+AMD, 1 SimplicialLDLT+METIS, 2 CHOLMOD), r_end_to_end_floor and
// r_build_floor (and r_program_floor for the program): the ratios of issue 20.
//
// Environment:
//   TC_BENCH_SIZES       which meshes to register: a comma list of small (CGAL meshes, 5k-90k faces, and the
//                        300k subdivision), large (~1.2M faces: genus 0, 11 and 133), huge (~5M faces), or all.
//                        Default: small (a few minutes).
//   TC_BENCH_MESH_CACHE  directory of the subdivided meshes (binary PLY, made on first use; default: the
//                        benchmark-meshes directory of the build tree). Never commit it.
//
// Counters (seconds unless noted): faces, vertices, components, genus (sum over components), boundary_loops,
// singularities; t_reference; t_build (measured directly) and its phases t_mesh_setup, t_geometry, t_trees,
// t_assembly, t_factorization, t_loop_metric (from the progress callback; 0 until the solver reports them);
// t_solve, t_resolve (second singularity set on the same solver), measured directly, with t_solve_integers
// and t_resolve_integers (the loop-integer search, part of the solve); t_field; r_end_to_end = (build + solve + field)
// / reference, r_resolve = resolve / reference; peak_bytes (VmHWM above the resident size before the solver
// was built, over build + two solves + field), peak_bytes_per_face, ref_peak_bytes_per_face (same for the
// reference), ref_factor_nnz (nonzeros of the reference factor L, including the diagonal),
// ref_factor_bytes_per_face (nnz x 12 / faces), ref_factor_gflops (sum over the columns of L of nnz(column)^2,
// diagonal included, in 1e9: the work of the reference factorization, which the time of a simplicial one
// follows); for CHOLMOD ref_cholmod_ordering, the ordering its analysis chose (0 natural, 1 given, 2 AMD,
// 3 METIS, 4 NESDIS, 5 COLAMD, 6 postordered).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/solver_traits.h>

#include "benchmark_meshes.h"
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
#include <numeric>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Vertex = Mesh::Vertex_index;
using Singularities = std::vector<std::pair<Vertex, TC::Singularity_index>>;
using Clock = tc_bench::Clock;

namespace {

using tc_bench::seconds_since;
using tc_bench::Phase_times;
// the meshes and the reference (benchmark_meshes.h)
using tc_bench::Mesh_spec;
using tc_bench::Reference_result;
using tc_bench::Weighted_edge;
using tc_bench::file_exists;
using tc_bench::laplacian_edges;
using tc_bench::load_mesh;
using tc_bench::mesh_cache_dir;
using tc_bench::mesh_specs;
using tc_bench::stop_idle_blas_threads;
using tc_bench::reference_factorization;
using tc_bench::Floor_result;
using tc_bench::fastest_reference;
using tc_bench::reset_peak_memory;
using tc_bench::selected_sizes;
using tc_bench::status_bytes;

// ---------------------------------------------------------------------------------------------------------
// Singularities satisfying Poincare-Hopf on every closed component: |chi| vertices of index sign(chi), spread
// over the component's interior vertices. Set 1 differs from set 0: shifted positions and, in every
// component, an extra +1/-1 pair (so that bordered meshes also get a different right-hand side).

template <class Solver>
Singularities singularities_for(const Mesh& mesh, const Solver& solver, int set)
{
  const std::size_t nc = solver.components().size();
  const std::vector<std::vector<Vertex>> interior = tc_bench::interior_vertices_by_component(mesh, solver);

  Singularities s;
  for(std::size_t c = 0; c < nc; ++c) {
    const auto& report = solver.components()[c];
    const std::int64_t chi = report.number_of_boundary_loops == 0 ? report.euler_characteristic : 0;
    const std::size_t ph = std::size_t(chi < 0 ? -chi : chi);
    const std::size_t count = interior[c].size();
    std::size_t m = ph + (set == 1 ? 2 : 0);
    if(m + 1 > count)
      m = ph; // too small for the extra pair
    if(m == 0 || m + 1 > count)
      continue;
    const std::size_t stride = count / (m + 1);
    const std::size_t offset = set == 1 ? stride / 2 : 0;
    for(std::size_t i = 0; i < m; ++i) {
      const Vertex v = interior[c][(offset + i * stride) % count];
      const int sign = i < ph ? (chi < 0 ? -1 : 1) : (i == ph ? 1 : -1);
      s.emplace_back(v, TC::Singularity_index(sign));
    }
  }
  return s;
}

// ---------------------------------------------------------------------------------------------------------

template <class SolverTraits, class ReferenceSolver>
void pipeline(benchmark::State& state, const Mesh_spec& spec)
{
  using Solver = TC::Trivial_connection_solver<Mesh, CGAL::Default, SolverTraits>;
  Mesh mesh;
  const std::string error = load_mesh(spec, mesh);
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  auto field = mesh.add_property_map<Mesh::Face_index, K::Vector_3>("f:field").first;

  double t_build = 0, t_solve = 0, t_resolve = 0, t_field = 0, peak = -1, page_faults = 0;
  Phase_times build, solve1, solve2, field_phases;
  Reference_result ref;
  Floor_result fastest;
  std::int64_t genus = 0;
  std::size_t boundary_loops = 0, components = 0, singularities = 0;
  for(auto _ : state) {
    std::vector<Weighted_edge> edges;
    // with TC_BENCH_HEAP=warm all of it once untimed first (benchmark_meshes.h), the second pass is reported
    for(int pass = tc_bench::heap_state() == tc_bench::Heap_state::warm ? 0 : 1; pass < 2; ++pass) {
      build = solve1 = solve2 = field_phases = Phase_times();
      stop_idle_blas_threads();
      const double base = reset_peak_memory() ? status_bytes("VmRSS") : -1;
      const double faults = tc_bench::minor_page_faults();
      auto t0 = Clock::now();
      Solver solver(mesh, TC::parameters::progress(build.callback()));
      t_build = seconds_since(t0);

      genus = 0;
      boundary_loops = 0;
      components = solver.components().size();
      for(const auto& c : solver.components()) {
        genus += c.genus;
        boundary_loops += c.number_of_boundary_loops;
      }
      const Singularities first = singularities_for(mesh, solver, 0);
      const Singularities second = singularities_for(mesh, solver, 1);
      singularities = first.size();

      t0 = Clock::now();
      benchmark::DoNotOptimize(solver.solve(first, x, TC::parameters::progress(solve1.callback())).energy);
      t_solve = seconds_since(t0);
      t0 = Clock::now();
      benchmark::DoNotOptimize(solver.solve(second, x, TC::parameters::progress(solve2.callback())).energy);
      t_resolve = seconds_since(t0);
      t0 = Clock::now();
      solver.compute_field(x, field, TC::parameters::progress(field_phases.callback()));
      t_field = seconds_since(t0);
      page_faults = tc_bench::minor_page_faults() - faults; // with singularities_for(), which allocates little
      peak = base >= 0 ? status_bytes("VmHWM") - base : -1;

      edges = laplacian_edges(mesh, solver);
    } // the solver is gone before the reference runs
    ref = reference_factorization<ReferenceSolver>(num_vertices(mesh), edges);
    if(!ref.ok)
      state.SkipWithError("the reference factorization failed");
    fastest = fastest_reference(num_vertices(mesh), edges);
    state.SetIterationTime(t_build + t_solve + t_field);
  }

  const double nf = double(num_faces(mesh));
  auto& k = state.counters;
  k["faces"] = nf;
  k["vertices"] = double(num_vertices(mesh));
  k["components"] = double(components);
  k["genus"] = double(genus);
  k["boundary_loops"] = double(boundary_loops);
  k["singularities"] = double(singularities);
  k["t_reference"] = ref.seconds;
  k["t_build"] = t_build;
  k["t_mesh_setup"] = build[TC::Phase::mesh_setup];
  k["t_geometry"] = build[TC::Phase::geometry];
  k["t_trees"] = build[TC::Phase::trees];
  k["t_assembly"] = build[TC::Phase::assembly];
  k["t_factorization"] = build[TC::Phase::factorization];
  k["t_loop_metric"] = build[TC::Phase::loop_metric];
  k["t_solve"] = t_solve;
  k["t_solve_integers"] = solve1[TC::Phase::loop_integers];
  k["t_solve_loop_metric"] = solve1[TC::Phase::loop_metric]; // if the loop metric is computed lazily
  k["t_resolve"] = t_resolve;
  k["t_resolve_integers"] = solve2[TC::Phase::loop_integers];
  k["t_field"] = t_field;
  k["r_end_to_end"] = (t_build + t_solve + t_field) / ref.seconds;
  k["r_build"] = t_build / ref.seconds;
  k["r_resolve"] = t_resolve / ref.seconds;
  // against the fastest factorization of the machine (issue 20's floor)
  k["t_floor"] = fastest.best.seconds;
  k["floor_backend"] = double(fastest.backend);
  k["r_end_to_end_floor"] = (t_build + t_solve + t_field) / fastest.best.seconds;
  k["r_build_floor"] = t_build / fastest.best.seconds;
  k["peak_bytes"] = peak;
  k["peak_bytes_per_face"] = peak >= 0 ? peak / nf : -1;
  // new memory touched (4 KiB pages): build, solves and field, and the floor's analysis + factorization
  k["page_faults_per_face"] = page_faults / nf;
  k["floor_page_faults_per_face"] = fastest.best.page_faults / nf;
  k["ref_peak_bytes_per_face"] = ref.peak_bytes >= 0 ? ref.peak_bytes / nf : -1;
  k["ref_factor_nnz"] = ref.factor_nnz;
  k["ref_factor_gflops"] = ref.factor_flops * 1e-9;
  if(ref.ordering >= 0)
    k["ref_cholmod_ordering"] = double(ref.ordering);
  k["ref_factor_bytes_per_face"] = ref.factor_nnz * (8 + 4) / nf;
}

// ---------------------------------------------------------------------------------------------------------
// Design controls (issue 5): a solver with 20 constrained and 10 guided faces; a solve; a re-solve with new
// directions on the same faces (back-substitutions only); set_constraints() with 5 of the constrained faces
// dropped and 10 new ones (the factorization kept: one forward substitution per new link); a solve after it.
// Against the same reference factorization as the pipeline.

template <class SolverTraits, class ReferenceSolver>
void controls(benchmark::State& state, const Mesh_spec& spec)
{
  using Solver = TC::Trivial_connection_solver<Mesh, CGAL::Default, SolverTraits>;
  Mesh mesh;
  const std::string error = load_mesh(spec, mesh);
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  auto directions = mesh.add_property_map<Mesh::Face_index, K::Vector_3>("f:directions", K::Vector_3(1, 0, 0)).first;
  const std::size_t nf = num_faces(mesh);
  auto face_at = [&](std::size_t i) { return Mesh::Face_index(Mesh::size_type(i % nf)); };
  std::vector<Mesh::Face_index> constrained, guided, changed;
  for(std::size_t i = 0; i < 20; ++i)
    constrained.push_back(face_at(i * nf / 20 + 3));
  for(std::size_t i = 0; i < 10; ++i)
    guided.push_back(face_at(i * nf / 10 + nf / 40 + 5));
  changed.assign(constrained.begin() + 5, constrained.end());
  for(std::size_t i = 0; i < 10; ++i)
    changed.push_back(face_at(i * nf / 10 + nf / 30 + 11));
  // directions that vary over the mesh, never normal to a face: the tangent part of a fixed vector turned per face
  for(Mesh::Face_index f : faces(mesh)) {
    const double a = 0.001 * double(std::size_t(f));
    directions[f] = K::Vector_3(std::cos(a), std::sin(a), 0.5);
  }
  double t_build = 0, t_solve = 0, t_resolve = 0, t_set = 0, t_after = 0;
  std::size_t links = 0, outside = 0, forward = 0;
  Reference_result ref;
  for(auto _ : state) {
    std::vector<Weighted_edge> edges;
    {
      stop_idle_blas_threads();
      auto t0 = Clock::now();
      Solver solver(mesh, TC::parameters::constrained_faces(constrained, TC::parameters::guided_faces(guided)));
      t_build = seconds_since(t0);
      const Singularities sing = singularities_for(mesh, solver, 0);
      t0 = Clock::now();
      benchmark::DoNotOptimize(solver.solve(sing, x, TC::parameters::face_directions(directions, TC::parameters::symmetry_order(4))).energy);
      t_solve = seconds_since(t0);
      for(Mesh::Face_index f : constrained)
        directions[f] = K::Vector_3(-directions[f].y(), directions[f].x(), 0.5);
      t0 = Clock::now();
      benchmark::DoNotOptimize(solver.solve(sing, x, TC::parameters::face_directions(directions, TC::parameters::symmetry_order(4))).energy);
      t_resolve = seconds_since(t0);
      t0 = Clock::now();
      const TC::Constraint_update u =
        solver.set_constraints(TC::parameters::constrained_faces(changed, TC::parameters::guided_faces(guided)));
      t_set = seconds_since(t0);
      links = u.links;
      outside = u.links_outside_the_factor;
      forward = u.new_forward_substitutions;
      t0 = Clock::now();
      benchmark::DoNotOptimize(solver.solve(sing, x, TC::parameters::face_directions(directions, TC::parameters::symmetry_order(4))).energy);
      t_after = seconds_since(t0);
      edges = laplacian_edges(mesh, solver);
    }
    ref = reference_factorization<ReferenceSolver>(num_vertices(mesh), edges);
    if(!ref.ok)
      state.SkipWithError("the reference factorization failed");
    state.SetIterationTime(t_build + t_solve);
  }
  auto& k = state.counters;
  k["faces"] = double(nf);
  k["t_reference"] = ref.seconds;
  k["t_build"] = t_build;
  k["t_solve"] = t_solve;
  k["t_resolve"] = t_resolve;
  k["t_set_constraints"] = t_set;
  k["t_solve_after_set"] = t_after;
  k["links_after_set"] = double(links);
  k["links_outside_the_factor"] = double(outside);
  k["new_forward_substitutions"] = double(forward);
  k["r_build"] = t_build / ref.seconds;
  k["r_resolve"] = t_resolve / ref.seconds;
  k["r_set_constraints"] = t_set / ref.seconds;
  k["r_solve_after_set"] = t_after / ref.seconds;
}

// ---------------------------------------------------------------------------------------------------------
// The main program as a whole process (read, solve, field, both files written), on a closed genus-0 mesh
// written as OFF (a usual input): its wall time against reading the same file with CGAL
// (read_polygon_mesh into a Surface_mesh) plus one analysis + factorization of the mesh's cotan Laplacian with
// the program's backend.
// Counters: t_program, program_peak_bytes (the largest child's maximum resident size), t_read,
// t_reference, r_program = t_program / (t_read + t_reference); t_laplacian, the Laplacian a user builds before
// factoring it (cotan weights of the mesh read, then the sparse matrix), r_program_floor = t_program / (t_read +
// t_laplacian + t_floor), issue 20's target, and r_program_floor_without_laplacian = t_program / (t_read + t_floor).

#ifdef TC_PROGRAM_PATH
template <class ReferenceSolver>
void program_run(benchmark::State& state, const Mesh_spec& spec)
{
  Mesh mesh;
  std::string error = load_mesh(spec, mesh);
  if(error.empty() && (num_vertices(mesh) - num_edges(mesh) + num_faces(mesh) != 2 || !CGAL::is_closed(mesh)))
    error = spec.name + " is not a closed genus-0 mesh";
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  const std::string dir = mesh_cache_dir();
  const std::string off = dir + "/" + spec.name + ".off";
  if(!file_exists(off)) {
    const std::string tmp = off + ".tmp." + std::to_string(::getpid());
    {
      std::ofstream out(tmp);
      if(!out || !CGAL::IO::write_OFF(out, mesh, CGAL::parameters::stream_precision(17))) {
        std::remove(tmp.c_str());
        state.SkipWithError(("cannot write " + tmp).c_str());
        return;
      }
    }
    std::rename(tmp.c_str(), off.c_str());
  }
  // two +1 singularities (Poincare-Hopf on a sphere), far apart in the vertex order
  const std::string singularities = dir + "/" + spec.name + ".program.sing";
  {
    std::ofstream out(singularities);
    out << "0 1\n" << num_vertices(mesh) / 2 << " 1\n";
  }
  const std::string connection = dir + "/" + spec.name + ".program.connection.txt";
  const std::string field = dir + "/" + spec.name + ".program.field.txt";
  const std::string phases_log = dir + "/" + spec.name + ".program.progress.txt";
  const std::string command = std::string(TC_PROGRAM_PATH) + " '" + off + "' --singularities '" + singularities +
                              "' --n 1 --connection '" + connection + "' --field '" + field +
                              "' --progress > /dev/null 2> '" + phases_log + "'";
  mesh.clear();
  mesh.collect_garbage();

  double t_program = 0, t_read = 0, t_laplacian_weights = 0, peak = -1;
  Reference_result ref;
  Floor_result fastest;
  std::size_t faces = 0;
  for(auto _ : state) {
    auto t0 = Clock::now();
    const int status = std::system(command.c_str());
    t_program = seconds_since(t0);
    if(status != 0) {
      state.SkipWithError(("the program failed: " + command).c_str());
      break;
    }
    struct rusage usage;
    if(::getrusage(RUSAGE_CHILDREN, &usage) == 0)
      peak = double(usage.ru_maxrss) * 1024;

    Mesh read;
    t0 = Clock::now();
    const bool ok = CGAL::IO::read_polygon_mesh(off, read);
    t_read = seconds_since(t0);
    if(!ok) {
      state.SkipWithError(("cannot read " + off).c_str());
      break;
    }
    faces = num_faces(read);
    const std::size_t nv = num_vertices(read);
    // the cotan Laplacian (the factorization's cost depends on the pattern only, but building it is timed)
    t0 = Clock::now();
    std::vector<Weighted_edge> edges;
    edges.reserve(num_edges(read));
    const auto& point = read.points();
    auto cotan = [&](Mesh::Halfedge_index h) {
      if(is_border(h, read))
        return 0.;
      const K::Point_3& a = point[source(h, read)];
      const K::Point_3& b = point[target(h, read)];
      const K::Point_3& c = point[target(next(h, read), read)];
      const K::Vector_3 u = a - c, v = b - c;
      return u * v / std::sqrt(CGAL::cross_product(u, v).squared_length());
    };
    for(auto e : CGAL::edges(read)) {
      const auto h = halfedge(e, read);
      edges.push_back({int(source(h, read)), int(target(h, read)), 0.5 * (cotan(h) + cotan(opposite(h, read)))});
    }
    t_laplacian_weights = seconds_since(t0);
    read.clear();
    ref = reference_factorization<ReferenceSolver>(nv, edges);
    fastest = fastest_reference(nv, edges);
    if(!ref.ok) {
      state.SkipWithError("the reference factorization failed");
      break;
    }
    state.SetIterationTime(t_program);
  }
  // the program's own phases (--progress: "[ elapsed ] phase ... done ( seconds )", 10 ms resolution), each
  // against the floor
  std::vector<std::pair<std::string, double>> phases;
  {
    std::ifstream in(phases_log);
    std::string line;
    while(std::getline(in, line)) {
      const std::size_t close = line.find("] "), dots = line.find(" ... done (");
      if(close == std::string::npos || dots == std::string::npos || dots < close)
        continue;
      std::string name = line.substr(close + 2, dots - close - 2);
      std::replace(name.begin(), name.end(), ' ', '_');
      phases.emplace_back(name, std::atof(line.c_str() + dots + 11));
    }
  }
  std::remove(phases_log.c_str());
  std::remove(connection.c_str());
  std::remove(field.c_str());
  auto& k = state.counters;
  for(const auto& phase : phases) {
    k["t_program_" + phase.first] = phase.second;
    k["r_program_" + phase.first + "_floor"] = phase.second / fastest.best.seconds;
  }
  k["faces"] = double(faces);
  k["t_program"] = t_program;
  k["program_peak_bytes"] = peak;
  k["t_read"] = t_read;
  k["t_reference"] = ref.seconds;
  k["r_program"] = t_program / (t_read + ref.seconds);
  k["t_floor"] = fastest.best.seconds;
  k["floor_backend"] = double(fastest.backend);
  const double t_laplacian = t_laplacian_weights + fastest.best.assembly_seconds;
  k["t_laplacian"] = t_laplacian;
  k["r_program_floor"] = t_program / (t_read + t_laplacian + fastest.best.seconds);
  k["r_program_floor_without_laplacian"] = t_program / (t_read + fastest.best.seconds);
}
#endif


template <class SolverTraits, class ReferenceSolver>
void register_backend(const std::string& backend, const std::vector<bool>& sizes, bool program)
{
  for(const Mesh_spec& spec : mesh_specs())
    if(sizes[std::size_t(spec.size)])
      benchmark::RegisterBenchmark((backend + "/" + spec.name).c_str(),
                                   [spec](benchmark::State& s) { pipeline<SolverTraits, ReferenceSolver>(s, spec); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  for(const Mesh_spec& spec : mesh_specs())
    if(sizes[std::size_t(spec.size)] &&
       (spec.name == "bunny00" || spec.name == "turbine" || spec.name == "bunny00_loop1" || spec.name == "bunny00_loop2"))
      benchmark::RegisterBenchmark((backend + "/controls/" + spec.name).c_str(),
                                   [spec](benchmark::State& s) { controls<SolverTraits, ReferenceSolver>(s, spec); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
#ifdef TC_PROGRAM_PATH
  // the program on the genus-0 series, 75k to 4.8M faces (issue 20's sizes)
  for(const Mesh_spec& spec : mesh_specs())
    if(program && sizes[std::size_t(spec.size)] &&
       (spec.name == "bunny00" || spec.name == "bunny00_loop1" || spec.name == "bunny00_loop2" ||
        spec.name == "bunny00_loop3"))
      benchmark::RegisterBenchmark((backend + "/program/" + spec.name).c_str(),
                                   [spec](benchmark::State& s) { program_run<ReferenceSolver>(s, spec); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
#else
  (void)program;
#endif
}

} // namespace

int main(int argc, char** argv)
{
  const std::vector<bool> sizes = selected_sizes();
  // the program, with the backend it uses (CHOLMOD whenever it is installed)
#ifdef TC_PROGRAM_USES_CHOLMOD
  const bool program_uses_cholmod = true;
#else
  const bool program_uses_cholmod = false;
#endif
  register_backend<TC::Default_solver_traits, Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(
    "ldlt", sizes, !program_uses_cholmod);
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  register_backend<TC::Cholmod_solver_traits, Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>(
    "cholmod", sizes, false);
  // the choice by predicted cost, which the program makes (against CHOLMOD's reference: the floor is the fair one)
  register_backend<TC::Automatic_solver_traits, Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>(
    "auto", sizes, program_uses_cholmod);
#endif
  benchmark::AddCustomContext("mesh_cache", mesh_cache_dir());
  benchmark::Initialize(&argc, argv);
  if(benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
