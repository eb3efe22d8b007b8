// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_OFF_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_OFF_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/IO/internal/text_parsing.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/IO/helpers.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

/*
  ASCII OFF read line by line, for the files the fast path does not take (polygons, colours, normals,
  comments in odd places): we read OFF ourselves rather than with CGAL's reader, which trusts facet sizes
  (a 60-byte file asks for gigabytes), casts negative sizes and indices read as doubles to unsigned, and
  reads the rest of a counts line with extra numbers as the first vertex. Accepted: the keyword
  `[ST][C][N]OFF` (texture coordinates, colours and normals are read past), the counts `nv nf ne` on one
  line, nv vertex lines of at least three finite coordinates, nf face lines `size i_1 ... i_size` with
  0-based indices < nv (a face colour may follow); `#` comments and blank lines anywhere. Refused with a
  parse_error naming the line: binary, homogeneous (4OFF) and n-dimensional (nOFF) variants, and anything
  malformed. Memory is proportional to the file's size whatever its counts say.
*/
template <class Point, class PolygonRange>
void read_off_soup(const std::string& path, std::vector<Point>& points, PolygonRange& polygons)
{
  std::ifstream is(path, std::ios::binary);
  if(!is)
    throw Invalid_input(Error_code::io_error, "cannot read mesh file '" + path + "'");
  std::string line;
  std::size_t line_number = 0;
  std::vector<std::string> t;
  auto next_tokens = [&]() {
    while(std::getline(is, line)) {
      ++line_number;
      t = tokens_of(line);
      if(!t.empty())
        return true;
    }
    return false;
  };
  const std::string at = path + ":";
  auto fail = [&](const std::string& what) {
    throw Invalid_input(Error_code::parse_error, at + std::to_string(line_number) + ": " + what);
  };
  if(!next_tokens())
    throw Invalid_input(Error_code::parse_error, path + ": the file is empty");
  {
    // CGAL's keyword grammar: [ST][C][N][4][n]OFF
    const std::string& magic = t[0];
    std::size_t j = 0;
    if(magic.compare(0, 2, "ST") == 0)
      j += 2;
    for(const char letter : {'C', 'N', '4', 'n'})
      if(j < magic.size() && magic[j] == letter)
        ++j;
    if(magic.compare(j, std::string::npos, "OFF") != 0)
      fail("expected the keyword OFF (or COFF, NOFF, STOFF, ...) at the start of an OFF file, found '" + magic + "'");
    if(magic.find_first_of("4n") != std::string::npos)
      fail("the OFF variant '" + magic + "' (homogeneous or n-dimensional coordinates) is not supported");
  }
  if(t.size() > 1 && t[1] == "BINARY")
    fail("binary OFF is not supported: write the mesh as ASCII OFF, or as PLY (ASCII or binary)");
  std::size_t k = 1;
  if(k == t.size()) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error, path + ": unexpected end of file: expected the vertex and face counts");
    k = 0;
  }
  long long nv = -1, nf = -1, ne = -1;
  if(t.size() != k + 3 || !parse_integer(t[k], nv) || !parse_integer(t[k + 1], nf) || !parse_integer(t[k + 2], ne) ||
     nv < 0 || nf < 0)
    fail("expected the vertex, face and edge counts of the OFF header, three integers on one line");
  for(long long v = 0; v < nv; ++v) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error,
                          path + ": unexpected end of file: the header announces " + std::to_string(nv) +
                            " vertices, the file has " + std::to_string(v));
    check_coordinates(t, 0, at + std::to_string(line_number) + ": vertex " + std::to_string(v), std::size_t(v));
    points.push_back(Point(std::strtod(t[0].c_str(), nullptr), std::strtod(t[1].c_str(), nullptr),
                           std::strtod(t[2].c_str(), nullptr)));
  }
  for(long long f = 0; f < nf; ++f) {
    if(!next_tokens())
      throw Invalid_input(Error_code::parse_error,
                          path + ": unexpected end of file: the header announces " + std::to_string(nf) +
                            " faces, the file has " + std::to_string(f));
    const std::string where = at + std::to_string(line_number) + ": face " + std::to_string(f);
    long long size = 0;
    if(!parse_integer(t[0], size) || size < 1)
      throw Invalid_input(Error_code::parse_error, where + ": expected the number of its vertices", std::size_t(f));
    if(t.size() < std::size_t(size) + 1)
      throw Invalid_input(Error_code::parse_error, where + ": expected " + std::to_string(size) + " vertex indices",
                          std::size_t(f));
    polygons.emplace_back();
    for(long long j = 1; j <= size; ++j) {
      long long v = 0;
      if(!parse_integer(t[std::size_t(j)], v))
        throw Invalid_input(Error_code::parse_error, where + ": the vertex index '" + t[std::size_t(j)] +
                                                       "' is not an integer", std::size_t(f));
      if(v < 0 || v >= nv)
        throw Invalid_input(Error_code::invalid_vertex,
                            where + " uses vertex " + std::to_string(v) + " but the mesh has only " +
                              std::to_string(nv) + " vertices (0-based indices 0 to " +
                              (nv == 0 ? std::string("none") : std::to_string(nv - 1)) + ")",
                            std::size_t(f));
      polygons.back().push_back(std::size_t(v));
    }
  }
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, path + ": the mesh has no face (" + std::to_string(nv) + " vertices, 0 faces)");
}

