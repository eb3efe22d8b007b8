// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Tests of the file formats (singularities, connection, field), of the atomic writes and of the mesh
// reader (validation with precise errors, input order kept) on Surface_mesh and Polyhedron_3.
// Self-contained: the meshes are written by the tests to a temporary directory.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <CGAL/Trivial_connections/IO/atomic_file.h>
#include <CGAL/Trivial_connections/IO/connection_file.h>
#include <CGAL/Trivial_connections/IO/face_directions.h>
#include <CGAL/Trivial_connections/IO/field_file.h>
#include <CGAL/Trivial_connections/IO/read_triangle_mesh.h>
#include <CGAL/Trivial_connections/IO/singularities.h>
#include <CGAL/Trivial_connections/IO/viewer_files.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace TC = CGAL::Trivial_connections;
namespace fs = std::filesystem;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using Surface_mesh = CGAL::Surface_mesh<Point>;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;

// A fresh directory under the system's temporary directory, removed at the end of the test.
class Temp_dir
{
public:
  Temp_dir()
  {
    static std::atomic<int> counter{0};
    std::mt19937_64 random(std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()));
    m_path = fs::temp_directory_path() /
             ("tc_test_io_" + std::to_string(random() % 1000000000ull) + "_" + std::to_string(counter++));
    fs::create_directories(m_path);
  }
  ~Temp_dir()
  {
    std::error_code ec;
    fs::remove_all(m_path, ec);
  }
  const fs::path& path() const { return m_path; }
  std::string file(const std::string& name) const { return (m_path / name).string(); }
  std::string write(const std::string& name, const std::string& content) const
  {
    std::ofstream os(file(name), std::ios::binary);
    os << content;
    return file(name);
  }
  std::vector<std::string> entries() const
  {
    std::vector<std::string> out;
    for(const auto& e : fs::directory_iterator(m_path))
      out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }

private:
  fs::path m_path;
};

std::string slurp(const std::string& path)
{
  std::ifstream is(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(is), std::istreambuf_iterator<char>());
}

// Runs `f`, expects Invalid_input with `code` and a message containing every string of `parts`.
template <class F>
TC::Invalid_input expect_error(F f, TC::Error_code code, const std::vector<std::string>& parts)
{
  try {
    f();
  } catch(const TC::Invalid_input& e) {
    EXPECT_EQ(TC::error_code_name(e.code()), std::string(TC::error_code_name(code))) << "message: " << e.what();
    for(const std::string& p : parts)
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
        << "message '" << e.what() << "' does not contain '" << p << "'";
    return e;
  }
  ADD_FAILURE() << "no Invalid_input thrown (expected " << TC::error_code_name(code) << ")";
  return TC::Invalid_input(code, "not thrown");
}

// A call that reads `content`, written to `dir/name`, into a fresh Mesh (for expect_error).
template <class Mesh>
auto reader_of(Temp_dir& dir, const std::string& name, const std::string& content)
{
  const std::string path = dir.write(name, content);
  return [path] {
    Mesh mesh;
    TC::read_triangle_mesh(path, mesh);
  };
}

std::vector<std::pair<std::size_t, TC::Singularity_index>> parse(const std::string& text,
                                                                 std::size_t nv = TC::unchecked_vertex_count)
{
  std::istringstream is(text);
  return TC::read_singularities(is, "test.sing", nv);
}

// ---------------------------------------------------------------------------------------------------
// Singularity files

TEST(IoSingularities, ParsesIntegersFractionsCommentsAndBlankLines)
{
  const auto s = parse("# header comment\n"
                       "\n"
                       "0 1\n"
                       "   12\t-1   # trailing comment\n"
                       "7 1/4\n"
                       "3 -3/6\r\n"
                       "  # indented comment\n"
                       "40 +2\n"
                       "5 0\n");
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s[0].first, 0u);
  EXPECT_EQ(s[0].second, TC::Singularity_index(1));
  EXPECT_EQ(s[1].first, 12u);
  EXPECT_EQ(s[1].second, TC::Singularity_index(-1));
  EXPECT_EQ(s[2].first, 7u);
  EXPECT_EQ(s[2].second, TC::Singularity_index(1, 4));
  EXPECT_EQ(s[3].first, 3u);
  EXPECT_EQ(s[3].second, TC::Singularity_index(-1, 2));
  EXPECT_EQ(s[4].first, 40u);
  EXPECT_EQ(s[4].second, TC::Singularity_index(2));
  EXPECT_EQ(s[5].second, TC::Singularity_index(0));
}

TEST(IoSingularities, EmptyInputGivesNoSingularity)
{
  EXPECT_TRUE(parse("").empty());
  EXPECT_TRUE(parse("# only a comment\n\n   \n").empty());
}

TEST(IoSingularities, MalformedLinesAreParseErrorsWithTheLine)
{
  const TC::Error_code pe = TC::Error_code::parse_error;
  expect_error([] { parse("0 1\n5\n"); }, pe, {"test.sing:2:", "1 field"});                 // missing field
  expect_error([] { parse("0 1\n\n5 1 2\n"); }, pe, {"test.sing:3:", "3 fields"});          // extra field
  expect_error([] { parse("# c\nabc 1\n"); }, pe, {"test.sing:2:", "abc"});                 // not an integer
  expect_error([] { parse("1.5 1\n"); }, pe, {"test.sing:1:", "1.5"});                      // not an integer
  expect_error([] { parse("0 1\n-3 1\n"); }, pe, {"test.sing:2:", "negative", "-3"});       // negative vertex
  expect_error([] { parse("4 1/x\n"); }, pe, {"test.sing:1:", "1/x"});                      // bad fraction
  expect_error([] { parse("4 1/2/3\n"); }, pe, {"test.sing:1:"});                           // bad fraction
  expect_error([] { parse("4 1/-2\n"); }, pe, {"test.sing:1:"});                            // signed denominator
  expect_error([] { parse("4 0.5\n"); }, pe, {"test.sing:1:", "0.5"});                      // not rational syntax
  expect_error([] { parse("0 1\n1 1\n4 3/0\n"); }, pe, {"test.sing:3:", "zero denominator"}); // zero denominator
  expect_error([] { parse("99999999999999999999999 1\n"); }, pe, {"test.sing:1:", "too large"});
}

TEST(IoSingularities, DuplicateVertexNamesTheVertexAndBothLines)
{
  const TC::Invalid_input e =
    expect_error([] { parse("# two +1\n17 1\n3 1\n\n17 1/2\n"); }, TC::Error_code::duplicate_singularity,
                 {"test.sing:5:", "vertex 17", "lines 2 and 5"});
  EXPECT_EQ(e.where(), 17u);
}

TEST(IoSingularities, VertexRangeIsCheckedWhenTheVertexCountIsGiven)
{
  EXPECT_EQ(parse("9 1\n", 10).size(), 1u);
  const TC::Invalid_input e =
    expect_error([] { parse("0 1\n10 1\n", 10); }, TC::Error_code::invalid_vertex,
                 {"test.sing:2:", "vertex 10", "10 vertices"});
  EXPECT_EQ(e.where(), 10u);
}

TEST(IoSingularities, FileOverloadReportsUnreadableFiles)
{
  Temp_dir dir;
  const std::string path = dir.write("s.txt", "1 1\n2 1\n");
  EXPECT_EQ(TC::read_singularities(path).size(), 2u);
  expect_error([&] { TC::read_singularities(dir.file("missing.txt")); }, TC::Error_code::io_error, {"missing.txt"});
  expect_error([&] { TC::read_singularities(dir.path().string()); }, TC::Error_code::io_error, {"directory"});
  const std::string bad = dir.write("bad.txt", "1 1\n2\n");
  expect_error([&] { TC::read_singularities(bad); }, TC::Error_code::parse_error, {bad + ":2:"});
}

TEST(IoSingularities, WriteThenReadRoundTrips)
{
  const std::vector<std::pair<std::size_t, TC::Singularity_index>> s = {
    {3, TC::Singularity_index(1)}, {0, TC::Singularity_index(-1, 4)}, {1000000, TC::Singularity_index(5, 2)}};
  std::ostringstream os;
  TC::write_singularities(os, s);
  const auto back = parse(os.str());
  ASSERT_EQ(back.size(), s.size());
  for(std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(back[i].first, s[i].first);
    EXPECT_EQ(back[i].second, s[i].second);
  }
}

// ---------------------------------------------------------------------------------------------------
// Small meshes built in the tests

// An octahedron: closed, 6 vertices, 8 faces oriented outwards.
const std::vector<Point> octahedron_points = {Point(1, 0, 0),  Point(-1, 0, 0), Point(0, 1, 0),
                                              Point(0, -1, 0), Point(0, 0, 1),  Point(0, 0, -1)};
const std::vector<std::vector<std::size_t>> octahedron_faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                                {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};

// A bordered grid of (n x n) squares split in two triangles, with an unused vertex inserted at `unused`.
void grid_soup(int n, std::size_t unused, std::vector<Point>& points, std::vector<std::vector<std::size_t>>& polys)
{
  points.clear();
  polys.clear();
  std::vector<std::size_t> id((n + 1) * (n + 1));
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i) {
      if(points.size() == unused)
        points.push_back(Point(-5, -5, 3)); // used by no face
      id[std::size_t(j * (n + 1) + i)] = points.size();
      points.push_back(Point(i, j, 0.1 * std::sin(i + 2. * j)));
    }
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i) {
      const std::size_t a = id[std::size_t(j * (n + 1) + i)], b = id[std::size_t(j * (n + 1) + i + 1)];
      const std::size_t c = id[std::size_t((j + 1) * (n + 1) + i + 1)], d = id[std::size_t((j + 1) * (n + 1) + i)];
      polys.push_back({a, b, c});
      polys.push_back({a, c, d});
    }
}

