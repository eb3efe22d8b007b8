// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The Python module `trivial_connections` (pybind11): the package's solver on numpy arrays. One translation
// unit, built by the top-level CMakeLists.txt when pybind11 and Python's headers are found.
//
// Arrays come in as numpy arrays of any integer (faces) or real (points) type and layout; each is read once
// into the Surface_mesh the solver refers to and into the solver's own arrays, made from the validated
// connectivity rather than read back out of the mesh. The results are numpy arrays that own the solver's output
// vectors (no copy on the way out). The GIL is released while the solver is built and while it solves, so
// solves on one solver from several Python threads run at the same time, as the C++ solver allows;
// set_constraints() waits for them and they for it.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <CGAL/Trivial_connections/IO/atomic_file.h>
#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/field_file.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/feature_alignment.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>
#include <CGAL/Trivial_connections/streamlines.h>
#include <CGAL/Trivial_connections/solver_traits.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <future>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <tuple>
#include <shared_mutex>
#include <string>
#include <utility>
#include <vector>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace py = pybind11;
namespace TC = CGAL::Trivial_connections;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using vertex_descriptor = Mesh::Vertex_index;
using halfedge_descriptor = Mesh::Halfedge_index;
using face_descriptor = Mesh::Face_index;
using Loop_periods = std::vector<std::optional<std::int64_t>>;
using Singularities = std::vector<std::pair<std::size_t, TC::Singularity_index>>;

// ---- numpy in -------------------------------------------------------------------------------------------

// `a` as an (rows, 3) array: its shape checked, its dtype of kind `kinds` ("f", "iu", ...).
void check_rows_of_three(const py::array& a, const char* name, const char* kinds, const char* what)
{
  if(a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(std::string(name) + " must be an (n, 3) array, got shape " +
                          std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(
                            a.shape(), a.shape() + a.ndim()))))));
  const char kind = a.dtype().kind();
  if(std::string(kinds).find(kind) == std::string::npos)
    throw py::type_error(std::string(name) + " must hold " + what + ", got dtype " +
                         std::string(py::str(a.dtype())));
}

py::array as_array(const py::handle& h, const char* name)
{
  if(py::isinstance<py::str>(h) || py::isinstance<py::bytes>(h) ||
     (!py::isinstance<py::array>(h) && !py::isinstance<py::sequence>(h)))
    throw py::type_error(std::string(name) + " must be a numpy array (or a nested sequence), got " +
                         std::string(py::str(py::type::of(h))));
  return py::array::ensure(h);
}

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

// A Python integer (int, numpy integer: anything with __index__) as an int64; `too_large` when it does not fit.
std::int64_t int64_of(const py::handle& h, TC::Error_code too_large, const std::string& what)
{
  const py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(h.ptr()));
  if(!i)
    throw py::error_already_set();
  int overflow = 0;
  const long long value = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if(overflow != 0)
    throw TC::Invalid_input(too_large, what + " " + std::string(py::str(i)) + " is too large");
  if(value == -1 && PyErr_Occurred())
    throw py::error_already_set();
  return std::int64_t(value);
}

// The largest symmetry order n the module accepts: the program's (--n takes at most nine digits). Beyond 2^30 the
// library's bound on n times an index (internal::max_scaled_index()) would refuse even an index of 1.
constexpr std::int64_t max_symmetry_order = 999999999;

// A symmetry order given in Python (`n`, `feature_n`): an int (or numpy integer, not a bool) from 1 to
// max_symmetry_order, else InvalidInput (a ValueError) with the library's code invalid_symmetry_order, naming the
// range (TypeError for another type)
int symmetry_order_of(const py::handle& h, const char* name)
{
  if(py::isinstance<py::bool_>(h) || !PyIndex_Check(h.ptr()))
    throw py::type_error(std::string(name) + " must be an integer from 1 to " + std::to_string(max_symmetry_order) +
                         ", got " + std::string(py::repr(h)));
  const py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(h.ptr()));
  if(!i)
    throw py::error_already_set();
  int overflow = 0;
  const long long value = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
  if(value == -1 && PyErr_Occurred())
    throw py::error_already_set();
  if(overflow != 0 || value < 1 || value > max_symmetry_order)
    throw TC::Invalid_input(TC::Error_code::invalid_symmetry_order,
                            std::string(name) + " must be an integer from 1 to " + std::to_string(max_symmetry_order) +
                              " (the program's --n; 1 vectors, 2 lines, 4 crosses, ...), got " + std::string(py::str(i)));
  return int(value);
}

// A file name given in Python: str, bytes or any os.PathLike (pathlib.Path), as the bytes the file system takes
// (os.fsencode); anything else is the TypeError of os.fspath()
std::string path_of(const py::handle& path)
{
  const py::object os = py::module_::import("os");
  return std::string(py::bytes(os.attr("fsencode")(os.attr("fspath")(path))));
}

// ---- progress, logging and Ctrl-C during long calls ------------------------------------------------------

// What the progress callback of one call reports to: the user's callable (or None) and the logger
// "trivial_connections". The callback the library gets holds a pointer to it, so that copying the callback
// (the library does, without the GIL) copies no Python object; it lives as long as the call.
struct Progress_context
{
  std::string call; // "Solver()", "solve()", ...
  py::object callable, logger;
  std::chrono::steady_clock::time_point phase_start;

  Progress_context(std::string c, py::object f) : call(std::move(c)), callable(std::move(f))
  {
    if(!callable.is_none() && !PyCallable_Check(callable.ptr()))
      throw py::type_error("progress must be a callable progress(phase, fraction) or None, got " +
                           std::string(py::repr(callable)));
    logger = py::module_::import("logging").attr("getLogger")("trivial_connections");
  }

  // Called by the library between phases and iterations, on the calling thread, without the GIL: takes it,
  // raises a pending KeyboardInterrupt (or whatever a signal handler raised) by throwing, which aborts the C++
  // call; logs the phase (INFO when it starts and ends, DEBUG in between); calls the user's callable, whose
  // exception aborts the call too.
  TC::Progress_callback callback()
  {
    Progress_context* self = this;
    return [self](TC::Phase phase, double fraction) {
      py::gil_scoped_acquire gil;
      if(PyErr_CheckSignals() != 0)
        throw py::error_already_set();
      const char* name = TC::phase_name(phase);
      const auto now = std::chrono::steady_clock::now();
      if(fraction <= 0)
        self->phase_start = now;
      const int level = (fraction <= 0 || fraction >= 1) ? 20 : 10; // logging.INFO, logging.DEBUG
      if(self->logger.attr("isEnabledFor")(level).cast<bool>()) {
        if(fraction <= 0)
          self->logger.attr("log")(level, "%s %s: started", self->call, name);
        else if(fraction >= 1)
          self->logger.attr("log")(level, "%s %s: done in %.3f s", self->call, name,
                                   std::chrono::duration<double>(now - self->phase_start).count());
        else
          self->logger.attr("log")(level, "%s %s: %.0f %%", self->call, name, 100 * fraction);
      }
      if(!self->callable.is_none())
        self->callable(name, fraction);
    };
  }
};

// An index: an int (or numpy integer), a fractions.Fraction, or a "p/q" string; exact, never a float.
TC::Singularity_index index_of(const py::handle& k)
{
  if(py::isinstance<py::bool_>(k) || PyFloat_Check(k.ptr()))
    throw py::type_error("an index must be an int, a fractions.Fraction or a string \"p/q\" (exact), got " +
                         std::string(py::repr(k)));
  if(py::isinstance<py::str>(k))
    return TC::Singularity_index::parse(k.cast<std::string>());
  if(PyIndex_Check(k.ptr()))
    return TC::Singularity_index(int64_of(k, TC::Error_code::invalid_index, "the index"));
  if(py::hasattr(k, "numerator") && py::hasattr(k, "denominator"))
    return TC::Singularity_index(int64_of(k.attr("numerator"), TC::Error_code::invalid_index, "the numerator"),
                                 int64_of(k.attr("denominator"), TC::Error_code::invalid_index, "the denominator"));
  throw py::type_error("an index must be an int, a fractions.Fraction or a string \"p/q\", got " +
                       std::string(py::repr(k)));
}

std::size_t vertex_number(const py::handle& v)
{
  if(py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr()))
    throw py::type_error("a singular vertex must be an integer, got " + std::string(py::repr(v)));
  const std::int64_t i = int64_of(v, TC::Error_code::invalid_vertex, "vertex");
  if(i < 0)
    throw TC::Invalid_input(TC::Error_code::invalid_vertex, "vertex " + std::to_string(i) + " does not exist (negative)");
  return std::size_t(i);
}

// {vertex: index} or pairs (vertex, index), e.g. a (k, 2) integer array
std::vector<std::pair<std::size_t, TC::Singularity_index>> singularities_of(const py::handle& s)
{
  std::vector<std::pair<std::size_t, TC::Singularity_index>> out;
  if(s.is_none())
    return out;
  if(py::isinstance<py::dict>(s)) {
    for(const auto& item : py::reinterpret_borrow<py::dict>(s))
      out.emplace_back(vertex_number(item.first), index_of(item.second));
    return out;
  }
  if(py::isinstance<py::array>(s)) {
    const py::array a = py::reinterpret_borrow<py::array>(s);
    if(a.ndim() != 2 || a.shape(1) != 2)
      throw py::value_error("singularities as an array must have shape (k, 2): rows (vertex, index)");
    if(a.dtype().kind() != 'i' && a.dtype().kind() != 'u' && a.dtype().kind() != 'O')
      throw py::type_error("singularities as an array must hold integers (or objects: Fraction, \"p/q\"), got "
                           "dtype " + std::string(py::str(a.dtype())));
  }
  if(!py::isinstance<py::sequence>(s) && !py::isinstance<py::array>(s))
    throw py::type_error("singularities must be a dict {vertex: index} or a sequence of (vertex, index)");
  for(const py::handle row : py::iter(s)) {
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(row);
    if(!py::isinstance<py::sequence>(row) && !py::isinstance<py::array>(row))
      throw py::type_error("each singularity must be a pair (vertex, index)");
    if(py::len(pair) != 2)
      throw py::value_error("each singularity must be a pair (vertex, index)");
    out.emplace_back(vertex_number(pair[0]), index_of(pair[1]));
  }
  return out;
}

// A face number of a file of face directions: an integer (not a bool), not negative
std::size_t face_number(const py::handle& f)
{
  if(py::isinstance<py::bool_>(f) || !PyIndex_Check(f.ptr()))
    throw py::type_error("a face must be an integer, got " + std::string(py::repr(f)));
  const std::int64_t i = int64_of(f, TC::Error_code::invalid_constraint, "face");
  if(i < 0)
    throw TC::Invalid_input(TC::Error_code::invalid_constraint, "face " + std::to_string(i) + " does not exist (negative)");
  return std::size_t(i);
}

// Three numbers (a sequence or a (3,) array) as a direction
std::array<double, 3> direction_of(const py::handle& h)
{
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
  if(!a || a.ndim() != 1 || a.shape(0) != 3)
    throw py::value_error("a direction must be three numbers, got " + std::string(py::repr(h)));
  return {{a.data()[0], a.data()[1], a.data()[2]}};
}

