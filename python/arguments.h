// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The Python values of the arguments, checked, as C++ values (indices, vertices, faces, directions, n, paths), and
// numpy arrays out that own the vectors they show.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_ARGUMENTS_H
#define TRIVIAL_CONNECTIONS_PYTHON_ARGUMENTS_H

namespace {

// ---- numpy arrays in ------------------------------------------------------------------------------------

// An array as C-ordered doubles (converted when it is not; ensure() gives a null array when it cannot be)
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Row i of rows of three doubles as a vector
Kernel::Vector_3 vector_at(const double* xyz, std::size_t i)
{
  return Kernel::Vector_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
}

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
  const auto a = Doubles::ensure(h);
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
  const auto d = Doubles::ensure(a);
  for(std::size_t i = 0; i < out.size(); ++i)
    out[i].direction = {{d.data()[3 * i], d.data()[3 * i + 1], d.data()[3 * i + 2]}};
  return out;
}

// Face numbers (an iterable of integers, or None: none), each checked against the mesh
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
    return vector_at(m.xyz, std::size_t(f));
  }
  friend void put(const Face_vector_map& m, face_descriptor f, const Kernel::Vector_3& v)
  {
    double* p = m.xyz + 3 * std::size_t(f);
    p[0] = CGAL::to_double(v.x());
    p[1] = CGAL::to_double(v.y());
    p[2] = CGAL::to_double(v.z());
  }
};

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_ARGUMENTS_H
