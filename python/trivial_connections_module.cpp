// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The Python module `trivial_connections` (pybind11): the package's solver on numpy arrays. One translation
// unit (one compilation of CGAL and pybind11, for the build's time), built by the top-level CMakeLists.txt when
// pybind11 and Python's headers are found, and by setup.py (pip install .). Its parts, one concept each, are the
// headers beside it, included below in the order of their dependencies: arguments.h (Python values and numpy
// arrays in and out), progress.h (progress callbacks, logging, Ctrl-C), mesh_input.h (V, F and mesh files;
// read_mesh()), features.h (sharp features), the solver: solver_backend.h (the C++ solver of either backend),
// solver_state.h (the class Solver: its state and construction), solving.h (solve(), set_constraints()),
// solver_outputs.h (Result, topology, the mesh's arrays), solver_bindings.h (Result's and Solver's binding), then
// placement.h (automatic placement and refinement), streamlines.h, quad_mesh.h (quad meshes) and files.h. This file holds the types they
// share and the module itself: numpy at import, __version__, the exception InvalidInput, the bindings' calls.
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
#include <CGAL/Trivial_connections/IO/repair_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>
#include <CGAL/Trivial_connections/feature_alignment.h>
#include <CGAL/Trivial_connections/singularity_placement.h>
#include <CGAL/Trivial_connections/singularity_refinement.h>
#include <CGAL/Trivial_connections/streamlines.h>
#include <CGAL/Trivial_connections/quad_mesh.h>
#include <CGAL/Trivial_connections/quad_size.h>
#include <CGAL/Trivial_connections/singularities_off_features.h>
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
using edge_descriptor = Mesh::Edge_index;
using face_descriptor = Mesh::Face_index;
using Loop_periods = std::vector<std::optional<std::int64_t>>;
using Singularities = std::vector<std::pair<std::size_t, TC::Singularity_index>>;

}  // namespace

// The parts, each one concept (each opens its own anonymous namespace), in the order of their dependencies
#include "arguments.h"
#include "progress.h"
#include "mesh_input.h"
#include "features.h"
#include "solver_backend.h"
#include "solver_state.h"
#include "solving.h"
#include "solver_outputs.h"
#include "solver_bindings.h"
#include "placement.h"
#include "streamlines.h"
#include "quad_mesh.h"
#include "files.h"

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

  bind_mesh_input(m);
  py::class_<Python_solver> solver = bind_solver(m);
  bind_placement(solver);
  bind_streamlines(m, solver);
  bind_quad_mesh(solver);
  bind_files(m, solver);
  bind_features(m);
}