std::string to_off(const std::vector<Point>& points, const std::vector<std::vector<std::size_t>>& polys)
{
  std::ostringstream os;
  os.precision(17);
  os << "OFF\n" << points.size() << ' ' << polys.size() << " 0\n";
  for(const Point& p : points)
    os << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for(const auto& f : polys) {
    os << f.size();
    for(std::size_t v : f)
      os << ' ' << v;
    os << '\n';
  }
  return os.str();
}

// ---------------------------------------------------------------------------------------------------
// Connection and field files

template <class Mesh>
void check_connection_round_trip()
{
  using GT = boost::graph_traits<Mesh>;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  grid_soup(3, 5, points, polygons);
  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::triangle_soup_to_mesh(points, polygons, mesh);

  std::map<typename GT::vertex_descriptor, std::size_t> vindex;
  for(std::size_t i = 0; i < order.vertices.size(); ++i)
    vindex[order.vertices[i]] = i;
  const auto vim = boost::make_assoc_property_map(vindex);

  // an antisymmetric "connection" with awkward values, and per-edge weights
  std::map<typename GT::halfedge_descriptor, double> xs;
  std::map<std::pair<std::size_t, std::size_t>, double> expected_x, expected_w;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-10, 10);
  for(auto e : edges(mesh)) {
    const auto h = halfedge(e, mesh);
    const double value = uniform(random) / 3.;
    xs[h] = value;
    xs[opposite(h, mesh)] = -value;
  }
  auto weight_of = [&](typename GT::edge_descriptor e) {
    const auto h = halfedge(e, mesh);
    return 1. / 7. + double(vindex[source(h, mesh)] + vindex[target(h, mesh)]);
  };
  std::size_t interior = 0;
  for(auto e : edges(mesh)) {
    if(CGAL::is_border(e, mesh))
      continue;
    ++interior;
    const auto h = halfedge(e, mesh);
    const std::size_t i = vindex[source(h, mesh)], j = vindex[target(h, mesh)];
    expected_x[{i, j}] = xs[h];
    expected_x[{j, i}] = -xs[h];
    expected_w[{i, j}] = expected_w[{j, i}] = weight_of(e);
  }

  std::ostringstream os;
  TC::write_connection(os, mesh, boost::make_assoc_property_map(xs), vim, weight_of);
  std::istringstream is(os.str());
  const auto back = TC::read_connection(is, "c.txt");
  EXPECT_EQ(back.size(), interior); // border edges are not written
  for(const auto& entry : back) {
    const std::size_t i = entry.first.first, j = entry.first.second;
    EXPECT_LT(i, j);
    ASSERT_EQ(expected_x.count({i, j}), 1u) << i << " " << j << " is not an interior edge";
    const std::pair<std::size_t, std::size_t> key(i, j);
    EXPECT_EQ(entry.second.x, expected_x[key]) << "not exact"; // exact round trip
    EXPECT_EQ(entry.second.w, expected_w[key]) << "not exact";
  }

  // the weight may also come from an object with a member weight(e), e.g. the solver
  struct Weights
  {
    decltype(weight_of) f;
    double weight(typename GT::edge_descriptor e) const { return f(e); }
  } weights{weight_of};
  std::ostringstream os2;
  TC::write_connection(os2, mesh, boost::make_assoc_property_map(xs), vim, weights);
  EXPECT_EQ(os.str(), os2.str());
}

TEST(IoConnectionFile, RoundTripSurfaceMesh) { check_connection_round_trip<Surface_mesh>(); }
TEST(IoConnectionFile, RoundTripPolyhedron) { check_connection_round_trip<Polyhedron>(); }

TEST(IoConnectionFile, ReaderReportsMalformedLines)
{
  auto read = [](const std::string& text) {
    std::istringstream is(text);
    return TC::read_connection(is, "c.txt");
  };
  const auto ok = read("# header\n0 1 0.5 2\n\n2 1 -1e-3 0.25 # comment\n");
  ASSERT_EQ(ok.size(), 2u);
  EXPECT_EQ((ok.at({2, 1}).x), -1e-3);
  EXPECT_EQ((ok.at({2, 1}).w), 0.25);
  const TC::Error_code pe = TC::Error_code::parse_error;
  expect_error([&] { read("0 1 0.5 2\n0 1\n"); }, pe, {"c.txt:2:"});
  expect_error([&] { read("0 1 abc 2\n"); }, pe, {"c.txt:1:", "abc"});
  expect_error([&] { read("0 1 0.5 2 7\n"); }, pe, {"c.txt:1:"});
  expect_error([&] { read("0 1 0.5 2\n\n1 0 0.5 2\n"); }, pe, {"c.txt:3:", "twice", "lines 1 and 3"});
}

template <class Mesh>
void check_field_round_trip()
{
  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::triangle_soup_to_mesh(octahedron_points, octahedron_faces, mesh);
  std::map<typename boost::graph_traits<Mesh>::face_descriptor, Vector> field;
  std::vector<Vector> expected;
  for(std::size_t f = 0; f < order.faces.size(); ++f) {
    const Vector v(std::cos(0.1 * double(f)) / 3., std::sin(0.1 * double(f)) / 3., 1e-300 * double(f) - 1. / 7.);
    field[order.faces[f]] = v;
    expected.push_back(v);
  }
  std::ostringstream os;
  TC::write_field(os, mesh, boost::make_assoc_property_map(field));
  std::istringstream is(os.str());
  const auto back = TC::read_field(is, "f.txt");
  ASSERT_EQ(back.size(), expected.size());
  for(std::size_t f = 0; f < back.size(); ++f) { // face-index order, exact
    EXPECT_EQ(back[f][0], expected[f].x());
    EXPECT_EQ(back[f][1], expected[f].y());
    EXPECT_EQ(back[f][2], expected[f].z());
  }
}