/*
  Fast path for the common ASCII OFF and OBJ files: the whole file is read into memory in one go and parsed
  with std::from_chars. It accepts only a strict subset of what CGAL's readers accept, and for that subset
  it produces exactly the polygon soup CGAL's reader produces (same points: the same correctly rounded
  doubles; same indices). Whenever it meets anything outside that subset (another OFF variant, colours,
  trailing values, a malformed or non-finite number, a truncated file, an index out of range, a polygon
  that is not a triangle, ...) it returns false and the caller falls back to CGAL's reader, so the set of
  accepted files and every error message stay exactly those of the CGAL path.
*/

// The comment-and-blank skipping of CGAL's OFF scanner (skip_comment_OFF): blanks, and lines whose first
// non-blank character is '#'.
inline const char* skip_off_comments(const char* p, const char* end)
{
  for(;;) {
    p = skip_blanks(p, end);
    if(p == end || *p != '#')
      return p;
    p = end_of_line(p, end);
  }
}

/*
  Plain ASCII OFF: the keyword `OFF`, the counts `nv nf ne`, nv lines of exactly three finite coordinates,
  nf lines `3 i j k` with 0-based indices < nv; `#` comments and blank lines where CGAL's scanner skips them.
*/
template <class Point>
bool fast_parse_off(const char* p, const char* end, std::vector<Point>& points,
                    std::vector<std::array<int, 3>>& triangles)
{
  p = skip_off_comments(p, end);
  if(end - p < 4 || p[0] != 'O' || p[1] != 'F' || p[2] != 'F' || !is_blank(p[3]))
    return false;
  p = skip_off_comments(p + 4, end);
  constexpr std::uint64_t int_max = std::uint64_t((std::numeric_limits<int>::max)());
  std::uint64_t counts[3];
  for(int k = 0; k < 3; ++k) {
    if(k > 0)
      p = skip_blanks(p, end); // CGAL reads the face and edge counts with operator>>: no comment there
    const char* e = token_end(p, end);
    if(!parse_plain_index(p, e, int_max, counts[k]))
      return false;
    p = e;
  }
  const std::size_t nv = std::size_t(counts[0]), nf = std::size_t(counts[1]);
  if(nv == 0 || nf == 0)
    return false;
  // a vertex line has at least 6 characters, a face line at least 7: do not trust absurd counts
  const std::size_t size = std::size_t(end - p);
  if(nv > size / 6 || nf > size / 7)
    return false;
  points.clear();
  triangles.clear();
  points.reserve(nv);
  triangles.reserve(nf);
  for(std::size_t v = 0; v < nv; ++v) {
    p = skip_off_comments(p, end);
    const char* eol = end_of_line(p, end);
    if(eol == end) // CGAL's reader fails when a vertex line ends the file
      return false;
    const void* hash = std::memchr(p, '#', std::size_t(eol - p));
    double xyz[3];
    if(!parse_three_doubles(p, hash != nullptr ? static_cast<const char*>(hash) : eol, xyz))
      return false;
    points.emplace_back();
    CGAL::IO::internal::fill_point(xyz[0], xyz[1], xyz[2], 1., points.back());
    p = eol;
  }
  for(std::size_t f = 0; f < nf; ++f) {
    p = skip_off_comments(p, end);
    if(p == end)
      return false;
    const char* eol = end_of_line(p, end);
    const void* hash = std::memchr(p, '#', std::size_t(eol - p));
    const char* last = hash != nullptr ? static_cast<const char*>(hash) : eol;
    const char* e = token_end(p, last);
    std::uint64_t n = 0;
    if(!parse_plain_index(p, e, 3, n) || n != 3)
      return false;
    std::array<int, 3> t;
    for(int k = 0; k < 3; ++k) {
      p = skip_blanks(e, last);
      e = token_end(p, last);
      std::uint64_t i = 0;
      if(!parse_plain_index(p, e, std::uint64_t(nv - 1), i))
        return false;
      t[std::size_t(k)] = int(i);
    }
    if(skip_blanks(e, last) != last)
      return false;
    triangles.push_back(t);
    p = eol;
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_OFF_H
