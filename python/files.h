// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Files: Solver.write_field() and the singularity and face direction files.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_FILES_H
#define TRIVIAL_CONNECTIONS_PYTHON_FILES_H

namespace {

// the field of `result` as a field file (.txt), or the mesh with it and the singularities as a VTK (.vtk) or PLY
// (.ply) file, written completely or not at all
void Python_solver::write_field(const py::object& path_in, const Result& result, const py::object& singularities) const
{
  const std::string path = path_of(path_in);
  const Singularities s = singularities_of(singularities);
  const auto singular = vertex_descriptors(*m_mesh, s);
  const std::vector<Kernel::Vector_3> field = field_of(result);
  const int n = result.n.cast<int>();
  const std::string extension = path.size() >= 4 ? path.substr(path.size() - 4) : std::string();
  if(extension != ".txt" && extension != ".vtk" && extension != ".ply")
    throw py::value_error("write_field: the file name must end in .txt (field file), .vtk or .ply, got \"" +
                          path + "\"");
  py::gil_scoped_release unlocked;
  auto field_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
    [&field](face_descriptor f) { return field[std::size_t(f)]; });
  TC::write_file_atomically(path, [&](std::ostream& os) {
    if(extension == ".txt")
      TC::write_field(os, *m_mesh, field_map);
    else if(extension == ".vtk")
      TC::write_field_vtk(os, *m_mesh, field_map, singular, TC::parameters::symmetry_order(n));
    else
      TC::write_field_ply(os, *m_mesh, field_map, singular, TC::parameters::symmetry_order(n));
  });
}

void bind_files(py::module_& m, py::class_<Python_solver>& solver)
{
  solver
    .def("write_field", &Python_solver::write_field, py::arg("path"), py::arg("result"), py::arg("singularities"),
         "Writes result's field to path (str, bytes or os.PathLike), by the file name's ending: .txt the program's "
         "field file (one line \"x y z\" per "
         "face, in face order, numbers that read back exactly; the singularities are checked but not written); .vtk "
         "or .ply the mesh, the field (its n directions) and the singularities as a legacy VTK or PLY file for "
         "ParaView, MeshLab or Blender. Completely or not at all.");
  m.def(
    "read_singularities",
    [](const py::object& path_in, const py::object& number_of_vertices) {
      const std::string path = path_of(path_in);
      const std::size_t count =
        number_of_vertices.is_none() ? TC::unchecked_vertex_count : number_of_vertices.cast<std::size_t>();
      std::vector<std::pair<std::size_t, TC::Singularity_index>> s;
      {
        py::gil_scoped_release unlocked;
        s = TC::read_singularities(path, count);
      }
      py::dict d;
      for(const auto& [v, k] : s)
        d[py::int_(v)] = fraction(k);
      return d;
    },
    py::arg("path"), py::arg("number_of_vertices") = py::none(),
    "Reads a singularity file (lines \"v k\", k an integer or p/q; # comments): {vertex: Fraction}. Raises "
    "InvalidInput (parse_error, duplicate_singularity, invalid_vertex, io_error) with the file and line.");
  m.def(
    "write_singularities",
    [](const py::object& path_in, const py::object& singularities) {
      const std::string path = path_of(path_in);
      const Singularities s = singularities_of(singularities);
      py::gil_scoped_release unlocked;
      TC::write_file_atomically(path, [&](std::ostream& os) { TC::write_singularities(os, s); });
    },
    py::arg("path"), py::arg("singularities"),
    "Writes singularities ({vertex: index} or pairs) in the format read_singularities() reads, completely or "
    "not at all.");

  m.def(
    "read_face_directions",
    [](const py::object& path_in, const py::object& number_of_faces) {
      const std::string path = path_of(path_in);
      const std::size_t count =
        number_of_faces.is_none() ? TC::unchecked_vertex_count : number_of_faces.cast<std::size_t>();
      std::vector<std::int64_t> faces;
      std::vector<double> xyz;
      {
        py::gil_scoped_release unlocked;
        const std::vector<TC::Face_direction> d = TC::read_face_directions(path, count);
        faces.reserve(d.size());
        xyz.reserve(3 * d.size());
        for(const TC::Face_direction& e : d) {
          if(e.face > std::size_t((std::numeric_limits<std::int64_t>::max)()))
            throw TC::Invalid_input(TC::Error_code::invalid_constraint,
                                    path + ": face " + std::to_string(e.face) + " is too large", e.face);
          faces.push_back(std::int64_t(e.face));
          xyz.insert(xyz.end(), e.direction.begin(), e.direction.end());
        }
      }
      const py::ssize_t k = py::ssize_t(faces.size());
      return py::make_tuple(owning_array(std::move(faces), {k}), owning_array(std::move(xyz), {k, 3}));
    },
    py::arg("path"), py::arg("number_of_faces") = py::none(),
    "Reads a face direction file (constraints or guides: lines \"f x y z\"; # comments): (faces, directions), a "
    "(k,) int64 and a (k, 3) float64 array in file order. Raises InvalidInput (parse_error, invalid_constraint: a "
    "face out of range, listed twice or with a zero vector; io_error) with the file and line.");
  m.def(
    "write_face_directions",
    [](const py::object& path_in, const py::object& faces, const py::object& directions) {
      const std::string path = path_of(path_in);
      const std::vector<TC::Face_direction> d = face_directions_of(faces, directions);
      py::gil_scoped_release unlocked;
      TC::write_file_atomically(path, [&](std::ostream& os) { TC::write_face_directions(os, d); });
    },
    py::arg("path"), py::arg("faces"), py::arg("directions") = py::none(),
    "Writes faces and their directions (faces: k integers and directions: a (k, 3) array, or one dict {face: "
    "vector}) in the format read_face_directions() reads, in their order, numbers that read back exactly; "
    "completely or not at all. Raises InvalidInput (invalid_constraint) for a negative face, a face listed twice, a "
    "zero or non-finite direction, and io_error.");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_FILES_H
