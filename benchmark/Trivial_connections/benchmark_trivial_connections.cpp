// Phases of the trivial-connection pipeline on CGAL's data meshes, each reported next to the reference
// measured in the same run: analysis + numeric factorization of the same mesh's vertex Laplacian with
// the same sparse backend (the method's physical limit). Timings are medians over the repetitions.
//
//   trivial_connections_benchmark [--benchmark_repetitions=5] [--benchmark_format=json]
// Counters: faces, genus, t_* in seconds, r_* = t_* / t_reference.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include <benchmark/benchmark.h>

#include <Eigen/SparseCholesky>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
using Vertex = Mesh::Vertex_index;
using Singularities = std::vector<std::pair<Vertex, TC::Singularity_index>>;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Singularities satisfying Poincare-Hopf on a closed mesh: index chi spread over |chi| vertices
// (for a torus none), starting at `offset` so that two sets differ.
Singularities singularities_for(const Mesh& mesh, std::int64_t chi, std::size_t offset)
{
  Singularities s;
  const std::size_t count = std::size_t(chi < 0 ? -chi : chi);
  const std::size_t stride = (std::max<std::size_t>)(1, num_vertices(mesh) / (count + 1));
  for(std::size_t i = 0; i < count; ++i)
    s.emplace_back(Vertex(Mesh::size_type((offset + i * stride) % num_vertices(mesh))),
                   TC::Singularity_index(chi < 0 ? -1 : 1));
  return s;
}

// The reference: the vertex Laplacian with the same edge weights (1 / w_e), one vertex pinned.
double reference_factorization(const Mesh& mesh)
{
  TC::Trivial_connection_solver<Mesh> weights(mesh);
  std::vector<Eigen::Triplet<double>> t;
  const int n = int(num_vertices(mesh)) - 1;
  for(auto e : edges(mesh)) {
    if(is_border(e, mesh))
      continue;
    const int a = int(source(halfedge(e, mesh), mesh)) - 1, b = int(target(halfedge(e, mesh), mesh)) - 1;
    const double c = 1 / weights.weight(e);
    if(a >= 0) t.emplace_back(a, a, c);
    if(b >= 0) t.emplace_back(b, b, c);
    if(a >= 0 && b >= 0) { t.emplace_back(a, b, -c); t.emplace_back(b, a, -c); }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  const auto t0 = std::chrono::steady_clock::now();
  TC::Default_solver_traits::Solver solver;
  solver.analyzePattern(L);
  solver.factorize(L);
  benchmark::DoNotOptimize(solver.info());
  return seconds_since(t0);
}

void pipeline(benchmark::State& state, const std::string& name)
{
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(std::string(TC_CGAL_DATA_DIR) + "/" + name, mesh)) {
    state.SkipWithError(("cannot read " + name + " (run scripts/fetch_cgal_data.sh)").c_str());
    return;
  }
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  auto field = mesh.add_property_map<Mesh::Face_index, K::Vector_3>("f:field").first;
  double t_ref = 0, t_build = 0, t_solve = 0, t_resolve = 0, t_field = 0;
  std::int64_t genus = 0;
  for(auto _ : state) {
    t_ref = reference_factorization(mesh);
    auto t0 = std::chrono::steady_clock::now();
    TC::Trivial_connection_solver<Mesh> solver(mesh);
    t_build = seconds_since(t0);
    const std::int64_t chi = solver.components().front().euler_characteristic;
    genus = solver.components().front().genus;
    const bool closed = solver.components().front().number_of_boundary_loops == 0;
    const Singularities first = closed ? singularities_for(mesh, chi, 0) : Singularities();
    const Singularities second = closed ? singularities_for(mesh, chi, 7) : Singularities();
    t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(solver.solve(first, x).energy);
    t_solve = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(solver.solve(second, x).energy);
    t_resolve = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    solver.compute_field(x, field);
    t_field = seconds_since(t0);
    state.SetIterationTime(t_build + t_solve + t_field);
  }
  state.counters["faces"] = double(num_faces(mesh));
  state.counters["genus"] = double(genus);
  state.counters["t_reference"] = t_ref;
  state.counters["t_build"] = t_build;
  state.counters["t_solve"] = t_solve;
  state.counters["t_resolve"] = t_resolve;
  state.counters["t_field"] = t_field;
  state.counters["r_end_to_end"] = (t_build + t_solve + t_field) / t_ref;
  state.counters["r_resolve"] = t_resolve / t_ref;
}

} // namespace

int main(int argc, char** argv)
{
  // genus 0, 1, 3, 11, 133, bordered; ~5k to ~90k faces
  for(const char* name : {"cow.off", "knot1.off", "elephant.off", "turbine.off", "cheese.off", "holes.off",
                          "refined_elephant.off", "bunny00.off"})
    benchmark::RegisterBenchmark(name, [name](benchmark::State& s) { pipeline(s, name); })
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