// The viewer files (VTK, PLY, singularity points) parsed back: the mesh, every direction of the n-field turned
// by 2 pi k / n about the face normal, the singularity indices; the PLY is also read by CGAL's own reader.
template <class Mesh>
void check_viewer_files()
{
  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::triangle_soup_to_mesh(octahedron_points, octahedron_faces, mesh);
  using face_descriptor = typename boost::graph_traits<Mesh>::face_descriptor;
  using vertex_descriptor = typename boost::graph_traits<Mesh>::vertex_descriptor;
  std::map<face_descriptor, Vector> field;
  std::vector<std::array<double, 3>> normals;
  const auto vpm = get(CGAL::vertex_point, mesh);
  for(face_descriptor f : faces(mesh)) { // a unit tangent vector: the first edge turned by 0.3 rad
    const auto h = halfedge(f, mesh);
    const Point a = get(vpm, source(h, mesh)), b = get(vpm, target(h, mesh)), c = get(vpm, target(next(h, mesh), mesh));
    Vector nrm = CGAL::cross_product(b - a, c - a);
    nrm = nrm / std::sqrt(nrm.squared_length());
    const Vector e = (b - a) / std::sqrt((b - a).squared_length());
    field[f] = std::cos(0.3) * e + std::sin(0.3) * CGAL::cross_product(nrm, e);
    normals.push_back({{nrm.x(), nrm.y(), nrm.z()}});
  }
  const std::vector<std::pair<vertex_descriptor, TC::Singularity_index>> singularities = {
    {order.vertices[0], TC::Singularity_index(1, 4)}, {order.vertices[5], TC::Singularity_index(-1, 2)}};
  const int n = 4;
  const auto map = boost::make_assoc_property_map(field);
  std::vector<std::array<double, 3>> points;
  for(vertex_descriptor v : vertices(mesh)) points.push_back({{get(vpm, v).x(), get(vpm, v).y(), get(vpm, v).z()}});
  std::vector<std::array<std::size_t, 3>> triangles;
  std::map<vertex_descriptor, std::size_t> number;
  for(vertex_descriptor v : vertices(mesh)) number.emplace(v, number.size());
  for(face_descriptor f : faces(mesh)) {
    const auto h = halfedge(f, mesh);
    triangles.push_back({{number[source(h, mesh)], number[target(h, mesh)], number[target(next(h, mesh), mesh)]}});
  }
  auto check_directions = [&](const std::vector<std::vector<std::array<double, 3>>>& d) {
    ASSERT_EQ(d.size(), std::size_t(n));
    std::size_t f = 0;
    for(face_descriptor fd : faces(mesh)) {
      const Vector v = field[fd];
      EXPECT_EQ(d[0][f][0], v.x());
      EXPECT_EQ(d[0][f][1], v.y());
      EXPECT_EQ(d[0][f][2], v.z());
      const auto& N = normals[f];
      for(int k = 1; k < n; ++k) {
        const auto& u = d[0][f];
        const auto& w = d[std::size_t(k)][f];
        const double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        const double angle = std::atan2(cr[0] * N[0] + cr[1] * N[1] + cr[2] * N[2], u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
        double expected = 2 * CGAL_PI * k / n;
        if(expected > CGAL_PI) expected -= 2 * CGAL_PI;
        EXPECT_NEAR(angle, expected, 1e-12) << "face " << f << ", direction " << k;
        EXPECT_NEAR(std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), 1., 1e-12);
      }
      ++f;
    }
  };
  auto expected_index = [&](std::size_t v) {
    return v == number[order.vertices[0]] ? 0.25 : v == number[order.vertices[5]] ? -0.5 : 0.;
  };

  { // VTK
    std::ostringstream os;
    TC::write_field_vtk(os, mesh, map, singularities, TC::parameters::symmetry_order(n));
    std::istringstream is(os.str());
    std::string line, word;
    std::getline(is, line);
    EXPECT_EQ(line, "# vtk DataFile Version 3.0");
    std::getline(is, line);
    std::getline(is, line);
    EXPECT_EQ(line, "ASCII");
    std::getline(is, line);
    EXPECT_EQ(line, "DATASET POLYDATA");
    std::size_t count = 0, size = 0;
    is >> word >> count >> line;
    EXPECT_EQ(word, "POINTS");
    ASSERT_EQ(count, points.size());
    for(const auto& p : points)
      for(double x : p) { double y; is >> y; EXPECT_EQ(y, x); }
    is >> word >> count >> size;
    EXPECT_EQ(word, "POLYGONS");
    ASSERT_EQ(count, triangles.size());
    EXPECT_EQ(size, 4 * count);
    for(const auto& t : triangles) {
      std::size_t three, a, b, c;
      is >> three >> a >> b >> c;
      EXPECT_EQ(three, 3u);
      EXPECT_EQ((std::array<std::size_t, 3>{{a, b, c}}), t);
    }
    is >> word >> count;
    EXPECT_EQ(word, "CELL_DATA");
    EXPECT_EQ(count, triangles.size());
    std::vector<std::vector<std::array<double, 3>>> d(static_cast<std::size_t>(n));
    for(int k = 0; k < n; ++k) {
      std::string name, type;
      is >> word >> name >> type;
      EXPECT_EQ(word, "VECTORS");
      EXPECT_EQ(name, "direction_" + std::to_string(k));
      for(std::size_t f = 0; f < triangles.size(); ++f) {
        std::array<double, 3> v;
        is >> v[0] >> v[1] >> v[2];
        d[std::size_t(k)].push_back(v);
      }
    }
    check_directions(d);
    is >> word >> count;
    EXPECT_EQ(word, "POINT_DATA");
    EXPECT_EQ(count, points.size());
    std::getline(is, line);
    std::getline(is, line);
    EXPECT_EQ(line, "SCALARS singularity_index double 1");
    std::getline(is, line);
    EXPECT_EQ(line, "LOOKUP_TABLE default");
    for(std::size_t v = 0; v < points.size(); ++v) { double k; is >> k; EXPECT_EQ(k, expected_index(v)); }
    EXPECT_TRUE(bool(is));
    is >> word;
    EXPECT_TRUE(is.eof()) << "trailing data";
  }
  { // PLY: CGAL reads it, and its own properties are right
    Temp_dir dir;
    const std::string path = (dir.path() / "field.ply").string();
    {
      std::ofstream os(path);
      TC::write_field_ply(os, mesh, map, singularities, TC::parameters::symmetry_order(n));
    }
    std::vector<Point> soup_points;
    std::vector<std::vector<std::size_t>> soup_faces;
    ASSERT_TRUE(CGAL::IO::read_polygon_soup(path, soup_points, soup_faces));
    ASSERT_EQ(soup_points.size(), points.size());
    ASSERT_EQ(soup_faces.size(), triangles.size());
    for(std::size_t f = 0; f < triangles.size(); ++f)
      EXPECT_EQ((std::array<std::size_t, 3>{{soup_faces[f][0], soup_faces[f][1], soup_faces[f][2]}}), triangles[f]);
    std::ifstream is(path);
    std::string line;
    while(std::getline(is, line) && line != "end_header") {}
    for(std::size_t v = 0; v < points.size(); ++v) {
      double x, y, z, k;
      is >> x >> y >> z >> k;
      EXPECT_EQ(k, expected_index(v));
    }
    std::vector<std::vector<std::array<double, 3>>> d(static_cast<std::size_t>(n));
    for(std::size_t f = 0; f < triangles.size(); ++f) {
      std::size_t three, a, b, c;
      is >> three >> a >> b >> c;
      for(int k = 0; k < n; ++k) {
        std::array<double, 3> v;
        is >> v[0] >> v[1] >> v[2];
        d[std::size_t(k)].push_back(v);
      }
    }
    EXPECT_TRUE(bool(is));
    check_directions(d);
  }
  { // singularity points
    std::ostringstream os;
    TC::write_singularity_points(os, mesh, singularities);
    std::istringstream is(os.str());
    std::string line;
    std::getline(is, line);
    EXPECT_EQ(line.substr(0, 1), "#");
    for(const auto& s : singularities) {
      double x, y, z;
      std::string k;
      is >> x >> y >> z >> k;
      EXPECT_EQ(x, get(vpm, s.first).x());
      EXPECT_EQ(y, get(vpm, s.first).y());
      EXPECT_EQ(z, get(vpm, s.first).z());
      EXPECT_EQ(k, s.second.to_string());
    }
  }
}

TEST(IoViewerFiles, VtkPlyAndPointsSurfaceMesh) { check_viewer_files<Surface_mesh>(); }
TEST(IoViewerFiles, VtkPlyAndPointsPolyhedron) { check_viewer_files<Polyhedron>(); }

TEST(IoFieldFile, RoundTripSurfaceMesh) { check_field_round_trip<Surface_mesh>(); }
TEST(IoFieldFile, RoundTripPolyhedron) { check_field_round_trip<Polyhedron>(); }

TEST(IoFieldFile, ReaderReportsMalformedLines)
{
  std::istringstream bad("# h\n1 2 3\n1 2\n");
  expect_error([&] { TC::read_field(bad, "f.txt"); }, TC::Error_code::parse_error, {"f.txt:3:", "2 fields"});
  std::istringstream nan("1 2 x\n");
  expect_error([&] { TC::read_field(nan, "f.txt"); }, TC::Error_code::parse_error, {"f.txt:1:"});
}

// ---------------------------------------------------------------------------------------------------
// Face direction (constraint) files

// The coordinates' bits, so that -0. differs from 0. and every last bit counts
std::array<std::uint64_t, 3> bits_of(const std::array<double, 3>& d)
{
  std::array<std::uint64_t, 3> b;
  for(std::size_t c = 0; c < 3; ++c)
    std::memcpy(&b[c], &d[c], sizeof(double));
  return b;
}

TEST(IoFaceDirections, WriteThenReadRoundTripsBitForBit)
{
  std::vector<TC::Face_direction> d;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  for(std::size_t f : {std::size_t(12), std::size_t(0), std::size_t(3), std::size_t(4000000000)}) // file order kept
    d.push_back({f, {{uniform(random), uniform(random) * 1e-300, uniform(random) * 1e300}}});
  d.push_back({5, {{-0., 5e-324, 1. / 3.}}});                      // a negative zero and the smallest subnormal
  d.push_back({6, {{0.1, -2.2250738585072014e-308, 1.7976931348623157e308}}});
  std::ostringstream os;
  TC::write_face_directions(os, d);
  EXPECT_EQ(os.str().rfind("# ", 0), 0u); // the header line
  std::istringstream is(os.str());
  const std::vector<TC::Face_direction> back = TC::read_face_directions(is, "d.txt", 4000000001u);
  ASSERT_EQ(back.size(), d.size());
  for(std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(back[i].face, d[i].face);
    EXPECT_EQ(bits_of(back[i].direction), bits_of(d[i].direction)) << "entry " << i;
  }
  // the same through a file written atomically
  Temp_dir dir;
  const std::string path = dir.file("d.txt");
  TC::write_file_atomically(path, [&](std::ostream& out) { TC::write_face_directions(out, d); });
  EXPECT_EQ(slurp(path), os.str());
  EXPECT_EQ(TC::read_face_directions(path).size(), d.size());
  // an empty range: the header only, read back as no constraint
  std::ostringstream empty;
  TC::write_face_directions(empty, std::vector<TC::Face_direction>());
  std::istringstream empty_in(empty.str());
  EXPECT_TRUE(TC::read_face_directions(empty_in, "e.txt").empty());
}

TEST(IoFaceDirections, WriterRefusesWhatTheReaderWouldRefuseAndWritesNothing)
{
  const TC::Error_code ic = TC::Error_code::invalid_constraint;
  const auto refused = [&](const std::vector<TC::Face_direction>& d, const std::vector<std::string>& parts) {
    std::ostringstream os;
    const TC::Invalid_input e = expect_error([&] { TC::write_face_directions(os, d); }, ic, parts);
    EXPECT_TRUE(os.str().empty());
    return e.where();
  };
  EXPECT_EQ(refused({{1, {{1, 0, 0}}}, {2, {{0, -0., 0}}}}, {"face 2", "zero vector"}), 2u);
  EXPECT_EQ(refused({{3, {{1, std::nan(""), 0}}}}, {"face 3", "not finite"}), 3u);
  EXPECT_EQ(refused({{4, {{HUGE_VAL, 0, 0}}}}, {"face 4", "not finite"}), 4u);
  EXPECT_EQ(refused({{7, {{1, 0, 0}}}, {8, {{1, 0, 0}}}, {7, {{0, 1, 0}}}}, {"face 7", "twice", "entries 0 and 2"}), 7u);
}

// ---------------------------------------------------------------------------------------------------
// Atomic writes

