// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

// The checks of test_support.h on meshes of CGAL's data set (Debian's libcgal-demo, data/meshes):
// closed genus 0, 1, 3, 4, 9, 11 and 133, bordered meshes with several holes (one of genus 3 with 106
// holes), multi-component meshes. Skipped, with a message, when the data set is missing.
//
// The expected topology of each file was computed beforehand by a separate python script (halfedge
// pairing, union-find over faces, border cycles), not by the package: it guards against reading a
// different file or a reader that repairs the mesh.

#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace tc_test;
using TC::Weighting;

struct Real_mesh
{
  const char* file;
  const char* what;
  int faces;
  int components;
  long long chi_sum;     // Σ over components of V - E + F
  int boundary_loops;    // Σ over components
  int genus_sum;         // Σ over components
  int max_genus;
  int brute_force_radius; // -1: no enumeration
};

std::ostream& operator<<(std::ostream& os, const Real_mesh& m) { return os << m.file; }

const Real_mesh real_meshes[] = {
  // closed, genus 0
  {"bull.off", "closed genus 0", 12396, 1, 2, 0, 0, 0, -1},
  {"cow.off", "closed genus 0, obtuse and non-Delaunay triangles", 5804, 1, 2, 0, 0, 0, -1},
  // closed, genus 1
  {"elk.off", "closed genus 1", 3290, 1, 0, 0, 1, 1, 2},
  {"knot1.off", "closed genus 1 (knotted tube)", 6400, 1, 0, 0, 1, 1, -1},
  // closed, genus 3
  {"elephant.off", "closed genus 3", 5558, 1, -4, 0, 3, 3, -1},
  {"helmet.off", "closed genus 3", 1000, 1, -4, 0, 3, 3, 1},
  // closed, genus >= 4
  {"anchor_dense.off", "closed genus 4", 7598, 1, -6, 0, 4, 4, -1},
  {"couplingdown.off", "closed genus 9", 3714, 1, -16, 0, 9, 9, -1},
  {"turbine.off", "closed genus 11", 18460, 1, -20, 0, 11, 11, -1},
  {"cheese.off", "closed genus 133", 17786, 1, -264, 0, 133, 133, -1},
  // bordered, several holes
  {"holes.off", "genus 0, 7 boundary loops", 8288, 1, -5, 7, 0, 0, 1},
  {"pig.off", "genus 0, 7 boundary loops", 891, 1, -5, 7, 0, 0, 1},
  {"mech-holes-shark.off", "genus 0, 4 boundary loops", 10192, 1, -2, 4, 0, 0, 2},
  {"elephant-with-holes.off", "genus 3, 106 boundary loops", 4463, 1, -110, 106, 3, 3, -1},
  // several components
  {"bones.off", "26 closed genus-0 components", 4204, 26, 52, 0, 0, 0, -1},
  {"knot2.off", "2 closed genus-1 components", 11520, 2, 0, 0, 2, 1, 1},
  {"blobby_3cc.off", "3 bordered components (4 boundary loops)", 3417, 3, 2, 4, 0, 0, 2},
  {"b9_mesh.off", "47 components: closed and bordered, genus up to 2, 76 boundary loops", 10174, 47, 10, 76, 4, 2,
   -1},
};

using Case = std::tuple<Real_mesh, int>;

class Real_meshes : public ::testing::TestWithParam<Case>
{
};

void expect_topology(const Mesh_view<Surface_mesh>& view, const Real_mesh& m)
{
  ASSERT_EQ(view.nf(), m.faces);
  ASSERT_EQ(view.ncomp, m.components);
  long long chi = 0;
  int b = 0, g = 0, gmax = 0;
  for(int c = 0; c < view.ncomp; ++c) {
    chi += view.chi[c]; b += view.boundary_count[c]; g += view.genus[c]; gmax = std::max(gmax, view.genus[c]);
  }
  EXPECT_EQ(chi, m.chi_sum);
  EXPECT_EQ(b, m.boundary_loops);
  EXPECT_EQ(g, m.genus_sum);
  EXPECT_EQ(gmax, m.max_genus);
}

