// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Automatic singularity placement (singularity_placement.h) and the refinement of the placed singularities to a
// local minimum of the trivial connection's energy (singularity_refinement.h), each measured next to the reference
// timed in the same run: analysis + numeric factorization of the same mesh's vertex Laplacian (edge weights 1 / w_e,
// one vertex pinned per component) with the same sparse backend, as in trivial_connections_benchmark
// (benchmark_meshes.h).
//
//   trivial_connections_placement_benchmark [--benchmark_filter=REGEX] [--benchmark_repetitions=N]
//
// Benchmarks are named BACKEND/placement/MESH (`ldlt`, and `cholmod` when CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
// is defined: the backend of the solver and of the reference; the placement itself always factors its complex
// face pencil with Eigen's SimplicialLDLT). Environment: TC_BENCH_SIZES and TC_BENCH_MESH_CACHE as for the suite
// (small: femur, 7.8k faces, genus 2, and the CGAL meshes of 52k-89k faces and their subdivisions of 71k-302k;
// large: ~1.2M faces; huge: ~5M faces).
//
// Per mesh, in one run (seconds unless noted):
//   t_build              the solver's constructor (the backend's factorization of the trivial-connection system)
//   t_place              place_singularities(solver, out, symmetry_order(4)): the smoothest field
//   t_solve              solver.solve() with the placed singularities
//   t_guide              principal_curvature_guide(solver, guide)
//   t_place_aligned      place_singularities with alignment_guide(guide, symmetry_order(4))
//   t_solve_aligned      solver.solve() with the aligned placement's singularities
//   then, for each n in {1, 2, 4} (suffix _nN), on the same prefactored solver, the refinement as users run it:
//   t_place_nN           place_singularities(solver, out, symmetry_order(n)) (t_place_n4 is t_place)
//   t_refine_nN          refine_singularities(solver, placed, x, cancel_pairs(true, symmetry_order(n))) from that
//                        placement, to a local minimum (no budget): its first solve of the placed set included
//   r_refine_over_place_nN = t_refine_nN / t_place_nN (issue 38's target: <= 1)
//   r_refine_nN          t_refine_nN / t_reference
//   singularities_before_nN, singularities_after_nN   Refinement_report::singularities_before, singularities.size()
//   energy_before_nN, energy_after_nN                 Refinement_report::energy_before, energy_after
//   rounds_nN, trials_nN, moves_nN, cancellations_nN, column_solves_nN   the same fields (moves: moves.size())
//   local_minimum_nN     1 when it stopped at a local minimum, 0 otherwise; stop_nN: Refinement_stop (0 local
//                        minimum, 1 maximum_trials, 2 rejected_moves)
//   t_pencil_assembly, t_pencil_factorization, t_pencil_solve
//                        where the placement's time goes, timed apart after the above through the library's
//                        internal classes (internal/placement/smoothest_field.h, as place_singularities() uses
//                        them): building the face pencil (A, B), the factorization of A + sigma B, and one solve
//                        with it (the median of 3; each eigensolver iteration (LOBPCG) is one such solve plus O(faces) work)
//   then, small meshes only, from the aligned placement (n = 4) on the same solver, the refinement under a design
//   control (suffix _none, _constrained, _guided): none, 64 faces of spread_guided_faces(solver, guide, 64) as
//   constrained_faces, then as guided_faces, each with face_directions(guide) and cancel_pairs (issue 38: a step
//   under pins and guidance at the cost of one without):
//   t_refactor_C         what the first refinement after set_constraints() pays once: the system factored again with
//                        the links (a first call with maximum_trials(0), less t_setup_C)
//   t_refine_C           to a local minimum, on that factor;   t_setup_C   the same with maximum_trials(0), which
//                        prices no round: the set-up (entries of M^-1, the integers' columns) and the first solve
//   t_step_C = (t_refine_C - t_setup_C) / trials_C   the cost of one step (a round's pricing + its trial solve;
//                        every round counted, the first one's pricing too, and the last one's, which finds no move)
//   r_step_C = t_step_C / t_step_none, r_whole_C = (t_refine_C + t_refactor_C) / (the same for none)
//   (C = constrained, guided);   control_faces_C, trials_C, local_minimum_C,
//   and on bordered meshes C = boundary: a second solver built with align_with_boundary (n = 4), the same start and
//   runs; t_refactor_boundary = what its construction takes more than t_build (the links it factors), control_faces_
//   boundary = the faces with a border edge;   t_solve_C: one solve() of the start under control C as the
//   refinement's trials make it (residuals refined from 1e-11 only, the other choices of the integers decided by
//   rounding not bounded), after the refinements (the links factored in; the median of 3)
//   singularities_before_C, singularities_after_C, energy_before_C, energy_after_C
//   t_reference          the reference factorization
//   r_end_to_end = (t_build + t_place + t_solve) / t_reference (issue target: <= 3)
//   r_end_to_end_aligned = (t_build + t_guide + t_place_aligned + t_solve_aligned) / t_reference
//   r_place, r_place_aligned (guide included), r_pencil_factorization: / t_reference
//   singularities, singularities_aligned, eigensolver_iterations, eigensolver_iterations_aligned
//   (Placement_report::iterations: the LOBPCG iterations of the smoothest field; 0 for an aligned field),
//   field_energy (Placement_report), solve_energy (Solve_report::energy of the placed set: at most field_energy
//   when the integers are optimal), faces, vertices, genus, peak_bytes_per_face (VmHWM above the resident size
//   before the build, over build, placements and solves of n = 4, per face; the refinements come after it).

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
#include <limits>
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

