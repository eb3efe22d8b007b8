// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// The command line of the program trivial_connections (trivial_connections.cpp): its help and version
// texts, its options and their parsing, and what it prints on stderr (progress lines, the error line).
// Included by that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_COMMAND_LINE_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_COMMAND_LINE_H

#include <CGAL/Trivial_connections/Progress.h>
#include <CGAL/Trivial_connections/feature_alignment.h>
#include <CGAL/Trivial_connections/parameters.h>
#include <CGAL/version.h>

#include <Eigen/Core>
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace trivial_connections_program {

inline const char* const program = "trivial_connections";

inline const char* const usage_text =
  "Usage: trivial_connections MESH [--triangulate] [--repair] [--write-mesh OUT] [--singularities FILE]\n"
  "                           [--boundary-indices FILE]\n"
  "                           [--constraints FILE] [--align-boundary] [--align-features [DEGREES]]\n"
  "                           [--feature-lines OUT] [--write-constraints OUT] [--guidance FILE]\n"
  "                           [--guidance-weight MU] [--n N] [--weights hodge|unit]\n"
  "                           [--connection OUT] [--field OUT] [--vtk OUT] [--ply OUT]\n"
  "                           [--singularity-points OUT] [--streamlines OUT] [--streamline-seeds K]\n"
  "                           [--auto] [--no-refine] [--align-curvature] [--alignment-strength S]\n"
  "                           [--refine] [--cancel-pairs] [--write-singularities OUT]\n"
  "                           [--quad-mesh OUT.obj (--quad-size H | --target-faces N)\n"
  "                            [--quad-scale-smoothness S] [--no-untangle] [--quad-cone-modes W]]\n"
  "                            [--progress] [--error-codes]\n"
  "                           [--help] [--version]\n"
  "\n"
  "Computes the trivial connection closest to Levi-Civita on a triangle mesh, with the prescribed\n"
  "singularity indices at vertices, and the n-direction field it defines.\n"
  "\n"
  "  MESH                  triangle mesh: .off, .obj, .ply, .stl or .ts (oriented 2-manifold, boundary\n"
  "                        allowed)\n"
  "  --triangulate         split faces of more than three vertices into triangles (CGAL's PMP); face\n"
  "                        indices (--constraints, --guidance, --field) then number the triangles: those of\n"
  "                        a face are consecutive, in file order. Without it such faces are an error.\n"
  "  --repair              repair the mesh with CGAL's Polygon Mesh Processing before the solve: duplicate\n"
  "                        points merged, degenerate and duplicate faces removed, faces oriented consistently,\n"
  "                        non-manifold vertices split, borders stitched, polygons triangulated; a line\n"
  "                        'repaired: ...' says what changed. Vertex and face indices (input files, --field)\n"
  "                        then number the repaired mesh (--write-mesh writes it); unchanged when nothing was\n"
  "                        repaired. Without it such meshes are an error.\n"
  "  --write-mesh OUT      the mesh the field is on (after --triangulate or --repair), as an OFF file\n"
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
  "                        there, as one of its N directions. Faces that touch are linked the short way\n"
  "                        (rounded integers, almost no cost); each further cluster of touching faces of\n"
  "                        a component adds one free integer, chosen with the loop integers.\n"
  "  --align-features [DEGREES]  pin every face beside a feature curve (edges whose faces' normals differ by\n"
  "                        more than DEGREES, default 30; the value is taken only if it is a number) to the\n"
  "                        curve's direction there (a line fitted to the curve, not each jagged edge). The\n"
  "                        faces of --constraints keep their targets; with --align-boundary the boundary faces\n"
  "                        follow the boundary. A mesh without sharp edge gets a note and no pin.\n"
  "  --feature-lines OUT   the sharp edges of the feature curves as legacy VTK lines (with --align-features;\n"
  "                        scripts/render_field.py --features OUT draws them)\n"
  "  --write-constraints OUT  the directional constraints used (the file's and the features'), in the\n"
  "                        --constraints format\n"
  "  --align-boundary      the field follows the boundary on every boundary face: along its border edge\n"
  "                        (the longer one when it has two); for N = 4, tangent and normal to it.\n"
  "  --guidance FILE       soft guidance, lines 'f x y z' as for --constraints: the solve minimises the\n"
  "                        energy plus MU times the sum over these faces of the squared angle between the\n"
  "                        field and the guide (modulo 2pi/N), still with exactly the given singularities.\n"
  "  --guidance-weight MU  the weight MU > 0 of the guidance (default 1)\n"
  "  --auto                place the singularities automatically: those of the globally smoothest N-direction\n"
  "                        field (Knoeppel et al. 2013), then refine them to a local minimum of the trivial\n"
  "                        connection's energy (moves to neighbouring vertices and cancellations of opposite\n"
  "                        pairs), and compute the trivial connection with exactly them. With --singularities,\n"
  "                        the file's singularities are kept and the others placed around them (the automatic\n"
  "                        ones nearest to them give way).\n"
  "  --no-refine           with --auto, keep the placed singularities: exactly those of the smoothest field\n"
  "                        (of the curvature-aligned field with --align-curvature); the fastest run\n"
  "  --align-curvature     follow the principal curvature directions (N even): with --auto the placement is\n"
  "                        that of the curvature-aligned field, and the trivial connection is guided (weight\n"
  "                        --guidance-weight) towards them on 64 spread faces of strong anisotropy.\n"
  "  --alignment-strength S  how closely the aligned placement follows the curvature (default 100)\n"
  "  --refine              move the singularities of --singularities to neighbouring vertices while that\n"
  "                        lowers the energy. Implied by --auto (with --cancel-pairs; the file's singularities\n"
  "                        then stay where they are)\n"
  "  --cancel-pairs        with --refine, opposite singularities may also cancel (a unit of 1/N each, at any\n"
  "                        distance in a component) when that lowers the energy. Implied by --auto\n"
  "  --write-singularities OUT  the singularities used, in the --singularities format (edit, run again)\n"
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
  "  --quad-mesh OUT      a quad mesh of the cross field (needs --n 4), as an OBJ file of quads: the integer\n"
  "                        iso-lines of a seamless parametrisation whose gradients follow the field, with\n"
  "                        quad vertices of valence 4 - 4k exactly at the singularities of index k. A line\n"
  "                        'quad mesh: ...' reports the quads, valence errors, folded triangles of the map,\n"
  "                        flipped quads and the Hausdorff distance to the input over H. With\n"
  "                        --align-features the sharp edges are put on iso-lines (quad edges follow them);\n"
  "                        borders always are: a mesh with border needs --align-boundary. With --auto\n"
  "                        --align-features, the singularities placed closer than H to a sharp edge are\n"
  "                        first moved to the nearest vertex at least H from every one, unless the quads\n"
  "                        have fewer flaws without the move (both made then; reported).\n"
  "  --quad-size H         the quads' edge length, in the mesh's unit (with --quad-mesh)\n"
  "  --target-faces N      instead of --quad-size: about N quads (H = sqrt(area / N))\n"
  "  --quad-scale-smoothness S  (with --quad-mesh) scale the field per face first, so that it is closer\n"
  "                        to a gradient; its log varies over about sqrt(S) H (0.1: fewer folds near\n"
  "                        singularities on fine organic meshes). Not given: when the quads have flaws\n"
  "                        (folded or degenerate triangles, valence errors), they are made again with\n"
  "                        S = 0.1 and kept if they have fewer (reported). 0: never scaled\n"
  "  --no-untangle         (with --quad-mesh) keep the rounded map as it is: by default a map with\n"
  "                        folded or degenerate triangles is moved out of them, its integers kept\n"
  "                        (a barrier energy; kept when it has fewer; reported)\n"
  "  --quad-cone-modes W   (with --quad-mesh) W > 0: make the map wind around every singular vertex as\n"
  "                        its index asks (quad_cone_mode_weight: the wrongly winding harmonics of the\n"
  "                        singular one-rings penalised with weight W, the continuous map untangled\n"
  "                        first and the integers rounded against it). Not given: tried with W = 30\n"
  "                        when the quads have wrongly wound singular vertices, kept if they have\n"
  "                        fewer flaws (reported). 0: never\n"
  "  --error-codes         the error line names the error code: 'trivial_connections: error [CODE]: ...'\n"
  "                        (CODE: an error code of the library, usage_error, out_of_memory or internal_error)\n"
  "  --progress            print each phase and the elapsed time to stderr (the default when stderr\n"
  "                        is a terminal)\n"
  "  --help, -h            print this help and exit\n"
  "  --version             print the version (and those of CGAL, Eigen and the sparse solver) and exit\n"
  "\n"
  "The integers of the homology generators and boundary loops are chosen to minimise the energy.\n"
  "Both output files are written only if everything succeeded. Exit status: 0 success, 1 input error,\n"
  "2 usage error; errors are reported as one line on stderr.\n";

inline void print_version(std::ostream& out)
{
#ifndef TC_VERSION
#define TC_VERSION "unknown"
#endif
  out << program << " " << TC_VERSION << " (CGAL " << CGAL_VERSION_STR << ", Eigen " << EIGEN_WORLD_VERSION << "."
      << EIGEN_MAJOR_VERSION << "." << EIGEN_MINOR_VERSION << ", sparse solver "
#ifdef CGAL_TRIVIAL_CONNECTIONS_USE_CHOLMOD
      << "Eigen SimplicialLDLT or CHOLMOD " << CHOLMOD_MAIN_VERSION << "." << CHOLMOD_SUB_VERSION << "."
      << CHOLMOD_SUBSUB_VERSION << " by predicted cost"
#else
      << "Eigen SimplicialLDLT"
#endif
      << ")\n";
}

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
  bool repair = false;       // --repair
  bool error_codes = false;  // --error-codes
  std::string write_mesh;    // --write-mesh OUT
  std::string guidance;
  double guidance_weight = 1;
  int n = 1;
  CGAL::Trivial_connections::Weighting weighting = CGAL::Trivial_connections::Weighting::hodge_star;
  std::string weights_name = "hodge";
  std::string connection;
  std::string field;
  std::string vtk, ply, singularity_points, streamlines; // optional outputs for viewers
  std::size_t streamline_seeds = 100;
  // --auto sets refine and cancel_pairs too unless no_refine
  bool automatic = false, no_refine = false, align_curvature = false, refine = false, cancel_pairs = false;
  double alignment_strength = 100;
  std::string write_singularities;
  bool align_features = false;
  double feature_angle = CGAL::Trivial_connections::default_feature_angle_degrees; // --align-features DEGREES
  std::string feature_lines, write_constraints;
  std::string quad_mesh;     // --quad-mesh OUT
  double quad_size = 0;      // --quad-size H (0: not given)
  std::size_t target_faces = 0; // --target-faces N (0: not given)
  double quad_scale_smoothness = -1; // --quad-scale-smoothness S (-1: not given)
  bool no_untangle = false;  // --no-untangle
  double quad_cone_modes = -1; // --quad-cone-modes W (-1: not given)
};

