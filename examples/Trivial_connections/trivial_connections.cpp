// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The command-line program: computes the trivial connection closest to Levi-Civita with prescribed
// singularities on a triangle mesh, and the n-direction field it defines, and writes both to files.
//
//   trivial_connections MESH [--singularities FILE] [--boundary-indices FILE] [--constraints FILE]
//                            [--triangulate] [--align-boundary] [--guidance FILE] [--guidance-weight MU] [--n N] [--weights hodge|unit]
//                            [--connection OUT] [--field OUT] [--vtk OUT] [--ply OUT] [--singularity-points OUT]
//                            [--streamlines OUT] [--streamline-seeds K] [--progress] [--help] [--version]
//
// Exit status: 0 on success, 1 on an input error (mesh, singularities, solver, output files), 2 on a usage
// error. On any error one line `trivial_connections: error: <message>` goes to stderr and no output file is
// written (both files are committed together, only after everything succeeded).
// Progress (one line per phase with the elapsed time) goes to stderr when stderr is a terminal or with
// --progress, never otherwise.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/version.h>

#include <CGAL/Trivial_connections/IO/atomic_file.h>
#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/field_file.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>
#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/Trivial_connection_solver.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace TC = CGAL::Trivial_connections;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Solver = TC::Trivial_connection_solver<Mesh, CGAL::Default, TC::Recommended_solver_traits>;
using vertex_descriptor = boost::graph_traits<Mesh>::vertex_descriptor;
using halfedge_descriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
using face_descriptor = boost::graph_traits<Mesh>::face_descriptor;