TEST(IoAtomicFile, WritesAndReplacesWithoutLeavingTemporaries)
{
  Temp_dir dir;
  const std::string target = dir.file("out.txt");
  TC::write_file_atomically(target, [](std::ostream& os) { os << "first\n"; });
  EXPECT_EQ(slurp(target), "first\n");
  TC::write_file_atomically(target, [](std::ostream& os) { os << "second\n"; });
  EXPECT_EQ(slurp(target), "second\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomicFile, TargetInMissingDirectoryFailsAndWritesNothing)
{
  Temp_dir dir;
  const std::string target = (dir.path() / "no_such_dir" / "out.txt").string();
  expect_error([&] { TC::write_file_atomically(target, [](std::ostream& os) { os << "x"; }); },
               TC::Error_code::io_error, {"no_such_dir"});
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomicFile, SetIsAllOrNothingWhenOneTargetIsADirectory)
{
  Temp_dir dir;
  fs::create_directory(dir.path() / "a_directory");
  const std::string good = dir.file("good.txt");
  expect_error(
    [&] {
      TC::write_files_atomically({{good, [](std::ostream& os) { os << "complete\n"; }},
                                  {dir.file("a_directory"), [](std::ostream& os) { os << "x\n"; }}});
    },
    TC::Error_code::io_error, {"a_directory"});
  EXPECT_FALSE(fs::exists(good)); // the first file of the set was not committed
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a_directory"});
  EXPECT_TRUE(fs::is_empty(dir.path() / "a_directory"));
}

TEST(IoAtomicFile, FailingWriterLeavesExistingTargetsUntouched)
{
  Temp_dir dir;
  const std::string a = dir.write("a.txt", "old a\n");
  const std::string b = dir.write("b.txt", "old b\n");
  EXPECT_THROW(TC::write_files_atomically({{a, [](std::ostream& os) { os << "new a\n"; }},
                                           {b,
                                            [](std::ostream& os) {
                                              os << "half of b";
                                              throw std::runtime_error("writer failed");
                                            }}}),
               std::runtime_error);
  EXPECT_EQ(slurp(a), "old a\n");
  EXPECT_EQ(slurp(b), "old b\n");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.txt", "b.txt"}));

  TC::write_files_atomically({{a, [](std::ostream& os) { os << "new a\n"; }},
                              {b, [](std::ostream& os) { os << "new b\n"; }}});
  EXPECT_EQ(slurp(a), "new a\n");
  EXPECT_EQ(slurp(b), "new b\n");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.txt", "b.txt"}));
}

TEST(IoAtomicFile, RelativeTargetInCurrentDirectory)
{
  Temp_dir dir;
  const fs::path cwd = fs::current_path();
  fs::current_path(dir.path());
  try {
    TC::write_file_atomically("relative.txt", [](std::ostream& os) { os << "r\n"; });
  } catch(...) {
    fs::current_path(cwd);
    throw;
  }
  fs::current_path(cwd);
  EXPECT_EQ(slurp(dir.file("relative.txt")), "r\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"relative.txt"});
}

// ---------------------------------------------------------------------------------------------------
// Mesh reader, on both mesh types

template <class Mesh>
class IoMeshReader : public ::testing::Test
{};
using Mesh_types = ::testing::Types<Surface_mesh, Polyhedron>;
TYPED_TEST_SUITE(IoMeshReader, Mesh_types);

template <class Mesh>
std::size_t index_in(const std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor>& vs,
                     typename boost::graph_traits<Mesh>::vertex_descriptor v)
{
  return std::size_t(std::find(vs.begin(), vs.end(), v) - vs.begin());
}

// vertex i / face f of the input are the i-th / f-th elements, with the input's points and corners
template <class Mesh>
void expect_input_order(const Mesh& mesh, const TC::Mesh_input_order<Mesh>& order, const std::vector<Point>& points,
                        const std::vector<std::vector<std::size_t>>& polys)
{
  ASSERT_EQ(order.vertices.size(), points.size());
  ASSERT_EQ(order.faces.size(), polys.size());
  ASSERT_EQ(std::size_t(num_vertices(mesh)), points.size());
  ASSERT_EQ(std::size_t(num_faces(mesh)), polys.size());
  std::size_t i = 0;
  for(auto v : vertices(mesh)) {
    EXPECT_EQ(v, order.vertices[i]) << "vertex " << i;
    EXPECT_EQ(get(CGAL::vertex_point, mesh, v), points[i]) << "vertex " << i;
    ++i;
  }
  std::size_t f = 0;
  for(auto fd : faces(mesh)) {
    EXPECT_EQ(fd, order.faces[f]) << "face " << f;
    // same vertices in the same cyclic order, starting at halfedge(f)'s source
    std::vector<std::size_t> corners;
    for(auto h : CGAL::halfedges_around_face(halfedge(fd, mesh), mesh))
      corners.push_back(index_in<Mesh>(order.vertices, source(h, mesh)));
    EXPECT_EQ(corners, polys[f]) << "face " << f;
    ++f;
  }
}

TYPED_TEST(IoMeshReader, KeepsInputOrderIncludingAnUnusedVertex)
{
  using Mesh = TypeParam;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polys;
  grid_soup(4, 7, points, polys); // vertex 7 is used by no face
  // shuffle the faces so that face order differs from any traversal order
  std::mt19937 random(3);
  std::shuffle(polys.begin(), polys.end(), random);
  Temp_dir dir;
  const std::string path = dir.write("grid.off", to_off(points, polys));

  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::read_triangle_mesh(path, mesh);
  expect_input_order(mesh, order, points, polys);
  EXPECT_EQ(halfedge(order.vertices[7], mesh), boost::graph_traits<Mesh>::null_halfedge());
  // 4 x 4 grid: 16 border edges
  std::size_t border = 0;
  for(auto e : edges(mesh))
    border += CGAL::is_border(e, mesh) ? 1 : 0;
  EXPECT_EQ(border, 16u);
  EXPECT_EQ(std::size_t(num_edges(mesh)), std::size_t(4 * 5 * 2 + 16));
}

TYPED_TEST(IoMeshReader, ClosedMeshIsValidAndMatchesCGALsConversion)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  const std::string path = dir.write("octahedron.off", to_off(octahedron_points, octahedron_faces));
  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::read_triangle_mesh(path, mesh);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  EXPECT_TRUE(CGAL::is_closed(mesh));
  EXPECT_TRUE(CGAL::is_triangle_mesh(mesh));
  expect_input_order(mesh, order, octahedron_points, octahedron_faces);

  // same incidences as CGAL's own polygon_soup_to_polygon_mesh, on a bordered mesh too
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polys;
  grid_soup(5, std::size_t(-1), points, polys);
  Mesh ours, cgal;
  const TC::Mesh_input_order<Mesh> o = TC::triangle_soup_to_mesh(points, polys, ours);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polys, cgal);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(ours));
  ASSERT_EQ(num_faces(ours), num_faces(cgal));
  ASSERT_EQ(num_edges(ours), num_edges(cgal));
  std::size_t f = 0;
  auto cgal_face = faces(cgal).begin();
  std::vector<typename boost::graph_traits<Mesh>::vertex_descriptor> cgal_vertices(vertices(cgal).begin(),
                                                                                   vertices(cgal).end());
  for(auto fd : faces(ours)) {
    std::vector<std::size_t> a, b;
    for(auto v : CGAL::vertices_around_face(halfedge(fd, ours), ours))
      a.push_back(index_in<Mesh>(o.vertices, v));
    for(auto v : CGAL::vertices_around_face(halfedge(*cgal_face, cgal), cgal))
      b.push_back(index_in<Mesh>(cgal_vertices, v));
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    std::rotate(b.begin(), std::min_element(b.begin(), b.end()), b.end());
    EXPECT_EQ(a, b) << "face " << f;
    ++cgal_face;
    ++f;
  }
}

TYPED_TEST(IoMeshReader, ReadsObjAndPly)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  std::ostringstream obj;
  obj << "# tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 9 9 9\n"
         "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
  const std::string obj_path = dir.write("tet.OBJ", obj.str());
  Mesh m1;
  const auto o1 = TC::read_triangle_mesh(obj_path, m1);
  EXPECT_EQ(o1.vertices.size(), 5u);
  EXPECT_EQ(o1.faces.size(), 4u);
  EXPECT_TRUE(CGAL::is_closed(m1));

  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                          "property double z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  Mesh m2;
  const auto o2 = TC::read_triangle_mesh(dir.write("tet.ply", ply), m2);
  expect_input_order(m2, o2,
                     {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)},
                     {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
}