using String_field = std::string Options::*;

// Parsers of the option values that are not kept as given: each stores the value or throws.
inline void parse_symmetry_order(Options& o, const std::string& text)
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
  o.n = trimmed.empty() ? 0 : std::stoi(trimmed);
  if(o.n < 1)
    throw Usage_error("--n must be at least 1 (got " + text + ")");
}

inline void parse_guidance_weight(Options& o, const std::string& text)
{
  char* end = nullptr;
  o.guidance_weight = std::strtod(text.c_str(), &end);
  if(end != text.c_str() + text.size() || !(o.guidance_weight > 0) || !std::isfinite(o.guidance_weight))
    throw Usage_error("--guidance-weight expects a positive finite number, got '" + text + "'");
}

inline void parse_quad_size(Options& o, const std::string& text)
{
  char* end = nullptr;
  o.quad_size = std::strtod(text.c_str(), &end);
  if(text.empty() || end != text.c_str() + text.size() || !(o.quad_size > 0) || !std::isfinite(o.quad_size))
    throw Usage_error("--quad-size expects a positive finite number, got '" + text + "'");
}

inline void parse_quad_scale_smoothness(Options& o, const std::string& text)
{
  char* end = nullptr;
  o.quad_scale_smoothness = std::strtod(text.c_str(), &end);
  if(text.empty() || end != text.c_str() + text.size() || !(o.quad_scale_smoothness >= 0) ||
     !std::isfinite(o.quad_scale_smoothness))
    throw Usage_error("--quad-scale-smoothness expects a non-negative finite number, got '" + text + "'");
}