namespace {

const char* const program = "trivial_connections";

const char* const usage_text =
  "Usage: trivial_connections MESH [--triangulate] [--singularities FILE] [--boundary-indices FILE]\n"
  "                           [--constraints FILE] [--align-boundary] [--guidance FILE]\n"
  "                           [--guidance-weight MU] [--n N] [--weights hodge|unit]\n"
  "                           [--connection OUT] [--field OUT] [--vtk OUT] [--ply OUT]\n"
  "                           [--singularity-points OUT] [--streamlines OUT] [--streamline-seeds K]\n"
  "                           [--progress] [--help] [--version]\n"
  "\n"
  "Computes the trivial connection closest to Levi-Civita on a triangle mesh, with the prescribed\n"
  "singularity indices at vertices, and the n-direction field it defines.\n"
  "\n"
  "  MESH                  triangle mesh: .off, .obj, .ply, .stl or .ts (oriented 2-manifold, boundary\n"
  "                        allowed)\n"
  "  --triangulate         split faces of more than three vertices into triangles (CGAL's PMP); face\n"
  "                        indices (--constraints, --guidance, --field) then number the triangles: those of\n"
  "                        a face are consecutive, in file order. Without it such faces are an error.\n"
  "  --singularities FILE  one line 'v k' per singular vertex: 0-based vertex index (file order) and index k,\n"
  "                        an integer or a fraction p/q that is a multiple of 1/N; '#' starts a comment.\n"
  "                        Default: no singularity (then every closed component must have genus 1).\n"
  "                        On each closed component the indices must sum to its Euler characteristic.\n"
  "  --boundary-indices FILE  the index of every boundary loop, one line 'v k' per loop: any vertex v of\n"
  "                        the loop (0-based, file order) and its index k (as for --singularities). Every\n"
  "                        boundary loop of a component listed, or none; vertex and boundary indices then\n"
  "                        sum to the Euler characteristic. Default: chosen to minimise the energy.\n"
  "  --constraints FILE    directional constraints, one line 'f x y z' per face: 0-based face index (file\n"
  "                        order) and a direction (projected onto the face) that the field must have\n"
  "                        there, as one of its N directions. Each extra constrained face of a component\n"
  "                        adds one free integer, chosen with the loop integers.\n"
  "  --align-boundary      the field follows the boundary on every boundary face: along its border edge\n"
  "                        (the longer one when it has two); for N = 4, tangent and normal to it.\n"
  "  --guidance FILE       soft guidance, lines 'f x y z' as for --constraints: the solve minimises the\n"
  "                        energy plus MU times the sum over these faces of the squared angle between the\n"
  "                        field and the guide (modulo 2pi/N), still with exactly the given singularities.\n"
  "  --guidance-weight MU  the weight MU > 0 of the guidance (default 1)\n"
  "  --n N                 symmetry order: 1 vector field, 2 line field, 4 cross field, ... (default 1)\n"
  "  --weights W           energy weights: hodge (|e|/|e*|, default) or unit\n"
  "  --connection OUT      connection file, one line 'i j x w' per interior edge\n"
  "                        (default: <mesh stem>.connection.txt in the current directory)\n"
  "  --field OUT           field file, one line 'x y z' per face in input face order\n"
  "                        (default: <mesh stem>.field.txt in the current directory)\n"
  "  --vtk OUT             also the mesh with the field for viewers, legacy VTK (ParaView): per face the N\n"
  "                        directions (direction_0 ...), per vertex its singularity index\n"
  "  --ply OUT             the same as an ASCII PLY file (MeshLab): face properties dk_x dk_y dk_z\n"
  "  --singularity-points OUT  one line 'x y z k' per singular vertex\n"
  "  --streamlines OUT     streamlines of the field as legacy VTK polylines (ParaView), traced from K seed\n"
  "                        faces spread over the mesh (--streamline-seeds K, default 100); a ray stops at\n"
  "                        a singularity, a boundary, where it meets itself, or after 50 sqrt(faces) faces\n"
  "  --progress            print each phase and the elapsed time to stderr (the default when stderr\n"
  "                        is a terminal)\n"
  "  --help, -h            print this help and exit\n"
  "  --version             print the version (and those of CGAL, Eigen and the sparse solver) and exit\n"
  "\n"
  "The integers of the homology generators and boundary loops are chosen to minimise the energy.\n"
  "Both output files are written only if everything succeeded. Exit status: 0 success, 1 input error,\n"
  "2 usage error; errors are reported as one line on stderr.\n";

// A bad command line (exit status 2).
struct Usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

struct Options
{
  bool help = false;
  bool version = false;
  bool progress = false;
  std::string mesh;
  std::string singularities;
  std::string boundary_indices;
  std::string constraints;
  bool align_boundary = false;
  bool triangulate = false;
  std::string guidance;
  double guidance_weight = 1;
  int n = 1;
  TC::Weighting weighting = TC::Weighting::hodge_star;
  std::string weights_name = "hodge";
  std::string connection;
  std::string field;
  std::string vtk, ply, singularity_points, streamlines; // optional outputs for viewers
  std::size_t streamline_seeds = 100;
};

int parse_symmetry_order(const std::string& text)
{
  const std::string digits = (!text.empty() && text[0] == '+') ? text.substr(1) : text;
  if(digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) {
    if(!text.empty() && text[0] == '-' && text.size() > 1 &&
       text.find_first_not_of("0123456789", 1) == std::string::npos)
      throw Usage_error("--n must be at least 1 (got " + text + ")");
    throw Usage_error("--n expects a positive integer, got '" + text + "'");
  }
  const std::string trimmed = digits.substr((std::min)(digits.find_first_not_of('0'), digits.size()));
  if(trimmed.size() > 9)
    throw Usage_error("--n is too large (got " + text + ")");
  const int n = trimmed.empty() ? 0 : std::stoi(trimmed);
  if(n < 1)
    throw Usage_error("--n must be at least 1 (got " + text + ")");
  return n;
}

Options parse_arguments(int argc, char** argv)
{
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  for(const std::string& a : args) {
    if(a == "--help" || a == "-h") {
      o.help = true;
      return o;
    }
    if(a == "--version") {
      o.version = true;
      return o;
    }
  }
  bool seen_singularities = false, seen_boundary = false, seen_constraints = false, seen_guidance = false,
       seen_guidance_weight = false, seen_n = false, seen_weights = false, seen_connection = false, seen_field = false,
       seen_vtk = false, seen_ply = false, seen_points = false, seen_streamlines = false, seen_seeds = false;
  for(std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    if(a == "--progress") {
      o.progress = true;
      continue;
    }
    if(a == "--triangulate") {
      if(o.triangulate)
        throw Usage_error("option --triangulate given twice");
      o.triangulate = true;
      continue;
    }
    if(a == "--align-boundary") {
      if(o.align_boundary)
        throw Usage_error("option --align-boundary given twice");
      o.align_boundary = true;
      continue;
    }
    if(a.size() > 1 && a[0] == '-' && a != "-") {
      std::string name = a, value;
      bool has_value = false;
      const std::string::size_type eq = a.find('=');
      if(a.compare(0, 2, "--") == 0 && eq != std::string::npos) {
        name = a.substr(0, eq);
        value = a.substr(eq + 1);
        has_value = true;
      }
      bool* seen = nullptr;
      if(name == "--singularities") seen = &seen_singularities;
      else if(name == "--boundary-indices") seen = &seen_boundary;
      else if(name == "--constraints") seen = &seen_constraints;
      else if(name == "--guidance") seen = &seen_guidance;
      else if(name == "--guidance-weight") seen = &seen_guidance_weight;
      else if(name == "--n") seen = &seen_n;
      else if(name == "--weights") seen = &seen_weights;
      else if(name == "--connection") seen = &seen_connection;
      else if(name == "--field") seen = &seen_field;
      else if(name == "--vtk") seen = &seen_vtk;
      else if(name == "--ply") seen = &seen_ply;
      else if(name == "--singularity-points") seen = &seen_points;
      else if(name == "--streamlines") seen = &seen_streamlines;
      else if(name == "--streamline-seeds") seen = &seen_seeds;
      else
        throw Usage_error("unknown option '" + name + "' (see --help)");
      if(*seen)
        throw Usage_error("option " + name + " given twice");
      *seen = true;
      if(!has_value) {
        if(i + 1 >= args.size())
          throw Usage_error("option " + name + " needs a value (see --help)");
        value = args[++i];
      }
      if(value.empty())
        throw Usage_error("option " + name + " needs a non-empty value");
      if(name == "--singularities") o.singularities = value;
      else if(name == "--boundary-indices") o.boundary_indices = value;
      else if(name == "--constraints") o.constraints = value;
      else if(name == "--guidance") o.guidance = value;
      else if(name == "--guidance-weight") {
        char* end = nullptr;
        o.guidance_weight = std::strtod(value.c_str(), &end);
        if(end != value.c_str() + value.size() || !(o.guidance_weight > 0) || !std::isfinite(o.guidance_weight))
          throw Usage_error("--guidance-weight expects a positive finite number, got '" + value + "'");
      }
      else if(name == "--connection") o.connection = value;
      else if(name == "--field") o.field = value;
      else if(name == "--vtk") o.vtk = value;
      else if(name == "--ply") o.ply = value;
      else if(name == "--singularity-points") o.singularity_points = value;
      else if(name == "--streamlines") o.streamlines = value;
      else if(name == "--streamline-seeds") {
        if(value.empty() || value.size() > 9 || value.find_first_not_of("0123456789") != std::string::npos ||
           std::stoul(value) == 0)
          throw Usage_error("--streamline-seeds expects a positive integer, got '" + value + "'");
        o.streamline_seeds = std::stoul(value);
      }
      else if(name == "--n") o.n = parse_symmetry_order(value);
      else if(name == "--weights") {
        if(value == "hodge") o.weighting = TC::Weighting::hodge_star;
        else if(value == "unit") o.weighting = TC::Weighting::unit;
        else throw Usage_error("unknown weights '" + value + "' (expected hodge or unit)");
        o.weights_name = value;
      }
    } else {
      if(!o.mesh.empty())
        throw Usage_error("more than one mesh given ('" + o.mesh + "' and '" + a + "')");
      if(a.empty())
        throw Usage_error("empty mesh file name");
      o.mesh = a;
    }
  }
  if(o.mesh.empty())
    throw Usage_error("no mesh given (usage: trivial_connections MESH [options], see --help)");
  const std::string stem = std::filesystem::path(o.mesh).stem().string();
  if(o.connection.empty())
    o.connection = stem + ".connection.txt";
  if(o.field.empty())
    o.field = stem + ".field.txt";

  auto same_file = [](const std::string& a, const std::string& b) {
    std::error_code ec1, ec2;
    // absolute() first: weakly_canonical() leaves a relative path relative when its first element does not exist
    const std::filesystem::path pa = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ec1), ec1);
    const std::filesystem::path pb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, ec2), ec2);
    return !ec1 && !ec2 ? pa == pb : a == b;
  };
  std::vector<const std::string*> outputs = {&o.connection, &o.field};
  for(const std::string* extra : {&o.vtk, &o.ply, &o.singularity_points, &o.streamlines})
    if(!extra->empty())
      outputs.push_back(extra);
  for(std::size_t a = 0; a < outputs.size(); ++a)
    for(std::size_t b = a + 1; b < outputs.size(); ++b)
      if(same_file(*outputs[a], *outputs[b]))
        throw Usage_error("two outputs are the same file '" + *outputs[a] + "'");
  for(const std::string* out : outputs) {
    if(same_file(*out, o.mesh))
      throw Usage_error("the output '" + *out + "' would overwrite the input mesh");
    if(!o.singularities.empty() && same_file(*out, o.singularities))
      throw Usage_error("the output '" + *out + "' would overwrite the singularity file");
    if(!o.boundary_indices.empty() && same_file(*out, o.boundary_indices))
      throw Usage_error("the output '" + *out + "' would overwrite the boundary index file");
    if(!o.constraints.empty() && same_file(*out, o.constraints))
      throw Usage_error("the output '" + *out + "' would overwrite the constraint file");
    if(!o.guidance.empty() && same_file(*out, o.guidance))
      throw Usage_error("the output '" + *out + "' would overwrite the guidance file");
  }
  return o;
}