TYPED_TEST(IoMeshReader, RejectsEachBadInputWithItsError)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  auto read = [&](const std::string& name, const std::string& content) { return reader_of<Mesh>(dir, name, content); };
  const std::string four = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string six = four + "1 1 1\n-1 0 0\n";

  expect_error(read("quad.off", "OFF\n5 2 0\n" + four + "1 1 0\n3 0 1 3\n4 0 1 4 2\n"),
               TC::Error_code::not_triangle_mesh, {"quad.off", "face 1", "4 vertices"});
  // index 7 of 4 vertices: CGAL's OFF reader refuses the file, the diagnosis names the face and the line
  const TC::Invalid_input out_of_range =
    expect_error(read("range.off", "OFF\n4 2 0\n" + four + "3 0 1 2\n3 0 2 7\n"), TC::Error_code::invalid_vertex,
                 {"range.off:8", "face 1", "vertex 7", "4 vertices"});
  EXPECT_EQ(out_of_range.where(), 1u);
  // OBJ: index 5 of 4 vertices (1-based), which CGAL's OBJ reader lets through
  expect_error(read("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 5\n"),
               TC::Error_code::invalid_vertex, {"face 1", "4 vertices"});
  expect_error(read("nonmanifold_edge.off", "OFF\n6 3 0\n" + six + "3 0 1 2\n3 1 0 3\n3 0 1 4\n"),
               TC::Error_code::non_manifold, {"edge", "vertices 0 and 1", "3 faces", "0, 1 and 2"});
  const TC::Invalid_input orientation =
    expect_error(read("orientation.off", "OFF\n4 3 0\n" + four + "3 0 1 2\n3 2 3 0\n3 0 1 3\n"),
                 TC::Error_code::inconsistent_orientation, {"faces 0 and 2", "vertex 0 to vertex 1"});
  EXPECT_EQ(orientation.where(), 2u);
  const TC::Invalid_input pinched =
    expect_error(read("pinched.off", "OFF\n5 2 0\n" + four + "1 1 1\n3 0 1 2\n3 0 3 4\n"),
                 TC::Error_code::non_manifold, {"vertex 0", "2 separate fans"});
  EXPECT_EQ(pinched.where(), 0u);
  expect_error(read("degenerate.off", "OFF\n4 2 0\n" + four + "3 0 1 2\n3 3 1 3\n"), TC::Error_code::degenerate_face,
               {"face 1", "same vertex"});
  expect_error(read("empty.off", "OFF\n4 0 0\n" + four), TC::Error_code::empty_mesh, {"empty.off", "no face"});
  expect_error(read("nothing.off", "OFF\n0 0 0\n"), TC::Error_code::empty_mesh, {"no face"});
  expect_error(read("empty.obj", "v 0 0 0\nv 1 0 0\n"), TC::Error_code::empty_mesh, {"no face"});
  expect_error(read("truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1\n"), TC::Error_code::parse_error,
               {"truncated.off"});
  expect_error(read("mesh.xyz", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), TC::Error_code::parse_error,
               {"mesh.xyz", "extension"});
  expect_error(read("noextension", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), TC::Error_code::parse_error,
               {"extension"});

  const std::string missing = dir.file("missing.off");
  expect_error([&] { Mesh m; TC::read_triangle_mesh(missing, m); }, TC::Error_code::io_error, {"missing.off"});
  expect_error([&] { Mesh m; TC::read_triangle_mesh(dir.path().string(), m); }, TC::Error_code::io_error,
               {"directory"});
}

TYPED_TEST(IoMeshReader, RangeIsCheckedBeforeAnythingElse)
{
  using Mesh = TypeParam;
  // face 0 is a quad, face 1 uses a vertex out of range: the range error comes first
  const std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(1, 1, 0)};
  const std::vector<std::vector<std::size_t>> polys = {{0, 1, 3, 2}, {0, 1, 99}};
  Mesh mesh;
  const TC::Invalid_input e = expect_error([&] { TC::triangle_soup_to_mesh(points, polys, mesh); },
                                           TC::Error_code::invalid_vertex, {"face 1", "vertex 99", "4 vertices"});
  EXPECT_EQ(e.where(), 1u);
  EXPECT_EQ(num_faces(mesh), 0u);
}

TYPED_TEST(IoMeshReader, TwoComponentsAndBorderVertices)
{
  using Mesh = TypeParam;
  // an octahedron and a disjoint open fan of 3 triangles around vertex 6 (its centre)
  std::vector<Point> points = octahedron_points;
  std::vector<std::vector<std::size_t>> polys = octahedron_faces;
  for(const Point& p : {Point(10, 0, 0), Point(11, 0, 0), Point(10, 1, 0), Point(9, 0, 0), Point(10, -1, 0)})
    points.push_back(p);
  polys.push_back({6, 7, 8});
  polys.push_back({6, 8, 9});
  polys.push_back({6, 9, 10});
  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::triangle_soup_to_mesh(points, polys, mesh);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  expect_input_order(mesh, order, points, polys);
  for(std::size_t v = 0; v < 6; ++v)
    EXPECT_FALSE(bool(CGAL::is_border(order.vertices[v], mesh))) << v;
  for(std::size_t v = 6; v < 11; ++v)
    EXPECT_TRUE(bool(CGAL::is_border(order.vertices[v], mesh))) << v;
  std::size_t border = 0;
  for(auto h : halfedges(mesh))
    border += CGAL::is_border(h, mesh) ? 1 : 0;
  EXPECT_EQ(border, 5u);
}

// ---------------------------------------------------------------------------------------------------
// The fast OFF / OBJ path of the mesh reader: same meshes as CGAL's reader, same errors

// The mesh built from CGAL's own polygon soup reader (the path read_triangle_mesh falls back to).
template <class Mesh>
TC::Mesh_input_order<Mesh> read_through_cgal(const std::string& path, Mesh& mesh)
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if(!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false)))
    throw std::runtime_error("CGAL cannot read " + path);
  return TC::triangle_soup_to_mesh(points, polygons, mesh);
}

// Same elements in the same order, same points (exactly), same halfedge structure.
template <class Mesh>
void expect_same_mesh(const Mesh& a, const TC::Mesh_input_order<Mesh>& oa, const Mesh& b,
                      const TC::Mesh_input_order<Mesh>& ob)
{
  ASSERT_EQ(oa.vertices.size(), ob.vertices.size());
  ASSERT_EQ(oa.faces.size(), ob.faces.size());
  ASSERT_EQ(num_vertices(a), num_vertices(b));
  ASSERT_EQ(num_edges(a), num_edges(b));
  ASSERT_EQ(num_faces(a), num_faces(b));
  bool isolated = false; // is_valid_polygon_mesh() refuses isolated vertices
  for(auto v : vertices(a))
    isolated = isolated || halfedge(v, a) == boost::graph_traits<Mesh>::null_halfedge();
  if(!isolated)
    EXPECT_TRUE(CGAL::is_valid_polygon_mesh(a));
  std::map<typename boost::graph_traits<Mesh>::vertex_descriptor, std::size_t> ia, ib;
  for(std::size_t i = 0; i < oa.vertices.size(); ++i) {
    ia[oa.vertices[i]] = i;
    ib[ob.vertices[i]] = i;
    ASSERT_EQ(get(CGAL::vertex_point, a, oa.vertices[i]), get(CGAL::vertex_point, b, ob.vertices[i])) << "vertex " << i;
  }
  std::size_t mismatches = 0;
  for(std::size_t f = 0; f < oa.faces.size() && mismatches < 5; ++f) {
    std::vector<std::size_t> ca, cb;
    for(auto h : CGAL::halfedges_around_face(halfedge(oa.faces[f], a), a))
      ca.push_back(ia[source(h, a)]);
    for(auto h : CGAL::halfedges_around_face(halfedge(ob.faces[f], b), b))
      cb.push_back(ib[source(h, b)]);
    if(ca != cb) {
      ++mismatches;
      ADD_FAILURE() << "face " << f;
    }
  }
  // edges in the same order, with the same vertices and border status
  auto eb = edges(b).begin();
  for(auto e : edges(a)) {
    ASSERT_EQ(ia[source(halfedge(e, a), a)], ib[source(halfedge(*eb, b), b)]);
    ASSERT_EQ(ia[target(halfedge(e, a), a)], ib[target(halfedge(*eb, b), b)]);
    ASSERT_EQ(CGAL::is_border(e, a), CGAL::is_border(*eb, b));
    ++eb;
  }
}

template <class Mesh>
void expect_fast_reader_matches_cgal(const std::string& path)
{
  // the file is one the fast path takes
  {
    std::vector<Point> points;
    std::vector<std::array<int, 3>> triangles;
    const TC::internal::io::File_contents data(path);
    ASSERT_TRUE(data.ok()) << path;
    const bool off = TC::internal::io::lower_extension(path) == "off";
    EXPECT_TRUE(off ? TC::internal::io::fast_parse_off(data.begin(), data.end(), points, triangles)
                    : TC::internal::io::fast_parse_obj(data.begin(), data.end(), points, triangles))
      << path << " does not take the fast path";
  }
  Mesh fast, cgal;
  const TC::Mesh_input_order<Mesh> of = TC::read_triangle_mesh(path, fast);
  const TC::Mesh_input_order<Mesh> oc = read_through_cgal(path, cgal);
  expect_same_mesh(fast, of, cgal, oc);
}

TYPED_TEST(IoMeshReader, FastReaderGivesCGALsMeshOnTheExampleAndCGALMeshes)
{
  using Mesh = TypeParam;
  std::vector<std::string> paths = {std::string(TC_EXAMPLE_DATA_DIR) + "/sphere.off"};
  for(const char* name : {"cow.off", "elephant.off", "knot1.off", "rotor.off", "pig.off", "mesh_with_border.off"}) {
    const std::string path = std::string(TC_CGAL_DATA_DIR) + "/" + name;
    if(fs::exists(path))
      paths.push_back(path);
  }
  if(paths.size() == 1)
    std::cout << "[ note ] CGAL data set not found at " << TC_CGAL_DATA_DIR << ": only the example is compared\n";
  for(const std::string& path : paths) {
    SCOPED_TRACE(path);
    expect_fast_reader_matches_cgal<Mesh>(path);
  }
}

