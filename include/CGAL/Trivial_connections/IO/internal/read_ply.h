// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_PLY_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_PLY_H

#include <CGAL/Trivial_connections/IO/internal/text_parsing.h>
#include <CGAL/Trivial_connections/exceptions.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

/*
  A PLY reader of our own (ASCII, binary little and big endian), used instead of CGAL's: CGAL 5.5's reader
  trusts list sizes (a 250-byte file asks for 16 GB), dereferences a null pointer on integer coordinates,
  loops forever on an element without properties and reads no face from a list of other index types.
  Every count here is checked against the bytes that are left before anything is allocated for it, so
  memory stays proportional to the file's size and every malformed file ends with a parse_error that names
  its line (header) or its element and item (body).

  What it reads: the x, y, z properties of every `vertex` element item (any scalar type, converted to
  double; they must be finite), and the `vertex_indices` (or `vertex_index`) list of every `face` item (any
  integer type, non-negative). Every other element and property is read past.
*/
enum class Ply_type { int8, uint8, int16, uint16, int32, uint32, float32, float64, none };

inline Ply_type ply_type_of(const std::string& name)
{
  static const std::array<std::pair<const char*, const char*>, 8> names = {{{"char", "int8"},
                                                                           {"uchar", "uint8"},
                                                                           {"short", "int16"},
                                                                           {"ushort", "uint16"},
                                                                           {"int", "int32"},
                                                                           {"uint", "uint32"},
                                                                           {"float", "float32"},
                                                                           {"double", "float64"}}};
  for(std::size_t i = 0; i < names.size(); ++i)
    if(name == names[i].first || name == names[i].second)
      return Ply_type(i);
  return Ply_type::none;
}

inline std::size_t ply_size_of(Ply_type t)
{
  static const std::size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[int(t)];
}

inline bool ply_is_integer(Ply_type t) { return t != Ply_type::float32 && t != Ply_type::float64; }

struct Ply_property
{
  std::string name;
  Ply_type type = Ply_type::none;       // the items' type for a list
  Ply_type count_type = Ply_type::none; // none: not a list
};

struct Ply_element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Ply_property> properties;
};

class Ply_reader
{
public:
  Ply_reader(const char* begin, const char* end, const std::string& path)
    : m_p(begin), m_end(end), m_path(path)
  {}