inline void parse_quad_cone_modes(Options& o, const std::string& text)
{
  char* end = nullptr;
  o.quad_cone_modes = std::strtod(text.c_str(), &end);
  if(text.empty() || end != text.c_str() + text.size() || !(o.quad_cone_modes >= 0) || !std::isfinite(o.quad_cone_modes))
    throw Usage_error("--quad-cone-modes expects a non-negative finite number, got '" + text + "'");
}

inline void parse_target_faces(Options& o, const std::string& text)
{
  if(text.empty() || text.size() > 12 || text.find_first_not_of("0123456789") != std::string::npos ||
     std::stoull(text) == 0)
    throw Usage_error("--target-faces expects a positive integer, got '" + text + "'");
  o.target_faces = std::size_t(std::stoull(text));
}

inline void parse_alignment_strength(Options& o, const std::string& text)
{
  char* end = nullptr;
  o.alignment_strength = std::strtod(text.c_str(), &end);
  if(end != text.c_str() + text.size() || !(o.alignment_strength > 0) || !std::isfinite(o.alignment_strength))
    throw Usage_error("--alignment-strength expects a positive finite number, got '" + text + "'");
}

inline void parse_weights(Options& o, const std::string& text)
{
  if(text == "hodge")
    o.weighting = CGAL::Trivial_connections::Weighting::hodge_star;
  else if(text == "unit")
    o.weighting = CGAL::Trivial_connections::Weighting::unit;
  else
    throw Usage_error("unknown weights '" + text + "' (expected hodge or unit)");
  o.weights_name = text;
}

