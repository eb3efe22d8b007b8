// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the benchmarks on meshes share: the meshes (CGAL's data set and the Loop subdivisions cached on first use),
// the sizes selected by TC_BENCH_SIZES, the peak memory, and the reference, the factorization of the same mesh's
// vertex Laplacian with the same backend that every ratio is taken against.
// Needs TC_CGAL_DATA_DIR (and optionally TC_BENCH_DEFAULT_MESH_CACHE) defined by the build.

#ifndef CGAL_TRIVIAL_CONNECTIONS_BENCHMARK_MESHES_H
#define CGAL_TRIVIAL_CONNECTIONS_BENCHMARK_MESHES_H

#include "benchmark_support.h"
#include "../../examples/Trivial_connections/trivial_connections_process.h"

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Surface_mesh/IO/PLY.h>
#include <CGAL/subdivision_method_3.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#ifdef TC_BENCH_HAVE_METIS
#include <Eigen/MetisSupport>
#endif
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <type_traits>
#include <unistd.h>
#include <vector>

#ifndef TC_BENCH_DEFAULT_MESH_CACHE
#define TC_BENCH_DEFAULT_MESH_CACHE "benchmark-meshes"
#endif

namespace tc_bench {
// ---------------------------------------------------------------------------------------------------------
// Memory: VmHWM is reset to the current resident size by writing 5 to /proc/self/clear_refs (Linux >= 4.0).

// Before a timed section, OpenBLAS's idle worker threads (behind CHOLMOD) are stopped as the program stops them
// at its start: after each parallel BLAS call they spin for about 0.1 s, and on two cores the one that spins
// takes the core of whatever is timed next (the solver's second thread, or the next reference).
using trivial_connections_program::stop_idle_blas_threads;

/*
  The state of the heap at the start of every timed section, the solver's and each reference's alike, from
  TC_BENCH_HEAP:
  - cold (the default): the freed heap is given back to the system first (malloc_trim), so what a timed section
    touches is new memory for both, whatever ran before it. On a virtual machine the first touch of a page can
    cost more than the work done on it (about 11 us per 4 KiB page on the machine of RESULTS.md, see
    minor_page_faults()).
  - warm: malloc keeps all freed memory (no mmap, no trimming, set once), and each timed section runs once
    untimed just before, so that both reuse memory already touched: the work alone. Peak memory is not
    measured then (the resident size does not grow).
  - warm-floor: the way of the runs before 2026-12-03: the solver cold, the floor reusing the memory its untimed
    assembly had just freed.
*/
enum class Heap_state { cold, warm, warm_floor };

inline Heap_state heap_state()
{
  static const Heap_state state = [] {
    const char* env = std::getenv("TC_BENCH_HEAP");
    const std::string s = env ? env : "cold";
    const Heap_state h = s == "warm" ? Heap_state::warm : s == "warm-floor" ? Heap_state::warm_floor : Heap_state::cold;
    if(s != "cold" && s != "warm" && s != "warm-floor")
      std::cerr << "[benchmark] TC_BENCH_HEAP: unknown state '" << s << "' (cold, warm, warm-floor): cold\n";
#if defined(__GLIBC__)
    if(h == Heap_state::warm) {
      mallopt(M_MMAP_MAX, 0);
      mallopt(M_TRIM_THRESHOLD, -1);
    }
#endif
    return h;
  }();
  return state;
}

inline void release_free_heap()
{
#if defined(__GLIBC__)
  if(heap_state() != Heap_state::warm)
    malloc_trim(0);
#endif
}

// minor page faults of the process so far (all threads), -1 if unavailable
inline double minor_page_faults()
{
  rusage usage;
  return ::getrusage(RUSAGE_SELF, &usage) == 0 ? double(usage.ru_minflt) : -1;
}

inline bool reset_peak_memory()
{
  release_free_heap(); // also so that the baseline is what is really in use
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return bool(out);
}

// a "Vm...:   N kB" field of /proc/self/status in bytes, -1 if unavailable
inline double status_bytes(const char* field)
{
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while(std::getline(in, line))
    if(line.compare(0, key.size(), key) == 0) {
      std::istringstream s(line.substr(key.size()));
      double kb = -1;
      s >> kb;
      return kb * 1024;
    }
  return -1;
}

// ---------------------------------------------------------------------------------------------------------
// Meshes

enum class Size { small, large, huge };

struct Mesh_spec
{
  std::string name;   // benchmark name
  std::string source; // file in CGAL's data set
  int subdivisions;   // Loop subdivision steps (x4 faces each)
  Size size;
};

inline const std::vector<Mesh_spec>& mesh_specs()
{
  static const std::vector<Mesh_spec> specs = {
    {"cow", "cow.off", 0, Size::small},                   // genus 0, 5.8k faces, obtuse triangles
    {"knot1", "knot1.off", 0, Size::small},               // genus 1, 6.4k
    {"elephant", "elephant.off", 0, Size::small},         // genus 3, 5.6k
    {"holes", "holes.off", 0, Size::small},               // bordered, 8.3k
    {"bull", "bull.off", 0, Size::small},                 // genus 0, 12k: genus-0 neighbours of the 18k meshes
    {"cow_loop1", "cow.off", 1, Size::small},             // genus 0, 23k
    {"turbine", "turbine.off", 0, Size::small},           // genus 11, 18k
    {"cheese", "cheese.off", 0, Size::small},             // genus 133, 18k
    {"bunny00", "bunny00.off", 0, Size::small},           // genus 0, 75k
    {"refined_elephant", "refined_elephant.off", 0, Size::small}, // genus 3, 89k
    {"bunny00_loop1", "bunny00.off", 1, Size::small},     // genus 0, 302k
    {"bunny00_loop2", "bunny00.off", 2, Size::large},     // genus 0, 1.2M
    {"turbine_loop3", "turbine.off", 3, Size::large},     // genus 11, 1.2M
    {"cheese_loop3", "cheese.off", 3, Size::large},       // genus 133, 1.1M
    {"bunny00_loop3", "bunny00.off", 3, Size::huge},      // genus 0, 4.8M
  };
  return specs;
}

inline std::string mesh_cache_dir()
{
  const char* env = std::getenv("TC_BENCH_MESH_CACHE");
  return env && *env ? std::string(env) : std::string(TC_BENCH_DEFAULT_MESH_CACHE);
}

inline bool file_exists(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

// Loads a CGAL mesh, or its Loop subdivision from the cache (made and written there on first use).
// Returns an empty string on success, the reason otherwise.
template <class Mesh>
std::string load_mesh(const Mesh_spec& spec, Mesh& mesh)
{
  const std::string source = std::string(TC_CGAL_DATA_DIR) + "/" + spec.source;
  if(spec.subdivisions == 0)
    return CGAL::IO::read_polygon_mesh(source, mesh) ? "" : "cannot read " + source + " (run scripts/fetch_cgal_data.sh)";

  const std::string dir = mesh_cache_dir();
  const std::string cached = dir + "/" + spec.name + ".ply";
  if(file_exists(cached)) {
    std::ifstream in(cached, std::ios::binary);
    if(CGAL::IO::read_PLY(in, mesh) && num_faces(mesh) > 0)
      return "";
    mesh.clear();
  }
  if(!CGAL::IO::read_polygon_mesh(source, mesh))
    return "cannot read " + source + " (run scripts/fetch_cgal_data.sh)";
  const auto t0 = Clock::now();
  CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(spec.subdivisions));
  std::cerr << "[benchmark] " << spec.name << ": " << spec.subdivisions << " Loop subdivision steps of "
            << spec.source << " -> " << num_faces(mesh) << " faces in " << seconds_since(t0) << " s" << std::endl;
  ::mkdir(dir.c_str(), 0755);
  const std::string tmp = cached + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    if(!out || !CGAL::IO::write_PLY(out, mesh, CGAL::parameters::use_binary_mode(true))) {
      std::cerr << "[benchmark] cannot write " << tmp << " (the subdivided mesh is not cached)" << std::endl;
      std::remove(tmp.c_str());
      return "";
    }
  }
  if(std::rename(tmp.c_str(), cached.c_str()) != 0)
    std::remove(tmp.c_str());
  return "";
}