  template <class Point, class PolygonRange>
  void read(std::vector<Point>& points, PolygonRange& polygons)
  {
    read_header();
    for(const Ply_element& e : m_elements) {
      const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
      int coordinate[3] = {-1, -1, -1}, indices = -1;
      for(std::size_t k = 0; k < e.properties.size(); ++k) {
        const Ply_property& p = e.properties[k];
        for(int c = 0; c < 3 && is_vertex; ++c)
          if(p.name == std::string(1, char('x' + c))) {
            if(p.count_type != Ply_type::none)
              fail_element(e, "its coordinate '" + p.name + "' is a list");
            coordinate[c] = int(k);
          }
        if(is_face && (p.name == "vertex_indices" || (p.name == "vertex_index" && indices < 0))) {
          if(p.count_type == Ply_type::none || !ply_is_integer(p.type))
            fail_element(e, "its property '" + p.name + "' is not a list of integers");
          indices = int(k);
        }
      }
      if(is_vertex && (coordinate[0] < 0 || coordinate[1] < 0 || coordinate[2] < 0))
        fail_element(e, "the vertex element needs the properties x, y and z");
      if(is_face && indices < 0)
        fail_element(e, "the face element has no list property vertex_indices (or vertex_index)");

      for(std::uint64_t item = 0; item < e.count; ++item) {
        double xyz[3] = {0, 0, 0};
        for(std::size_t k = 0; k < e.properties.size(); ++k) {
          const Ply_property& p = e.properties[k];
          if(p.count_type == Ply_type::none) {
            const double value = scalar(p.type, e, item);
            for(int c = 0; c < 3; ++c)
              if(int(k) == coordinate[c])
                xyz[c] = value;
            continue;
          }
          const double size = scalar(p.count_type, e, item);
          if(size < 0)
            fail_item(e, item, "a negative list size");
          // every item takes at least one byte: a size beyond what is left cannot be right
          if(size > double(m_end - m_p))
            fail_item(e, item, "a list of " + std::to_string(std::uint64_t(size)) + " items, more than the file holds");
          const std::size_t n = std::size_t(size);
          if(int(k) == indices)
            polygons.emplace_back();
          for(std::size_t j = 0; j < n; ++j) {
            const double v = scalar(p.type, e, item);
            if(int(k) != indices)
              continue;
            if(v < 0)
              fail_item(e, item, "a negative vertex index");
            polygons.back().push_back(std::size_t(v));
          }
        }
        if(is_vertex) {
          for(int c = 0; c < 3; ++c)
            if(!std::isfinite(xyz[c]))
              fail_item(e, item, std::string("its coordinate ") + char('x' + c) + " is not a finite number");
          points.push_back(Point(xyz[0], xyz[1], xyz[2]));
        }
      }
    }
  }

private:
  [[noreturn]] void fail_line(std::size_t line, const std::string& what) const
  {
    throw Invalid_input(Error_code::parse_error, m_path + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void fail_element(const Ply_element& e, const std::string& what) const
  {
    throw Invalid_input(Error_code::parse_error, m_path + ": element '" + e.name + "': " + what);
  }
  [[noreturn]] void fail_item(const Ply_element& e, std::uint64_t item, const std::string& what) const
  {
    throw Invalid_input(Error_code::parse_error,
                        m_path + ": element '" + e.name + "' item " + std::to_string(item) + ": " + what);
  }

  static std::vector<std::string> words(const char* b, const char* e)
  {
    std::vector<std::string> out;
    while(b != e) {
      const char* w = skip_blanks(b, e);
      b = token_end(w, e);
      if(w != b)
        out.emplace_back(w, b);
    }
    return out;
  }

  // The header, up to and including the end_header line; m_p is then at the first byte of the body.
  void read_header()
  {
    std::size_t line = 0;
    bool format_seen = false;
    if(m_p == m_end)
      throw Invalid_input(Error_code::parse_error, m_path + ": the file is empty");
    while(m_p != m_end) {
      const void* nl = std::memchr(m_p, '\n', std::size_t(m_end - m_p));
      const char* eol = nl != nullptr ? static_cast<const char*>(nl) : m_end;
      const std::vector<std::string> t = words(m_p, eol);
      m_p = eol == m_end ? m_end : eol + 1;
      ++line;
      if(line == 1) {
        if(t.size() != 1 || t[0] != "ply")
          fail_line(line, "not a PLY file (the first line must be 'ply')");
        continue;
      }
      if(t.empty() || t[0] == "comment" || t[0] == "obj_info")
        continue;
      if(t[0] == "format") {
        if(t.size() != 3 || (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
          fail_line(line, "expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
        m_format = t[1] == "ascii" ? 0 : t[1] == "binary_little_endian" ? 1 : 2;
        format_seen = true;
      } else if(t[0] == "element") {
        std::uint64_t count = 0;
        if(t.size() != 3 || !parse_count(t[2], count))
          fail_line(line, "expected 'element NAME COUNT' with a count that is a non-negative integer");
        if(!m_elements.empty() && m_elements.back().properties.empty())
          fail_line(line, "the element before this line has no property");
        m_elements.push_back(Ply_element{t[1], count, {}});
      } else if(t[0] == "property") {
        if(m_elements.empty())
          fail_line(line, "a property before any element");
        Ply_property p;
        if(t.size() == 3 && t[1] != "list") {
          p.type = ply_type_of(t[1]);
          p.name = t[2];
        } else if(t.size() == 5 && t[1] == "list") {
          p.count_type = ply_type_of(t[2]);
          p.type = ply_type_of(t[3]);
          p.name = t[4];
          if(p.count_type == Ply_type::none || !ply_is_integer(p.count_type))
            fail_line(line, "the size type of a list must be an integer type, not '" + t[2] + "'");
        } else {
          fail_line(line, "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
        }
        if(p.type == Ply_type::none)
          fail_line(line, "unknown property type '" + t[t.size() - 2] +
                            "' (expected char, uchar, short, ushort, int, uint, float, double or int8 ... float64)");
        m_elements.back().properties.push_back(p);
      } else if(t[0] == "end_header") {
        if(!format_seen)
          fail_line(line, "end of the header without a format line");
        if(!m_elements.empty() && m_elements.back().properties.empty())
          fail_line(line, "the last element of the header has no property");
        return;
      } else {
        fail_line(line, "unexpected '" + t[0] + "' in the header");
      }
    }
    throw Invalid_input(Error_code::parse_error, m_path + ": the PLY header has no end_header line");
  }

  static bool parse_count(const std::string& s, std::uint64_t& count)
  {
    const std::from_chars_result r = std::from_chars(s.data(), s.data() + s.size(), count, 10);
    return !s.empty() && s[0] != '-' && r.ec == std::errc() && r.ptr == s.data() + s.size();
  }

  // The next value of type t in the body, as a double (exact for every integer type).
  double scalar(Ply_type t, const Ply_element& e, std::uint64_t item)
  {
    if(m_format == 0)
      return ascii_scalar(t, e, item);
    const std::size_t size = ply_size_of(t);
    if(std::size_t(m_end - m_p) < size)
      fail_item(e, item, "unexpected end of file (the header announces " + std::to_string(e.count) + " items)");
    unsigned char b[8];
    std::memcpy(b, m_p, size);
    m_p += size;
    const bool swap = (m_format == 2) == is_little_endian();
    if(swap)
      for(std::size_t i = 0; i < size / 2; ++i)
        std::swap(b[i], b[size - 1 - i]);
    switch(t) {
    case Ply_type::int8: return double(from_bytes<std::int8_t>(b));
    case Ply_type::uint8: return double(from_bytes<std::uint8_t>(b));
    case Ply_type::int16: return double(from_bytes<std::int16_t>(b));
    case Ply_type::uint16: return double(from_bytes<std::uint16_t>(b));
    case Ply_type::int32: return double(from_bytes<std::int32_t>(b));
    case Ply_type::uint32: return double(from_bytes<std::uint32_t>(b));
    case Ply_type::float32: return double(from_bytes<float>(b));
    default: return from_bytes<double>(b);
    }
  }

  template <class T>
  static T from_bytes(const unsigned char* b)
  {
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
  }

  static bool is_little_endian()
  {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }

  double ascii_scalar(Ply_type t, const Ply_element& e, std::uint64_t item)
  {
    const char* w = skip_blanks(m_p, m_end);
    m_p = token_end(w, m_end);
    if(w == m_p)
      fail_item(e, item, "unexpected end of file (the header announces " + std::to_string(e.count) + " items)");
    const std::string word(w, m_p);
    if(ply_is_integer(t)) {
      static const double limits[6][2] = {{-128., 127.}, {0., 255.}, {-32768., 32767.}, {0., 65535.},
                                          {-2147483648., 2147483647.}, {0., 4294967295.}};
      long long v = 0;
      const char* first = w + (*w == '+' ? 1 : 0);
      const std::from_chars_result r = std::from_chars(first, m_p, v, 10);
      if(r.ec != std::errc() || r.ptr != m_p || double(v) < limits[int(t)][0] || double(v) > limits[int(t)][1])
        fail_item(e, item, "'" + word + "' is not a value of the property's integer type");
      return double(v);
    }
    // strtod: overflow gives an infinity (refused where it matters, in coordinates), underflow 0
    char* stop = nullptr;
    const double d = std::strtod(word.c_str(), &stop);
    if(stop != word.c_str() + word.size())
      fail_item(e, item, "'" + word + "' is not a number");
    if(t == Ply_type::float32 && std::isfinite(d)) // the value of a float property is a float, as in binary
      return std::fabs(d) <= double(std::numeric_limits<float>::max()) ? double(float(d))
                                                                         : std::numeric_limits<double>::infinity();
    return d;
  }

  const char* m_p;
  const char* m_end;
  std::string m_path;
  int m_format = 0; // 0 ascii, 1 binary little endian, 2 binary big endian
  std::vector<Ply_element> m_elements;
};

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_READ_PLY_H