inline void parse_streamline_seeds(Options& o, const std::string& text)
{
  if(text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos || std::stoul(text) == 0)
    throw Usage_error("--streamline-seeds expects a positive integer, got '" + text + "'");
  o.streamline_seeds = std::stoul(text);
}

// Whether the whole text is a number as strtod reads it ("30", "12.5", "-4", "nan", "1e2"), for the optional value
// of --align-features
inline bool is_number(const std::string& text)
{
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

inline void parse_feature_angle(Options& o, const std::string& text)
{
  char* end = nullptr;
  o.feature_angle = std::strtod(text.c_str(), &end);
  if(text.empty() || end != text.c_str() + text.size() || !(o.feature_angle >= 0 && o.feature_angle <= 180))
    throw Usage_error("--align-features expects an angle in degrees between 0 and 180, got '" + text + "'");
}

// An option that takes a value: kept as given in `field`, or read by `parse`.
struct Valued_option
{
  const char* name;
  String_field field;
  void (*parse)(Options&, const std::string& text);
};

// The options that take a value. Each may be given once, as `--name value` or `--name=value`.
inline const std::array<Valued_option, 24> valued_options = {{
  {"--write-mesh", &Options::write_mesh, nullptr},
  {"--write-singularities", &Options::write_singularities, nullptr},
  {"--write-constraints", &Options::write_constraints, nullptr},
  {"--feature-lines", &Options::feature_lines, nullptr},
  {"--alignment-strength", nullptr, parse_alignment_strength},
  {"--singularities", &Options::singularities, nullptr},
  {"--boundary-indices", &Options::boundary_indices, nullptr},
  {"--constraints", &Options::constraints, nullptr},
  {"--guidance", &Options::guidance, nullptr},
  {"--connection", &Options::connection, nullptr},
  {"--field", &Options::field, nullptr},
  {"--vtk", &Options::vtk, nullptr},
  {"--ply", &Options::ply, nullptr},
  {"--singularity-points", &Options::singularity_points, nullptr},
  {"--streamlines", &Options::streamlines, nullptr},
  {"--guidance-weight", nullptr, parse_guidance_weight},
  {"--n", nullptr, parse_symmetry_order},
  {"--weights", nullptr, parse_weights},
  {"--streamline-seeds", nullptr, parse_streamline_seeds},
  {"--quad-mesh", &Options::quad_mesh, nullptr},
  {"--quad-size", nullptr, parse_quad_size},
  {"--target-faces", nullptr, parse_target_faces},
  {"--quad-scale-smoothness", nullptr, parse_quad_scale_smoothness},
  {"--quad-cone-modes", nullptr, parse_quad_cone_modes},
}};

inline bool same_file(const std::string& a, const std::string& b)
{
  std::error_code ec1, ec2;
  // absolute() first: weakly_canonical() leaves a relative path relative when its first element does not exist
  const std::filesystem::path pa = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ec1), ec1);
  const std::filesystem::path pb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, ec2), ec2);
  return !ec1 && !ec2 ? pa == pb : a == b;
}