TYPED_TEST(IoMeshReader, FastReaderGivesCGALsMeshOnObjAndCommentedOff)
{
  using Mesh = TypeParam;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polys;
  grid_soup(6, 11, points, polys);
  Temp_dir dir;
  // OFF with comments, blank lines, CRLF line ends, counts on the keyword line, signs and exponents
  std::ostringstream off;
  off.precision(17);
  off << "# a grid\r\nOFF " << points.size() << ' ' << polys.size() << " 0 # counts\r\n\r\n";
  for(std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    if(i % 5 == 0)
      off << "  # a comment line\n";
    off << (i % 3 == 0 ? "+" : "") << p.x() << "\t" << std::scientific << p.y() << std::defaultfloat << ' ' << p.z()
        << (i % 4 == 0 ? " # comment\r\n" : "\n");
  }
  for(const auto& f : polys)
    off << "3  " << f[0] << ' ' << f[1] << ' ' << f[2] << " \n";
  expect_fast_reader_matches_cgal<Mesh>(dir.write("grid.off", off.str()));

  std::ostringstream obj;
  obj.precision(17);
  obj << "# a grid\nmtllib grid.mtl\no grid\n";
  for(const Point& p : points)
    obj << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << "\nvt 0 0\n";
  obj << "g all\ns off\n";
  std::size_t k = 0;
  for(const auto& f : polys) {
    if(k++ % 2 == 0)
      obj << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
    else
      obj << "f " << f[0] + 1 << "/1/1 " << f[1] + 1 << "//2 " << f[2] + 1 << "/3\n";
  }
  expect_fast_reader_matches_cgal<Mesh>(dir.write("grid.obj", obj.str()));
}

TYPED_TEST(IoMeshReader, FilesOutsideTheFastPathGiveCGALsMesh)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  const std::string four = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string tet = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  for(const auto& [name, content] : std::vector<std::pair<std::string, std::string>>{
        {"colours.off", "OFF\n4 4 0\n" + four + "3 0 2 1 255 0 0\n3 0 1 3 0 255 0\n3 1 2 3\n3 2 0 3\n"},
        {"coff.off", "COFF\n4 4 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n0 0 1 1 1 1 1\n" + tet},
        {"no_final_newline.off", "OFF\n4 4 0\n" + four + tet.substr(0, tet.size() - 1)}}) {
    SCOPED_TRACE(name);
    const std::string path = dir.write(name, content);
    Mesh fast, cgal;
    const TC::Mesh_input_order<Mesh> of = TC::read_triangle_mesh(path, fast);
    const TC::Mesh_input_order<Mesh> oc = read_through_cgal(path, cgal);
    expect_same_mesh(fast, of, cgal, oc);
  }
}

// A binary PLY of `points` (float32 coordinates, as CGAL reads them) and triangles (uchar sizes, int32
// indices), little or big endian; `extra` adds a double property per vertex and an `edge` element, which the
// readers must read past.
std::string binary_ply(const std::vector<Point>& points, const std::vector<std::vector<std::size_t>>& polys,
                       bool big_endian, bool extra)
{
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment made by the test\nelement vertex " + std::to_string(points.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\n" + (extra ? "property double quality\n" : "") +
                  "element face " + std::to_string(polys.size()) + "\nproperty list uchar int vertex_indices\n" +
                  (extra ? "element edge 1\nproperty int vertex1\nproperty int vertex2\n" : "") + "end_header\n";
  const std::uint16_t one = 1;
  const bool host_little = *reinterpret_cast<const unsigned char*>(&one) == 1;
  auto put = [&](const auto value) {
    char b[sizeof(value)];
    std::memcpy(b, &value, sizeof(value));
    if(host_little == big_endian)
      std::reverse(b, b + sizeof(value));
    s.append(b, sizeof(value));
  };
  for(const Point& p : points) {
    put(float(p.x()));
    put(float(p.y()));
    put(float(p.z()));
    if(extra)
      put(double(0.5));
  }
  for(const auto& f : polys) {
    put(std::uint8_t(f.size()));
    for(std::size_t v : f)
      put(std::int32_t(v));
  }
  if(extra) {
    put(std::int32_t(0));
    put(std::int32_t(1));
  }
  return s;
}