// {face: (3,) vector}, or faces (a sequence of k integers) and directions (a (k, 3) array), in their order
std::vector<TC::Face_direction> face_directions_of(const py::object& faces, const py::object& directions)
{
  std::vector<TC::Face_direction> out;
  if(py::isinstance<py::dict>(faces)) {
    if(!directions.is_none())
      throw py::type_error("give the faces and their directions as one dict {face: vector}, or as faces and "
                           "directions, not both");
    for(const auto& item : py::reinterpret_borrow<py::dict>(faces))
      out.push_back({face_number(item.first), direction_of(item.second)});
    return out;
  }
  if(directions.is_none())
    throw py::type_error("directions missing: give faces and directions, or one dict {face: vector}");
  if(py::isinstance<py::str>(faces) || py::isinstance<py::bytes>(faces))
    throw py::type_error("faces must be a sequence of integers, got " + std::string(py::repr(faces)));
  for(const py::handle f : py::iter(faces))
    out.push_back({face_number(f), {{0, 0, 0}}});
  const py::array a = as_array(directions, "directions");
  if(out.empty() && a.size() == 0) // no face: [] or a (0, 3) array
    return out;
  check_rows_of_three(a, "directions", "fiu", "real numbers");
  if(std::size_t(a.shape(0)) != out.size())
    throw py::value_error("directions must have one row per face (" + std::to_string(out.size()) + "), got " +
                          std::to_string(a.shape(0)));
  const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  for(std::size_t i = 0; i < out.size(); ++i)
    out[i].direction = {{d.data()[3 * i], d.data()[3 * i + 1], d.data()[3 * i + 2]}};
  return out;
}

// ---- numpy out: arrays that own the vectors they show ---------------------------------------------------

template <class T>
py::array_t<T> owning_array(std::vector<T>&& values, std::vector<py::ssize_t> shape)
{
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owned->data(), free_when_done);
}

py::object fraction(const TC::Singularity_index& k)
{
  return py::module_::import("fractions").attr("Fraction")(k.numerator(), k.denominator());
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

// ---- the solver, whatever its backend ------------------------------------------------------------------

struct Solve_output
{
  TC::Solve_report report;
  double solve_seconds = 0, field_seconds = 0, output_seconds = 0; // the C++ calls, and the outputs' vectors
  std::vector<double> connection; // per interior edge, in the order of `edges`
  std::vector<double> field;      // 3 per face
  std::vector<double> directions; // 3 n per face (n > 1)
};

class Solver_interface
{
public:
  virtual ~Solver_interface() = default;
  // all_directions: also the n directions per face (Solve_output::directions), for n > 1
  virtual Solve_output solve(const std::vector<std::pair<std::size_t, TC::Singularity_index>>& singularities,
                             int n, const std::vector<Kernel::Vector_3>* directions,
                             const Loop_periods* loop_periods, bool all_directions,
                             const TC::Progress_callback& progress) = 0;
  virtual std::size_t number_of_loops() const = 0;
  virtual std::vector<double> weights() const = 0; // w_e per interior edge, in edges() order
  // per loop of the solver: a boundary loop?, its component, the halfedges it crosses
  virtual std::vector<std::tuple<bool, std::size_t, std::vector<halfedge_descriptor>>> loops() const = 0;
  virtual TC::Placement_report place(int n, bool align_boundary, const std::vector<Kernel::Vector_3>* guide,
                                     double strength, const Singularities& fixed, const Loop_periods* periods,
                                     const std::vector<Kernel::Vector_3>* directions, Singularities& placed,
                                     const TC::Progress_callback& progress) const = 0;
  virtual std::vector<Kernel::Vector_3> curvature_guide(std::vector<std::pair<double, double>>& curvatures) const = 0;
  virtual std::vector<std::size_t> spread(const std::vector<Kernel::Vector_3>& guide, std::size_t count) const = 0;
  virtual TC::Refinement_report<vertex_descriptor> refine(const Singularities& start, int n,
                                                          const std::vector<Kernel::Vector_3>* directions,
                                                          const Loop_periods* periods,
                                                          const std::vector<std::size_t>& fixed, bool cancel_pairs,
                                                          std::size_t trials, const TC::Progress_callback& progress) = 0;
  // `known`: the targets known already (per face, zero where not known; empty: none), with their n
  virtual TC::Constraint_update set_constraints(const std::vector<face_descriptor>& constrained,
                                                const std::vector<face_descriptor>& guided,
                                                const std::vector<Kernel::Vector_3>& known, int known_n) = 0;
  virtual const char* backend() const = 0;
  // the topology of each connected component, and the component of each face (Trivial_connection_solver's)
  virtual std::vector<TC::Component_report> components() const = 0;
  virtual std::vector<std::size_t> face_components() const = 0;
  // the vertices of each interior edge, two per edge (smaller first), in the order of Result.connection
  virtual const std::vector<std::int64_t>& edge_vertices() const = 0;
};

// Vertex v of `mesh` (vertex i is the i-th of the arrays or the file); a vertex out of range is the user's error.
vertex_descriptor vertex_of(const Mesh& mesh, std::size_t v)
{
  if(v >= mesh.number_of_vertices())
    throw TC::Invalid_input(TC::Error_code::invalid_vertex,
                            "vertex " + std::to_string(v) + " does not exist (the mesh has " +
                              std::to_string(mesh.number_of_vertices()) + " vertices)",
                            v);
  return vertex_descriptor(Mesh::size_type(v));
}

// The vertices of `s` in `mesh`, each checked by vertex_of()
std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> vertex_descriptors(const Mesh& mesh,
                                                                                    const Singularities& s)
{
  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> out;
  out.reserve(s.size());
  for(const auto& [v, k] : s)
    out.emplace_back(vertex_of(mesh, v), k);
  return out;
}

// x(h) kept straight in the per-edge output array: x of the halfedge from the smaller vertex index to the larger
// one, its opposite's the negative (nothing on the border)
struct Edge_connection_map
{
  using key_type = halfedge_descriptor;
  using value_type = double;
  using reference = double;
  using category = boost::read_write_property_map_tag;
  const Mesh* mesh;
  const std::vector<std::int64_t>* slot; // per edge: its entry, -1 on the border
  double* x;
  friend double get(const Edge_connection_map& m, halfedge_descriptor h)
  {
    const std::int64_t i = (*m.slot)[std::size_t(m.mesh->edge(h))];
    if(i < 0)
      return 0.;
    return m.mesh->source(h) < m.mesh->target(h) ? m.x[i] : -m.x[i];
  }
  friend void put(const Edge_connection_map& m, halfedge_descriptor h, double value)
  {
    const std::int64_t i = (*m.slot)[std::size_t(m.mesh->edge(h))];
    if(i >= 0)
      m.x[i] = m.mesh->source(h) < m.mesh->target(h) ? value : -value;
  }
};

// a face's vector kept straight in the (m, 3) output array
struct Face_vector_map
{
  using key_type = face_descriptor;
  using value_type = Kernel::Vector_3;
  using reference = Kernel::Vector_3;
  using category = boost::read_write_property_map_tag;
  double* xyz;
  friend Kernel::Vector_3 get(const Face_vector_map& m, face_descriptor f)
  {
    const double* p = m.xyz + 3 * std::size_t(f);
    return Kernel::Vector_3(p[0], p[1], p[2]);
  }
  friend void put(const Face_vector_map& m, face_descriptor f, const Kernel::Vector_3& v)
  {
    double* p = m.xyz + 3 * std::size_t(f);
    p[0] = CGAL::to_double(v.x());
    p[1] = CGAL::to_double(v.y());
    p[2] = CGAL::to_double(v.z());
  }
};

// The points the solver reads while it is built: V's rows (Solver(V, F): the mesh may still be under
// construction), else the mesh's own
struct Point_source
{
  using key_type = vertex_descriptor;
  using value_type = Kernel::Point_3;
  using reference = Kernel::Point_3;
  using category = boost::readable_property_map_tag;
  const double* xyz;
  const Mesh* mesh;

  friend Kernel::Point_3 get(const Point_source& m, vertex_descriptor v)
  {
    if(m.xyz == nullptr)
      return m.mesh->point(v);
    const double* p = m.xyz + 3 * std::size_t(v);
    return Kernel::Point_3(p[0], p[1], p[2]);
  }
};

struct Options
{
  TC::Weighting weighting = TC::Weighting::hodge_star;
  std::vector<face_descriptor> constrained, guided;
  double guidance_weight = 1;
  bool align_boundary = false;
  // the targets known when the solver is built (per face, zero where not known) and their n: touching pins that
  // disagree are then left to the lattice rather than rounded
  std::vector<Kernel::Vector_3> known_directions;
  int known_n = 1;
  TC::Progress_callback progress; // the constructor's phases (empty: none)
};

// Per face, the direction of `directions` (one per face), or the zero vector everywhere without them
inline auto face_direction_map(const std::vector<Kernel::Vector_3>* directions)
{
  return boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
    [directions](face_descriptor f) { return directions ? (*directions)[std::size_t(f)] : CGAL::NULL_VECTOR; });
}

template <class SolverTraits>
class Solver_of : public Solver_interface
{
  using Solver = TC::Trivial_connection_solver<Mesh, Kernel, SolverTraits>;

public:
  // From `source`: its arrays when it has them (mesh_of_arrays(); the mesh may then still be under construction,
  // and is waited for once the solver is built), else from its mesh
  Solver_of(Mesh_of_arrays& source, const Options& o, const char* name)
    : m_mesh(*source.mesh), m_name(name)
  {
    const Mesh& mesh = *source.mesh;
    const auto known_map = face_direction_map(o.known_directions.empty() ? nullptr : &o.known_directions);
    const auto np = TC::parameters::progress(o.progress, TC::parameters::weighting(
      o.weighting,
      TC::parameters::constrained_faces(
        o.constrained,
        TC::parameters::guided_faces(
          o.guided, TC::parameters::guidance_weight(
                      o.guidance_weight, TC::parameters::align_with_boundary(
                                           o.align_boundary,
                                           TC::parameters::face_directions(
                                             known_map, TC::parameters::symmetry_order(
                                                          o.known_n, CGAL::parameters::vertex_point_map(
                                                                       Point_source{source.points, &mesh})))))))));
    if(source.arrays)
      m_solver = TC::internal::Solver_access<Solver>::make(mesh, std::move(*source.arrays), np);
    else
      m_solver = std::make_unique<Solver>(mesh, np);
    source.wait_for_mesh();
    m_edge_slot.assign(mesh.number_of_edges(), -1);
    for(auto e : mesh.edges())
      if(!mesh.is_border(e)) {
        m_edge_slot[std::size_t(e)] = m_interior_edges++;
        const auto h = mesh.halfedge(e);
        const std::int64_t a = std::int64_t(mesh.source(h)), b = std::int64_t(mesh.target(h));
        m_edge_vertices.push_back((std::min)(a, b));
        m_edge_vertices.push_back((std::max)(a, b));
      }
  }

