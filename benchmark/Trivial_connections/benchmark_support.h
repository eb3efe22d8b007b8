// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// What the benchmarks share: wall-clock seconds, and the time of every phase from the solver's progress callback.

#ifndef CGAL_TRIVIAL_CONNECTIONS_BENCHMARK_SUPPORT_H
#define CGAL_TRIVIAL_CONNECTIONS_BENCHMARK_SUPPORT_H

#include <CGAL/Trivial_connections/Progress.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <vector>

namespace tc_bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int number_of_phases = int(CGAL::Trivial_connections::Phase::field) + 1;

// Phase times from the progress callback: time stamps at fraction 0 and 1, summed per phase.
struct Phase_times
{
  std::array<double, number_of_phases> seconds{};
  std::array<Clock::time_point, number_of_phases> started{};
  std::array<bool, number_of_phases> open{};

  CGAL::Trivial_connections::Progress_callback callback()
  {
    return [this](CGAL::Trivial_connections::Phase phase, double fraction) {
      const int p = int(phase);
      if(p < 0 || p >= number_of_phases)
        return;
      if(fraction <= 0) {
        started[p] = Clock::now();
        open[p] = true;
      } else if(fraction >= 1 && open[p]) {
        seconds[p] += seconds_since(started[p]);
        open[p] = false;
      }
    };
  }
  double operator[](CGAL::Trivial_connections::Phase p) const { return seconds[int(p)]; }
};

// per component of the solver, the interior vertices of a Surface_mesh (where singularities may go)
template <class Mesh, class Solver>
std::vector<std::vector<typename Mesh::Vertex_index>> interior_vertices_by_component(const Mesh& mesh,
                                                                                   const Solver& solver)
{
  std::vector<std::vector<typename Mesh::Vertex_index>> interior(solver.components().size());
  std::vector<int> component(num_vertices(mesh), -1);
  for(auto f : faces(mesh))
    for(auto v : vertices_around_face(halfedge(f, mesh), mesh))
      component[std::size_t(v)] = int(solver.component(f));
  for(auto v : vertices(mesh))
    if(component[std::size_t(v)] >= 0 && !mesh.is_border(v, true))
      interior[std::size_t(component[std::size_t(v)])].push_back(v);
  return interior;
}

} // namespace tc_bench

#endif // CGAL_TRIVIAL_CONNECTIONS_BENCHMARK_SUPPORT_H