// ---------------------------------------------------------------------------------------------------------
// The reference: the vertex Laplacian with edge weights 1 / w_e, one vertex pinned per component, factored by
// the backend as a user would call it, with its own fill-reducing ordering in the analysis (the solver's traits
// may be set up differently, e.g. for a matrix the solver has already ordered).

struct Weighted_edge
{
  int a, b;
  double c;
};

struct Reference_result
{
  double seconds = 0;
  double assembly_seconds = 0; // the sparse matrix from the weighted edges (pins, triplets, compression)
  double factor_nnz = 0;
  double factor_flops = 0; // sum over the columns of L of nnz(column)^2 (diagonal included), as CHOLMOD counts
  int ordering = -1; // CHOLMOD: the ordering its analysis chose (CHOLMOD_AMD, CHOLMOD_METIS, ...)
  double peak_bytes = 0;
  double page_faults = 0; // minor page faults of the timed section
  bool ok = true;
};

template <class EigenSolver>
int chosen_ordering(const EigenSolver&) { return -1; }

template <class EigenSolver>
double factor_nonzeros(const EigenSolver& solver, Eigen::Index n)
{
  return double(solver.matrixL().nestedExpression().nonZeros()) + double(n); // strict L + diagonal D
}

template <class EigenSolver>
double factor_flops(const EigenSolver& solver)
{
  const auto& L = solver.matrixL().nestedExpression();
  double flops = 0;
  for(Eigen::Index j = 0; j < L.outerSize(); ++j) {
    double column = 1; // the diagonal
    for(typename std::decay<decltype(L)>::type::InnerIterator it(L, j); it; ++it)
      ++column;
    flops += column * column;
  }
  return flops;
}