  Solve_output solve(const std::vector<std::pair<std::size_t, TC::Singularity_index>>& singularities, int n,
                     const std::vector<Kernel::Vector_3>* directions, const Loop_periods* loop_periods,
                     bool all_directions, const TC::Progress_callback& progress) override
  {
    const auto s = vertex_descriptors(m_mesh, singularities);
    Solve_output out;
    out.connection.assign(std::size_t(m_interior_edges), 0.);
    out.field.assign(3 * m_mesh.number_of_faces(), 0.);
    const Edge_connection_map halfedge_x{&m_mesh, &m_edge_slot, out.connection.data()};
    const Face_vector_map face_field{out.field.data()};
    // directions_of() gives one per face
    const auto target_map = face_direction_map(directions);

    using Clock = std::chrono::steady_clock;
    const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    Clock::time_point start = Clock::now();
    const auto np = TC::parameters::symmetry_order(
      n, TC::parameters::face_directions(target_map, TC::parameters::progress(progress)));
    out.report = loop_periods != nullptr ? m_solver->solve(s, halfedge_x, TC::parameters::loop_periods(*loop_periods, np))
                                         : m_solver->solve(s, halfedge_x, np);
    out.solve_seconds = seconds_since(start);
    start = Clock::now();
    m_solver->compute_field(halfedge_x, face_field, np);
    out.field_seconds = seconds_since(start);
    start = Clock::now();

    if(n > 1 && all_directions) { // the n directions: the field turned by 2 pi j / n about the face's normal
      std::vector<double> cosine(static_cast<std::size_t>(n)), sine(static_cast<std::size_t>(n));
      for(int j = 0; j < n; ++j) { // once, not per face (the trigonometry was most of this loop's time)
        const double t = 2 * CGAL_PI * j / n;
        cosine[std::size_t(j)] = std::cos(t);
        sine[std::size_t(j)] = std::sin(t);
      }
      out.directions.resize(3 * std::size_t(n) * m_mesh.number_of_faces());
      double* d = out.directions.data();
      for(auto f : m_mesh.faces()) {
        const auto h = m_mesh.halfedge(f);
        const auto& a = m_mesh.point(m_mesh.source(h));
        const auto& b = m_mesh.point(m_mesh.target(h));
        const auto& c = m_mesh.point(m_mesh.target(m_mesh.next(h)));
        Kernel::Vector_3 normal = CGAL::cross_product(b - a, c - a);
        normal = normal / std::sqrt(CGAL::to_double(normal.squared_length()));
        const Kernel::Vector_3 u = get(face_field, f);
        const Kernel::Vector_3 w = CGAL::cross_product(normal, u);
        for(std::size_t j = 0; j < std::size_t(n); ++j, d += 3) { // cos(t) u + sin(t) w, as before, in place
          d[0] = cosine[j] * CGAL::to_double(u.x()) + sine[j] * CGAL::to_double(w.x());
          d[1] = cosine[j] * CGAL::to_double(u.y()) + sine[j] * CGAL::to_double(w.y());
          d[2] = cosine[j] * CGAL::to_double(u.z()) + sine[j] * CGAL::to_double(w.z());
        }
      }
    }
    out.output_seconds = seconds_since(start);
    return out;
  }

  std::size_t number_of_loops() const override { return m_solver->loops().size(); }

  TC::Placement_report place(int n, bool align_boundary, const std::vector<Kernel::Vector_3>* guide, double strength,
                             const Singularities& fixed, const Loop_periods* periods,
                             const std::vector<Kernel::Vector_3>* directions, Singularities& placed,
                             const TC::Progress_callback& progress) const override
  {
    namespace P = TC::parameters;
    const auto kept = descriptors(fixed);
    std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> out;
    const Loop_periods none(m_solver->loops().size()); // every integer chosen, as without the parameter
    const auto np = P::progress(
      progress, P::symmetry_order(n, P::align_with_boundary(align_boundary, P::fixed_singularities(
                                                              kept, P::loop_periods(periods ? *periods : none)))));
    TC::Placement_report report;
    auto place_with = [&](const auto& with) {
      if(guide != nullptr) {
        auto guide_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
          [guide](face_descriptor f) { return (*guide)[std::size_t(f)]; });
        return TC::place_singularities(*m_solver, std::back_inserter(out),
                                       P::alignment_guide(guide_map, P::alignment_strength(strength, with)));
      }
      return TC::place_singularities(*m_solver, std::back_inserter(out), with);
    };
    // the constrained faces' directions, held in the smooth field (without them, a solver with constrained faces
    // refuses as solve() does)
    if(directions != nullptr) {
      auto target_map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
        [directions](face_descriptor f) { return (*directions)[std::size_t(f)]; });
      report = place_with(P::face_directions(target_map, np));
    } else
      report = place_with(np);
    for(const auto& [v, k] : out)
      placed.emplace_back(std::size_t(v), k);
    return report;
  }

  std::vector<Kernel::Vector_3> curvature_guide(std::vector<std::pair<double, double>>& curvatures) const override
  {
    std::vector<Kernel::Vector_3> guide(m_mesh.number_of_faces(), CGAL::NULL_VECTOR);
    auto map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3&>(
      [&guide](face_descriptor f) -> Kernel::Vector_3& { return guide[std::size_t(f)]; });
    TC::principal_curvature_guide(*m_solver, map, &curvatures);
    return guide;
  }

  std::vector<std::size_t> spread(const std::vector<Kernel::Vector_3>& guide, std::size_t count) const override
  {
    auto map = boost::make_function_property_map<face_descriptor, Kernel::Vector_3>(
      [&guide](face_descriptor f) { return guide[std::size_t(f)]; });
    std::vector<std::size_t> faces;
    for(face_descriptor f : TC::spread_guided_faces(*m_solver, map, count))
      faces.push_back(std::size_t(f));
    return faces;
  }

  TC::Refinement_report<vertex_descriptor> refine(const Singularities& start, int n,
                                                  const std::vector<Kernel::Vector_3>* directions,
                                                  const Loop_periods* periods, const std::vector<std::size_t>& fixed,
                                                  bool cancel_pairs, std::size_t trials,
                                                  const TC::Progress_callback& progress) override
  {
    namespace P = TC::parameters;
    std::vector<double> x(m_mesh.number_of_halfedges(), 0.);
    auto halfedge_x = boost::make_function_property_map<halfedge_descriptor, double&>(
      [&x](halfedge_descriptor h) -> double& { return x[std::size_t(h)]; });
    // directions_of() gives one per face
    const auto target_map = face_direction_map(directions);
    std::vector<vertex_descriptor> fixed_vertices;
    for(std::size_t v : fixed)
      fixed_vertices.push_back(vertex_of(m_mesh, v));
    const Loop_periods none(m_solver->loops().size()); // every integer chosen, as without the parameter
    return TC::refine_singularities(
      *m_solver, descriptors(start), halfedge_x,
      P::symmetry_order(n, P::face_directions(target_map, P::loop_periods(periods ? *periods : none,
        P::fixed_vertices(fixed_vertices, P::cancel_pairs(cancel_pairs, P::maximum_trials(trials, P::progress(progress))))))));
  }

  std::vector<std::tuple<bool, std::size_t, std::vector<halfedge_descriptor>>> loops() const override
  {
    std::vector<std::tuple<bool, std::size_t, std::vector<halfedge_descriptor>>> out;
    for(const auto& l : m_solver->loops())
      out.emplace_back(l.kind == TC::Loop_kind::boundary, l.component, l.halfedges);
    return out;
  }

  std::vector<double> weights() const override
  {
    std::vector<double> w;
    for(auto e : m_mesh.edges())
      if(!m_mesh.is_border(e))
        w.push_back(m_solver->weight(e));
    return w;
  }

  TC::Constraint_update set_constraints(const std::vector<face_descriptor>& constrained,
                                        const std::vector<face_descriptor>& guided,
                                        const std::vector<Kernel::Vector_3>& known, int known_n) override
  {
    const auto known_map = face_direction_map(known.empty() ? nullptr : &known);
    return m_solver->set_constraints(TC::parameters::constrained_faces(
      constrained, TC::parameters::guided_faces(
                     guided, TC::parameters::face_directions(known_map, TC::parameters::symmetry_order(known_n)))));
  }

  const char* backend() const override { return m_name; }

  std::vector<TC::Component_report> components() const override { return m_solver->components(); }
  std::vector<std::size_t> face_components() const override
  {
    std::vector<std::size_t> c;
    c.reserve(m_mesh.number_of_faces());
    for(auto f : m_mesh.faces())
      c.push_back(m_solver->component(f));
    return c;
  }

  const std::vector<std::int64_t>& edge_vertices() const override { return m_edge_vertices; }

private:
  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> descriptors(const Singularities& s) const
  {
    return vertex_descriptors(m_mesh, s);
  }

  const Mesh& m_mesh;
  const char* m_name;
  std::unique_ptr<Solver> m_solver; // not movable: made in place
  std::vector<std::int64_t> m_edge_slot; // per edge, its entry in Result.connection (-1: border)
  std::int64_t m_interior_edges = 0;
  std::vector<std::int64_t> m_edge_vertices; // per interior edge in that order, its vertices (smaller first)
};

}  // namespace