/*
  Singularities (plan_singularities): closed genus 0: two +1 (n = 1) or eight +1/4 (n = 4), far apart;
  closed genus 1: +1/n and -1/n; closed genus g >= 2: 2g - 2 vertices of index -1 (n = 1) or 4(2g - 2)
  of index -1/4 (n = 4); bordered components: +1/n and -2/n (the boundary loops take the rest).
*/
TEST_P(Real_meshes, every_check)
{
  const auto& [m, n] = GetParam();
  Surface_mesh sm;
  TC_READ_CGAL_MESH_OR_SKIP(m.file, sm);
  SCOPED_TRACE(std::string(m.file) + " (" + m.what + "), n = " + std::to_string(n));
  const Mesh_view<Surface_mesh> view(sm);
  expect_topology(view, m);
  if(HasFatalFailure()) return;

  TC::Trivial_connection_solver<Surface_mesh> solver(sm);
  {
    SCOPED_TRACE("solver geometry");
    check_solver_geometry(view, solver);
  }
  {
    SCOPED_TRACE("solver loops");
    check_loops(view, solver);
  }
  const Singularities sing = plan_singularities(view, n);
  const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, n);
  if(m.brute_force_radius >= 0) {
    SCOPED_TRACE("brute force around the chosen integers");
    check_integers_by_enumeration(view, solver, sing, n, s.report, m.brute_force_radius);
  } else {
    SCOPED_TRACE("single-loop changes of the chosen integers");
    check_integers_locally_optimal(view, solver, sing, n, s.report);
  }
}

/*
  No node gathers the rounding of its whole component: the pinned node of a component (a vertex when it is
  closed, a boundary loop otherwise) has no row of its own, and the rounding of Gauss-Bonnet over the component
  grows linearly with it (about 2e-16 per vertex: 9e-12 on bunny00, 6e-10 at 4.8M faces) while the solve's
  own residuals, gathered there too, add up like a random walk (1.5e-13 on bunny00). Residuals recomputed here
  from x, with our own angle defects.
*/
TEST(Residuals, stay_at_rounding_level_on_every_node)
{
  for(const char* file : {"bunny00.off", "holes.off", "elephant-with-holes.off"}) {
    Surface_mesh sm;
    TC_READ_CGAL_MESH_OR_SKIP(file, sm);
    SCOPED_TRACE(file);
    const Mesh_view<Surface_mesh> view(sm);
    TC::Trivial_connection_solver<Surface_mesh> solver(sm);
    const Singularities sing = plan_singularities(view, 1);
    const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, 1);
    const std::vector<long long> k = scaled_indices(view.nv(), sing, 1);
    const std::vector<double> S = ring_sums(view, s.x);
    double worst = 0;
    for(int v = 0; v < view.nv(); ++v)
      if(view.interior_vertex(v))
        worst = std::max(worst, std::abs(view.defect(v) + S[v] - two_pi * double(k[v])));
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(s.report.max_vertex_residual, 1e-12);
    EXPECT_LT(s.report.max_loop_residual, 1e-12);
  }
}

class Real_meshes_unit_weights : public ::testing::TestWithParam<Real_mesh>
{
};

// unit weights, n = 4, integer indices (closed genus g >= 2: 2g - 2 vertices of index -1)
TEST_P(Real_meshes_unit_weights, every_check)
{
  const Real_mesh& m = GetParam();
  const int n = 4;
  Surface_mesh sm;
  TC_READ_CGAL_MESH_OR_SKIP(m.file, sm);
  SCOPED_TRACE(std::string(m.file) + " (" + m.what + "), unit weights, n = 4");
  const Mesh_view<Surface_mesh> view(sm);
  expect_topology(view, m);
  if(HasFatalFailure()) return;
  TC::Trivial_connection_solver<Surface_mesh> solver(sm, TC::parameters::weighting(Weighting::unit));
  check_solver_geometry(view, solver);
  const Singularities sing = plan_singularities(view, n, /*unit_indices=*/true);
  solve_and_check(view, solver, sing, n);
}

