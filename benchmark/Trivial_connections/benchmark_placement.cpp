// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Automatic singularity placement (singularity_placement.h) and one refinement trial (singularity_refinement.h)
// for n = 4, each measured next to the reference timed in the same run: analysis + numeric factorization of the
// same mesh's vertex Laplacian (edge weights 1 / w_e, one vertex pinned per component) with the same sparse
// backend, as in trivial_connections_benchmark (benchmark_meshes.h).
//
//   trivial_connections_placement_benchmark [--benchmark_filter=REGEX] [--benchmark_repetitions=N]
//
// Benchmarks are named BACKEND/placement/MESH (`ldlt`, and `cholmod` when CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// is defined: the backend of the solver and of the reference; the placement itself always factors its complex
// face pencil with Eigen's SimplicialLDLT). Environment: TC_BENCH_SIZES and TC_BENCH_MESH_CACHE as for the suite
// (small: CGAL meshes of 52k-89k faces, and of the 71k-302k subdivisions; large: ~1.2M faces; huge: ~5M faces).
//
// Per mesh, in one run (seconds unless noted):
//   t_build              the solver's constructor (the backend's factorization of the trivial-connection system)
//   t_place              place_singularities(solver, out, symmetry_order(4)): the smoothest field
//   t_solve              solver.solve() with the placed singularities
//   t_guide              principal_curvature_guide(solver, guide)
//   t_place_aligned      place_singularities with alignment_guide(guide, symmetry_order(4))
//   t_solve_aligned      solver.solve() with the aligned placement's singularities
//   t_trial              one refinement trial as refine_singularities() makes it: one solve() on the prefactored
//                        solver, with energy_gradient, of the placed set with one singularity moved to a
//                        neighbouring interior vertex that is not singular; the median of up to 5 such moves
//                        (different singularities); t_trial_min, t_trial_max their range
//   t_pencil_assembly, t_pencil_factorization, t_pencil_solve
//                        where the placement's time goes, timed apart after the above through the library's
//                        internal classes (internal/placement/smoothest_field.h, as place_singularities() uses
//                        them): building the face pencil (A, B), the factorization of A + sigma B, and one solve
//                        with it (the median of 3; each eigensolver iteration (LOBPCG) is one such solve plus O(faces) work)
//   t_reference          the reference factorization
//   r_end_to_end = (t_build + t_place + t_solve) / t_reference (issue target: <= 3)
//   r_end_to_end_aligned = (t_build + t_guide + t_place_aligned + t_solve_aligned) / t_reference
//   r_place, r_place_aligned (guide included), r_trial (issue target: <= 0.1), r_pencil_factorization: / t_reference
//   singularities, singularities_aligned, eigensolver_iterations, eigensolver_iterations_aligned
//   (Placement_report::iterations: the LOBPCG iterations of the smoothest field; 0 for an aligned field),
//   field_energy (Placement_report), solve_energy (Solve_report::energy of the placed set: at most field_energy
//   when the integers are optimal), trials (moves timed), faces, vertices, genus, peak_bytes_per_face
//   (VmHWM above the resident size before the build, over build, placements and solves, per face).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>
#include <CGAL/Trivial_connections/solver_traits.h>
// for the breakdown of the placement's time only (t_pencil_*): not public API
#include <CGAL/Trivial_connections/internal/placement/smoothest_field.h>

#include "benchmark_meshes.h"
#include "benchmark_support.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Vertex = Mesh::Vertex_index;
using Singularities = std::vector<std::pair<Vertex, TC::Singularity_index>>;

