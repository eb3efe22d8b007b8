// A user's program: the installed headers, the one linked target, a cross field on an icosahedron.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <CGAL/Trivial_connections/trivial_connection.h>

#include <iostream>
#include <utility>
#include <vector>

namespace TC = CGAL::Trivial_connections;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;

int main()
{
  Mesh mesh;
  CGAL::make_icosahedron<Mesh, K::Point_3>(mesh, K::Point_3(0, 0, 0), 1.0);
  // eight +1/4 singularities: their indices sum to 2
  std::vector<std::pair<Mesh::Vertex_index, TC::Singularity_index>> singularities;
  for(unsigned i = 0; i < 8; ++i)
    singularities.push_back({Mesh::Vertex_index(i), TC::Singularity_index(1, 4)});
  auto x = mesh.add_property_map<Mesh::Halfedge_index, double>("h:x", 0.).first;
  auto field = mesh.add_property_map<Mesh::Face_index, K::Vector_3>("f:field", CGAL::NULL_VECTOR).first;
  const TC::Solve_report report =
    TC::compute_direction_field(mesh, singularities, x, field, TC::parameters::symmetry_order(4));
  std::cout << "energy " << report.energy << ", residual " << report.max_vertex_residual << std::endl;
  return report.max_vertex_residual < 1e-9 ? 0 : 1;
}