constexpr int symmetry = 4;                       // n of the placements timed apart (t_place, t_place_aligned, ...)
constexpr int refined_orders[] = {1, 2, 4};       // n of the refinements (_nN counters)

// femur (issue 38's mesh for the refinement), the meshes of at least 50k faces: the suite's, and three more
// small ones of other genera; two bordered ones (holes: seven loops; mannequin_devil: one) for the boundary alignment
const std::vector<Mesh_spec>& placement_specs()
{
  static const std::vector<Mesh_spec> specs = [] {
    std::vector<Mesh_spec> s = {
      {"femur", "femur.off", 0, Size::small},                     // genus 2, 7.8k faces, ~566 singularities (n = 4)
      {"armadillo", "armadillo.off", 0, Size::small},             // 52k faces
      {"cheese_loop1", "cheese.off", 1, Size::small},             // genus 133, 71k
      {"turbine_loop1", "turbine.off", 1, Size::small},           // genus 11, 74k
      {"mannequin_devil", "mannequin-devil.off", 0, Size::small}, // bordered (one loop), 26k
    };
    const std::set<std::string> from_suite = {"holes",         "bunny00",       "refined_elephant", "bunny00_loop1",
                                              "bunny00_loop2", "turbine_loop3", "cheese_loop3",     "bunny00_loop3"};
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

// one refinement as users run it: the placement of order n, then refine_singularities() from it
struct Refinement_run
{
  int n = 0;
  double t_place = 0, t_refine = 0;
  TC::Refinement_report<Vertex> report;
};

// one refinement from the curvature-aligned placement (n = 4) under a design control, or none: the cost of a step
// is (t_refine - t_setup) / trials, its set-up and first solve (a budget of 0 trials: no round priced) taken apart
struct Controlled_refinement
{
  std::string control; // "none", "constrained", "guided", "boundary" (bordered meshes: align_with_boundary)
  std::size_t faces = 0;
  double t_refine = 0, t_setup = 0, t_refactor = 0, t_solve = 0; // t_solve: one solve() of the start
  TC::Refinement_report<Vertex> report;
  double step() const { return report.trials > 0 ? (t_refine - t_setup) / double(report.trials) : -1; }
};

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

  double t_build = 0, t_place = 0, t_solve = 0, t_guide = 0, t_place_aligned = 0, t_solve_aligned = 0;
  double t_assembly = 0, t_factorization = 0, t_pencil_solve = 0, peak = -1;
  double field_energy = 0, solve_energy = 0;
  std::vector<Refinement_run> refinements;
  std::vector<Controlled_refinement> controlled;
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

      // the refinement to a local minimum, from the placement of the same order (n = 4: the one timed above)
      refinements.clear();
      for(const int n : refined_orders) {
        Refinement_run run;
        run.n = n;
        Singularities start;
        if(n == symmetry) {
          start = placed;
          run.t_place = t_place;
        } else {
          tc_bench::stop_idle_blas_threads();
          t0 = Clock::now();
          TC::place_singularities(solver, std::back_inserter(start), P::symmetry_order(n));
          run.t_place = seconds_since(t0);
        }
        tc_bench::stop_idle_blas_threads();
        t0 = Clock::now();
        run.report = TC::refine_singularities(solver, start, x, P::cancel_pairs(true, P::symmetry_order(n)));
        run.t_refine = seconds_since(t0);
        refinements.push_back(std::move(run));
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

      // a step of the refinement under design controls against one without (issue 38: "at the same cost per
      // step"), from the same start, the aligned placement: no control, then 64 faces spread over the curvature
      // guide (spread_guided_faces(), as the program's --align-curvature) held at its directions, then guided
      // towards them (the program's --align-curvature). Small meshes only (a dozen refinements more).
      controlled.clear();
      if(spec.size == Size::small) {
        const bool has_border = std::any_of(halfedges(mesh).begin(), halfedges(mesh).end(),
                                            [&](Mesh::Halfedge_index h) { return is_border(h, mesh); });
        const std::vector<Mesh::Face_index> spread = TC::spread_guided_faces(solver, guide, 64);
        // one solve() of the start, the median of 3 (what a trial is made of), once the links are factored in
        auto median_solve = [&](Solver& on) {
          // as a trial: the bound of the decided integers' other choices is a solve more, which trials skip
          const TC::internal::Trial_accuracy<Solver> as_a_trial(on);
          std::vector<double> times;
          for(int i = 0; i < 3; ++i) {
            t0 = Clock::now();
            benchmark::DoNotOptimize(
              on.solve(placed_aligned, x, P::face_directions(guide, P::symmetry_order(symmetry))).energy);
            times.push_back(seconds_since(t0));
          }
          return median(times);
        };
        // a refinement with maximum_trials(0), one to a local minimum (c.t_refine, c.report), one with
        // maximum_trials(0) again (c.t_setup), from the same start; returns the first call's time
        auto three_runs = [&](Solver& on, Controlled_refinement& c) {
          double t_first_call = 0;
          for(int run = 0; run < 3; ++run) {
            const std::size_t budget = run == 1 ? (std::numeric_limits<std::size_t>::max)() : std::size_t(0);
            tc_bench::stop_idle_blas_threads();
            t0 = Clock::now();
            auto r = TC::refine_singularities(
              on, placed_aligned, x,
              P::maximum_trials(budget, P::cancel_pairs(true, P::face_directions(guide, P::symmetry_order(symmetry)))));
            (run == 0 ? t_first_call : run == 1 ? c.t_refine : c.t_setup) = seconds_since(t0);
            if(run == 1)
              c.report = std::move(r);
          }
          return t_first_call;
        };
        for(const char* control : {"none", "constrained", "guided"}) {
          Controlled_refinement c;
          c.control = control;
          c.faces = c.control == "none" ? 0 : spread.size();
          if(c.control == "constrained")
            solver.set_constraints(P::constrained_faces(spread));
          else if(c.control == "guided")
            solver.set_constraints(P::guided_faces(spread));
          // the first call factors the system again with the links (once per set_constraints()), then to a local
          // minimum and its first round alone on that factor
          const double t_first_call = three_runs(solver, c);
          c.t_refactor = (std::max)(t_first_call - c.t_setup, 0.);
          c.t_solve = median_solve(solver);
          controlled.push_back(std::move(c));
        }
        solver.set_constraints();

        // bordered meshes: the field aligned with the boundary, a solver option (its links are factored by the
        // constructor), from the same start; what it costs more than the solver without is its set-up
        if(has_border) {
          tc_bench::stop_idle_blas_threads();
          t0 = Clock::now();
          Solver aligned_solver(mesh, P::align_with_boundary(true, P::symmetry_order(symmetry)));
          const double t_build_aligned = seconds_since(t0);
          Controlled_refinement c;
          c.control = "boundary";
          for(Mesh::Face_index f : faces(mesh))
            c.faces += CGAL::is_border_edge(halfedge(f, mesh), mesh) ||
                       CGAL::is_border_edge(next(halfedge(f, mesh), mesh), mesh) ||
                       CGAL::is_border_edge(prev(halfedge(f, mesh), mesh), mesh);
          three_runs(aligned_solver, c);
          c.t_refactor = (std::max)(t_build_aligned - t_build, 0.);
          c.t_solve = median_solve(aligned_solver);
          controlled.push_back(std::move(c));
        }
      }
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
  for(const Refinement_run& run : refinements) {
    const std::string n = "_n" + std::to_string(run.n);
    const TC::Refinement_report<Vertex>& r = run.report;
    k["t_place" + n] = run.t_place;
    k["t_refine" + n] = run.t_refine;
    k["r_refine_over_place" + n] = run.t_place > 0 ? run.t_refine / run.t_place : -1;
    k["r_refine" + n] = run.t_refine / ref.seconds;
    k["singularities_before" + n] = double(r.singularities_before);
    k["singularities_after" + n] = double(r.singularities.size());
    k["energy_before" + n] = r.energy_before;
    k["energy_after" + n] = r.energy_after;
    k["rounds" + n] = double(r.rounds);
    k["trials" + n] = double(r.trials);
    k["moves" + n] = double(r.moves.size());
    k["cancellations" + n] = double(r.cancellations);
    k["column_solves" + n] = double(r.column_solves);
    k["local_minimum" + n] = r.local_minimum ? 1 : 0;
    k["stop" + n] = double(int(r.stop));
  }
  for(const Controlled_refinement& c : controlled) {
    const std::string s = "_" + c.control;
    const TC::Refinement_report<Vertex>& r = c.report;
    k["control_faces" + s] = double(c.faces);
    k["t_refine" + s] = c.t_refine;
    k["t_setup" + s] = c.t_setup;
    k["t_refactor" + s] = c.t_refactor;
    k["t_step" + s] = c.step();
    if(c.t_solve > 0)
      k["t_solve" + s] = c.t_solve;
    k["singularities_before" + s] = double(r.singularities_before);
    k["singularities_after" + s] = double(r.singularities.size());
    k["energy_before" + s] = r.energy_before;
    k["energy_after" + s] = r.energy_after;
    k["trials" + s] = double(r.trials);
    k["local_minimum" + s] = r.local_minimum ? 1 : 0;
    const Controlled_refinement& none = controlled.front();
    if(c.control != "none" && none.step() > 0 && c.step() >= 0)
      k["r_step" + s] = c.step() / none.step();
    if(c.control != "none" && none.t_refine > 0)
      k["r_whole" + s] = (c.t_refine + c.t_refactor) / (none.t_refine + none.t_refactor);
  }
  k["t_pencil_assembly"] = t_assembly;
  k["t_pencil_factorization"] = t_factorization;
  k["t_pencil_solve"] = t_pencil_solve;
  k["r_end_to_end"] = (t_build + t_place + t_solve) / ref.seconds;
  k["r_end_to_end_aligned"] = (t_build + t_guide + t_place_aligned + t_solve_aligned) / ref.seconds;
  k["r_build"] = t_build / ref.seconds;
  k["r_place"] = t_place / ref.seconds;
  k["r_place_aligned"] = (t_guide + t_place_aligned) / ref.seconds;
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
  benchmark::AddCustomContext("refined_orders", "1,2,4");
  benchmark::Initialize(&argc, argv);
  if(benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