namespace {

// ---- sharp features (feature_alignment.h) ----------------------------------------------------------------

// What feature_aligned_faces() found on a mesh: the faces beside the feature curves, in increasing face number,
// and the direction of the curve on each
struct Feature_pins
{
  TC::Feature_alignment_report report;
  std::vector<std::size_t> faces;
  std::vector<double> directions; // 3 per face of `faces`
};

Feature_pins feature_pins_of(const Mesh& mesh, double threshold, int n, int smoothing)
{
  Feature_pins out;
  std::vector<double> xyz(3 * mesh.number_of_faces(), 0.);
  std::vector<face_descriptor> faces;
  out.report = TC::feature_aligned_faces(mesh, threshold, std::back_inserter(faces), Face_vector_map{xyz.data()},
                                         TC::parameters::symmetry_order(n, TC::parameters::feature_smoothing(smoothing)));
  out.faces.reserve(faces.size());
  out.directions.reserve(3 * faces.size());
  for(face_descriptor f : faces) {
    out.faces.push_back(std::size_t(f));
    out.directions.insert(out.directions.end(), xyz.begin() + 3 * std::ptrdiff_t(f), xyz.begin() + 3 * std::ptrdiff_t(f) + 3);
  }
  return out;
}

py::dict feature_report_dict(const TC::Feature_alignment_report& r)
{
  py::dict d;
  d["threshold_degrees"] = r.threshold_degrees;
  d["number_of_sharp_edges"] = r.number_of_sharp_edges;
  d["number_of_curves"] = r.number_of_curves;
  d["dropped_curves"] = r.dropped_curves;
  d["dropped_edges"] = r.dropped_edges;
  d["number_of_pinned_faces"] = r.number_of_pinned_faces;
  d["faces_with_several_edges"] = r.faces_with_several_edges;
  d["neighbouring_pairs"] = r.neighbouring_pairs;
  d["disagreeing_pairs"] = r.disagreeing_pairs;
  d["max_disagreement_degrees"] = r.max_disagreement_degrees;
  return d;
}

// Solver(align_features=...): off (None, False), the default threshold (True) or a threshold in degrees
struct Feature_options
{
  bool on = false;
  double threshold = TC::default_feature_angle_degrees;
  int n = 4;
  int smoothing = TC::default_feature_smoothing;
};

Feature_options feature_options_of(const py::object& align, int n, int smoothing)
{
  Feature_options o;
  o.n = n;
  o.smoothing = smoothing;
  if(align.is_none())
    return o;
  if(py::isinstance<py::bool_>(align)) {
    o.on = align.cast<bool>();
    return o;
  }
  if(!PyFloat_Check(align.ptr()) && !PyIndex_Check(align.ptr()) &&
     !(py::hasattr(align, "__float__") && !py::isinstance<py::str>(align)))
    throw py::type_error("align_features must be True, False, None or a threshold in degrees, got " +
                         std::string(py::repr(align)));
  o.on = true;
  o.threshold = align.cast<double>();
  // checked here, before the solver is built (the library's message and code: invalid_argument)
  TC::internal::features::check_threshold(o.threshold);
  return o;
}

// ---- the Python classes ---------------------------------------------------------------------------------

struct Result
{
  py::object connection, edges, field, directions, energy, guidance_energy, max_residual, max_loop_residual,
    loop_periods, boundary_indices, integers_proven_optimal, energy_lower_bound, rounding_energy, constraints,
    guidance, n, timings;
};

std::vector<face_descriptor> faces_of(const py::handle& list, std::size_t number_of_faces, const char* what)
{
  std::vector<face_descriptor> faces;
  if(list.is_none())
    return faces;
  for(const py::handle f : py::iter(list)) {
    if(py::isinstance<py::bool_>(f) || !PyIndex_Check(f.ptr()))
      throw py::type_error(std::string(what) + " must be face numbers (integers), got " + std::string(py::repr(f)));
    const std::int64_t i = int64_of(f, TC::Error_code::invalid_constraint, std::string(what) + ": face");
    if(i < 0 || std::size_t(i) >= number_of_faces)
      throw TC::Invalid_input(TC::Error_code::invalid_constraint,
                              std::string(what) + ": face " + std::to_string(i) + " does not exist (the mesh has " +
                                std::to_string(number_of_faces) + " faces)",
                              i < 0 ? TC::Invalid_input::no_location : std::size_t(i));
    faces.push_back(face_descriptor(Mesh::size_type(i)));
  }
  return faces;
}

void check_backend(const std::string& backend)
{
  if(backend != "auto" && backend != "ldlt" && backend != "cholmod")
    throw py::value_error("backend must be \"auto\", \"ldlt\" or \"cholmod\", got \"" + backend + "\"");
#ifndef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  if(backend == "cholmod")
    throw py::value_error("backend \"cholmod\": this build of the module has no CHOLMOD (libsuitesparse-dev)");
#endif
}

// The solver of `source` (as for Solver_of) with the backend named (checked by check_backend())
std::unique_ptr<Solver_interface> make_solver(Mesh_of_arrays& source, const Options& o, const std::string& backend)
{
  if(backend == "ldlt")
    return std::make_unique<Solver_of<TC::Default_solver_traits>>(source, o, "ldlt");
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
  if(backend == "cholmod")
    return std::make_unique<Solver_of<TC::Cholmod_solver_traits>>(source, o, "cholmod");
  return std::make_unique<Solver_of<TC::Automatic_solver_traits>>(source, o, "auto");
#else
  return std::make_unique<Solver_of<TC::Default_solver_traits>>(source, o, "auto");
#endif
}

class Python_solver
{
public:
  // `mesh` keeps its mesh until the solver is built and the mesh complete: on an error before, its destructor waits
  // for the mesh's construction before freeing it
  Python_solver(Mesh_of_arrays mesh, const std::string& weights, const std::string& backend,
                const py::object& constrained, const py::object& guided, double guidance_weight, bool align_boundary,
                const Feature_options& features, const TC::Progress_callback& progress)
  {
    Options o;
    if(weights == "unit")
      o.weighting = TC::Weighting::unit;
    else if(weights != "hodge")
      throw py::value_error("weights must be \"hodge\" or \"unit\", got \"" + weights + "\"");
    o.constrained = faces_of(constrained, mesh.number_of_faces, "constrained_faces");
    o.guided = faces_of(guided, mesh.number_of_faces, "guided_faces");
    m_user_pins = o.constrained.size() + o.guided.size();
    o.progress = progress;
    o.guidance_weight = guidance_weight;
    o.align_boundary = align_boundary;
    check_backend(backend);
    m_align_boundary = align_boundary;
    py::gil_scoped_release unlocked;
    const auto start = std::chrono::steady_clock::now();
    if(features.on) { // the feature pins need the whole mesh (from arrays, it is still being built)
      mesh.wait_for_mesh();
      m_features.emplace();
      m_align_features = true;
      m_features->all = feature_pins_of(*mesh.mesh, features.threshold, features.n, features.smoothing);
      o.constrained = merge_feature_pins(*mesh.mesh, o.constrained, o.guided, *m_features);
      m_feature_n = features.n;
      known_feature_directions(*mesh.mesh, *m_features, features.n, o);
    }
    m_solver = make_solver(mesh, o, backend); // the mesh complete when it returns
    m_solver_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m_mesh = std::move(mesh.mesh);
  }

  Result solve(const py::object& singularities, const py::object& n_in, const py::object& directions,
               const py::object& loop_periods, bool all_directions, const py::object& progress)
  {
    const int n = symmetry_order_of(n_in, "n");
    const auto s = singularities_of(singularities);
    check_directions_are_read(directions, "solve()");
    const Optional_inputs in = optional_inputs(directions, loop_periods);
    if(all_directions && n > 1)
      check_directions_fit(n);
    Progress_context context("solve()", progress);
    Solve_output out = reading([&] {
      const auto targets = with_feature_targets(in.directions);
      return m_solver->solve(s, n, targets ? &*targets : nullptr, in.periods_or_null(), all_directions,
                             context.callback());
    });
    m_last_n = n;
    return result_of(std::move(out), n);
  }

  py::dict set_constraints(const py::object& constrained, const py::object& guided)
  {
    auto c = faces_of(constrained, m_mesh->number_of_faces(), "constrained_faces");
    const auto g = faces_of(guided, m_mesh->number_of_faces(), "guided_faces");
    const std::size_t user_pins = c.size() + g.size();
    TC::Constraint_update u;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock<std::shared_mutex> writing(m_mutex);
      if(m_features) { // merged again with the new faces; kept as they were when the solver refuses them
        Features merged = *m_features;
        c = merge_feature_pins(*m_mesh, c, g, merged);
        Options known;
        known_feature_directions(*m_mesh, merged, m_feature_n, known);
        u = m_solver->set_constraints(c, g, known.known_directions, known.known_n);
        m_features = std::move(merged);
      } else
        u = m_solver->set_constraints(c, g, {}, 1);
      m_user_pins = user_pins; // after the solver took them (it may refuse them)
    }
    py::dict d;
    d["refactored"] = u.refactored;
    d["links"] = u.links;
    d["links_outside_the_factor"] = u.links_outside_the_factor;
    d["new_forward_substitutions"] = u.new_forward_substitutions;
    return d;
  }

  py::tuple place_singularities(const py::object& n_in, bool align_boundary, const py::object& alignment_guide,
                                double strength, const py::object& fixed, const py::object& loop_periods,
                                const py::object& directions, const py::object& progress)
  {
    const int n = symmetry_order_of(n_in, "n");
    check_directions_are_read(directions, "place_singularities()");
    const Singularities kept = singularities_of(fixed);
    const Optional_inputs in = optional_inputs(alignment_guide, loop_periods);
    const Optional_inputs targets = optional_inputs(directions, py::none());
    Singularities placed;
    Progress_context context("place_singularities()", progress);
    const TC::Placement_report report = reading([&] {
      const auto pinned = with_feature_targets(targets.directions);
      return m_solver->place(n, align_boundary, in.directions_or_null(), strength, kept, in.periods_or_null(),
                             pinned ? &*pinned : nullptr, placed, context.callback());
    });
    py::dict d;
    d["n"] = report.symmetry_order;
    d["aligned"] = report.aligned;
    d["field_energy"] = report.field_energy;
    d["rayleigh_quotients"] = report.rayleigh_quotients;
    d["iterations"] = report.iterations;
    d["max_rounding"] = report.max_rounding;
    py::dict per_index;
    for(const auto& [k, count] : report.singularities_per_index)
      per_index[fraction(k)] = count;
    d["singularities_per_index"] = per_index;
    d["fixed"] = report.fixed;
    d["units_removed"] = report.units_removed;
    d["units_added"] = report.units_added;
    d["pinned"] = report.pinned;
    return py::make_tuple(singularity_dict(placed), d);
  }

  py::tuple principal_curvature_guide() const
  {
    std::vector<std::pair<double, double>> c;
    std::vector<Kernel::Vector_3> guide;
    {
      py::gil_scoped_release unlocked;
      guide = m_solver->curvature_guide(c);
    }
    std::vector<double> g, k;
    for(const auto& v : guide)
      for(int i = 0; i < 3; ++i)
        g.push_back(CGAL::to_double(v[i]));
    for(const auto& [a, b] : c) {
      k.push_back(a);
      k.push_back(b);
    }
    const py::ssize_t nf = py::ssize_t(guide.size());
    return py::make_tuple(owning_array(std::move(g), {nf, 3}), owning_array(std::move(k), {nf, 2}));
  }

  std::vector<std::size_t> spread_guided_faces(const py::object& guide, std::size_t count) const
  {
    const std::vector<Kernel::Vector_3> g = directions_of(guide);
    py::gil_scoped_release unlocked;
    return m_solver->spread(g, count);
  }

  py::tuple refine_singularities(const py::object& start, const py::object& n_in, const py::object& directions,
                                 const py::object& loop_periods, const py::object& fixed_vertices, bool cancel_pairs,
                                 const py::object& maximum_trials_or_none, const py::object& progress)
  {
    const int n = symmetry_order_of(n_in, "n");
    check_directions_are_read(directions, "refine_singularities()");
    // None: no budget, to a local minimum
    const std::size_t maximum_trials = maximum_trials_or_none.is_none()
                                         ? (std::numeric_limits<std::size_t>::max)()
                                         : maximum_trials_or_none.cast<std::size_t>();
    const Singularities s = singularities_of(start);
    const Optional_inputs in = optional_inputs(directions, loop_periods);
    std::vector<std::size_t> fixed;
    if(!fixed_vertices.is_none())
      for(const py::handle v : py::iter(fixed_vertices))
        fixed.push_back(vertex_number(v));
    // it solves again and again on the solver: as a solve, beside other solves
    Progress_context context("refine_singularities()", progress);
    const TC::Refinement_report<vertex_descriptor> r = reading([&] {
      const auto targets = with_feature_targets(in.directions);
      return m_solver->refine(s, n, targets ? &*targets : nullptr, in.periods_or_null(), fixed, cancel_pairs,
                              maximum_trials, context.callback());
    });
    Singularities refined;
    for(const auto& [v, k] : r.singularities)
      refined.emplace_back(std::size_t(v), k);
    py::list moves;
    for(const auto& m : r.moves) {
      py::dict d;
      d["from"] = std::size_t(m.from);
      d["to"] = std::size_t(m.to);
      d["index"] = fraction(m.index);
      d["energy"] = m.energy;
      moves.append(d);
    }
    py::dict d;
    d["energy_before"] = r.energy_before;
    d["energy_after"] = r.energy_after;
    d["moves"] = moves;
    d["trials"] = r.trials;
    d["rounds"] = r.rounds;
    d["cancellations"] = r.cancellations;
    d["singularities_before"] = r.singularities_before;
    d["local_minimum"] = r.local_minimum;
    d["stop"] = r.stop == TC::Refinement_stop::local_minimum    ? "local_minimum"
                : r.stop == TC::Refinement_stop::maximum_trials ? "maximum_trials"
                                                                : "rejected_moves";
    return py::make_tuple(singularity_dict(refined), d);
  }