std::string one_line(std::string s)
{
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

// Prints one line per phase to stderr: "[  1.23 s] factorization ... done (0.45 s)", the time since the
// program started. Lines are written with one fputs each, so that they are never interleaved.
class Progress_printer
{
public:
  explicit Progress_printer(bool enabled) : m_enabled(enabled), m_start(std::chrono::steady_clock::now()) {}

  bool enabled() const { return m_enabled; }
  void begin(const char* phase)
  {
    if(!m_enabled)
      return;
    end_line();
    m_starts[phase] = std::chrono::steady_clock::now();
    m_open_phase = phase;
    m_open = true;
    print("[" + seconds(m_start) + " s] " + phase + " ...");
  }
  void end(const char* phase)
  {
    if(!m_enabled)
      return;
    const auto start = m_starts.find(phase);
    if(start == m_starts.end())
      return;
    const std::string took = seconds(start->second);
    m_starts.erase(start);
    if(m_open && m_open_phase == phase) {
      m_open = false;
      print(" done (" + took + " s)\n");
    } else { // another phase ran inside this one
      end_line();
      print("[" + seconds(m_start) + " s] " + phase + " done (" + took + " s)\n");
    }
  }
  // ends an open line (before an error message or the report of an exception out of a phase)
  void end_line()
  {
    if(m_enabled && m_open) {
      m_open = false;
      print("\n");
    }
  }
  TC::Progress_callback callback()
  {
    if(!m_enabled)
      return TC::Progress_callback();
    return [this](TC::Phase p, double fraction) {
      if(fraction <= 0)
        begin(TC::phase_name(p));
      else if(fraction >= 1)
        end(TC::phase_name(p));
    };
  }

private:
  std::string seconds(std::chrono::steady_clock::time_point since) const
  {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%7.2f",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count());
    return buffer;
  }
  static void print(const std::string& text)
  {
    std::fputs(text.c_str(), stderr);
    std::fflush(stderr);
  }

  bool m_enabled;
  std::chrono::steady_clock::time_point m_start;
  std::map<std::string, std::chrono::steady_clock::time_point> m_starts; // of the phases not ended yet
  std::string m_open_phase; // the phase whose line is not ended yet, if m_open
  bool m_open = false;
};

bool stderr_is_terminal()
{
#if defined(__unix__) || defined(__APPLE__)
  return ::isatty(2) == 1;
#else
  return false;
#endif
}

int fail(const std::string& message, int status)
{
  std::cerr << program << ": error: " << one_line(message) << std::endl;
  return status;
}

double seconds_since(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string fixed(double x, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

std::string scientific(double x)
{
  std::ostringstream s;
  s << std::scientific << std::setprecision(2) << x;
  return s.str();
}

int run(const Options& o, Progress_printer& progress)
{
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  const TC::Progress_callback solver_progress = progress.callback();

  Mesh mesh;
  progress.begin("reading mesh");
  const TC::Mesh_input_order<Mesh> order = [&] {
    try {
      return TC::read_triangle_mesh(o.mesh, mesh, TC::parameters::triangulate(o.triangulate));
    } catch(const TC::Invalid_input& e) {
      if(e.code() != TC::Error_code::not_triangle_mesh || o.triangulate)
        throw;
      throw TC::Invalid_input(e.code(), std::string(e.what()) + " (--triangulate splits such faces)", e.where());
    }
  }();
  progress.end("reading mesh");
  const double t_read = seconds_since(t_start);

  std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> singularities;
  if(!o.singularities.empty()) {
    for(const auto& s : TC::read_singularities(o.singularities, order.vertices.size()))
      singularities.emplace_back(order.vertices[s.first], s.second);
  }

  std::vector<std::pair<std::size_t, TC::Singularity_index>> boundary_indices;
  if(!o.boundary_indices.empty())
    boundary_indices = TC::read_singularities(o.boundary_indices, order.vertices.size());

  std::vector<TC::Face_direction> constraints;
  if(!o.constraints.empty())
    constraints = TC::read_face_directions(o.constraints, order.faces.size());
  std::vector<TC::Face_direction> guides;
  if(!o.guidance.empty())
    guides = TC::read_face_directions(o.guidance, order.faces.size());
  std::vector<face_descriptor> constrained_faces, guided_faces;
  Mesh::Property_map<face_descriptor, Kernel::Vector_3> directions =
    mesh.add_property_map<face_descriptor, Kernel::Vector_3>("f:tc_directions", CGAL::NULL_VECTOR).first;
  std::vector<char> in_constraints(order.faces.size(), 0);
  for(const TC::Face_direction& d : constraints) {
    constrained_faces.push_back(order.faces[d.face]);
    in_constraints[d.face] = 1;
    directions[order.faces[d.face]] = Kernel::Vector_3(d.direction[0], d.direction[1], d.direction[2]);
  }
  for(const TC::Face_direction& d : guides) {
    if(in_constraints[d.face])
      throw TC::Invalid_input(TC::Error_code::invalid_constraint,
                              "face " + std::to_string(d.face) + " is in both " + o.constraints + " and " + o.guidance,
                              d.face);
    guided_faces.push_back(order.faces[d.face]);
    directions[order.faces[d.face]] = Kernel::Vector_3(d.direction[0], d.direction[1], d.direction[2]);
  }
  // the solver's errors about the constraints and guides name faces: name the file that has the face too
  auto naming_the_constraint_file = [&](auto&& call) {
    try {
      return call();
    } catch(const TC::Invalid_input& e) {
      if(e.code() != TC::Error_code::invalid_constraint || (o.constraints.empty() && o.guidance.empty()))
        throw;
      std::string file = o.constraints.empty() ? o.guidance : o.constraints;
      if(!o.guidance.empty() && e.where() < in_constraints.size() && !in_constraints[e.where()])
        file = o.guidance;
      throw TC::Invalid_input(e.code(), file + ": " + e.what(), e.where());
    }
  };

  auto t = clock::now();
  Solver solver = naming_the_constraint_file([&] {
    return Solver(mesh, TC::parameters::progress(
                          solver_progress,
                          TC::parameters::weighting(
                            o.weighting,
                            TC::parameters::constrained_faces(
                              constrained_faces,
                              TC::parameters::align_with_boundary(
                                o.align_boundary, TC::parameters::guided_faces(
                                                    guided_faces, TC::parameters::guidance_weight(o.guidance_weight)))))));
  });
  const double t_setup = seconds_since(t);

  // the boundary loops named by one of their vertices; the generators are left to the solver
  std::vector<std::optional<std::int64_t>> loop_periods(solver.loops().size());
  std::vector<std::size_t> named_by(solver.loops().size());
  for(const auto& [v, index] : boundary_indices) {
    const std::optional<std::size_t> l = solver.boundary_loop_of(order.vertices[v]);
    if(!l)
      throw TC::Invalid_input(TC::Error_code::invalid_loop_periods,
                              o.boundary_indices + ": vertex " + std::to_string(v) + " is not on a boundary", v);
    if(loop_periods[*l])
      throw TC::Invalid_input(TC::Error_code::invalid_loop_periods,
                              o.boundary_indices + ": vertices " + std::to_string(named_by[*l]) + " and " +
                                std::to_string(v) + " are on the same boundary loop",
                              v);
    if(!index.is_multiple_of_one_over(o.n))
      throw TC::Invalid_input(TC::Error_code::index_not_multiple,
                              o.boundary_indices + ": the index " + index.to_string() + " of the boundary loop of vertex " +
                                std::to_string(v) + " is not a multiple of 1/" + std::to_string(o.n),
                              v);
    // bounded like the vertex indices, so that the sums stay far from overflow
    if(std::abs(index.numerator()) > (std::int64_t(1) << 30) / (o.n / index.denominator()))
      throw TC::Invalid_input(TC::Error_code::invalid_index,
                              o.boundary_indices + ": the index " + index.to_string() + " of the boundary loop of vertex " +
                                std::to_string(v) + " is too large",
                              v);
    loop_periods[*l] = index.times(o.n);
    named_by[*l] = v;
  }

  t = clock::now();
  Mesh::Property_map<halfedge_descriptor, double> x =
    mesh.add_property_map<halfedge_descriptor, double>("h:tc_connection", 0.).first;
  Mesh::Property_map<face_descriptor, Kernel::Vector_3> field =
    mesh.add_property_map<face_descriptor, Kernel::Vector_3>("f:tc_field", CGAL::NULL_VECTOR).first;
  const auto np = TC::parameters::progress(solver_progress, TC::parameters::face_directions(
                                                              directions, TC::parameters::symmetry_order(o.n)));
  auto solve = [&] {
    if(boundary_indices.empty())
      return naming_the_constraint_file([&] { return solver.solve(singularities, x, np); });
    // the solver checks the loops (every hole of a component or none, Poincare-Hopf): name the file
    try {
      return naming_the_constraint_file(
        [&] { return solver.solve(singularities, x, TC::parameters::loop_periods(loop_periods, np)); });
    } catch(const TC::Invalid_input& e) {
      if(e.code() != TC::Error_code::invalid_loop_periods)
        throw;
      throw TC::Invalid_input(e.code(), o.boundary_indices + ": " + e.what(), e.where());
    }
  };
  const TC::Solve_report report = solve();
  solver.compute_field(x, field, TC::parameters::progress(
                                   solver_progress, TC::parameters::face_directions(
                                                      directions, TC::parameters::symmetry_order(o.n))));
  const double t_solve = seconds_since(t);

  std::size_t interior_edges = 0;
  for(auto e : edges(mesh))
    if(!CGAL::is_border(e, mesh))
      ++interior_edges;

  t = clock::now();
  progress.begin("writing files");
  const std::string provenance = "# computed by trivial_connections from '" + o.mesh + "'" +
                                 (o.singularities.empty() ? std::string(", no singularity")
                                                          : ", singularities '" + o.singularities + "'") +
                                 (o.constraints.empty() ? std::string() : ", constraints '" + o.constraints + "'") +
                                 (o.align_boundary ? ", aligned with the boundary" : "") +
                                 (o.guidance.empty() ? std::string()
                                                     : ", guidance '" + o.guidance + "' with weight " +
                                                         std::to_string(o.guidance_weight)) +
                                 ", n = " + std::to_string(o.n) + ", weights " + o.weights_name + "\n";
  const auto vertex_index = get(boost::vertex_index, mesh);
  std::vector<std::pair<std::string, TC::File_writer>> files = {
    {o.connection,
     [&](std::ostream& os) {
       os << provenance;
       TC::write_connection(os, mesh, x, vertex_index, solver);
     }},
    {o.field, [&](std::ostream& os) {
       os << provenance;
       TC::write_field(os, mesh, field);
     }}};
  if(!o.vtk.empty())
    files.push_back({o.vtk, [&](std::ostream& os) {
                       TC::write_field_vtk(os, mesh, field, singularities, TC::parameters::symmetry_order(o.n));
                     }});
  if(!o.ply.empty())
    files.push_back({o.ply, [&](std::ostream& os) {
                       TC::write_field_ply(os, mesh, field, singularities, TC::parameters::symmetry_order(o.n));
                     }});
  if(!o.singularity_points.empty())
    files.push_back({o.singularity_points, [&](std::ostream& os) {
                       os << provenance;
                       TC::write_singularity_points(os, mesh, singularities);
                     }});
  std::vector<TC::Streamline<Mesh>> streamlines;
  if(!o.streamlines.empty()) {
    // K faces spread over those without a singular vertex (a seed there would give no line)
    std::vector<char> singular(num_vertices(mesh), 0);
    for(const auto& sv : singularities)
      singular[std::size_t(sv.first)] = 1;
    std::vector<face_descriptor> candidates, seeds;
    for(face_descriptor f : order.faces) {
      bool touches = false;
      for(auto v : CGAL::vertices_around_face(halfedge(f, mesh), mesh))
        touches = touches || singular[std::size_t(v)];
      if(!touches)
        candidates.push_back(f);
    }
    const std::size_t count = (std::min)(o.streamline_seeds, candidates.size());
    for(std::size_t i = 0; i < count; ++i)
      seeds.push_back(candidates[i * candidates.size() / count]);
    // a line across the mesh crosses about sqrt(faces) faces: 50 times that bounds recurrent ones
    const std::size_t bound = 50 * std::size_t(std::sqrt(double(order.faces.size()))) + 1000;
    streamlines = TC::trace_streamlines(mesh, x, field, singularities, seeds,
                                        TC::parameters::maximum_faces_per_ray(bound, TC::parameters::symmetry_order(o.n)));
    files.push_back({o.streamlines, [&](std::ostream& os) { TC::write_streamlines_vtk(os, streamlines); }});
  }
  // all written or none; the writers only read the mesh, the maps and the solver
  TC::write_files_atomically(files, /* concurrently = */ true);
  progress.end("writing files");
  const double t_write = seconds_since(t);

  // ---- report
  std::ostream& out = std::cout;
  out << "mesh: " << o.mesh << ": " << num_vertices(mesh) << " vertices, " << num_faces(mesh) << " faces, "
      << num_edges(mesh) << " edges (" << interior_edges << " interior), " << report.components.size()
      << (report.components.size() == 1 ? " component\n" : " components\n");
  if(!order.source_faces.empty()) {
    const std::size_t file_faces = order.source_faces.back() + 1;
    std::size_t split = 0;
    for(std::size_t t = 0; t < order.source_faces.size(); ++t)
      split += (t == 0 || order.source_faces[t] != order.source_faces[t - 1]) &&
               t + 1 < order.source_faces.size() && order.source_faces[t + 1] == order.source_faces[t];
    out << "triangulated: " << split << " of the file's " << file_faces << " faces had more than three vertices, "
        << order.source_faces.size() << " triangles\n";
  }
  const std::size_t max_lines = 10;
  for(std::size_t c = 0; c < report.components.size() && c < max_lines; ++c) {
    const TC::Component_report& r = report.components[c];
    out << "  component " << c << ": " << r.number_of_faces << " faces, chi = " << r.euler_characteristic
        << ", genus " << r.genus << ", " << r.number_of_boundary_loops << " boundary loop"
        << (r.number_of_boundary_loops == 1 ? "" : "s") << ", vertex index sum " << r.vertex_index_sum << "\n";
  }
  if(report.components.size() > max_lines)
    out << "  ... and " << report.components.size() - max_lines << " more components\n";
  out << "singularities: " << singularities.size()
      << (o.singularities.empty() ? std::string() : " (from " + o.singularities + ")")
      << (o.boundary_indices.empty() ? std::string() : "; boundary indices from " + o.boundary_indices) << "; n = " << o.n
      << "; weights " << o.weights_name << "\n";
  out << "energy: " << std::setprecision(10) << report.energy;
  if(!guides.empty())
    out << " + guidance " << report.guidance_energy << " = " << report.energy + report.guidance_energy;
  if(!report.loops.empty() || !report.constraints.empty())
    out << " (with the integers rounded one by one: " << report.rounding_energy << ")";
  out << "\n";
  out << "max residual: vertices " << scientific(report.max_vertex_residual) << ", loops "
      << scientific(report.max_loop_residual);
  if(!report.constraints.empty())
    out << ", constraints " << scientific(report.max_constraint_residual);
  out << "\n";
  if(!guides.empty()) {
    double worst = 0;
    for(const TC::Guidance_report& g : report.guidance)
      worst = (std::max)(worst, std::abs(g.mismatch));
    out << "guidance: " << guides.size() << " face" << (guides.size() == 1 ? "" : "s") << " from " << o.guidance
        << ", weight " << o.guidance_weight << "; guidance energy " << report.guidance_energy
        << ", largest angle to a guide " << fixed(worst, 6) << " rad\n";
  }
  if(!constraints.empty() || o.align_boundary || !guides.empty()) {
    std::string parts;
    auto part = [&](const std::string& p) { parts += (parts.empty() ? "" : "; ") + p; };
    if(!constraints.empty())
      part(std::to_string(constraints.size()) + (constraints.size() == 1 ? " face" : " faces") + " from " +
           o.constraints);
    if(o.align_boundary)
      part("aligned with the boundary");
    if(!guides.empty())
      part(std::to_string(guides.size()) + " guided");
    out << "constraints: " << parts << "; " << report.constraints.size()
        << (report.constraints.size() == 1 ? " path" : " paths")
        << " between constrained or guided faces, their integers chosen with the loops'\n";
  }
  if(report.loops.empty()) {
    out << "loops: none (no generator, no boundary loop)\n";
  } else {
    std::size_t boundary = 0, generators = 0;
    for(const TC::Loop_report& l : report.loops)
      (l.kind == TC::Loop_kind::boundary ? boundary : generators) += 1;
    out << "loops: " << boundary << " boundary, " << generators << " generators; integers "
        << (report.integers_proven_optimal ? "proven optimal" : "chosen by a heuristic (not proven optimal)")
        << "\n";
    const std::size_t max_loops = 20;
    for(std::size_t l = 0; l < report.loops.size() && l < max_loops; ++l) {
      const TC::Loop_report& r = report.loops[l];
      out << "  loop " << l << " (component " << r.component << "): ";
      if(r.kind == TC::Loop_kind::boundary)
        out << "boundary, index " << r.index;
      else
        out << "generator, period " << r.period << " (holonomy 2pi*" << r.period << "/" << o.n << ")";
      out << (r.prescribed ? " (prescribed)" : "") << ", residual " << scientific(r.residual) << "\n";
    }
    if(report.loops.size() > max_loops)
      out << "  ... and " << report.loops.size() - max_loops << " more loops\n";
  }
  std::error_code ec;
  const std::filesystem::path connection_path = std::filesystem::absolute(o.connection, ec);
  const std::filesystem::path field_path = std::filesystem::absolute(o.field, ec);
  out << "connection: " << connection_path.string() << " (" << interior_edges << " interior edges)\n";
  out << "field: " << field_path.string() << " (" << num_faces(mesh) << " faces)\n";
  out << "time: read " << fixed(t_read, 3) << " s, set-up " << fixed(t_setup, 3) << " s, solve "
      << fixed(t_solve, 3) << " s, write " << fixed(t_write, 3) << " s\n";
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  Options options;
  try {
    options = parse_arguments(argc, argv);
  } catch(const Usage_error& e) {
    return fail(e.what(), 2);
  } catch(const std::exception& e) {
    return fail(e.what(), 2);
  }
  if(options.help) {
    std::cout << usage_text;
    return 0;
  }
  if(options.version) {
#ifndef TC_VERSION
#define TC_VERSION "unknown"
#endif
    std::cout << program << " " << TC_VERSION << " (CGAL " << CGAL_VERSION_STR << ", Eigen " << EIGEN_WORLD_VERSION
              << "." << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION << ", sparse solver "
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
              << "CHOLMOD " << CHOLMOD_MAIN_VERSION << "." << CHOLMOD_SUB_VERSION << "." << CHOLMOD_SUBSUB_VERSION
#else
              << "Eigen SimplicialLDLT"
#endif
              << ")\n";
    return 0;
  }
  Progress_printer progress(options.progress || stderr_is_terminal());
  try {
    return run(options, progress);
  } catch(const TC::Invalid_input& e) {
    progress.end_line();
    return fail(e.what(), 1);
  } catch(const std::bad_alloc&) {
    progress.end_line();
    return fail("out of memory", 1);
  } catch(const std::exception& e) {
    progress.end_line();
    return fail(e.what(), 1);
  } catch(...) {
    progress.end_line();
    return fail("unexpected error", 1);
  }
}
