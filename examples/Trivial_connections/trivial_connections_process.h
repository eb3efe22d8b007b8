// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// How the program trivial_connections sets up its own process before the work (trivial_connections.cpp):
// transparent huge pages for the heap, and OpenBLAS's idle threads stopped. Both change
// only the speed, never a result. Included by that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#if defined(__linux__) && defined(__GLIBC__)
#include <dlfcn.h>
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace trivial_connections_program {

// Mesh files from this size on run with huge pages; below it the heap the program needs fills less than a
// couple of them.
inline constexpr std::uintmax_t huge_page_file_size = std::uintmax_t(256) << 10;
// Mesh files from this size on get them by a second start of the program instead (see use_huge_pages()).
inline constexpr std::uintmax_t restart_file_size = std::uintmax_t(128) << 20;
// The program's heap against the size of its mesh file (OFF): about 12 to 14 times on 75k to 1.2M faces.
inline constexpr std::uintmax_t heap_per_file_byte = 16;

/*
  This process's heap made ready for huge pages before the work: every allocation from the main heap (one arena
  for all threads, no mmap), which is grown once by `reserve` bytes, marked for transparent huge pages and kept
  (no trimming). Returns false, with malloc as it was, when glibc refuses a setting or the heap could not grow.
*/
inline bool huge_page_heap(std::uintmax_t reserve)
{
#if defined(__linux__) && defined(__GLIBC__)
  constexpr std::uintptr_t huge_page = std::uintptr_t(2) << 20;
  reserve = (std::min)(reserve, std::uintmax_t(0x7fffffff) - huge_page); // M_TOP_PAD is an int
  if(reserve < 2 * huge_page)
    return false;
  char* const before = static_cast<char*>(::sbrk(0));
  auto as_it_was = [] { // glibc's defaults
    ::mallopt(M_TOP_PAD, 128 << 10);
    ::mallopt(M_MMAP_MAX, 65536);
    return false;
  };
  if(::mallopt(M_MMAP_MAX, 0) == 0 || ::mallopt(M_TOP_PAD, int(reserve + huge_page)) == 0)
    return as_it_was();
  // a request above what the heap holds now grows it by the request and the pad, all at once
  void* volatile grown = std::malloc(std::size_t(1) << 20); // volatile: the compiler may drop a malloc-free pair
  std::free(grown);
  char* const after = static_cast<char*>(::sbrk(0));
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(before) + huge_page - 1) & ~(huge_page - 1);
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(after) & ~(huge_page - 1);
  if(before == reinterpret_cast<char*>(-1) || end < begin + 2 * huge_page ||
     ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE) != 0 || ::mallopt(M_ARENA_MAX, 1) == 0 ||
     ::mallopt(M_TRIM_THRESHOLD, 0x7fffffff) == 0)
    return as_it_was();
  ::mallopt(M_TOP_PAD, 128 << 10); // the reserve is in place; later growth goes as usual
  return true;
#else
  (void)reserve;
  return false;
#endif
}

/*
  On Linux with glibc, transparent huge pages for the program's heap when the mesh file has at least
  huge_page_file_size bytes, the kernel grants huge pages on request (transparent_hugepage/enabled is `always`
  or `madvise`) and the user has not set glibc's tunable glibc.malloc.hugetlb (GLIBC_TUNABLES=glibc.malloc.hugetlb=0
  keeps the program from all this). Why: on a virtual machine every page fault is a trap to the hypervisor, and
  the program touches its memory once, so 4 KiB faults cost it about a quarter of its time on a 75k-face mesh.
  - Below restart_file_size, in this process (huge_page_heap()): the heap is grown once, heap_per_file_byte times
    the file, and marked for huge pages; everything is allocated there. Measured on bunny00 (75k faces, perf stat,
    15 runs each): 0.153 to 0.158 s, against 0.21 to 0.23 s with the restart below and 0.28 s without huge pages;
    page faults 0.9k against 4.5k and 11.7k.
  - From restart_file_size on (or when that fails), glibc's own malloc asks for huge pages: the program starts
    itself again with glibc.malloc.hugetlb=1 (the tunables are read by the dynamic loader only, hence the second
    start, some 10 to 20 ms; glibc 2.35 or later). A reserve in the heap would have to guess a peak of gigabytes.
  Returns only when the program goes on in this process.
*/
inline void use_huge_pages(char** argv, const std::string& mesh)
{
#if defined(__linux__) && defined(__GLIBC__)
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string current = tunables != nullptr ? tunables : "";
  if(current.find("glibc.malloc.hugetlb") != std::string::npos)
    return;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(mesh, ec);
  if(ec || size < huge_page_file_size)
    return;
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string setting;
  std::getline(thp, setting);
  if(setting.find("[always]") == std::string::npos && setting.find("[madvise]") == std::string::npos)
    return;
  if(size < restart_file_size && huge_page_heap(size * heap_per_file_byte))
    return;
#if __GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35)
  const std::string with_huge_pages = (current.empty() ? "" : current + ":") + "glibc.malloc.hugetlb=1";
  if(::setenv("GLIBC_TUNABLES", with_huge_pages.c_str(), 1) != 0)
    return;
  ::execv("/proc/self/exe", argv);
  // not restarted (no /proc, say): go on as we are, without the variable for the programs we might start
  if(tunables != nullptr)
    ::setenv("GLIBC_TUNABLES", current.c_str(), 1);
  else
    ::unsetenv("GLIBC_TUNABLES");
#else
  (void)argv;
#endif
#else
  (void)argv;
  (void)mesh;
#endif
}

/*
  OpenBLAS (Debian's libopenblas0-pthread, behind CHOLMOD) starts its worker threads when it is loaded, and
  they spin for about 0.1 s waiting for work: on a 2-core machine that takes a core from the program's own
  second thread while the mesh is read and set up, long before CHOLMOD's supernodal factorization (if the
  backend is chosen at all) calls BLAS. They are stopped here; OpenBLAS starts them again at its first
  parallel call. Nothing happens with another BLAS.
*/
inline void stop_idle_blas_threads()
{
#if defined(__linux__) && defined(__GLIBC__)
  using Shutdown = int (*)();
  if(void* f = ::dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"))
    reinterpret_cast<Shutdown>(f)();
#endif
}

} // namespace trivial_connections_program

#endif // CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H
