// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_STORAGE_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_STORAGE_H

#include <CGAL/Trivial_connections/internal/concurrency.h>

#include <Eigen/SparseCholesky>

#include <cstddef>
#include <cstdint>
#include <future>

#if defined(__linux__) && !defined(CGAL_TRIVIAL_CONNECTIONS_NO_HUGE_PAGES)
#include <sys/mman.h>
#endif

namespace CGAL {
namespace Trivial_connections {
namespace internal {

/*
  The first write to a page of new memory costs a page fault; on a virtual machine it can cost more than the
  arithmetic done there afterwards (about 11 us per 4 KiB page on the machine of benchmark/RESULTS.md, where the
  factor of a 75k-face mesh is 3,000 pages and its numeric factorization 35 ms). The factorizations allocate the
  factor in their symbolic analysis and first write it in the numeric one, on one thread. Between the two, these
  functions write every page of it once, half on a second thread (concurrently()): page faults of two threads are
  served at the same time. The factor is not yet written, so nothing is overwritten. On Linux, an array of the
  factor of 16 MiB or more is also offered transparent huge pages (madvise(MADV_HUGEPAGE) on the 2 MiB blocks
  inside it, which the system's "madvise" setting of transparent huge pages honours): one fault per 2 MiB instead
  of 512. Measured there: the numeric factorization of a 302k-face mesh 570-660 -> 470-515 ms, of a 1.2M-face one
  (CHOLMOD) 2.8-3.5 -> 2.35 s; no gain on a 75k-face one (an 8 MiB factor), hence the threshold. Defining
  CGAL_TRIVIAL_CONNECTIONS_NO_HUGE_PAGES leaves that out.
*/
template <class T>
void write_every_page(T* first, std::ptrdiff_t count)
{
  constexpr std::ptrdiff_t per_page = std::ptrdiff_t(4096 / sizeof(T));
  for(std::ptrdiff_t i = 0; i < count; i += per_page)
    first[i] = T();
}

// madvise(MADV_HUGEPAGE) on the 2 MiB blocks inside [first, first + bytes), whatever its size (a hint: failure
// changes nothing); for memory that is known to pay, as the refinement's column store (placement/move_energy.h)
inline void advise_huge_page_blocks(void* first, std::size_t bytes)
{
#if defined(__linux__) && !defined(CGAL_TRIVIAL_CONNECTIONS_NO_HUGE_PAGES) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t(1) << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(first) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(first) + bytes) & ~(huge - 1);
  if(end > begin)
    ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)first;
  (void)bytes;
#endif
}

// the same for an array of the factor of 16 MiB or more (see above)
inline void advise_huge_pages(void* first, std::size_t bytes)
{
  if(bytes >= (std::size_t(16) << 20))
    advise_huge_page_blocks(first, bytes);
}

// Below a megabyte, nothing: the second thread would cost more than it saves.
template <class T>
void write_every_page_on_two_threads(T* first, std::ptrdiff_t count)
{
  if(count * std::ptrdiff_t(sizeof(T)) < (std::ptrdiff_t(1) << 20))
    return;
  advise_huge_pages(first, std::size_t(count) * sizeof(T));
  const std::ptrdiff_t half = count / 2;
  std::future<int> second = concurrently([first, half, count] {
    write_every_page(first + half, count - half);
    return 0;
  });
  write_every_page(first, half);
  second.get();
}

// the protected members of an Eigen simplicial factorization (matrixL() asserts a finished factorization), reached
// through pointers to members
template <class Simplicial>
struct Simplicial_members : Simplicial
{
  static auto& factor(Simplicial& s) { return s.*(&Simplicial_members::m_matrix); }
  static auto& diagonal(Simplicial& s) { return s.*(&Simplicial_members::m_diag); }
  static auto& parent(Simplicial& s) { return s.*(&Simplicial_members::m_parent); }
  static auto& column_counts(Simplicial& s) { return s.*(&Simplicial_members::m_nonZerosPerCol); }
  static auto& permutation(Simplicial& s) { return s.*(&Simplicial_members::m_P); }
  static bool analysed(Simplicial& s) { return s.*(&Simplicial_members::m_analysisIsOk); }
  static double shift_offset(Simplicial& s) { return s.*(&Simplicial_members::m_shiftOffset); }
  static double shift_scale(Simplicial& s) { return s.*(&Simplicial_members::m_shiftScale); }
  static void set_factorized(Simplicial& s, Eigen::ComputationInfo info)
  {
    s.*(&Simplicial_members::m_info) = info;
    s.*(&Simplicial_members::m_factorizationIsOk) = true;
  }
};

// After analyzePattern() of an Eigen simplicial factorization: transparent huge pages offered for the factor's
// arrays (see advise_huge_pages()), for a numeric factorization that writes them on two threads itself.
template <class Simplicial>
void advise_huge_pages_for_simplicial_factor(Simplicial& factorization)
{
  auto& L = Simplicial_members<Simplicial>::factor(factorization);
  const std::size_t capacity = std::size_t(L.data().allocatedSize());
  advise_huge_pages(L.valuePtr(), capacity * sizeof(*L.valuePtr()));
  advise_huge_pages(L.innerIndexPtr(), capacity * sizeof(*L.innerIndexPtr()));
}

// After analyzePattern() of an Eigen simplicial factorization (SimplicialLDLT, SimplicialLLT), before factorize():
// the analysis reserved the factor's storage without writing it.
template <class Simplicial>
void touch_simplicial_factor_storage(Simplicial& factorization)
{
  auto& L = Simplicial_members<Simplicial>::factor(factorization);
  const std::ptrdiff_t capacity = std::ptrdiff_t(L.data().allocatedSize());
  write_every_page_on_two_threads(L.valuePtr(), capacity);
  write_every_page_on_two_threads(L.innerIndexPtr(), capacity);
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_FACTORIZATION_FACTOR_STORAGE_H