// OFF and PLY are read by the package's own readers: what CGAL reads correctly they read the same (the
// variants and encodings CGAL's test data uses), and what CGAL's readers trust or crash on they refuse.
TYPED_TEST(IoMeshReader, OwnOffAndPlyReadersGiveCGALsMesh)
{
  using Mesh = TypeParam;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polys;
  grid_soup(5, 7, points, polys);
  for(Point& p : points) // float-exact coordinates, so that the float32 PLY files hold them exactly
    p = Point(float(p.x()), float(p.y()), float(p.z()));
  std::ostringstream ascii;
  ascii.precision(9);
  ascii << "ply\r\nformat ascii 1.0\r\nelement vertex " << points.size()
        << "\r\nproperty double nx\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
        << "property uchar red\r\nelement face " << polys.size()
        << "\r\nproperty list uchar int vertex_indices\r\nproperty uchar flags\r\nend_header\r\n";
  for(const Point& p : points)
    ascii << "0.25 " << p.x() << ' ' << p.y() << "\n " << p.z() << " 255\n"; // ASCII PLY ignores lines
  for(const auto& f : polys)
    ascii << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << " 7\n";
  std::ostringstream noff;
  noff.precision(17);
  noff << "NOFF\n" << points.size() << ' ' << polys.size() << " 0\n";
  for(const Point& p : points)
    noff << p.x() << ' ' << p.y() << ' ' << p.z() << " 0 0 1\n";
  for(const auto& f : polys)
    noff << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << " 0.5 0.5 0.5\n";
  Temp_dir dir;
  for(const auto& [name, content] : std::vector<std::pair<std::string, std::string>>{
        {"ascii.ply", ascii.str()},
        {"little.ply", binary_ply(points, polys, false, false)},
        {"big.ply", binary_ply(points, polys, true, false)},
        {"little_extra.ply", binary_ply(points, polys, false, true)},
        {"big_extra.ply", binary_ply(points, polys, true, true)},
        {"normals.off", noff.str()}}) {
    SCOPED_TRACE(name);
    const std::string path = dir.write(name, content);
    Mesh ours, cgal;
    const TC::Mesh_input_order<Mesh> oo = TC::read_triangle_mesh(path, ours);
    const TC::Mesh_input_order<Mesh> oc = read_through_cgal(path, cgal);
    expect_same_mesh(ours, oo, cgal, oc);
    expect_input_order(ours, oo, points, polys);
  }
  // beyond CGAL's reader (which asserts, or dereferences a null pointer, on integer coordinates, and reads no
  // face from a list of uchar indices): any numeric coordinate type, any integer index type
  const std::string int_ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty int x\nproperty short y\n"
                              "property uchar z\nelement face 4\nproperty list ushort uchar vertex_index\nend_header\n"
                              "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  Mesh m;
  const TC::Mesh_input_order<Mesh> o = TC::read_triangle_mesh(dir.write("integers.ply", int_ply), m);
  expect_input_order(m, o, {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)},
                     {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
}

TYPED_TEST(IoMeshReader, OwnOffAndPlyReadersRefuseWhatCGALsTrust)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  auto read = [&](const std::string& name, const std::string& content) { return reader_of<Mesh>(dir, name, content); };
  const std::string four = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string tet = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  // OFF: variants that CGAL reads with facet sizes it trusts (the fuzzer's findings)
  expect_error(read("binary.off", std::string("OFF BINARY\n\0\0\0\4\0\0\0\4\0\0\0\0", 23)),
               TC::Error_code::parse_error, {"binary.off:1", "binary OFF is not supported"});
  expect_error(read("homogeneous.off", "4OFF\n4 4 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1\n" + tet),
               TC::Error_code::parse_error, {"homogeneous.off:1", "'4OFF'", "not supported"});
  expect_error(read("ndim.off", "nOFF\n3\n4 4 0\n" + four + tet), TC::Error_code::parse_error,
               {"ndim.off:1", "'nOFF'", "not supported"});
  expect_error(read("skel.off", "SKEL\n4 0\n" + four), TC::Error_code::parse_error, {"skel.off:1", "keyword OFF"});
  expect_error(read("no_keyword.off", "4 4 0\n" + four + tet), TC::Error_code::parse_error,
               {"no_keyword.off:1", "keyword OFF"});
  // the counts: exactly three on their line (CGAL read the rest of a longer line as vertex 0)
  expect_error(read("counts6.off", "OFF\n4 4 0 0 0 0\n" + four + tet), TC::Error_code::parse_error,
               {"counts6.off:2", "three integers on one line"});
  expect_error(read("counts2.off", "OFF\n4 4\n" + four + tet), TC::Error_code::parse_error,
               {"counts2.off:2", "three integers on one line"});
  expect_error(read("facet_size.off", "COFF\n4 4 0\n" + four + "1000000000 0 1 2\n" + tet),
               TC::Error_code::parse_error, {"facet_size.off:7", "face 0", "expected 1000000000 vertex indices"});
  expect_error(read("negative_size.off", "NOFF\n4 4 0\n" + four + "-1 0 1 2\n" + tet), TC::Error_code::parse_error,
               {"negative_size.off:7", "face 0", "number of its vertices"});

  // PLY
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\n";
  const std::string body = four + tet;
  EXPECT_NO_THROW(read("tet.ply", header + "property list uchar int vertex_indices\nend_header\n" + body)());
  expect_error(read("list_size.ply", header + "property list uint int vertex_indices\nend_header\n" + four +
                                       "4000000000 0 1 2\n" + tet),
               TC::Error_code::parse_error, {"list_size.ply", "element 'face' item 0", "4000000000 items, more than the file holds"});
  {
    std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
    bin += std::string("\xff\xff\xff\x0f\0\0\0\0", 8);
    expect_error(read("binary_list_size.ply", bin), TC::Error_code::parse_error,
                 {"element 'face' item 0", "268435455 items, more than the file holds"});
  }
  expect_error(read("cut.ply", header + "property list uchar int vertex_indices\nend_header\n" + four +
                                 "3 0 2 1\n3 0 1 3\n3 1 2 3\n"),
               TC::Error_code::parse_error, {"cut.ply", "element 'face' item 3", "unexpected end of file", "4 items"});
  expect_error(read("cut_list.ply", header + "property list uchar int vertex_indices\nend_header\n" + four + "3 0 2 1\n3 0"),
               TC::Error_code::parse_error, {"cut_list.ply", "element 'face' item 1", "3 items, more than the file holds"});
  expect_error(read("float_list.ply", header + "property list uchar float vertex_indices\nend_header\n" + body),
               TC::Error_code::parse_error, {"float_list.ply", "'vertex_indices' is not a list of integers"});
  expect_error(read("float_size.ply", header + "property list float int vertex_indices\nend_header\n" + body),
               TC::Error_code::parse_error, {"float_size.ply:8", "size type of a list", "'float'"});
  expect_error(read("no_indices.ply", header + "property int flags\nend_header\n" + four + "0\n0\n0\n0\n"),
               TC::Error_code::parse_error, {"no_indices.ply", "no list property vertex_indices"});
  expect_error(read("no_z.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                                "0 0\n1 0\n0 1\n0 0\n" + tet),
               TC::Error_code::parse_error, {"no_z.ply", "x, y and z"});
  expect_error(read("negative.ply", header + "property list uchar int vertex_indices\nend_header\n" + four +
                                      "3 0 -2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"),
               TC::Error_code::parse_error, {"negative.ply", "item 0", "negative vertex index"});
  expect_error(read("out_of_type.ply", header + "property list uchar int vertex_indices\nend_header\n" + four +
                                         "300 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"),
               TC::Error_code::parse_error, {"out_of_type.ply", "'300' is not a value of the property's integer type"});
  for(const std::string bad : {"nan", "inf", "1e999"}) {
    SCOPED_TRACE(bad);
    expect_error(read("nonfinite.ply", header + "property list uchar int vertex_indices\nend_header\n0 0 0\n1 " + bad +
                                         " 0\n0 1 0\n0 0 1\n" + tet),
                 TC::Error_code::parse_error, {"nonfinite.ply", "element 'vertex' item 1", "y is not a finite number"});
  }
  expect_error(read("range.ply", header + "property list uchar int vertex_indices\nend_header\n" + four +
                                   "3 0 2 1\n3 0 1 3\n3 1 2 9\n3 2 0 3\n"),
               TC::Error_code::invalid_vertex, {"range.ply", "face 2", "vertex 9"});
  expect_error(read("empty.ply", ""), TC::Error_code::parse_error, {"empty.ply", "empty"});
  expect_error(read("unknown_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n0\n"),
               TC::Error_code::parse_error, {"unknown_type.ply:4", "unknown property type 'float128'"});
}

TYPED_TEST(IoMeshReader, FastReaderRejectsMalformedFilesWithTheUsualErrors)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  auto read = [&](const std::string& name, const std::string& content) { return reader_of<Mesh>(dir, name, content); };
  const std::string four = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  const std::string tet = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";
  // the well-formed file reads
  EXPECT_NO_THROW(read("tet.off", "OFF\n4 4 0\n" + four + tet)());
  // truncated: in the vertices, in the faces, after the header
  expect_error(read("cut_vertices.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n"), TC::Error_code::parse_error,
               {"cut_vertices.off", "end of file", "4 vertices"});
  expect_error(read("cut_faces.off", "OFF\n4 4 0\n" + four + "3 0 2 1\n3 0 1 3\n"), TC::Error_code::parse_error,
               {"cut_faces.off", "end of file", "4 faces"});
  expect_error(read("cut_header.off", "OFF\n"), TC::Error_code::parse_error, {"cut_header.off"});
  expect_error(read("cut_face.off", "OFF\n4 4 0\n" + four + "3 0 2 1\n3 0 1\n3 1 2 3\n3 2 0 3\n"),
               TC::Error_code::parse_error, {"cut_face.off:8", "face 1"});
  // garbage numbers
  expect_error(read("garbage.off", "OFF\n4 4 0\n0 0 0\n1 zero 0\n0 1 0\n0 0 1\n" + tet), TC::Error_code::parse_error,
               {"garbage.off:4", "vertex 1", "'zero' is not a number"});
  expect_error(read("garbage_index.off", "OFF\n4 4 0\n" + four + "3 0 2 1\n3 0 x 3\n3 1 2 3\n3 2 0 3\n"),
               TC::Error_code::parse_error, {"garbage_index.off:8", "face 1"});
  expect_error(read("garbage_counts.off", "OFF\n4 four 0\n" + four + tet), TC::Error_code::parse_error,
               {"garbage_counts.off:2", "counts"});
  // non-finite coordinates
  for(const std::string& bad : {"nan", "-nan", "inf", "-inf", "infinity", "1e999"}) {
    SCOPED_TRACE(bad);
    expect_error(read("nonfinite.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 " + bad + " 0\n0 0 1\n" + tet),
                 TC::Error_code::parse_error, {"nonfinite.off:5", "vertex 2", "'" + bad + "'", "not a finite number"});
    expect_error(read("nonfinite.obj", "v 0 0 0\nv 1 0 0\nv 0 1 " + bad + "\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"),
                 TC::Error_code::parse_error, {"nonfinite.obj:3", "vertex 2", "not a finite number"});
  }
  // index out of range, in OFF and OBJ
  const TC::Invalid_input range =
    expect_error(read("range.off", "OFF\n4 4 0\n" + four + "3 0 2 1\n3 0 1 3\n3 1 2 4\n3 2 0 3\n"),
                 TC::Error_code::invalid_vertex, {"range.off:9", "face 2", "vertex 4", "4 vertices"});
  EXPECT_EQ(range.where(), 2u);
  expect_error(read("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 9\nf 3 1 4\n"),
               TC::Error_code::invalid_vertex, {"range.obj:7", "face 2", "vertex 9"});
  // not a triangle, in OFF and OBJ
  expect_error(read("quad.off", "OFF\n5 4 0\n" + four + "1 1 1\n3 0 2 1\n4 0 1 4 3\n3 1 2 3\n3 2 0 3\n"),
               TC::Error_code::not_triangle_mesh, {"quad.off", "face 1", "4 vertices"});
  expect_error(read("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 2 5 4\nf 2 3 4\nf 3 1 4\n"),
               TC::Error_code::not_triangle_mesh, {"quad.obj", "face 1", "4 vertices"});
  // validation errors after a fast parse keep their messages (prefixed with the path)
  expect_error(read("degenerate_fast.off", "OFF\n4 4 0\n" + four + "3 0 2 1\n3 0 1 3\n3 1 1 3\n3 2 0 3\n"),
               TC::Error_code::degenerate_face, {"degenerate_fast.off: face 2", "same vertex"});
  expect_error(read("orientation_fast.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 3 4\n"),
               TC::Error_code::inconsistent_orientation, {"orientation_fast.obj", "faces 0 and 1"});
}

// Faces of more than three vertices are split on request: into triangles inside the face (their areas add
// up to the face's, which a wrong split of a non-convex face does not give), with the face's orientation,
// the vertex numbering kept and source_faces naming each triangle's face.
// A polygon of five or more corners is split into m - 2 triangles of its own corners whose directed edges
// are the polygon's boundary, once each in the polygon's direction, plus diagonals in both directions: a
// triangulation of the polygon with its orientation. Among them, the slightly non-planar pentagon on which
// CGAL's triangulate_face() left a broken face cycle (an endless loop, found by the fuzzer).
TYPED_TEST(IoMeshReader, TriangulatedPolygonsKeepTheirBoundaryAndOrientation)
{
  using Mesh = TypeParam;
  const std::vector<std::pair<std::string, std::string>> files = {
    {"fuzzer_pentagon.obj", "v 0 0 0\nv 0 0 2\nv 0 1 0\nv 0 1 1\nv 22 0 0\nv 1 0 1\nv 1 1 0\nv 1 0 1\nf 1 5 2 3 8\n"},
    {"star.obj", "v 0 0 0\nv 4 -1 0\nv 1 1 0\nv 4 3 0\nv 0 2 0\nv -3 3 0\nv -1 1 0\nv -3 -1 0\nf 1 2 3 4 5 6 7 8\n"},
    {"collinear_corners.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4 5 6\n"}};
  Temp_dir dir;
  for(const auto& [name, content] : files) {
    SCOPED_TRACE(name);
    std::vector<std::size_t> corners;
    for(std::istringstream is(content.substr(content.find("f "))); is;) {
      std::string t;
      if(is >> t && t != "f")
        corners.push_back(std::stoul(t) - 1);
    }
    Mesh mesh;
    const TC::Mesh_input_order<Mesh> order =
      TC::read_triangle_mesh(dir.write(name, content), mesh, TC::parameters::triangulate(true));
    ASSERT_EQ(order.faces.size(), corners.size() - 2);
    std::map<std::pair<std::size_t, std::size_t>, int> directed;
    auto index = [&order](auto v) {
      return std::size_t(std::find(order.vertices.begin(), order.vertices.end(), v) - order.vertices.begin());
    };
    for(auto f : order.faces)
      for(auto h : CGAL::halfedges_around_face(halfedge(f, mesh), mesh))
        ++directed[{index(source(h, mesh)), index(target(h, mesh))}];
    auto count_of = [&directed](std::size_t a, std::size_t b) {
      const auto it = directed.find({a, b});
      return it == directed.end() ? 0 : it->second;
    };
    const std::size_t m = corners.size();
    std::set<std::pair<std::size_t, std::size_t>> boundary;
    for(std::size_t k = 0; k < m; ++k) {
      const std::size_t a = corners[k], b = corners[(k + 1) % m];
      boundary.insert({a, b});
      EXPECT_EQ(count_of(a, b), 1) << "boundary edge " << a << "-" << b;
      EXPECT_EQ(count_of(b, a), 0) << "boundary edge " << a << "-" << b << " reversed";
    }
    for(const auto& entry : directed) {
      const std::size_t a = entry.first.first, b = entry.first.second;
      EXPECT_EQ(entry.second, 1) << a << "-" << b;
      EXPECT_TRUE(std::find(corners.begin(), corners.end(), a) != corners.end()) << a;
      if(boundary.count(entry.first) == 0)
        EXPECT_EQ(count_of(b, a), 1) << "diagonal " << a << "-" << b << " not used in both directions";
    }
  }
}