namespace {

using tc_bench::Clock;
using tc_bench::Mesh_spec;
using tc_bench::Reference_result;
using tc_bench::Size;
using tc_bench::seconds_since;

constexpr int symmetry = 4;
constexpr std::size_t maximum_timed_trials = 5;

// the meshes of at least 50k faces: the suite's, and three more small ones of other genera
const std::vector<Mesh_spec>& placement_specs()
{
  static const std::vector<Mesh_spec> specs = [] {
    std::vector<Mesh_spec> s = {
      {"armadillo", "armadillo.off", 0, Size::small},   // 52k faces
      {"cheese_loop1", "cheese.off", 1, Size::small},   // genus 133, 71k
      {"turbine_loop1", "turbine.off", 1, Size::small}, // genus 11, 74k
    };
    const std::set<std::string> from_suite = {"bunny00",       "refined_elephant", "bunny00_loop1", "bunny00_loop2",
                                              "turbine_loop3", "cheese_loop3",     "bunny00_loop3"};
    for(const Mesh_spec& spec : tc_bench::mesh_specs())
      if(from_suite.count(spec.name))
        s.push_back(spec);
    return s;
  }();
  return specs;
}

double median(std::vector<double> v)
{
  if(v.empty())
    return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : (v[h - 1] + v[h]) / 2;
}

// Up to maximum_timed_trials moves of the placed singularities, each to a neighbouring interior vertex that is
// not singular (the moves refine_singularities() tries); with no singularity, a +1/n, -1/n pair on an edge.
std::vector<Singularities> trial_sets(const Mesh& mesh, const Singularities& placed)
{
  std::vector<Singularities> sets;
  std::vector<char> singular(num_vertices(mesh), 0);
  for(const auto& s : placed)
    singular[std::size_t(s.first)] = 1;
  auto free_interior = [&](Vertex w) { return !singular[std::size_t(w)] && !mesh.is_border(w, true); };
  if(placed.empty()) {
    for(Vertex v : vertices(mesh)) {
      if(mesh.is_isolated(v) || !free_interior(v))
        continue;
      for(Vertex w : vertices_around_target(halfedge(v, mesh), mesh))
        if(w != v && free_interior(w)) {
          sets.push_back({{v, TC::Singularity_index(1, symmetry)}, {w, TC::Singularity_index(-1, symmetry)}});
          return sets;
        }
    }
    return sets;
  }
  const std::size_t count = std::min(maximum_timed_trials, placed.size());
  for(std::size_t t = 0; t < count; ++t) {
    const std::size_t i = t * placed.size() / count; // spread over the set
    const Vertex v = placed[i].first;
    if(mesh.is_border(v, true))
      continue;
    for(Vertex w : vertices_around_target(halfedge(v, mesh), mesh))
      if(w != v && free_interior(w)) {
        Singularities moved = placed;
        moved[i].first = w;
        sets.push_back(std::move(moved));
        break;
      }
  }
  return sets;
}

template <class SolverTraits, class ReferenceSolver>
void placement(benchmark::State& state, const Mesh_spec& spec)
{
  using Solver = TC::Trivial_connection_solver<Mesh, CGAL::Default, SolverTraits>;
  using Access = TC::internal::Solver_access<Solver>;
  namespace P = TC::parameters;
  Mesh mesh;
  const std::string error = tc_bench::load_mesh(spec, mesh);
  if(!error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  auto guide = mesh.add_property_map<Mesh::Face_index, K::Vector_3>("f:guide", K::Vector_3(0, 0, 0)).first;
  auto gradient = mesh.add_property_map<Vertex, double>("v:gradient", 0.).first;

  double t_build = 0, t_place = 0, t_solve = 0, t_guide = 0, t_place_aligned = 0, t_solve_aligned = 0;
  double t_assembly = 0, t_factorization = 0, t_pencil_solve = 0, peak = -1;
  double field_energy = 0, solve_energy = 0;
  std::vector<double> trials;
  TC::Placement_report smooth, aligned;
  std::int64_t genus = 0;
  Reference_result ref;
  for(auto _ : state) {
    std::vector<tc_bench::Weighted_edge> edges;
    try {
      tc_bench::stop_idle_blas_threads();
      const double base = tc_bench::reset_peak_memory() ? tc_bench::status_bytes("VmRSS") : -1;
      auto t0 = Clock::now();
      Solver solver(mesh);
      t_build = seconds_since(t0);
      genus = 0;
      for(const auto& c : solver.components())
        genus += c.genus;

      Singularities placed;
      t0 = Clock::now();
      smooth = TC::place_singularities(solver, std::back_inserter(placed), P::symmetry_order(symmetry));
      t_place = seconds_since(t0);
      t0 = Clock::now();
      const TC::Solve_report solved = solver.solve(placed, x, P::symmetry_order(symmetry));
      t_solve = seconds_since(t0);
      field_energy = smooth.field_energy;
      solve_energy = solved.energy;

      t0 = Clock::now();
      TC::principal_curvature_guide(solver, guide);
      t_guide = seconds_since(t0);
      Singularities placed_aligned;
      t0 = Clock::now();
      aligned = TC::place_singularities(solver, std::back_inserter(placed_aligned),
                                        P::alignment_guide(guide, P::symmetry_order(symmetry)));
      t_place_aligned = seconds_since(t0);
      t0 = Clock::now();
      benchmark::DoNotOptimize(solver.solve(placed_aligned, x, P::symmetry_order(symmetry)).energy);
      t_solve_aligned = seconds_since(t0);
      peak = base >= 0 ? tc_bench::status_bytes("VmHWM") - base : -1;

      // refinement trials: what refine_singularities() calls for each candidate move
      trials.clear();
      for(const Singularities& moved : trial_sets(mesh, placed)) {
        t0 = Clock::now();
        benchmark::DoNotOptimize(
          solver.solve(moved, x, P::energy_gradient(gradient, P::symmetry_order(symmetry))).energy);
        trials.push_back(seconds_since(t0));
      }

      // where the placement's time goes, timed apart
      {
        const auto& m = Access::mesh(solver);
        t0 = Clock::now();
        const TC::internal::Smoothest_field_problem problem(m, Access::geometry(solver), Access::topology(solver),
                                                            symmetry);
        t_assembly = seconds_since(t0);
        t0 = Clock::now();
        const TC::internal::Smoothest_field_factor factor(problem, TC::internal::preconditioner_shifts(problem));
        t_factorization = seconds_since(t0);
        Eigen::VectorXcd r(m.nf);
        for(int f = 0; f < m.nf; ++f)
          r[f] = problem.area[std::size_t(f)] * problem.start[std::size_t(f)];
        std::vector<double> solves;
        for(int i = 0; i < 3; ++i) {
          t0 = Clock::now();
          const Eigen::VectorXcd u = factor.solve(r);
          solves.push_back(seconds_since(t0));
          benchmark::DoNotOptimize(u.data());
        }
        t_pencil_solve = median(solves);
      }
      edges = tc_bench::laplacian_edges(mesh, solver);
    } catch(const std::exception& e) {
      state.SkipWithError((spec.name + ": " + e.what()).c_str());
      break;
    } // the solver is gone before the reference runs
    ref = tc_bench::reference_factorization<ReferenceSolver>(num_vertices(mesh), edges);
    if(!ref.ok)
      state.SkipWithError("the reference factorization failed");
    state.SetIterationTime(t_build + t_place + t_solve);
  }

  const double nf = double(num_faces(mesh));
  const double t_trial = median(trials);
  auto& k = state.counters;
  k["faces"] = nf;
  k["vertices"] = double(num_vertices(mesh));
  k["genus"] = double(genus);
  k["t_reference"] = ref.seconds;
  k["ref_factor_gflops"] = ref.factor_flops * 1e-9;
  k["t_build"] = t_build;
  k["t_place"] = t_place;
  k["t_solve"] = t_solve;
  k["t_guide"] = t_guide;
  k["t_place_aligned"] = t_place_aligned;
  k["t_solve_aligned"] = t_solve_aligned;
  k["t_trial"] = t_trial;
  k["t_trial_min"] = trials.empty() ? 0 : *std::min_element(trials.begin(), trials.end());
  k["t_trial_max"] = trials.empty() ? 0 : *std::max_element(trials.begin(), trials.end());
  k["trials"] = double(trials.size());
  k["t_pencil_assembly"] = t_assembly;
  k["t_pencil_factorization"] = t_factorization;
  k["t_pencil_solve"] = t_pencil_solve;
  k["r_end_to_end"] = (t_build + t_place + t_solve) / ref.seconds;
  k["r_end_to_end_aligned"] = (t_build + t_guide + t_place_aligned + t_solve_aligned) / ref.seconds;
  k["r_build"] = t_build / ref.seconds;
  k["r_place"] = t_place / ref.seconds;
  k["r_place_aligned"] = (t_guide + t_place_aligned) / ref.seconds;
  k["r_trial"] = t_trial / ref.seconds;
  k["r_pencil_factorization"] = t_factorization / ref.seconds;
  k["singularities"] = double(smooth.number_of_singularities);
  k["singularities_aligned"] = double(aligned.number_of_singularities);
  k["eigensolver_iterations"] = double(smooth.iterations);
  k["eigensolver_iterations_aligned"] = double(aligned.iterations);
  k["field_energy"] = field_energy;
  k["solve_energy"] = solve_energy;
  k["peak_bytes_per_face"] = peak >= 0 ? peak / nf : -1;
}

template <class SolverTraits, class ReferenceSolver>
void register_backend(const std::string& backend, const std::vector<bool>& sizes)
{
  for(const Mesh_spec& spec : placement_specs())
    if(sizes[std::size_t(spec.size)])
      benchmark::RegisterBenchmark((backend + "/placement/" + spec.name).c_str(),
                                   [spec](benchmark::State& s) { placement<SolverTraits, ReferenceSolver>(s, spec); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
}

} // namespace

int main(int argc, char** argv)
{
  const std::vector<bool> sizes = tc_bench::selected_sizes();
  register_backend<TC::Default_solver_traits, Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>("ldlt", sizes);
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  register_backend<TC::Cholmod_solver_traits, Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>("cholmod",
                                                                                                        sizes);
#endif
  benchmark::AddCustomContext("mesh_cache", tc_bench::mesh_cache_dir());
  benchmark::AddCustomContext("symmetry_order", std::to_string(symmetry));
  benchmark::Initialize(&argc, argv);
  if(benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
