// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// How the program trivial_connections sets up its own process before the work (trivial_connections.cpp):
// transparent huge pages for the heap, and OpenBLAS's idle threads stopped. Both change
// only the speed, never a result. Included by that file (the program is one translation unit) and by the
// benchmark, which stops OpenBLAS's idle threads the same way.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <system_error>

#if defined(__linux__) && defined(__GLIBC__)
#include <dlfcn.h>
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace trivial_connections_program {

// The heap reserved for the program against the size of its mesh file: --auto's peak heap is 35 to 55 times
// an OFF file on CGAL's meshes of 5k to 90k faces (the smoothest field's complex factor next to the solver's);
// past the reserve the heap grows on 4 KiB pages, as without it.
inline constexpr std::uintmax_t heap_per_file_byte = 64;
// ... and at least this: a small mesh's run touches a few MiB, which cost hundreds of faults on 4 KiB pages.
inline constexpr std::uintmax_t minimum_heap_reserve = std::uintmax_t(16) << 20;

/*
  This process's heap made ready for huge pages before the work: every allocation from the main heap (one arena
  for all threads, no mmap), which is grown once by `reserve` bytes (at most half the machine's memory), marked
  for transparent huge pages and never trimmed. The reserve is address space until it is touched. Returns false,
  with malloc's settings as they were, when glibc refuses a setting or the heap cannot grow that much.
*/
inline bool huge_page_heap(std::uintmax_t reserve)
{
#if defined(__linux__) && defined(__GLIBC__)
  constexpr std::uintptr_t huge_page = std::uintptr_t(2) << 20;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  if(pages > 0 && page_size > 0)
    reserve = (std::min)(reserve, std::uintmax_t(pages) * std::uintmax_t(page_size) / 2);
  if(reserve < 2 * huge_page || reserve > std::uintmax_t((std::numeric_limits<std::size_t>::max)() / 2))
    return false;
  auto as_it_was = [] { // glibc's defaults
    ::mallopt(M_MMAP_MAX, 65536);
    ::mallopt(M_TRIM_THRESHOLD, 128 << 10);
    return false;
  };
  // -1: never trim (the threshold is read as a size_t)
  if(::mallopt(M_MMAP_MAX, 0) == 0 || ::mallopt(M_TRIM_THRESHOLD, -1) == 0)
    return as_it_was();
  char* const before = static_cast<char*>(::sbrk(0));
  // grows the heap by about `reserve`, without touching it; volatile: the compiler may drop a malloc-free pair
  void* volatile grown = std::malloc(std::size_t(reserve));
  const bool got = grown != nullptr;
  std::free(grown);
  char* const after = static_cast<char*>(::sbrk(0));
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(before) + huge_page - 1) & ~(huge_page - 1);
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(after) & ~(huge_page - 1);
  if(!got || before == reinterpret_cast<char*>(-1) || end < begin + 2 * huge_page ||
     ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE) != 0 || ::mallopt(M_ARENA_MAX, 1) == 0)
    return as_it_was();
  return true;
#else
  (void)reserve;
  return false;
#endif
}

/*
  On Linux with glibc, transparent huge pages for the program's heap when the kernel grants huge pages on request (transparent_hugepage/enabled is `always`
  or `madvise`) and the user has not set glibc's tunable glibc.malloc.hugetlb (GLIBC_TUNABLES=glibc.malloc.hugetlb=0
  keeps the program from all this). Why: on a virtual machine every page fault is a trap to the hypervisor, and
  the program touches its memory once, so 4 KiB faults cost it about a third of its time on a 75k-face mesh.
  In this process (huge_page_heap()): the heap is grown once, heap_per_file_byte times the file (at least
  minimum_heap_reserve; a 5k-face mesh's run pays 2.3k faults on 4 KiB pages, a fifth of its time), marked for huge
  pages, and everything is allocated there. Measured on bunny00 (75k faces, perf stat, 15 runs each): 0.144 to
  0.160 s, against 0.19 to 0.23 s with glibc's own huge pages for malloc (below) and 0.28 s without; page faults
  0.9k against 4.5k and 11.7k. When that fails (the heap cannot grow, or glibc refuses a setting), glibc's
  malloc asks for huge pages itself: the program starts itself again with glibc.malloc.hugetlb=1 (the tunables
  are read by the dynamic loader only, hence the second start, some 10 to 20 ms; glibc 2.35 or later). Nothing
  in AddressSanitizer builds, whose allocator is not glibc's. Returns only when the program goes on in this
  process.
*/
inline void use_huge_pages(char** argv, const std::string& mesh)
{
#if defined(__linux__) && defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string current = tunables != nullptr ? tunables : "";
  if(current.find("glibc.malloc.hugetlb") != std::string::npos)
    return;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(mesh, ec);
  if(ec)
    return;
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string setting;
  std::getline(thp, setting);
  if(setting.find("[always]") == std::string::npos && setting.find("[madvise]") == std::string::npos)
    return;
  if(size <= (std::numeric_limits<std::uintmax_t>::max)() / heap_per_file_byte &&
     huge_page_heap((std::max)(minimum_heap_reserve, size * heap_per_file_byte)))
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
  Under a limit on the address space (`ulimit -v`, RLIMIT_AS), OpenBLAS's worker threads, started when it is
  loaded, retry forever to map their 128 MB buffers, and stop_idle_blas_threads() then waits for them forever:
  the program hung on a 5k-face mesh under 150 MB. With one thread OpenBLAS starts none, and a BLAS call that
  finds no memory is a clear out-of-memory error. OPENBLAS_NUM_THREADS is read only when the library is loaded,
  so the program starts itself again with it (10 to 20 ms, only under such a limit; a value the user set stays).
  Under about 65 MB OpenBLAS cannot even create those threads when it is loaded, before main(), and ends the
  process itself: OPENBLAS_NUM_THREADS=1 set by the user avoids that too.
*/
inline void one_blas_thread_under_address_limit(char** argv)
{
#if defined(__linux__) && defined(__GLIBC__)
  struct rlimit limit;
  if(::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY || std::getenv("OPENBLAS_NUM_THREADS"))
    return;
  if(::setenv("OPENBLAS_NUM_THREADS", "1", 1) != 0)
    return;
  ::execv("/proc/self/exe", argv);
  ::unsetenv("OPENBLAS_NUM_THREADS"); // not restarted: go on as we are
#else
  (void)argv;
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