  // the polylines of the field of `result`, from the barycentres of `seed_faces` (default: every face)
  py::list trace_streamlines(const Result& result, const py::object& singularities, const py::object& seed_faces,
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

  // the field of `result` as a field file (.txt), or the mesh with it and the singularities as a VTK (.vtk) or PLY
  // (.ply) file, written completely or not at all
  void write_field(const py::object& path_in, const Result& result, const py::object& singularities) const
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

  // the loops of loop_periods: boundary loops and homology generators, each with the halfedges it crosses as
  // (source, target) vertex pairs, crossed from the face on their left to the other one
  py::list loops() const
  {
    py::list out;
    for(const auto& [boundary, component, halfedges] : m_solver->loops()) {
      std::vector<std::int64_t> pairs;
      for(halfedge_descriptor h : halfedges) {
        pairs.push_back(std::int64_t(m_mesh->source(h)));
        pairs.push_back(std::int64_t(m_mesh->target(h)));
      }
      py::dict d;
      d["kind"] = boundary ? "boundary" : "generator";
      d["component"] = component;
      d["halfedges"] = owning_array(std::move(pairs), {py::ssize_t(halfedges.size()), 2});
      out.append(d);
    }
    return out;
  }

  // per connected component: its faces, Euler characteristic, genus and boundary loops (as the program prints them)
  py::list topology() const
  {
    const std::vector<TC::Component_report> reports = m_solver->components();
    const std::vector<std::size_t> of_face = m_solver->face_components();
    std::vector<std::vector<std::int64_t>> faces(reports.size());
    for(std::size_t f = 0; f < of_face.size(); ++f)
      faces[of_face[f]].push_back(std::int64_t(f));
    py::list out;
    for(std::size_t c = 0; c < reports.size(); ++c) {
      py::dict d;
      d["number_of_faces"] = reports[c].number_of_faces;
      d["euler_characteristic"] = reports[c].euler_characteristic;
      d["genus"] = reports[c].genus;
      d["number_of_boundary_loops"] = reports[c].number_of_boundary_loops;
      d["closed"] = reports[c].number_of_boundary_loops == 0;
      const py::ssize_t k = py::ssize_t(faces[c].size());
      d["faces"] = owning_array(std::move(faces[c]), {k});
      out.append(d);
    }
    return out;
  }

  std::string repr() const
  {
    const std::vector<TC::Component_report> reports = m_solver->components();
    std::string chi;
    for(std::size_t c = 0; c < reports.size() && c < 4; ++c)
      chi += (c ? ", " : "") + std::to_string(reports[c].euler_characteristic);
    if(reports.size() > 4)
      chi += ", ...";
    const auto plural = [](std::size_t k, const char* word) {
      return std::to_string(k) + " " + word + (k == 1 ? "" : "s");
    };
    std::string out = "<trivial_connections.Solver: " + std::to_string(m_mesh->number_of_vertices()) +
          (m_mesh->number_of_vertices() == 1 ? " vertex, " : " vertices, ") + plural(m_mesh->number_of_faces(), "face") +
          ", " + plural(reports.size(), "component") + " (chi " + chi + "), " +
          plural(m_solver->number_of_loops(), "loop") + ", backend \"" + m_solver->backend() + "\"";
    if(m_user_pins > 0)
      out += ", " + std::to_string(m_user_pins.load()) + " constrained or guided faces";
    const std::optional<std::size_t> feature_pins =
      reading([&] { return m_features ? std::optional<std::size_t>(m_features->pinned.size()) : std::nullopt; });
    if(feature_pins)
      out += ", " + std::to_string(*feature_pins) + " feature pins";
    const int last = m_last_n;
    if(last > 0)
      out += ", last solve n=" + std::to_string(last);
    return out + ">";
  }

  std::size_t number_of_vertices() const { return m_mesh->number_of_vertices(); }
  std::size_t number_of_faces() const { return m_mesh->number_of_faces(); }
  std::size_t number_of_loops() const { return m_solver->number_of_loops(); }
  std::string backend() const { return m_solver->backend(); }
  py::array_t<double> vertices() const
  {
    std::vector<double> p;
    p.reserve(3 * m_mesh->number_of_vertices());
    for(auto v : m_mesh->vertices())
      for(int i = 0; i < 3; ++i)
        p.push_back(CGAL::to_double(m_mesh->point(v)[i]));
    return owning_array(std::move(p), {py::ssize_t(m_mesh->number_of_vertices()), 3});
  }
  py::array_t<std::int64_t> faces() const
  {
    std::vector<std::int64_t> t = corners_in_input_order(*m_mesh);
    return owning_array(std::move(t), {py::ssize_t(m_mesh->number_of_faces()), 3});
  }
  py::array_t<double> weights() const
  {
    std::vector<double> w = m_solver->weights();
    const py::ssize_t ne = py::ssize_t(w.size());
    return owning_array(std::move(w), {ne});
  }
  // one read-only array for the solver and all its results
  py::object edges() const
  {
    if(!m_edges_array) {
      std::vector<std::int64_t> copy = m_solver->edge_vertices();
      const py::ssize_t ne = py::ssize_t(copy.size() / 2);
      py::array_t<std::int64_t> a = owning_array(std::move(copy), {ne, 2});
      a.attr("setflags")(py::arg("write") = false);
      m_edges_array = a;
    }
    return m_edges_array;
  }

  // Solver.feature_pins: (faces, directions) of the feature pins the solver holds, or None
  py::object feature_pins() const
  {
    std::vector<std::int64_t> faces;
    std::vector<double> xyz;
    const bool on = reading([&] {
      if(!m_features)
        return false;
      for(std::size_t i : m_features->pinned) {
        faces.push_back(std::int64_t(m_features->all.faces[i]));
        xyz.insert(xyz.end(), m_features->all.directions.begin() + 3 * std::ptrdiff_t(i),
                   m_features->all.directions.begin() + 3 * std::ptrdiff_t(i) + 3);
      }
      return true;
    });
    if(!on)
      return py::none();
    const py::ssize_t k = py::ssize_t(faces.size());
    return py::make_tuple(owning_array(std::move(faces), {k}), owning_array(std::move(xyz), {k, 3}));
  }

  // Solver.feature_alignment: the report of feature_aligned_faces() and what the merge did, or None
  py::object feature_alignment() const
  {
    std::optional<Features> f = reading([&] { return m_features; });
    if(!f)
      return py::none();
    py::dict d = feature_report_dict(f->all.report);
    d["pinned"] = f->pinned.size();
    d["named_by_user"] = f->named_by_user;
    d["on_guided_faces"] = f->on_guided_faces;
    d["on_aligned_boundary"] = f->on_aligned_boundary;
    return d;
  }

private:
  // The feature pins of Solver(align_features=...): all the faces beside the feature curves, and which of them the
  // solver holds (the others are named by the user's constrained or guided faces, or on an aligned boundary)
  struct Features
  {
    Feature_pins all;
    std::vector<std::size_t> pinned; // entries of all.faces given to the solver
    std::size_t named_by_user = 0, on_guided_faces = 0, on_aligned_boundary = 0;
  };

  // The constrained faces of the solver: the user's `constrained`, then the feature pins on the faces that are
  // neither constrained nor guided by the user (the user wins, as the program's --constraints), and, with
  // align_boundary, not on the boundary (the solver refuses targets there; the field follows the boundary).
  // `features.pinned` and its counts are set.
  std::vector<face_descriptor> merge_feature_pins(const Mesh& mesh, const std::vector<face_descriptor>& constrained,
                                                  const std::vector<face_descriptor>& guided, Features& features) const
  {
    std::vector<char> taken(mesh.number_of_faces(), 0);
    for(face_descriptor f : constrained)
      taken[std::size_t(f)] = 1;
    for(face_descriptor f : guided)
      taken[std::size_t(f)] = 2;
    features.pinned.clear();
    features.named_by_user = features.on_guided_faces = features.on_aligned_boundary = 0;
    std::vector<face_descriptor> out = constrained;
    for(std::size_t i = 0; i < features.all.faces.size(); ++i) {
      const face_descriptor f(Mesh::size_type(features.all.faces[i]));
      if(taken[std::size_t(f)]) {
        ++(taken[std::size_t(f)] == 1 ? features.named_by_user : features.on_guided_faces);
        continue;
      }
      bool on_boundary = false;
      for(auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh))
        on_boundary = on_boundary || mesh.is_border(mesh.opposite(h));
      if(m_align_boundary && on_boundary) {
        ++features.on_aligned_boundary;
        continue;
      }
      features.pinned.push_back(i);
      out.push_back(f);
    }
    return out;
  }

  // The feature pins' directions (zero elsewhere: the user's come with each solve) and their n, for the solver's
  // constructor: touching feature pins that disagree are then left to the lattice, as in the program
  static void known_feature_directions(const Mesh& mesh, const Features& features, int n, Options& o)
  {
    o.known_directions.assign(mesh.number_of_faces(), CGAL::NULL_VECTOR);
    const std::vector<double>& d = features.all.directions;
    for(std::size_t i : features.pinned)
      o.known_directions[features.all.faces[i]] = Kernel::Vector_3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
    o.known_n = n;
  }

  // The targets of a call (the user's directions, or none) with the feature pins' directions on their faces
  // (those faces are not the user's: their rows are not read otherwise). Under the solver's lock.
  std::optional<std::vector<Kernel::Vector_3>> with_feature_targets(
    const std::optional<std::vector<Kernel::Vector_3>>& user) const
  {
    std::optional<std::vector<Kernel::Vector_3>> out = user;
    if(!m_features || m_features->pinned.empty())
      return out;
    if(!out)
      out.emplace(m_mesh->number_of_faces(), CGAL::NULL_VECTOR);
    const std::vector<double>& d = m_features->all.directions;
    for(std::size_t i : m_features->pinned)
      (*out)[m_features->all.faces[i]] = Kernel::Vector_3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
    return out;
  }

  // directions= of a call is read only for the user's constrained and guided faces: given (not None, not empty)
  // to a solver without any, it would be ignored; a ValueError says so rather than a field that ignores it
  void check_directions_are_read(const py::object& directions, const char* call) const
  {
    if(directions.is_none() || m_user_pins > 0)
      return;
    if(py::isinstance<py::dict>(directions) && py::len(directions) == 0)
      return;
    throw py::value_error(std::string(call) + ": directions= is given but this solver has no constrained or guided "
                          "face, so it would be ignored: give the faces it is for as constrained_faces= or "
                          "guided_faces= (to Solver() or set_constraints()), or leave directions=None" +
                          (m_align_features ? std::string(" (the feature pins of align_features take their directions "
                                                    "themselves)")
                                      : std::string()));
  }

  // Result.directions holds 3 n numbers per face: refused, before the solve, when it could not fit in the
  // machine's memory (n = 10^6 on a mesh of 10^4 faces would be 240 GB), with the way out
  void check_directions_fit(int n) const
  {
    const double bytes = 3. * double(n) * double(m_mesh->number_of_faces()) * sizeof(double);
    double memory = std::numeric_limits<double>::infinity(); // MemAvailable, else the physical memory
#ifdef __linux__
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if(pages > 0 && page > 0)
      memory = double(pages) * double(page);
    if(std::FILE* meminfo = std::fopen("/proc/meminfo", "r")) {
      char line[256];
      double kb = 0;
      while(std::fgets(line, sizeof line, meminfo))
        if(std::sscanf(line, "MemAvailable: %lf kB", &kb) == 1) {
          memory = kb * 1024;
          break;
        }
      std::fclose(meminfo);
    }
#endif
    if(bytes > memory || bytes > double((std::numeric_limits<py::ssize_t>::max)())) {
      const std::string text = "Result.directions for n = " + std::to_string(n) + " on " +
                               std::to_string(m_mesh->number_of_faces()) + " faces would take " +
                               std::to_string(std::llround(bytes / 1e9)) + " GB (3 n numbers per face), more than " +
                               "the memory available: pass all_directions=False (Result.field alone)";
      PyErr_SetString(PyExc_MemoryError, text.c_str());
      throw py::error_already_set();
    }
  }