#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
template <class MatrixType, int UpLo>
double factor_nonzeros(const Eigen::CholmodSupernodalLLT<MatrixType, UpLo>& solver, Eigen::Index)
{
  // nnz(L) from the analysis (excluding the zeros of supernodal amalgamation)
  return const_cast<Eigen::CholmodSupernodalLLT<MatrixType, UpLo>&>(solver).cholmod().lnz;
}

template <class MatrixType, int UpLo>
double factor_flops(const Eigen::CholmodSupernodalLLT<MatrixType, UpLo>& solver)
{
  return const_cast<Eigen::CholmodSupernodalLLT<MatrixType, UpLo>&>(solver).cholmod().fl;
}

template <class MatrixType, int UpLo>
int chosen_ordering(const Eigen::CholmodSupernodalLLT<MatrixType, UpLo>& solver)
{
  cholmod_common& c = const_cast<Eigen::CholmodSupernodalLLT<MatrixType, UpLo>&>(solver).cholmod();
  return c.selected >= 0 && c.selected < CHOLMOD_MAXMETHODS ? c.method[c.selected].ordering : -1;
}
#endif

template <class ReferenceSolver>
Reference_result reference_factorization(std::size_t nv, const std::vector<Weighted_edge>& edges)
{
  Reference_result result;
  stop_idle_blas_threads();
  const double base = reset_peak_memory() ? status_bytes("VmRSS") : -1;
  const auto t_assembly = Clock::now();
  // union-find: pin the first vertex of each component (isolated vertices included)
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while(parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for(const Weighted_edge& e : edges) {
    const int ra = find(e.a), rb = find(e.b);
    if(ra != rb) parent[(std::max)(ra, rb)] = (std::min)(ra, rb);
  }
  std::vector<int> row(nv, -1);
  int n = 0;
  for(std::size_t v = 0; v < nv; ++v)
    if(find(int(v)) != int(v))
      row[v] = n++;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(4 * edges.size());
  for(const Weighted_edge& e : edges) {
    const int a = row[e.a], b = row[e.b];
    if(a >= 0) t.emplace_back(a, a, e.c);
    if(b >= 0) t.emplace_back(b, b, e.c);
    if(a >= 0 && b >= 0) { t.emplace_back(a, b, -e.c); t.emplace_back(b, a, -e.c); }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  L.makeCompressed();
  std::vector<Eigen::Triplet<double>>().swap(t);
  result.assembly_seconds = seconds_since(t_assembly);

  if(heap_state() == Heap_state::warm) { // the same factorization once, untimed, on memory it then leaves free
    ReferenceSolver untimed;
    untimed.analyzePattern(L);
    untimed.factorize(L);
  }
  ReferenceSolver solver;
  if(heap_state() == Heap_state::cold)
    release_free_heap();
  const double faults = minor_page_faults();
  const auto t0 = Clock::now();
  solver.analyzePattern(L);
  solver.factorize(L);
  result.seconds = seconds_since(t0);
  result.page_faults = minor_page_faults() - faults;
  result.ok = solver.info() == Eigen::Success;
  result.factor_nnz = factor_nonzeros(solver, n);
  result.factor_flops = factor_flops(solver);
  result.ordering = chosen_ordering(solver);
  result.peak_bytes = base >= 0 ? status_bytes("VmHWM") - base : -1;
  return result;
}

/*
  The floor: the fastest sparse Cholesky of the same Laplacian that this build has, each backend with its best
  ordering: SimplicialLDLT with AMD, SimplicialLDLT with METIS (with libmetis-dev), and supernodal CHOLMOD with the
  ordering its own analysis chooses (AMD, or METIS when AMD fills too much). Each is timed as a user would call it
  (analysis, ordering included, + numeric factorization), one after the other in the same run.
*/
struct Floor_result
{
  Reference_result best;
  int backend = -1; // FLOOR_NAMES
};
static const char* const FLOOR_NAMES[] = {"SimplicialLDLT+AMD", "SimplicialLDLT+METIS", "CHOLMOD"};

inline Floor_result fastest_reference(std::size_t nv, const std::vector<Weighted_edge>& edges)
{
  Floor_result floor;
  auto consider = [&](const Reference_result& r, int backend) {
    if(r.ok && (floor.backend < 0 || r.seconds < floor.best.seconds)) {
      floor.best = r;
      floor.backend = backend;
    }
  };
  consider(reference_factorization<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(nv, edges), 0);
#ifdef TC_BENCH_HAVE_METIS
  consider(reference_factorization<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower,
                                                         Eigen::MetisOrdering<int>>>(nv, edges), 1);
#endif
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  consider(reference_factorization<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>>>(nv, edges), 2);
#endif
  return floor;
}

// ---------------------------------------------------------------------------------------------------------

// the edges of the reference Laplacian: the solver's interior edges, weighted 1/w_e
template <class Mesh, class Solver>
std::vector<Weighted_edge> laplacian_edges(const Mesh& mesh, const Solver& solver)
{
  std::vector<Weighted_edge> edges;
  edges.reserve(num_edges(mesh));
  for(auto e : CGAL::edges(mesh))
    if(solver.is_interior(e))
      edges.push_back({int(source(halfedge(e, mesh), mesh)), int(target(halfedge(e, mesh), mesh)), 1 / solver.weight(e)});
  return edges;
}

// TC_BENCH_SIZES: comma list of small, large, huge, all
inline std::vector<bool> selected_sizes()
{
  std::vector<bool> on(3, false);
  const char* env = std::getenv("TC_BENCH_SIZES");
  std::string list = env && *env ? env : "small";
  std::stringstream ss(list);
  std::string item;
  while(std::getline(ss, item, ',')) {
    if(item == "small") on[0] = true;
    else if(item == "large") on[1] = true;
    else if(item == "huge") on[2] = true;
    else if(item == "all") on.assign(3, true);
    else std::cerr << "[benchmark] TC_BENCH_SIZES: unknown size '" << item << "' (small, large, huge, all)\n";
  }
  return on;
}

} // namespace tc_bench

#endif // CGAL_TRIVIAL_CONNECTIONS_BENCHMARK_MESHES_H