// An output must not overwrite another output nor an input: checked before anything is read.
inline void check_outputs(const Options& o)
{
  std::vector<const std::string*> outputs = {&o.connection, &o.field};
  for(const std::string* extra : {&o.vtk, &o.ply, &o.singularity_points, &o.streamlines, &o.write_singularities,
                                  &o.feature_lines, &o.write_constraints, &o.write_mesh, &o.quad_mesh})
    if(!extra->empty())
      outputs.push_back(extra);
  for(std::size_t a = 0; a < outputs.size(); ++a)
    for(std::size_t b = a + 1; b < outputs.size(); ++b)
      if(same_file(*outputs[a], *outputs[b]))
        throw Usage_error("two outputs are the same file '" + *outputs[a] + "'");
  const std::pair<String_field, const char*> inputs[] = {{&Options::mesh, "input mesh"},
                                                         {&Options::singularities, "singularity file"},
                                                         {&Options::boundary_indices, "boundary index file"},
                                                         {&Options::constraints, "constraint file"},
                                                         {&Options::guidance, "guidance file"}};
  for(const std::string* out : outputs)
    for(const auto& [input, what] : inputs)
      if(!(o.*input).empty() && same_file(*out, o.*input))
        throw Usage_error("the output '" + *out + "' would overwrite the " + what);
}

using Seen_options = std::array<bool, valued_options.size()>;

// Reads the option args[i] and its value (`--name=value`, or `--name value`: then `i` moves to the value).
inline void read_valued_option(const std::vector<std::string>& args, std::size_t& i, Seen_options& seen, Options& o)
{
  const std::string& a = args[i];
  std::string name = a, value;
  bool has_value = false;
  const std::string::size_type eq = a.find('=');
  if(a.compare(0, 2, "--") == 0 && eq != std::string::npos) {
    name = a.substr(0, eq);
    value = a.substr(eq + 1);
    has_value = true;
  }
  const auto option = std::find_if(valued_options.begin(), valued_options.end(),
                                   [&](const Valued_option& v) { return name == v.name; });
  if(option == valued_options.end())
    throw Usage_error("unknown option '" + name + "' (see --help)");
  bool& seen_option = seen[std::size_t(option - valued_options.begin())];
  if(seen_option)
    throw Usage_error("option " + name + " given twice");
  seen_option = true;
  if(!has_value) {
    if(i + 1 >= args.size())
      throw Usage_error("option " + name + " needs a value (see --help)");
    value = args[++i];
  }
  if(value.empty())
    throw Usage_error("option " + name + " needs a non-empty value");
  if(option->field)
    o.*(option->field) = value;
  else
    option->parse(o, value);
}

