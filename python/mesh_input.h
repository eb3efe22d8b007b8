// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Mesh input: V and F checked and made into the Surface_mesh and the solver's arrays; a mesh file read by the package's
// reader; read_mesh().
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_MESH_INPUT_H
#define TRIVIAL_CONNECTIONS_PYTHON_MESH_INPUT_H

namespace {

// ---- numpy in -------------------------------------------------------------------------------------------

// The mesh of V, F, and the solver's arrays of it, made from the soup's validated connectivity rather than read
// back out of the mesh (Solver_access::make). The Surface_mesh is built on a second thread meanwhile: the solver
// reads nothing of it while it is constructed (its arrays and a vertex point map over V stand for it), and
// wait_for_mesh() joins that thread before anything reads the mesh. This is what makes a solver from arrays cost
// no more than from a Surface_mesh made of them. Vertex i and face f of the arrays are vertex i and face f of the
// mesh. From a file: the mesh only, complete.
struct Mesh_of_arrays
{
  std::unique_ptr<Mesh> mesh;
  std::size_t number_of_faces = 0;
  std::optional<TC::internal::Mesh_arrays<Mesh>> arrays; // consumed by the solver
  const double* points = nullptr; // V as C-ordered float64 rows, owned by points_owner
  py::object points_owner;
  std::unique_ptr<TC::internal::io::Triangle_soup_connectivity> soup; // read by the mesh's construction
  std::future<void> building; // the mesh's construction; last, so that it is joined before the rest goes

