// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_HOMOLOGY_CHECKS_H
#define CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_HOMOLOGY_CHECKS_H

// Test support: the generators independent of the vertex and boundary stars in homology.

#include "placement_and_integers.h"

namespace tc_test {

// =====================================================================================================
// Homology: the generators are independent of the vertex and boundary stars
// =====================================================================================================

/*
  Over the interior edges, the rows of every node star (interior vertex: its ring; boundary loop: the
  open fans of its vertices) span the null-homologous dual cycles (rank = nodes - components). The
  generator loops form a basis of H_1 of the surface with every boundary loop collapsed iff adding
  them raises the rank by exactly their number. Dense: for small meshes only.
*/
template <class Mesh>
void check_generators_independent(const Mesh_view<Mesh>& view, const std::vector<std::vector<int>>& generators)
{
  std::map<int, int> col;
  for(int h : view.interior_edges) col[h] = int(col.size());
  std::vector<std::vector<int>> rows;
  int nodes = 0;
  for(int v = 0; v < view.nv(); ++v)
    if(view.interior_vertex(v)) {
      ++nodes; rows.emplace_back();
      for(int h : view.interior_halfedges) if(view.tgt[h] == v) rows.back().push_back(h);
    }
  for(const auto& B : view.boundary_loops) {
    ++nodes; rows.emplace_back();
    for(int v : B.vertices)
      for(int h : view.interior_halfedges) if(view.tgt[h] == v) rows.back().push_back(h);
  }
  const int star_rows = int(rows.size());
  for(const auto& g : generators) rows.push_back(g);
  auto matrix = [&](int count) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(count, Eigen::Index(col.size()));
    for(int r = 0; r < count; ++r)
      for(const auto& kv : crossing_counts(view, rows[r])) A(r, col.at(kv.first)) += kv.second;
    return A;
  };
  const Eigen::MatrixXd stars = matrix(star_rows), all = matrix(int(rows.size()));
  Eigen::FullPivLU<Eigen::MatrixXd> lu_stars(stars), lu_all(all);
  EXPECT_EQ(int(lu_stars.rank()), nodes - view.ncomp) << "test self-check: rank of the node stars";
  EXPECT_EQ(int(lu_all.rank()), nodes - view.ncomp + int(generators.size()))
    << "generators are not independent in homology (or are null-homologous)";
  int expected = 0;
  for(int c = 0; c < view.ncomp; ++c) expected += 2 * view.genus[c];
  EXPECT_EQ(int(generators.size()), expected) << "number of generators (2g per component)";
}

} // namespace tc_test

#endif // CGAL_TRIVIAL_CONNECTIONS_TEST_SUPPORT_HOMOLOGY_CHECKS_H