// The first `--help`, `-h` or `--version` wins over everything else, even over errors.
inline Options parse_arguments(int argc, char** argv)
{
  Options o;
  const std::vector<std::string> args(argv + 1, argv + argc);
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
  Seen_options seen{};
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if(a == "--progress") {
      o.progress = true;
      continue;
    }
    if(a == "--triangulate" || a == "--align-boundary" || a == "--auto" || a == "--no-refine" ||
       a == "--align-curvature" || a == "--refine" || a == "--cancel-pairs" || a == "--repair" ||
       a == "--error-codes" || a == "--no-untangle") {
      bool& flag = a == "--triangulate"       ? o.triangulate
                   : a == "--repair"          ? o.repair
                   : a == "--error-codes"     ? o.error_codes
                   : a == "--align-boundary"  ? o.align_boundary
                   : a == "--auto"            ? o.automatic
                   : a == "--no-refine"       ? o.no_refine
                   : a == "--align-curvature" ? o.align_curvature
                   : a == "--refine"          ? o.refine
                   : a == "--no-untangle"     ? o.no_untangle
                                              : o.cancel_pairs;
      if(flag)
        throw Usage_error("option " + a + " given twice");
      flag = true;
      continue;
    }
    if(a == "--align-features" || a.compare(0, 17, "--align-features=") == 0) {
      if(o.align_features)
        throw Usage_error("option --align-features given twice");
      o.align_features = true;
      if(a.size() > 16) // --align-features=DEGREES
        parse_feature_angle(o, a.substr(17));
      else if(i + 1 < args.size() && is_number(args[i + 1])) // an optional value: only a number is taken
        parse_feature_angle(o, args[++i]);
      continue;
    }
    if(a.size() > 1 && a[0] == '-' && a != "-") {
      read_valued_option(args, i, seen, o);
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
  if(o.align_curvature && o.n % 2 != 0)
    throw Usage_error("--align-curvature needs an even --n (a principal direction has no sign)");
  if(o.align_curvature && !o.guidance.empty())
    throw Usage_error("--align-curvature and --guidance cannot be combined (both choose the guided faces)");
  if(o.no_refine && !o.automatic)
    throw Usage_error("--no-refine is an option of --auto");
  if(o.no_refine && (o.refine || o.cancel_pairs))
    throw Usage_error(std::string("--no-refine and ") + (o.refine ? "--refine" : "--cancel-pairs") +
                      " contradict each other (--no-refine keeps the placed singularities as they are)");
  if(o.cancel_pairs && !o.refine && !o.automatic)
    throw Usage_error("--cancel-pairs is an option of --refine (or of --auto, which refines with it)");
  // --auto refines by default: the refined field's energy is never higher, and it usually has fewer singularities
  if(o.automatic && !o.no_refine)
    o.refine = o.cancel_pairs = true;
  if(!o.feature_lines.empty() && !o.align_features)
    throw Usage_error("--feature-lines is an option of --align-features");
  if(o.quad_mesh.empty() && (o.quad_size > 0 || o.target_faces > 0))
    throw Usage_error(std::string(o.quad_size > 0 ? "--quad-size" : "--target-faces") + " is an option of --quad-mesh");
  if(o.quad_mesh.empty() && o.quad_scale_smoothness >= 0)
    throw Usage_error("--quad-scale-smoothness is an option of --quad-mesh");
  if(o.quad_mesh.empty() && o.no_untangle)
    throw Usage_error("--no-untangle is an option of --quad-mesh");
  if(o.quad_mesh.empty() && o.quad_cone_modes >= 0)
    throw Usage_error("--quad-cone-modes is an option of --quad-mesh");
  if(!o.quad_mesh.empty() && o.n != 4)
    throw Usage_error("--quad-mesh needs a cross field: --n 4 (got --n " + std::to_string(o.n) + ")");
  if(!o.quad_mesh.empty() && (o.quad_size > 0) == (o.target_faces > 0))
    throw Usage_error(o.quad_size > 0 ? "--quad-size and --target-faces cannot be combined (give one)"
                                      : "--quad-mesh needs --quad-size H or --target-faces N");
  const std::string stem = std::filesystem::path(o.mesh).stem().string();
  if(o.connection.empty())
    o.connection = stem + ".connection.txt";
  if(o.field.empty())
    o.field = stem + ".field.txt";
  check_outputs(o);
  return o;
}

inline std::string one_line(std::string s)
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
  // `detail`: what the phase did, after its time ("16 iterations, 36 singularities")
  void end(const char* phase, const std::string& detail = std::string())
  {
    if(!m_enabled)
      return;
    const auto start = m_starts.find(phase);
    if(start == m_starts.end())
      return;
    const std::string took = seconds(start->second) + " s" + (detail.empty() ? "" : "; " + detail);
    m_starts.erase(start);
    if(m_open && m_open_phase == phase) {
      m_open = false;
      print(" done (" + took + ")\n");
    } else { // another phase ran inside this one
      end_line();
      print("[" + seconds(m_start) + " s] " + phase + " done (" + took + ")\n");
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
  CGAL::Trivial_connections::Progress_callback callback()
  {
    if(!m_enabled)
      return CGAL::Trivial_connections::Progress_callback();
    return [this](CGAL::Trivial_connections::Phase p, double fraction) {
      if(fraction <= 0)
        begin(CGAL::Trivial_connections::phase_name(p));
      else if(fraction >= 1)
        end(CGAL::Trivial_connections::phase_name(p));
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

inline bool stderr_is_terminal()
{
#if defined(__unix__) || defined(__APPLE__)
  return ::isatty(2) == 1;
#else
  return false;
#endif
}

inline int fail(const std::string& message, int status, const char* code = nullptr)
{
  std::cerr << program << ": error" << (code ? std::string(" [") + code + "]" : std::string()) << ": "
            << one_line(message) << std::endl;
  return status;
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_COMMAND_LINE_H
