// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_INDEX_H
#define CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_INDEX_H

#include <CGAL/Trivial_connections/exceptions.h>

#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <ostream>
#include <string>

namespace CGAL {
namespace Trivial_connections {

/*!
\ingroup PkgTrivialConnectionsRef
An exact rational singularity index `p/q`, always stored reduced with `q > 0`.
Indices of an n-direction field are multiples of `1/n`; this is checked exactly with
`is_multiple_of_one_over(n)`, never with a floating-point tolerance.
*/
class Singularity_index
{
public:
  /// the index 0
  Singularity_index() : m_num(0), m_den(1) {}

  /// the index `p/q`; throws `Invalid_input` (`invalid_index`) if `q == 0`, or if `|p|` or `|q|` is not below
  /// `2^62` (so that sums and products of two indices cannot overflow)
  /// \param p the numerator, of any sign
  /// \param q the denominator, non-zero, of any sign
  Singularity_index(std::int64_t p, std::int64_t q = 1) : m_num(p), m_den(q)
  {
    if(q == 0)
      throw Invalid_input(Error_code::invalid_index, "singularity index with a zero denominator");
    // |p|, |q| below 2^62 keep every sum and product of two indices below 2^63
    constexpr std::int64_t bound = std::int64_t(1) << 62;
    if(p <= -bound || p >= bound || q <= -bound || q >= bound)
      throw Invalid_input(Error_code::invalid_index, "singularity index out of range");
    if(m_den < 0) { m_num = -m_num; m_den = -m_den; }
    const std::int64_t g = std::gcd(m_num, m_den);
    if(g > 1) { m_num /= g; m_den /= g; }
  }

  /// `p` of the reduced fraction `p/q` (the sign is carried by `p`)
  /// \returns the numerator `p`
  std::int64_t numerator() const { return m_num; }
  /// `q > 0` of the reduced fraction `p/q`
  /// \returns the denominator `q`, positive
  std::int64_t denominator() const { return m_den; }
  /// `p / q` as a `double`
  /// \returns `double(p) / double(q)`
  double to_double() const { return double(m_num) / double(m_den); }

  /// `true` iff `n * (*this)` is an integer
  /// \param n the symmetry order of an n-direction field
  /// \returns `true` iff `n > 0` and `q` divides `n` (`false` for `n <= 0`)
  bool is_multiple_of_one_over(int n) const { return n > 0 && n % m_den == 0; }

  /// `n * (*this)`; \pre `is_multiple_of_one_over(n)`
  /// \param n the symmetry order
  /// \returns the integer `n p / q`
  std::int64_t times(int n) const { return m_num * (n / m_den); }

  /// parses `"p"` or `"p/q"` (optional sign, decimal digits only); throws `Invalid_input` (`parse_error`)
  /// \param text the whole text to parse, without spaces: an optional sign (`+` or `-`) and at most 18 digits
  ///        for `p`, then optionally `/` and at most 18 digits (no sign) for a non-zero `q`
  /// \returns the index `p/q`, reduced
  static Singularity_index parse(const std::string& text)
  {
    const std::string::size_type slash = text.find('/');
    auto parse_int = [&text](const std::string& s, bool allow_sign) {
      std::size_t i = 0;
      if(allow_sign && i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
      if(i == s.size() || s.size() - i > 18)
        throw Invalid_input(Error_code::parse_error, "malformed singularity index '" + text + "'");
      for(std::size_t j = i; j < s.size(); ++j)
        if(s[j] < '0' || s[j] > '9')
          throw Invalid_input(Error_code::parse_error, "malformed singularity index '" + text + "'");
      return std::int64_t(std::strtoll(s.c_str(), nullptr, 10));
    };
    if(slash == std::string::npos)
      return Singularity_index(parse_int(text, true));
    const std::int64_t p = parse_int(text.substr(0, slash), true);
    const std::int64_t q = parse_int(text.substr(slash + 1), false);
    if(q == 0)
      throw Invalid_input(Error_code::parse_error, "singularity index '" + text + "' has a zero denominator");
    return Singularity_index(p, q);
  }

  /// exact sum (reduced)
  /// \param a the first index
  /// \param b the second index
  /// \returns `a + b`
  friend Singularity_index operator+(const Singularity_index& a, const Singularity_index& b)
  {
    const std::int64_t g = std::gcd(a.m_den, b.m_den);
    return Singularity_index(a.m_num * (b.m_den / g) + b.m_num * (a.m_den / g), (a.m_den / g) * b.m_den);
  }
  /// exact opposite
  /// \param a the index
  /// \returns `-a`
  friend Singularity_index operator-(const Singularity_index& a)
  {
    return Singularity_index(-a.m_num, a.m_den);
  }
  /// exact difference (reduced)
  /// \param a the first index
  /// \param b the index subtracted
  /// \returns `a - b`
  friend Singularity_index operator-(const Singularity_index& a, const Singularity_index& b)
  {
    return a + (-b);
  }
  /// equality of the rational numbers (both are kept reduced)
  /// \param a the first index
  /// \param b the second index
  /// \returns `true` iff `a` and `b` are the same rational number
  friend bool operator==(const Singularity_index& a, const Singularity_index& b)
  {
    return a.m_num == b.m_num && a.m_den == b.m_den;
  }
  /// `!(a == b)`
  /// \param a the first index
  /// \param b the second index
  /// \returns `true` iff `a` and `b` are different rational numbers
  friend bool operator!=(const Singularity_index& a, const Singularity_index& b) { return !(a == b); }

  /// `"p"` or `"p/q"`
  /// \returns `"p"` when `q == 1`, `"p/q"` otherwise (reduced, the sign on `p`), as read by `parse()`
  std::string to_string() const
  {
    return m_den == 1 ? std::to_string(m_num) : std::to_string(m_num) + "/" + std::to_string(m_den);
  }
  /// writes `to_string()`
  /// \param os the output stream
  /// \param k the index written
  /// \returns `os`
  friend std::ostream& operator<<(std::ostream& os, const Singularity_index& k) { return os << k.to_string(); }

private:
  std::int64_t m_num, m_den;
};

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_SINGULARITY_INDEX_H