// a gtest-safe name from a mesh file name: "elephant-with-holes.off" -> "elephant_with_holes"
std::string test_name_of(const std::string& file)
{
  std::string name = file.substr(0, file.find('.'));
  for(char& c : name)
    if(!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

/*
  The sparse backends agree. The default traits read the metric of the loop integers from the factor's
  trailing block; traits with their own ordering (plain Eigen SimplicialLDLT with AMD) fall back to one
  back-substitution per loop; CHOLMOD (when built with it) reads its supernodal factor. Same integers
  when both enumerations are proven optimal, same energy, and with the integers prescribed the same
  connection; every check of solve_and_check holds on each.
*/
using Generic_ldlt_traits = CGAL::Eigen_solver_traits<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>;

template <class Traits>
void expect_same_as_default(const Mesh_view<Surface_mesh>& view, const Surface_mesh& sm, const Singularities& sing,
                            int n, const Solution<Surface_mesh>& reference)
{
  TC::Trivial_connection_solver<Surface_mesh, CGAL::Default, Traits> solver(sm);
  const Solution<Surface_mesh> s = solve_and_check(view, solver, sing, n, /*with_field=*/false);
  EXPECT_NEAR(s.report.energy, reference.report.energy, 1e-9 * std::max(1., reference.report.energy));
  std::vector<std::int64_t> periods;
  for(const auto& r : reference.report.loops) periods.push_back(r.period);
  if(s.report.integers_proven_optimal && reference.report.integers_proven_optimal) {
    std::vector<std::int64_t> own;
    for(const auto& r : s.report.loops) own.push_back(r.period);
    EXPECT_EQ(own, periods);
  }
  std::vector<double> x;
  solver.solve(descriptors(view, sing), view.halfedge_map(x),
               TC::parameters::loop_periods(periods, TC::parameters::symmetry_order(n)));
  ASSERT_EQ(x.size(), reference.x.size());
  double worst = 0;
  for(std::size_t h = 0; h < x.size(); ++h)
    worst = std::max(worst, std::abs(x[h] - reference.x[h]));
  EXPECT_LT(worst, 1e-8) << "largest difference of x(h) between backends";
}

class Backends : public ::testing::TestWithParam<Real_mesh>
{
};

TEST_P(Backends, agree)
{
  const Real_mesh& m = GetParam();
  const int n = 4;
  Surface_mesh sm;
  TC_READ_CGAL_MESH_OR_SKIP(m.file, sm);
  SCOPED_TRACE(std::string(m.file) + " (" + m.what + "), n = 4");
  const Mesh_view<Surface_mesh> view(sm);
  const Singularities sing = plan_singularities(view, n);
  TC::Trivial_connection_solver<Surface_mesh> solver(sm);
  const Solution<Surface_mesh> reference = solve_and_check(view, solver, sing, n, /*with_field=*/false);
  {
    SCOPED_TRACE("SimplicialLDLT with its own AMD ordering (metric by back-substitutions)");
    expect_same_as_default<Generic_ldlt_traits>(view, sm, sing, n, reference);
  }
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  {
    SCOPED_TRACE("CHOLMOD supernodal (metric from the supernodal factor)");
    expect_same_as_default<TC::Cholmod_solver_traits>(view, sm, sing, n, reference);
  }
  {
    SCOPED_TRACE("the choice by predicted cost (simplicial on these sizes, through every column)");
    expect_same_as_default<TC::Automatic_solver_traits>(view, sm, sing, n, reference);
  }
  {
    SCOPED_TRACE("the choice by predicted cost forced to CHOLMOD");
    expect_same_as_default<TC::Cost_based_solver_traits<Always_supernodal>>(view, sm, sing, n, reference);
  }
#endif
}

// from real_meshes: high genus, many boundary loops, several components
std::vector<Real_mesh> backend_meshes()
{
  std::vector<Real_mesh> chosen;
  for(const Real_mesh& m : real_meshes)
    for(const char* file : {"turbine.off", "cheese.off", "holes.off", "elephant-with-holes.off", "knot2.off",
                            "b9_mesh.off"})
      if(std::string(m.file) == file)
        chosen.push_back(m);
  return chosen;
}

INSTANTIATE_TEST_SUITE_P(CGAL_data, Backends, ::testing::ValuesIn(backend_meshes()),
                         [](const ::testing::TestParamInfo<Real_mesh>& info) { return test_name_of(info.param.file); });

std::string case_name(const ::testing::TestParamInfo<Case>& info)
{
  return test_name_of(std::get<0>(info.param).file) + "_n" + std::to_string(std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(CGAL_data, Real_meshes,
                         ::testing::Combine(::testing::ValuesIn(real_meshes), ::testing::Values(1, 4)), case_name);

INSTANTIATE_TEST_SUITE_P(CGAL_data, Real_meshes_unit_weights, ::testing::ValuesIn(real_meshes),
                         [](const ::testing::TestParamInfo<Real_mesh>& info) {
                           return case_name(::testing::TestParamInfo<Case>(Case(info.param, 4), info.index));
                         });

} // namespace

/*
  The integer choice does not depend on the loop basis the trees happen to give: the same mesh with its
  vertices and faces renumbered (other trees, other generators) reaches the same energy when both choices are
  proven optimal, and otherwise each energy is at least the other's certified lower bound. And the bound is a
  bound: any prescribed choice of the integers (here the chosen ones, each changed in turn by +-1) costs at
  least as much. Meshes of 111 (genus 3, 106 holes) and 266 (genus 133) free integers, n = 1 and 4.
*/
TEST(Integer_choice, independent_of_the_loop_basis_within_the_certificate)
{
  for(const char* file : {"elephant-with-holes.off", "cheese.off"}) {
    Surface_mesh sa;
    TC_READ_CGAL_MESH_OR_SKIP(file, sa);
    std::vector<int> perm;
    const Surface_mesh sb = to_surface_mesh(renumbered(mesh_to_soup(sa), 11, &perm, /*shuffle_faces=*/true));
    const Mesh_view<Surface_mesh> va(sa), vb(sb);
    TC::Trivial_connection_solver<Surface_mesh> solver_a(sa), solver_b(sb);
    for(int n : {1, 4}) {
      SCOPED_TRACE(std::string(file) + ", n = " + std::to_string(n));
      const Singularities sing = plan_singularities(va, n);
      Singularities moved;
      for(const auto& p : sing)
        moved.emplace_back(perm[p.first], p.second);
      std::vector<double> xa, xb;
      const TC::Solve_report ra = solver_a.solve(descriptors(va, sing), va.halfedge_map(xa), TC::parameters::symmetry_order(n));
      const TC::Solve_report rb = solver_b.solve(descriptors(vb, moved), vb.halfedge_map(xb), TC::parameters::symmetry_order(n));
      const double ea = ra.energy + ra.guidance_energy, eb = rb.energy + rb.guidance_energy;
      const double tolerance = 1e-9 * std::max(1., ea);
      EXPECT_LE(ra.energy_lower_bound, ea + tolerance);
      EXPECT_LE(rb.energy_lower_bound, eb + tolerance);
      EXPECT_LE(ea, ra.rounding_energy + tolerance);
      if(ra.integers_proven_optimal && rb.integers_proven_optimal) {
        EXPECT_NEAR(ea, eb, tolerance);
      } else {
        EXPECT_GE(ea, rb.energy_lower_bound - tolerance);
        EXPECT_GE(eb, ra.energy_lower_bound - tolerance);
      }
      std::cout << file << ", n = " << n << ": energies " << ea << " and " << eb << " (renumbered), lower bounds "
                << ra.energy_lower_bound << " and " << rb.energy_lower_bound << "\n";
      std::vector<std::int64_t> periods;
      for(const TC::Loop_report& l : ra.loops)
        periods.push_back(l.period);
      for(std::size_t l = 0; l < periods.size(); l += std::max<std::size_t>(1, periods.size() / 8)) {
        if(ra.loops[l].kind == TC::Loop_kind::boundary)
          continue; // the boundary loops of a component are prescribed all or none (Poincare-Hopf)
        for(int step : {-1, 1}) {
          std::vector<std::optional<std::int64_t>> given(periods.size());
          given[l] = periods[l] + step;
          std::vector<double> x;
          const TC::Solve_report r = solver_a.solve(descriptors(va, sing), va.halfedge_map(x),
                                                    TC::parameters::loop_periods(given, TC::parameters::symmetry_order(n)));
          EXPECT_GE(r.energy + r.guidance_energy, ra.energy_lower_bound - tolerance) << "loop " << l;
        }
      }
    }
  }
}