  // x per halfedge from a Result of this solver (its edges are the mesh's interior edges, in order)
  std::vector<double> halfedge_angles(const Result& result) const
  {
    const auto connection = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result.connection);
    std::vector<double> x(m_mesh->number_of_halfedges(), 0.);
    if(!connection || std::size_t(connection.size()) != m_solver->edge_vertices().size() / 2)
      throw py::value_error("the result is not one of this solver (its number of edges differs)");
    std::size_t i = 0;
    for(auto e : m_mesh->edges()) {
      if(m_mesh->is_border(e))
        continue;
      halfedge_descriptor h = m_mesh->halfedge(e);
      if(std::size_t(m_mesh->source(h)) > std::size_t(m_mesh->target(h)))
        h = m_mesh->opposite(h);
      x[std::size_t(h)] = connection.data()[i];
      x[std::size_t(m_mesh->opposite(h))] = -connection.data()[i];
      ++i;
    }
    return x;
  }
  std::vector<Kernel::Vector_3> field_of(const Result& result) const
  {
    const auto f = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result.field);
    if(!f || f.ndim() != 2 || std::size_t(f.shape(0)) != m_mesh->number_of_faces() || f.shape(1) != 3)
      throw py::value_error("the result is not one of this solver (its number of faces differs)");
    std::vector<Kernel::Vector_3> field(m_mesh->number_of_faces());
    for(std::size_t i = 0; i < field.size(); ++i)
      field[i] = Kernel::Vector_3(f.data()[3 * i], f.data()[3 * i + 1], f.data()[3 * i + 2]);
    return field;
  }

  static py::dict singularity_dict(const Singularities& s)
  {
    py::dict d;
    for(const auto& [v, k] : s)
      d[py::int_(v)] = fraction(k);
    return d;
  }

  // The optional per-face directions and loop periods of a call, read with the GIL
  struct Optional_inputs
  {
    std::optional<std::vector<Kernel::Vector_3>> directions;
    std::optional<Loop_periods> periods;
    const std::vector<Kernel::Vector_3>* directions_or_null() const { return directions ? &*directions : nullptr; }
    const Loop_periods* periods_or_null() const { return periods ? &*periods : nullptr; }
  };

  Optional_inputs optional_inputs(const py::object& directions, const py::object& loop_periods) const
  {
    Optional_inputs in;
    if(!directions.is_none())
      in.directions = directions_of(directions);
    in.periods = periods_of(loop_periods);
    return in;
  }

  // f() without the GIL, beside the solver's other readers (solves, placement), never during set_constraints()
  template <class F>
  auto reading(F&& f) const -> decltype(f())
  {
    py::gil_scoped_release unlocked;
    std::shared_lock<std::shared_mutex> lock(m_mutex);
    return f();
  }

  static std::optional<Loop_periods> periods_of(const py::object& loop_periods)
  {
    if(loop_periods.is_none())
      return std::nullopt;
    Loop_periods periods;
    for(const py::handle p : py::iter(loop_periods)) {
      if(p.is_none())
        periods.emplace_back();
      else if(py::isinstance<py::bool_>(p) || !PyIndex_Check(p.ptr()))
        throw py::type_error("loop_periods must hold integers or None, got " + std::string(py::repr(p)));
      else
        periods.emplace_back(int64_of(p, TC::Error_code::invalid_loop_periods, "the loop period"));
    }
    return periods;
  }

  // one target per face (rows of the faces that are neither constrained nor guided are not read), or a dict
  // {face: vector}
  std::vector<Kernel::Vector_3> directions_of(const py::object& directions) const
  {
    const std::size_t nf = m_mesh->number_of_faces();
    std::vector<Kernel::Vector_3> targets(nf, CGAL::NULL_VECTOR);
    auto vector_of = [](const py::handle& h) {
      const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
      if(!a || a.ndim() != 1 || a.shape(0) != 3)
        throw py::value_error("a direction must be three numbers, got " + std::string(py::repr(h)));
      return Kernel::Vector_3(a.data()[0], a.data()[1], a.data()[2]);
    };
    if(py::isinstance<py::dict>(directions)) {
      py::list keys;
      for(const auto& item : py::reinterpret_borrow<py::dict>(directions))
        keys.append(item.first);
      const std::vector<face_descriptor> faces = faces_of(keys, nf, "directions");
      std::size_t i = 0;
      for(const auto& item : py::reinterpret_borrow<py::dict>(directions))
        targets[std::size_t(faces[i++])] = vector_of(item.second);
      return targets;
    }
    const py::array a = as_array(directions, "directions");
    check_rows_of_three(a, "directions", "fiu", "real numbers");
    if(std::size_t(a.shape(0)) != nf)
      throw py::value_error("directions must have one row per face (" + std::to_string(nf) + "), got " +
                            std::to_string(a.shape(0)));
    const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    for(std::size_t f = 0; f < nf; ++f)
      targets[f] = Kernel::Vector_3(d.data()[3 * f], d.data()[3 * f + 1], d.data()[3 * f + 2]);
    return targets;
  }

  Result result_of(Solve_output&& out, int n) const
  {
    Result r;
    const TC::Solve_report& report = out.report;
    const py::ssize_t ne = py::ssize_t(out.connection.size()), nf = py::ssize_t(m_mesh->number_of_faces());
    r.connection = owning_array(std::move(out.connection), {ne});
    r.edges = edges();
    r.field = owning_array(std::move(out.field), {nf, 3});
    r.directions = n > 1 && !out.directions.empty()
                     ? py::object(owning_array(std::move(out.directions), {nf, py::ssize_t(n), 3}))
                     : py::none();
    r.n = py::int_(n);
    r.energy = py::float_(report.energy);
    r.guidance_energy = py::float_(report.guidance_energy);
    r.max_residual = py::float_(report.max_vertex_residual);
    r.max_loop_residual = py::float_(report.max_loop_residual);
    r.integers_proven_optimal = py::bool_(report.integers_proven_optimal);
    r.energy_lower_bound = py::float_(report.energy_lower_bound);
    r.rounding_energy = py::float_(report.rounding_energy);
    py::list periods;
    py::dict boundary;
    for(std::size_t l = 0; l < report.loops.size(); ++l) {
      periods.append(report.loops[l].period);
      if(report.loops[l].kind == TC::Loop_kind::boundary)
        boundary[py::int_(l)] = fraction(report.loops[l].index);
    }
    r.loop_periods = periods;
    r.boundary_indices = boundary;
    py::list constraints;
    for(const auto& c : report.constraints) {
      py::dict d;
      d["component"] = c.component;
      d["from_face"] = c.from_face;
      d["to_face"] = c.to_face;
      d["length"] = c.length;
      d["period"] = c.period;
      d["residual"] = c.residual;
      d["decided"] = c.decided;
      constraints.append(d);
    }
    r.constraints = constraints;
    py::list guidance;
    for(const auto& g : report.guidance) {
      py::dict d;
      d["face"] = g.face;
      d["mismatch"] = g.mismatch;
      guidance.append(d);
    }
    r.guidance = guidance;
    py::dict timings;
    timings["solve"] = out.solve_seconds;
    timings["field"] = out.field_seconds;
    timings["outputs"] = out.output_seconds;
    r.timings = timings;
    return r;
  }

public:
  double m_mesh_seconds = 0, m_solver_seconds = 0; // reading the arrays or the file into the mesh; the C++ solver

private:
  std::unique_ptr<Mesh> m_mesh; // before the solver, which refers to it
  std::unique_ptr<Solver_interface> m_solver;
  bool m_align_boundary = false;
  bool m_align_features = false;       // Solver(align_features=...) on (m_features is engaged for good)
  std::atomic<std::size_t> m_user_pins{0}; // the user's constrained and guided faces (not the feature pins)
  std::atomic<int> m_last_n{0};        // n of the last solve (0: none yet), for repr()
  std::optional<Features> m_features; // Solver(align_features=...); changed by set_constraints() under m_mutex
  int m_feature_n = 4;                 // the n of the feature pins (feature_n)
  mutable py::object m_edges_array; // made on first use, with the GIL
  mutable std::shared_mutex m_mutex;
};

std::unique_ptr<Mesh> mesh_of_file(const std::string& path, bool triangulate)
{
  auto mesh = std::make_unique<Mesh>();
  py::gil_scoped_release unlocked;
  TC::read_triangle_mesh(path, *mesh, TC::parameters::triangulate(triangulate));
  return mesh;
}

}  // namespace

#ifndef TC_VERSION
#error "TC_VERSION (the project's version) must be defined by the build (CMakeLists.txt, setup.py)"
#endif