TYPED_TEST(IoMeshReader, TriangulatesFacesOfMoreThanThreeVerticesOnRequest)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  // a unit cube of six quads (outward), plus an unused vertex, then an L-shaped hexagon and a triangle
  // on a separate, flat component
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0), Point(0, 0, 1),
                               Point(1, 0, 1), Point(1, 1, 1), Point(0, 1, 1), Point(9, 9, 9)};
  std::vector<std::vector<std::size_t>> polys = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for(const Point& p : {Point(3, 0, 0), Point(5, 0, 0), Point(5, 1, 0), Point(4, 1, 0), Point(4, 2, 0),
                        Point(3, 2, 0), Point(2, 0, 0)})
    points.push_back(p);
  polys.push_back({9, 10, 11, 12, 13, 14}); // L: area 3
  polys.push_back({9, 14, 15});             // triangle (2,0)-(3,0)-(3,2) on its left: area 1
  const std::string path = dir.write("polygons.off", to_off(points, polys));

  expect_error([&] { Mesh m; TC::read_triangle_mesh(path, m); }, TC::Error_code::not_triangle_mesh,
               {"polygons.off", "face 0", "4 vertices"});

  Mesh mesh;
  const TC::Mesh_input_order<Mesh> order = TC::read_triangle_mesh(path, mesh, TC::parameters::triangulate(true));
  ASSERT_TRUE(CGAL::is_triangle_mesh(mesh));
  ASSERT_EQ(order.vertices.size(), points.size());
  ASSERT_EQ(std::size_t(num_faces(mesh)), 6 * 2 + 4 + 1);
  ASSERT_EQ(order.faces.size(), order.source_faces.size());
  EXPECT_TRUE(std::is_sorted(order.source_faces.begin(), order.source_faces.end()));
  std::size_t v = 0;
  for(auto vd : vertices(mesh))
    EXPECT_EQ(get(CGAL::vertex_point, mesh, vd), points[v++]);

  std::vector<double> area(polys.size(), 0.);
  std::vector<std::size_t> count(polys.size(), 0);
  for(std::size_t t = 0; t < order.faces.size(); ++t) {
    const std::size_t f = order.source_faces[t];
    ASSERT_LT(f, polys.size());
    ++count[f];
    std::vector<Point> corners;
    for(auto h : CGAL::halfedges_around_face(halfedge(order.faces[t], mesh), mesh)) {
      const std::size_t i = index_in<Mesh>(order.vertices, source(h, mesh));
      EXPECT_NE(std::find(polys[f].begin(), polys[f].end(), i), polys[f].end()) << "triangle " << t;
      corners.push_back(points[i]);
    }
    ASSERT_EQ(corners.size(), 3u);
    const Vector n = CGAL::cross_product(corners[1] - corners[0], corners[2] - corners[0]);
    // the face's own normal (Newell), which the triangle must share
    Vector newell = CGAL::NULL_VECTOR;
    for(std::size_t k = 0; k < polys[f].size(); ++k) {
      const Point& a = points[polys[f][k]];
      const Point& b = points[polys[f][(k + 1) % polys[f].size()]];
      newell = newell + Vector((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                               (a.x() - b.x()) * (a.y() + b.y()));
    }
    EXPECT_GT(n * newell, 0.) << "triangle " << t << " is flipped against face " << f;
    area[f] += std::sqrt(n.squared_length()) / 2;
  }
  for(std::size_t f = 0; f < 6; ++f) {
    EXPECT_EQ(count[f], 2u);
    EXPECT_NEAR(area[f], 1., 1e-14);
  }
  EXPECT_EQ(count[6], 4u);
  EXPECT_NEAR(area[6], 3., 1e-14);
  EXPECT_EQ(count[7], 1u);
  // the cube became a closed sphere: chi = 2 (8 - 18 + 12)
  std::size_t border = 0;
  for(auto h : halfedges(mesh))
    border += is_border(h, mesh);
  EXPECT_EQ(border, 5u + 2u); // the L and the triangle share the edge 9-14
  EXPECT_EQ(std::size_t(num_edges(mesh)), 18u + 9u + 2u);

  // a triangle-only file is read as before: source_faces stays empty
  Mesh tet;
  const auto tet_order =
    TC::read_triangle_mesh(dir.write("tet.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n"
                                                "3 1 2 3\n3 2 0 3\n"),
                           tet, TC::parameters::triangulate(true));
  EXPECT_TRUE(tet_order.source_faces.empty());
  EXPECT_EQ(std::size_t(num_faces(tet)), 4u);

  // faces that cannot be split: collinear corners, a repeated vertex; too few corners
  const std::string line = "OFF\n4 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n";
  expect_error([&] { Mesh m; TC::read_triangle_mesh(dir.write("flat.off", line + "4 0 1 2 3\n"), m,
                                                    TC::parameters::triangulate(true)); },
               TC::Error_code::degenerate_face, {"flat.off", "face 0", "cannot be triangulated"});
  const std::string square = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
  expect_error([&] { Mesh m; TC::read_triangle_mesh(dir.write("repeat.off", square + "5 0 1 2 1 3\n"), m,
                                                    TC::parameters::triangulate(true)); },
               TC::Error_code::degenerate_face, {"repeat.off", "face 0", "vertex 1 twice"});
  expect_error([&] { Mesh m; TC::read_triangle_mesh(dir.write("range.off", square + "4 0 1 2 7\n"), m,
                                                    TC::parameters::triangulate(true)); },
               TC::Error_code::invalid_vertex, {"range.off", "face 0", "vertex 7"});
}

// GOCAD (.ts) goes through CGAL's reader, like PLY and STL
TYPED_TEST(IoMeshReader, ReadsGocadTs)
{
  using Mesh = TypeParam;
  Temp_dir dir;
  const std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)};
  const std::vector<std::vector<std::size_t>> polys = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  const std::string path = dir.file("tet.ts");
  ASSERT_TRUE(CGAL::IO::write_polygon_soup(path, points, polys, CGAL::parameters::stream_precision(17)));
  Mesh mesh;
  const auto order = TC::read_triangle_mesh(path, mesh);
  expect_input_order(mesh, order, points, polys);
  expect_error([&] { Mesh m; TC::read_triangle_mesh(dir.write("tet.vtp", "<VTKFile/>"), m); },
               TC::Error_code::parse_error, {"unknown file extension '.vtp'", ".ts"});
}

TYPED_TEST(IoMeshReader, NonManifoldVerticesAreFoundByTheFanWalk)
{
  using Mesh = TypeParam;
  // two closed octahedra sharing vertex 0 (two closed fans), and an open fan next to a closed one
  std::vector<Point> points = octahedron_points;
  std::vector<std::vector<std::size_t>> polys = octahedron_faces;
  for(int i = 1; i < 6; ++i)
    points.push_back(Point(octahedron_points[std::size_t(i)].x() + 2, octahedron_points[std::size_t(i)].y(),
                           octahedron_points[std::size_t(i)].z()));
  for(const auto& f : octahedron_faces) {
    std::vector<std::size_t> g;
    for(std::size_t v : f)
      g.push_back(v == 1 ? 0 : (v == 0 ? 6 : v + 5)); // second octahedron: its vertex 1 is vertex 0
    polys.push_back(g);
  }
  Mesh mesh;
  const TC::Invalid_input e = expect_error([&] { TC::triangle_soup_to_mesh(points, polys, mesh); },
                                           TC::Error_code::non_manifold, {"non-manifold vertex 0", "2 separate fans"});
  EXPECT_EQ(e.where(), 0u);
}

TEST(IoAtomicFile, ConcurrentWritersGiveTheSameFilesAndStayAllOrNothing)
{
  Temp_dir dir;
  const std::string a = dir.file("a.txt"), b = dir.file("b.txt");
  TC::write_files_atomically({{a, [](std::ostream& os) { os << "a\n"; }}, {b, [](std::ostream& os) { os << "b\n"; }}},
                             true);
  EXPECT_EQ(slurp(a), "a\n");
  EXPECT_EQ(slurp(b), "b\n");
  for(int failing = 0; failing < 2; ++failing) {
    expect_error(
      [&] {
        TC::write_files_atomically(
          {{a, [&](std::ostream& os) {
              os << "new a\n";
              if(failing == 0) throw TC::Invalid_input(TC::Error_code::io_error, "writer a failed");
            }},
           {b, [&](std::ostream& os) {
              os << "new b\n";
              if(failing == 1) throw TC::Invalid_input(TC::Error_code::io_error, "writer b failed");
            }}},
          true);
      },
      TC::Error_code::io_error, {failing == 0 ? "writer a failed" : "writer b failed"});
    EXPECT_EQ(slurp(a), "a\n");
    EXPECT_EQ(slurp(b), "b\n");
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.txt", "b.txt"}));
  }
}

} // namespace