  void wait_for_mesh()
  {
    if(building.valid())
      building.get();
  }
  Mesh_of_arrays() = default;
  Mesh_of_arrays(Mesh_of_arrays&&) = default;
  ~Mesh_of_arrays()
  {
    if(building.valid())
      building.wait();
  }
};

// The rows of a C-ordered (m, 3) int64 array, seen as triangles (no copy), for the package's soup validation
struct Triangle_rows
{
  using Row = std::array<std::int64_t, 3>;
  static_assert(sizeof(Row) == 3 * sizeof(std::int64_t), "rows of an (m, 3) array");
  const Row* first;
  std::size_t count;
  const Row* begin() const { return first; }
  const Row* end() const { return first + count; }
  std::size_t size() const { return count; }
};

// The rows of a C-ordered (n, 3) float64 array as points, made as they are read (no copy)
struct Point_rows
{
  struct iterator
  {
    const double* p;
    Kernel::Point_3 operator*() const { return Kernel::Point_3(p[0], p[1], p[2]); }
    iterator& operator++() { p += 3; return *this; }
    bool operator!=(const iterator& o) const { return p != o.p; }
  };
  const double* first;
  std::size_t count;
  iterator begin() const { return {first}; }
  iterator end() const { return {first + 3 * count}; }
};

// V and F checked and as C-ordered float64 and int64 arrays (one copy at most, when the dtype or the layout differs)
using Point_array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Face_array = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

std::pair<Point_array, Face_array> checked_arrays(const py::handle& v_in, const py::handle& f_in)
{
  const py::array V = as_array(v_in, "V"), F = as_array(f_in, "F");
  check_rows_of_three(V, "V", "fiu", "real numbers");
  check_rows_of_three(F, "F", "iu", "integers (vertex indices)");
  if(F.dtype().kind() == 'u' && F.dtype().itemsize() == 8) { // uint64: values over int64's range, said as they are
    const auto u = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(F);
    const std::uint64_t limit = std::uint64_t((std::numeric_limits<std::int64_t>::max)());
    const std::size_t nv = std::size_t(V.shape(0));
    for(std::size_t i = 0; i < std::size_t(u.size()); ++i)
      if(u.data()[i] > limit)
        throw TC::Invalid_input(TC::Error_code::invalid_vertex,
                                "face " + std::to_string(i / 3) + " uses vertex " + std::to_string(u.data()[i]) +
                                  " but the mesh has only " + std::to_string(nv) + " vertices (0-based indices 0 to " +
                                  (nv == 0 ? std::string("none") : std::to_string(nv - 1)) + ")",
                                i / 3);
  }
  auto points = Point_array::ensure(V);
  auto faces = Face_array::ensure(F);
  if(!points || !faces)
    throw py::type_error("V and F must be convertible to float64 and int64 arrays");
  return {std::move(points), std::move(faces)};
}

Mesh_of_arrays mesh_of_arrays(const py::handle& v_in, const py::handle& f_in)
{
  const auto [points, faces] = checked_arrays(v_in, f_in);
  const Point_rows p{points.data(), std::size_t(points.shape(0))};
  const Triangle_rows t{reinterpret_cast<const Triangle_rows::Row*>(faces.data()), std::size_t(faces.shape(0))};
  Mesh_of_arrays out;
  out.mesh = std::make_unique<Mesh>();
  out.points = points.data();
  out.points_owner = points;
  out.number_of_faces = t.size();
  py::gil_scoped_release unlocked; // the arrays are held above
  for(std::size_t i = 0; i < t.size(); ++i)
    for(std::size_t j = 0; j < 3; ++j)
      if(t.first[i][j] < 0)
        throw TC::Invalid_input(TC::Error_code::invalid_vertex,
                                "face " + std::to_string(i) + " uses vertex " + std::to_string(t.first[i][j]) +
                                  ": vertex indices start at 0",
                                i);
  out.soup = std::make_unique<TC::internal::io::Triangle_soup_connectivity>(
    TC::internal::io::validate_triangle_soup(p.count, t));
  const TC::internal::io::Triangle_soup_connectivity& soup = *out.soup;
  out.building = std::async(std::launch::async, [p, &soup, mesh = out.mesh.get()] {
#ifdef __linux__
    // in the time the solver's own threads leave (a Linux thread's nice value is its own)
    setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), 19);
#endif
    TC::internal::io::build_mesh(p, soup, *mesh);
  });
  // meanwhile, the solver's arrays (the soup is only read on both sides)
  std::vector<vertex_descriptor> vertices(p.count);
  for(std::size_t i = 0; i < p.count; ++i)
    vertices[i] = vertex_descriptor(Mesh::size_type(i));
  std::vector<face_descriptor> face_descriptors(t.size());
  for(std::size_t f = 0; f < t.size(); ++f)
    face_descriptors[f] = face_descriptor(Mesh::size_type(f));
  std::vector<int> corner_vertices(3 * t.size());
  for(std::size_t f = 0; f < t.size(); ++f)
    for(std::size_t k = 0; k < 3; ++k)
      corner_vertices[3 * f + k] = soup.triangles[f][k];
  const Mesh& mesh = *out.mesh; // its index maps read nothing of it
  out.arrays.emplace(get(boost::vertex_index, mesh), get(boost::face_index, mesh), std::move(vertices),
                     std::move(face_descriptors),
                     TC::internal::io::surface_mesh_corner_halfedges<Kernel::Point_3>(soup),
                     std::move(corner_vertices), std::vector<int>(soup.opposite));
  return out;
}

// The vertices of each face, 3 per face, as the arrays or the file gave them: a mesh built by the package's
// build_mesh() (triangle_soup_to_mesh(), read_triangle_mesh(), Solver(V, F)) has as the halfedge of face f the one
// from its corner 0 to its corner 1, so the sources of its halfedges from there are the face's row, in order.
std::vector<std::int64_t> corners_in_input_order(const Mesh& mesh)
{
  std::vector<std::int64_t> t;
  t.reserve(3 * mesh.number_of_faces());
  for(auto f : mesh.faces())
    for(auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh))
      t.push_back(std::int64_t(mesh.source(h)));
  return t;
}

std::unique_ptr<Mesh> mesh_of_file(const std::string& path, bool triangulate)
{
  auto mesh = std::make_unique<Mesh>();
  py::gil_scoped_release unlocked;
  TC::read_triangle_mesh(path, *mesh, TC::parameters::triangulate(triangulate));
  return mesh;
}


