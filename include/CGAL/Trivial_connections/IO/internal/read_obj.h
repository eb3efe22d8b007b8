// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_OBJ_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_OBJ_H

#include <CGAL/disable_warnings.h>

#include <CGAL/Trivial_connections/IO/internal/text_parsing.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <CGAL/IO/helpers.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

// Checks an OBJ file before CGAL's reader reads it, as read_off_soup() checks OFF: a vertex without three finite
// coordinates, a face index out of range, no face at all.
inline void diagnose_obj(const std::string& path)
{
  std::ifstream is(path);
  if(!is)
    return;
  std::string line;
  std::size_t line_number = 0, nv = 0, nf = 0;
  while(std::getline(is, line)) {
    ++line_number;
    const std::vector<std::string> t = tokens_of(line);
    if(t.empty())
      continue;
    if(t[0] == "v") {
      check_coordinates(t, 1, path + ":" + std::to_string(line_number) + ": vertex " + std::to_string(nv), nv);
      ++nv;
    } else if(t[0] == "f") {
      for(std::size_t j = 1; j < t.size(); ++j) {
        long long v = 0;
        if(!parse_integer(t[j].substr(0, t[j].find('/')), v))
          continue;
        const long long index = v < 0 ? (long long)(nv) + v : v - 1;
        if(index < 0 || index >= (long long)(nv))
          throw Invalid_input(Error_code::invalid_vertex,
                              path + ":" + std::to_string(line_number) + ": face " + std::to_string(nf) +
                                " uses vertex " + t[j] + " (1-based) but only " + std::to_string(nv) +
                                " vertices are defined before it",
                              nf);
      }
      ++nf;
    }
  }
  if(nf == 0)
    throw Invalid_input(Error_code::empty_mesh, path + ": the mesh has no face (" + std::to_string(nv) + " vertices, 0 faces)");
}

/*
  The OBJ half of the fast path described in read_off.h.
  Plain OBJ: lines `v x y z` (exactly three finite numbers), `f a b c` (three positive 1-based indices, each
  optionally followed by `/...`, separated by a space), comments, blank lines, and the lines CGAL's reader
  ignores (vt, vn, vp, o, g, s, usemtl, mtllib). Indices may refer to vertices defined later, as in CGAL's reader.
*/
template <class Point>
bool fast_parse_obj(const char* p, const char* end, std::vector<Point>& points,
                    std::vector<std::array<int, 3>>& triangles)
{
  points.clear();
  triangles.clear();
  const std::size_t size = std::size_t(end - p);
  points.reserve(size / 48 + 1);
  triangles.reserve(size / 24 + 1);
  constexpr std::uint64_t int_max = std::uint64_t((std::numeric_limits<int>::max)());
  std::uint64_t max_index = 0;
  while(p != end) {
    const char* eol = end_of_line(p, end);
    const char* first = p;
    p = eol == end ? end : eol + 1;
    first = skip_blanks(first, eol);
    if(first == eol || *first == '#')
      continue;
    const char* e = token_end(first, eol);
    const std::size_t length = std::size_t(e - first);
    if(length == 1 && *first == 'v') {
      double xyz[3];
      if(!parse_three_doubles(e, eol, xyz))
        return false;
      points.emplace_back();
      CGAL::IO::internal::fill_point(xyz[0], xyz[1], xyz[2], 1., points.back());
    } else if(length == 1 && *first == 'f') {
      std::array<int, 3> t;
      const char* q = e;
      for(int k = 0; k < 3; ++k) {
        q = skip_blanks(q, eol);
        const char* digits_end = q;
        while(digits_end != eol && *digits_end >= '0' && *digits_end <= '9')
          ++digits_end;
        const char* te = token_end(q, eol);
        std::uint64_t i = 0;
        // CGAL reads the integer, then skips past the next space (at most 256 characters)
        if(!parse_plain_index(q, digits_end, int_max, i) || i == 0 || te - q > 200 ||
           (digits_end != te && *digits_end != '/') || (k < 2 && (te == eol || *te != ' ')))
          return false;
        t[std::size_t(k)] = int(i - 1);
        max_index = (std::max)(max_index, i - 1);
        q = te;
      }
      if(skip_blanks(q, eol) != eol)
        return false;
      triangles.push_back(t);
    } else {
      const std::string keyword(first, e);
      if(keyword != "vt" && keyword != "vn" && keyword != "vp" && keyword != "o" && keyword != "g" &&
         keyword != "s" && keyword != "usemtl" && keyword != "mtllib")
        return false;
    }
  }
  // CGAL's reader refuses an empty soup and an index beyond the vertex count (it lets index nv through,
  // which the validation then reports)
  return !points.empty() && !triangles.empty() && max_index <= std::uint64_t(points.size());
}

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_OBJ_H
