// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Streamlines: Solver.trace_streamlines() and write_streamlines().
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_STREAMLINES_H
#define TRIVIAL_CONNECTIONS_PYTHON_STREAMLINES_H

namespace {

// the polylines of the field of `result`, from the barycentres of `seed_faces` (default: every face)
py::list Python_solver::trace_streamlines(const Result& result, const py::object& singularities, const py::object& seed_faces,
                                          std::size_t maximum_faces_per_ray)
{
  const Singularities s = singularities_of(singularities);
  const auto singular = vertex_descriptors(*m_mesh, s);
  std::vector<face_descriptor> seeds;
  if(seed_faces.is_none())
    for(auto f : m_mesh->faces())
      seeds.push_back(f);
  else
    seeds = faces_of(seed_faces, m_mesh->number_of_faces(), "seed_faces");
  const std::vector<double> x = halfedge_angles(result);
  const std::vector<Kernel::Vector_3> field = field_of(result);
  const int n = result.n.cast<int>();
  std::vector<TC::Streamline<Mesh>> lines;
  {
    py::gil_scoped_release unlocked;
    auto x_map = boost::make_function_property_map<halfedge_descriptor, double>(
      [&x](halfedge_descriptor h) { return x[std::size_t(h)]; });
    auto field_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
      [&field](face_descriptor f) { return field[std::size_t(f)]; });
    const std::size_t limit = maximum_faces_per_ray > 0 ? maximum_faces_per_ray
                                                        : std::size_t(n) * m_mesh->number_of_faces();
    lines = TC::trace_streamlines(*m_mesh, x_map, field_map, singular, seeds,
                                  TC::parameters::symmetry_order(n, TC::parameters::maximum_faces_per_ray(limit)));
  }
  py::list out;
  for(auto& line : lines) {
    std::vector<double> p;
    p.reserve(3 * line.points.size());
    for(const auto& q : line.points)
      p.insert(p.end(), q.begin(), q.end());
    out.append(owning_array(std::move(p), {py::ssize_t(line.points.size()), 3}));
  }
  return out;
}

void bind_streamlines(py::module_& m, py::class_<Python_solver>& solver)
{
  solver
    .def("trace_streamlines", &Python_solver::trace_streamlines, py::arg("result"), py::arg("singularities"),
         py::arg("seed_faces") = py::none(), py::arg("maximum_faces_per_ray") = 0,
         "The streamlines of result's field from the barycentres of seed_faces (default: every face): a list of "
         "(k, 3) polylines on the surface; a ray stops at the boundary, at a face with a singular vertex, when it "
         "closes, or after maximum_faces_per_ray faces (0: n times the number of faces).");
  m.def(
    "write_streamlines",
    [](const py::object& path_in, const py::list& lines) {
      const std::string path = path_of(path_in);
      std::vector<TC::Streamline<Mesh>> s;
      for(const py::handle line : lines) {
        const auto a = Doubles::ensure(line);
        if(!a || a.ndim() != 2 || a.shape(1) != 3)
          throw py::value_error("each streamline must be a (k, 3) array of points");
        TC::Streamline<Mesh> l;
        for(py::ssize_t i = 0; i < a.shape(0); ++i)
          l.points.push_back({a.at(i, 0), a.at(i, 1), a.at(i, 2)});
        s.push_back(std::move(l));
      }
      py::gil_scoped_release unlocked;
      TC::write_file_atomically(path, [&](std::ostream& os) { TC::write_streamlines_vtk(os, s); });
    },
    py::arg("path"), py::arg("lines"),
    "Writes polylines (from Solver.trace_streamlines()) as a legacy VTK file of lines, for ParaView and the "
    "package's renderer (--streamlines); completely or not at all.");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_STREAMLINES_H