// read_mesh(path, triangulate=False) -> (V, F); repair_mesh(path) -> (V, F, report)
void bind_mesh_input(py::module_& m)
{
  m.def(
    "read_mesh",
    [](const py::object& path_in, bool triangulate) {
      const std::string path = path_of(path_in);
      std::unique_ptr<Mesh> mesh = mesh_of_file(path, triangulate);
      std::vector<double> p;
      std::vector<std::int64_t> t;
      {
        py::gil_scoped_release unlocked;
        p.reserve(3 * mesh->number_of_vertices());
        for(auto v : mesh->vertices())
          for(int i = 0; i < 3; ++i)
            p.push_back(CGAL::to_double(mesh->point(v)[i]));
        t = corners_in_input_order(*mesh);
      }
      const py::ssize_t nv = py::ssize_t(mesh->number_of_vertices()), nf = py::ssize_t(mesh->number_of_faces());
      return py::make_tuple(owning_array(std::move(p), {nv, 3}), owning_array(std::move(t), {nf, 3}));
    },
    py::arg("path"), py::arg("triangulate") = false,
    R"(Reads a triangle mesh file into (V, F) numpy arrays, without building a solver.

path: str, bytes or os.PathLike; the extension gives the format: .off, .obj, .ply, .stl or .ts (GOCAD), the
formats the program reads, with the same validating reader (TC::read_triangle_mesh()). V is an (n, 3) float64
array of points, F an (m, 3) int64 array of vertex indices (0-based), vertex i and face f of the file being row i
and row f. triangulate=True splits faces of more than three vertices (as the program's --triangulate; the
triangles of one face are consecutive rows), else such a face is InvalidInput not_triangle_mesh. Solver(V, F)
then gives the same solver as Solver.from_file(path, triangulate). Raises InvalidInput (io_error for a file that
cannot be read or an unknown extension, parse_error, not_triangle_mesh, non_manifold_vertex, degenerate_face,
non_finite_point, ...) with the file's name, as the program.)");

  m.def(
    "repair_mesh",
    [](const py::object& path_in) {
      const std::string path = path_of(path_in);
      Mesh mesh;
      TC::Repair_report r;
      std::vector<double> p;
      std::vector<std::int64_t> t;
      {
        py::gil_scoped_release unlocked;
        TC::read_and_repair_triangle_mesh(path, mesh, r);
        p.reserve(3 * mesh.number_of_vertices());
        for(auto v : mesh.vertices())
          for(int i = 0; i < 3; ++i)
            p.push_back(CGAL::to_double(mesh.point(v)[i]));
        t = corners_in_input_order(mesh);
      }
      py::dict report;
      report["changed"] = r.changed();
      report["input_points"] = r.input_points;
      report["input_polygons"] = r.input_polygons;
      report["points_removed"] = r.points_removed;
      report["polygons_removed"] = r.polygons_removed;
      report["polygons_reoriented"] = r.polygons_reoriented;
      report["points_duplicated"] = r.points_duplicated;
      report["polygons_triangulated"] = r.polygons_triangulated;
      report["edges_stitched"] = r.edges_stitched;
      report["degenerate_faces_removed"] = r.degenerate_faces_removed;
      report["non_manifold_vertices_split"] = r.non_manifold_vertices_split;
      const py::ssize_t nv = py::ssize_t(mesh.number_of_vertices()), nf = py::ssize_t(mesh.number_of_faces());
      return py::make_tuple(owning_array(std::move(p), {nv, 3}), owning_array(std::move(t), {nf, 3}), report);
    },
    py::arg("path"),
    R"(Reads a mesh file and repairs it as the program's --repair does: (V, F, report).

A mesh that read_mesh(path) accepts is returned as it is (report["changed"] is False). A refused one (polygons,
inconsistent orientation, non-manifold vertices, degenerate faces) goes through CGAL's Polygon Mesh Processing:
soup repair (duplicate points merged, degenerate and duplicate faces removed), orientation, triangulation,
stitching of borders, removal of zero-area faces, splitting of non-manifold vertices. report counts what each
step changed (keys input_points, input_polygons, points_removed, polygons_removed, polygons_reoriented,
points_duplicated, polygons_triangulated, edges_stitched, degenerate_faces_removed, non_manifold_vertices_split)
and the rows of V and F number the repaired mesh: Solver(V, F) solves on it. The file is not modified. Raises
InvalidInput as read_mesh() for a file that cannot be read, and with the error's code for what the repair cannot
mend (e.g. empty_mesh for a point cloud).)");
}

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_MESH_INPUT_H