PYBIND11_MODULE(trivial_connections, m)
{
  // numpy at import, not at the first call that needs it
  try {
    py::module_::import("numpy");
  } catch(py::error_already_set& e) {
    if(!e.matches(PyExc_ImportError))
      throw;
    throw py::import_error("trivial_connections needs numpy, which this python3 (" +
                           std::string(py::str(py::module_::import("sys").attr("executable"))) +
                           ") cannot import: install it (Debian: apt install python3-numpy; in a virtual "
                           "environment made with --system-site-packages, or pip install numpy). The error: " +
                           std::string(e.what()));
  }
  m.attr("__version__") = TC_VERSION;
  m.attr("MAX_SYMMETRY_ORDER") = max_symmetry_order;
  m.doc() = R"(Trivial connections on triangle meshes (CGAL Trivial Connections).

Direction fields with exactly the singularities you prescribe, closest to Levi-Civita transport
(Crane, Desbrun, Schroeder, "Trivial Connections on Discrete Surfaces", SGP 2010).

    import trivial_connections as tc
    V, F = tc.read_mesh("sphere.off")             # V: (n, 3) float64, F: (m, 3) int64 (or any numpy arrays)
    solver = tc.Solver(V, F)                      # factored once
    solver.topology                               # per component: faces, euler_characteristic, genus, ...
    result = solver.solve({0: 1, 17: 1})          # on each closed component the indices sum to its
    result.connection, result.edges, result.field # euler_characteristic (2 here: a sphere)

Errors in the data raise trivial_connections.InvalidInput (a ValueError) with .code and .where; a bad n, a
directions= that would be ignored, a bad type are ValueError / TypeError. Paths may be str, bytes or os.PathLike.
Long calls take progress=callable(phase, fraction), log their phases to the logger "trivial_connections" and
honour Ctrl-C (KeyboardInterrupt) between phases. Type stubs: trivial_connections.pyi beside the module.)";

  static py::exception<TC::Invalid_input> invalid_input(m, "InvalidInput", PyExc_ValueError);
  invalid_input.doc() = "Bad input data: .code names the error (e.g. \"poincare_hopf_violated\"), .where is the "
                        "vertex, face or loop concerned (or None); str() is the library's one-line message.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if(p)
        std::rethrow_exception(p);
    } catch(const TC::Invalid_input& e) {
      // an instance, with the two attributes the class documents
      py::object error = py::reinterpret_borrow<py::object>(invalid_input.ptr())(e.what());
      error.attr("code") = TC::error_code_name(e.code());
      error.attr("where") = e.where() == TC::Invalid_input::no_location ? py::object(py::none())
                                                                          : py::object(py::int_(e.where()));
      PyErr_SetObject(invalid_input.ptr(), error.ptr());
    }
  });

  m.def(
    "_reference_build",
    [](const py::object& V, const py::object& F, const std::string& backend) {
      check_backend(backend);
      const auto [points, faces] = checked_arrays(V, F);
      // the arrays a C++ program holds (not timed)
      std::vector<Kernel::Point_3> p;
      for(py::ssize_t i = 0; i < points.shape(0); ++i)
        p.emplace_back(points.at(i, 0), points.at(i, 1), points.at(i, 2));
      std::vector<std::array<std::size_t, 3>> t;
      for(py::ssize_t i = 0; i < faces.shape(0); ++i)
        t.push_back({std::size_t(faces.at(i, 0)), std::size_t(faces.at(i, 1)), std::size_t(faces.at(i, 2))});
      double to_mesh = 0, solver = 0;
      {
        py::gil_scoped_release unlocked;
        const auto t0 = std::chrono::steady_clock::now();
        Mesh_of_arrays mesh;
        mesh.mesh = std::make_unique<Mesh>();
        TC::triangle_soup_to_mesh(p, t, *mesh.mesh);
        const auto t1 = std::chrono::steady_clock::now();
        std::unique_ptr<Solver_interface> s = make_solver(mesh, Options(), backend);
        const auto t2 = std::chrono::steady_clock::now();
        to_mesh = std::chrono::duration<double>(t1 - t0).count();
        solver = std::chrono::duration<double>(t2 - t1).count();
      }
      py::dict d;
      d["soup_to_mesh"] = to_mesh;
      d["solver"] = solver;
      return d;
    },
    py::arg("V"), py::arg("F"), py::arg("backend") = "auto",
    R"(The benchmark's reference (benchmark/python/binding_overhead.py), not part of the API: what a C++ program
holding V and F does, triangle_soup_to_mesh() into a Surface_mesh, then the Trivial_connection_solver
constructor on it, with default options. Returns the seconds of each: {"soup_to_mesh": s, "solver": s}.)");

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

  m.attr("DEFAULT_FEATURE_ANGLE") = TC::default_feature_angle_degrees;
  m.attr("DEFAULT_FEATURE_SMOOTHING") = TC::default_feature_smoothing;
  m.def(
    "feature_aligned_faces",
    [](const py::object& V, const py::object& F, double threshold, const py::object& n_in, int smoothing) {
      const int n = symmetry_order_of(n_in, "n");
      Mesh_of_arrays mesh = mesh_of_arrays(V, F);
      Feature_pins p;
      {
        py::gil_scoped_release unlocked;
        mesh.wait_for_mesh();
        p = feature_pins_of(*mesh.mesh, threshold, n, smoothing);
      }
      std::vector<std::int64_t> faces(p.faces.begin(), p.faces.end());
      const py::ssize_t k = py::ssize_t(faces.size());
      return py::make_tuple(owning_array(std::move(faces), {k}), owning_array(std::move(p.directions), {k, 3}),
                            feature_report_dict(p.report));
    },
    py::arg("V"), py::arg("F"), py::arg("threshold") = TC::default_feature_angle_degrees, py::kw_only(),
    py::arg("n") = 4, py::arg("smoothing") = TC::default_feature_smoothing,
    R"(Pins for a feature-aligned field: the faces beside the mesh's sharp feature curves and the curves' directions.

Returns (faces, directions, report): faces a (k,) int64 array in increasing face number, directions a (k, 3)
float64 array of unit vectors tangent to their faces, report a dict. An interior edge is sharp when the normals of
its two faces make an angle over `threshold` degrees (default DEFAULT_FEATURE_ANGLE, 30); sharp edges are joined
into feature curves through the vertices that are not corners, and isolated short curves are dropped (see
feature_curves()). Every face with an edge on a kept curve is pinned to the curve's direction there: the
least-squares line through the curve's vertices within `smoothing` sharp edges (default
DEFAULT_FEATURE_SMOOTHING, 3; 0: each edge its own direction), so that a jagged crease gives pins that agree.
A face beside several curve edges takes their mean modulo 2 pi / n (for n = 4 perpendicular edges agree).
Give faces as constrained_faces and directions as solve(directions={face: vector}) (or use
Solver(align_features=...), which does it, as the program's --align-features). Faces on the boundary are included:
drop them when the solver aligns with the boundary (it refuses targets there).
report: threshold_degrees, number_of_sharp_edges, number_of_curves, dropped_curves, dropped_edges,
number_of_pinned_faces, faces_with_several_edges, neighbouring_pairs (pinned faces sharing an edge),
disagreeing_pairs (those whose directions, moved across the edge, differ by more than 5 degrees modulo 2 pi / n)
and max_disagreement_degrees. A mesh without sharp edges gives no face and a report of zeros.
Raises InvalidInput (invalid_argument, a ValueError) for a threshold that is negative, over 180 or NaN, n < 1 or
smoothing < 0, and for a mesh the package refuses, as Solver().)");
  m.def(
    "feature_curves",
    [](const py::object& V, const py::object& F, double threshold) {
      Mesh_of_arrays mesh = mesh_of_arrays(V, F);
      TC::Feature_curves<Mesh> c;
      {
        py::gil_scoped_release unlocked;
        mesh.wait_for_mesh();
        c = TC::feature_curves(*mesh.mesh, threshold);
      }
      py::list curves, lengths;
      for(const auto& curve : c.curves) {
        std::vector<std::int64_t> pairs;
        pairs.reserve(2 * curve.halfedges.size());
        for(halfedge_descriptor h : curve.halfedges) {
          pairs.push_back(std::int64_t(mesh.mesh->source(h)));
          pairs.push_back(std::int64_t(mesh.mesh->target(h)));
        }
        curves.append(owning_array(std::move(pairs), {py::ssize_t(curve.halfedges.size()), 2}));
        lengths.append(curve.length);
      }
      py::dict report;
      report["threshold_degrees"] = threshold;
      report["number_of_sharp_edges"] = c.number_of_sharp_edges;
      report["number_of_curves"] = c.curves.size();
      report["dropped_curves"] = c.dropped_curves;
      report["dropped_edges"] = c.dropped_edges;
      report["lengths"] = lengths;
      return py::make_tuple(curves, report);
    },
    py::arg("V"), py::arg("F"), py::arg("threshold") = TC::default_feature_angle_degrees,
    R"(The feature curves of a triangle mesh: (curves, report).

curves: one (k, 2) int64 array per kept curve, the (source, target) vertices of its sharp edges (breadth-first
from one of them; which one and each edge's orientation depend on the numbering). An interior edge is sharp when
the normals of its two faces make an angle over `threshold` degrees (default DEFAULT_FEATURE_ANGLE, 30; border
edges never are). A curve is a set of sharp edges connected through vertices that are not corners (a corner: where
three creases meet, or a crease turns by more than about 60 degrees). An isolated curve (touching no corner) with
fewer than 2 edges and shorter than 3 mean edge lengths is dropped. report: threshold_degrees,
number_of_sharp_edges (of kept and dropped curves), number_of_curves, dropped_curves, dropped_edges and lengths
(of the kept curves, in their order). Raises InvalidInput as feature_aligned_faces().)");

  m.def(
    "write_streamlines",
    [](const py::object& path_in, const py::list& lines) {
      const std::string path = path_of(path_in);
      std::vector<TC::Streamline<Mesh>> s;
      for(const py::handle line : lines) {
        const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(line);
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

  py::class_<Result>(m, "Result", "What Solver.solve() returns: the connection, the field and the report.")
    .def_readonly("connection", &Result::connection,
                  "(e,) float64: x of each interior edge, for the halfedge from edges[i, 0] to edges[i, 1]")
    .def_readonly("edges", &Result::edges, "(e, 2) int64: the interior edges (i < j), in the mesh's edge order")
    .def_readonly("field", &Result::field, "(m, 3) float64: a unit tangent vector per face (one of the n directions)")
    .def_readonly("directions", &Result::directions, "(m, n, 3) float64 for n > 1: the n directions per face; else None (and with "
                  "solve(all_directions=False))")
    .def_readonly("n", &Result::n, "n of the n-direction field")
    .def_readonly("energy", &Result::energy, "sum over interior edges of w_e x_e^2")
    .def_readonly("guidance_energy", &Result::guidance_energy, "mu sum_g d_g^2 over the guided faces")
    .def_readonly("max_residual", &Result::max_residual, "max over interior vertices of |K_v + sum x - 2 pi k_v|")
    .def_readonly("max_loop_residual", &Result::max_loop_residual, "max residual over the loops")
    .def_readonly("loop_periods", &Result::loop_periods, "the integer of every loop (Solver.number_of_loops)")
    .def_readonly("boundary_indices", &Result::boundary_indices, "{loop: Fraction}: the index of every boundary loop")
    .def_readonly("integers_proven_optimal", &Result::integers_proven_optimal,
                  "True when the loop integers were proven energy-optimal")
    .def_readonly("energy_lower_bound", &Result::energy_lower_bound,
                  "no choice of the free integers gives less energy than this")
    .def_readonly("rounding_energy", &Result::rounding_energy, "the energy with the integers rounded one by one")
    .def_readonly("constraints", &Result::constraints,
                  "one dict per link joining two constrained (or guided) faces: component, from_face, to_face, "
                  "length (edges crossed), period (its integer), residual, decided (True for a link between two "
                  "faces that touch, whose integer is the rounding, the short way from one target to the other, "
                  "rather than a free integer of the lattice problem)")
    .def_readonly("guidance", &Result::guidance, "one dict per guided face: face, mismatch")
    .def_readonly("timings", &Result::timings,
                  "seconds in C++: solve (Trivial_connection_solver::solve), field (compute_field) and outputs "
                  "(the arrays filled); the rest of a call's time is the binding's")
    .def("__repr__", [](const Result& r) {
      return "<trivial_connections.Result n=" + std::string(py::str(r.n)) +
             " energy=" + std::string(py::str(r.energy)) + " max_residual=" + std::string(py::str(r.max_residual)) +
             ">";
    });

  py::class_<Python_solver>(m, "Solver", R"(A prefactored trivial-connection solver for one triangle mesh.

Solver(V, F, weights="hodge", backend="auto", constrained_faces=None, guided_faces=None,
       guidance_weight=1.0, align_boundary=False, align_features=None, feature_smoothing=3, feature_n=4)

V: (n, 3) array of real numbers (any float or integer dtype, any layout); F: (m, 3) array of vertex indices
(any integer dtype). The mesh must be an oriented 2-manifold of triangles (boundaries allowed). Building the
solver factors the system once; every solve() after that costs back-substitutions only.
weights: "hodge" (w_e = |e| / |e*|) or "unit". backend: "auto" (SimplicialLDLT or CHOLMOD by predicted cost,
as the program), "ldlt" or "cholmod". constrained_faces / guided_faces: face numbers whose direction
solve() prescribes (exactly) or draws the field towards (with weight guidance_weight).
align_boundary: the field follows the boundary.
align_features: True (threshold 30 degrees) or a threshold in degrees in [0, 180]: the faces beside the mesh's
sharp feature curves are pinned to the curves' directions (feature_aligned_faces() with n=feature_n and
smoothing=feature_smoothing), as the program's --align-features: the user's constrained_faces and guided_faces
win on the faces they name, and with align_boundary the boundary faces are left to the boundary alignment.
solve(), place_singularities() and refine_singularities() then take the feature pins' directions themselves
(directions= is needed only for the user's own constrained and guided faces); set_constraints() merges the
feature pins again with its new faces. feature_pins and feature_alignment say what was pinned. A mesh with no
sharp edge pins nothing (feature_alignment["number_of_sharp_edges"] == 0), which is not an error.
progress: None or a callable progress(phase, fraction) for the constructor's phases ("mesh setup", "geometry",
"trees", "assembly", "factorization", "loop metric"; fraction 0 at a phase's start, 1 at its end), also logged to
the logger "trivial_connections"; Ctrl-C (KeyboardInterrupt) is honoured between them (no solver is made).
Raises InvalidInput for a mesh the package refuses (code and where say why), and (invalid_argument) for a
threshold that is negative, over 180 or NaN or feature_smoothing < 0, and (invalid_symmetry_order) for feature_n
outside 1 to MAX_SYMMETRY_ORDER.)")
    .def(py::init([](const py::object& V, const py::object& F, const std::string& weights, const std::string& backend,
                     const py::object& constrained, const py::object& guided, double mu, bool align,
                     const py::object& align_features, int feature_smoothing, const py::object& feature_n,
                     const py::object& progress) {
           const Feature_options features =
             feature_options_of(align_features, symmetry_order_of(feature_n, "feature_n"), feature_smoothing);
           Progress_context context("Solver()", progress);
           const auto start = std::chrono::steady_clock::now();
           Mesh_of_arrays mesh = mesh_of_arrays(V, F);
           const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
           auto solver = std::make_unique<Python_solver>(std::move(mesh), weights, backend, constrained, guided, mu,
                                                         align, features, context.callback());
           solver->m_mesh_seconds = seconds;
           return solver;
         }),
         py::arg("V"), py::arg("F"), py::kw_only(), py::arg("weights") = "hodge", py::arg("backend") = "auto",
         py::arg("constrained_faces") = py::none(), py::arg("guided_faces") = py::none(),
         py::arg("guidance_weight") = 1.0, py::arg("align_boundary") = false, py::arg("align_features") = py::none(),
         py::arg("feature_smoothing") = TC::default_feature_smoothing, py::arg("feature_n") = 4,
         py::arg("progress") = py::none())
    .def_static(
      "from_file",
      [](const py::object& path, bool triangulate, const std::string& weights, const std::string& backend,
         const py::object& constrained, const py::object& guided, double mu, bool align,
         const py::object& align_features, int feature_smoothing, const py::object& feature_n,
         const py::object& progress) {
        const Feature_options features =
          feature_options_of(align_features, symmetry_order_of(feature_n, "feature_n"), feature_smoothing);
        Progress_context context("Solver.from_file()", progress);
        const auto start = std::chrono::steady_clock::now();
        Mesh_of_arrays mesh;
        mesh.mesh = mesh_of_file(path_of(path), triangulate);
        mesh.number_of_faces = mesh.mesh->number_of_faces();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto solver = std::make_unique<Python_solver>(std::move(mesh), weights, backend, constrained, guided, mu,
                                                      align, features, context.callback());
        solver->m_mesh_seconds = seconds;
        return solver;
      },
      py::arg("path"), py::arg("triangulate") = false, py::kw_only(), py::arg("weights") = "hodge",
      py::arg("backend") = "auto", py::arg("constrained_faces") = py::none(), py::arg("guided_faces") = py::none(),
      py::arg("guidance_weight") = 1.0, py::arg("align_boundary") = false, py::arg("align_features") = py::none(),
      py::arg("feature_smoothing") = TC::default_feature_smoothing, py::arg("feature_n") = 4,
      py::arg("progress") = py::none(),
      "A solver for the mesh of an OFF, OBJ, PLY, STL or GOCAD file (path: str, bytes or os.PathLike; the "
      "package's validating reader, as read_mesh(); triangulate=True splits polygons). Options as Solver(), "
      "align_features and progress included (the program's --align-features [DEGREES]).")
    .def("solve", &Python_solver::solve, py::arg("singularities"), py::arg("n") = 1, py::arg("directions") = py::none(),
         py::arg("loop_periods") = py::none(), py::kw_only(), py::arg("all_directions") = true,
         py::arg("progress") = py::none(),
         R"(The trivial connection with exactly these singularities, and its field.

singularities: {vertex: index} or a sequence of (vertex, index) pairs (e.g. a (k, 2) integer array); an index
is an int, a fractions.Fraction or a string "p/q", a multiple of 1/n. On every closed component the indices
must sum to its Euler characteristic (Poincare-Hopf; see Solver.topology). n: 1 vectors, 2 lines, 4 crosses,
..., an integer from 1 to MAX_SYMMETRY_ORDER (else InvalidInput invalid_symmetry_order, a ValueError).
directions: for constrained or guided faces, an (m, 3) array (one row per face; the other rows are not read)
or {face: (3,) vector}; a ValueError when the solver has no constrained or guided face (it would be ignored).
loop_periods: one int (or None: chosen by the solver) per loop.
all_directions: False leaves Result.directions None (Result.field alone), which saves 3 n numbers per face and
their time (most of a solve's for large n); with True, a MemoryError before the solve when those numbers would
not fit in the memory available.
progress: None or a callable progress(phase, fraction), called between the phases ("solve", "loop integers",
"field") with fraction 0 at a phase's start, 1 at its end; the phases are also logged to the logger
"trivial_connections" (INFO, DEBUG in between). Ctrl-C (KeyboardInterrupt) is honoured between phases: the call
is abandoned and the solver stays usable; an exception raised by progress abandons it too.
Returns a Result. Releases the GIL: solves from several threads run concurrently.)")
    .def("set_constraints", &Python_solver::set_constraints, py::arg("constrained_faces") = py::none(),
         py::arg("guided_faces") = py::none(),
         "Changes the constrained and guided faces (as the constructor's options); returns what it did. With "
         "align_features, the feature pins are merged again with the new faces (the user's win).")
    .def_property_readonly("feature_pins", &Python_solver::feature_pins,
                           "With align_features: (faces, directions), a (k,) int64 and a (k, 3) float64 array, the "
                           "feature pins the solver holds besides the user's constrained faces (increasing face "
                           "number; unit vectors tangent to their faces). None without align_features.")
    .def_property_readonly("feature_alignment", &Python_solver::feature_alignment,
                           "With align_features: the report of feature_aligned_faces() (see there) and pinned (the "
                           "faces in feature_pins), named_by_user (left to constrained_faces), on_guided_faces (left "
                           "to guided_faces) and on_aligned_boundary (left to align_boundary). None without "
                           "align_features.")
    .def("place_singularities", &Python_solver::place_singularities, py::kw_only(), py::arg("n") = 1,
         py::arg("align_boundary") = false, py::arg("alignment_guide") = py::none(),
         py::arg("alignment_strength") = 100.0, py::arg("fixed_singularities") = py::none(),
         py::arg("loop_periods") = py::none(), py::arg("directions") = py::none(), py::arg("progress") = py::none(),
         R"(Automatic placement: the singularities of the globally smoothest n-direction field (Knoeppel et al. 2013).

Returns (singularities, report): {vertex: Fraction}, which satisfies Poincare-Hopf on every closed component and
can be given to solve() as it is, and a dict (field_energy, singularities_per_index, ...). alignment_guide: an
(m, 3) array (or {face: vector}) of guide directions whose length weighs them (principal_curvature_guide()), for
Knoeppel's aligned field, with alignment_strength. fixed_singularities: kept as they are, the automatic ones nearest
give way. align_boundary, loop_periods: as for the solver and solve(). directions: as for solve(), required when
the solver has constrained faces: the field is held at their directions (report["pinned"] counts them); a
ValueError when it has none. n: as for solve(). progress: as for solve() (phase "placement", with fractions in
between for the eigensolver's iterations); Ctrl-C is honoured there.)")
    .def("principal_curvature_guide", &Python_solver::principal_curvature_guide,
         "Per face, the direction of largest principal curvature times the anisotropy |k1 - k2| ((m, 3) array), "
         "and the two principal curvatures ((m, 2) array, larger absolute value first): a guide for n = 2 or 4.")
    .def("spread_guided_faces", &Python_solver::spread_guided_faces, py::arg("guide"), py::arg("count"),
         "Up to count faces spread over the mesh, strongest guide first: guided_faces for set_constraints().")
    .def("refine_singularities", &Python_solver::refine_singularities, py::arg("singularities"), py::kw_only(),
         py::arg("n") = 1, py::arg("directions") = py::none(), py::arg("loop_periods") = py::none(),
         py::arg("fixed_vertices") = py::none(), py::arg("cancel_pairs") = false, py::arg("maximum_trials") = py::none(),
         py::arg("progress") = py::none(),
         "Moves singularities to neighbouring vertices (and, with cancel_pairs, cancels opposite pairs) until no "
         "single move or cancellation lowers the trivial connection's energy: a local minimum (maximum_trials: a "
         "budget of solves; None: none). Returns (singularities, report) with energy_before, energy_after, moves, "
         "cancellations, rounds, trials, singularities_before, local_minimum and stop ('local_minimum', "
         "'maximum_trials' or 'rejected_moves'). n, directions: as for solve(). progress: as for solve(), called in "
         "every trial solve; Ctrl-C is honoured between them (the refinement is abandoned, the solver stays "
         "usable).")
    .def("trace_streamlines", &Python_solver::trace_streamlines, py::arg("result"), py::arg("singularities"),
         py::arg("seed_faces") = py::none(), py::arg("maximum_faces_per_ray") = 0,
         "The streamlines of result's field from the barycentres of seed_faces (default: every face): a list of "
         "(k, 3) polylines on the surface; a ray stops at the boundary, at a face with a singular vertex, when it "
         "closes, or after maximum_faces_per_ray faces (0: n times the number of faces).")
    .def("write_field", &Python_solver::write_field, py::arg("path"), py::arg("result"), py::arg("singularities"),
         "Writes result's field to path (str, bytes or os.PathLike), by the file name's ending: .txt the program's field file (one line \"x y z\" per "
         "face, in face order, numbers that read back exactly; the singularities are checked but not written); .vtk "
         "or .ply the mesh, the field (its n directions) and the singularities as a legacy VTK or PLY file for "
         "ParaView, MeshLab or Blender. Completely or not at all.")
    .def_property_readonly("loops", &Python_solver::loops,
                           "The loops whose integers loop_periods gives, in that order: dicts with kind (\"boundary\" "
                           "or \"generator\": the 2g homology generators of each component), component and "
                           "halfedges, a (k, 2) array of the (source, target) vertices of the halfedges crossed, each "
                           "from the face on its left to the face on its right.")
    .def_property_readonly(
      "build_timings",
      [](const Python_solver& s) {
        py::dict d;
        d["mesh"] = s.m_mesh_seconds;
        d["solver"] = s.m_solver_seconds;
        return d;
      },
      "seconds in C++ while the solver was built: mesh (the arrays validated and made into a Surface_mesh and the "
      "solver's arrays, or the file read into a validated Surface_mesh) and solver (the C++ constructor: from "
      "those arrays, or from the Surface_mesh of the file)")
    .def_property_readonly("number_of_vertices", &Python_solver::number_of_vertices,
                           "the mesh's vertices: the rows of V (and of Solver.vertices)")
    .def_property_readonly("number_of_faces", &Python_solver::number_of_faces,
                           "the mesh's triangles: the rows of F (and of Solver.faces, Result.field)")
    .def_property_readonly("topology", &Python_solver::topology,
                           "One dict per connected component, in the order of the components of Result and loops: "
                           "number_of_faces, euler_characteristic (V - E + F), genus ((2 - chi - b) / 2), "
                           "number_of_boundary_loops (b), closed (b == 0) and faces ((k,) int64, its face numbers). "
                           "On a closed component the singularity indices of solve() must sum to "
                           "euler_characteristic (2 on a sphere, 0 on a torus); the program prints the same lines.")
    .def("__repr__", &Python_solver::repr)
    .def_property_readonly("number_of_loops", &Python_solver::number_of_loops,
                           "boundary loops and homology generators: the entries of loop_periods")
    .def_property_readonly("backend", &Python_solver::backend, "\"ldlt\", \"cholmod\" or \"auto\"")
    .def_property_readonly("edges", &Python_solver::edges, "(e, 2) int64: the interior edges, as in Result.edges")
    .def_property_readonly("vertices", &Python_solver::vertices, "(n, 3) float64: the mesh's points (V)")
    .def_property_readonly("faces", &Python_solver::faces,
                           "(m, 3) int64: the mesh's triangles, each row as in F or the file (its corners in their order; the "
                           "triangles of a face split by from_file(triangulate=True) in their order)")
    .def_property_readonly("weights", &Python_solver::weights,
                           "(e,) float64: the weight w_e of each interior edge in the energy, as in Result.edges");
}
