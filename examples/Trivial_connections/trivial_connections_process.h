// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// How the program trivial_connections sets up its own process before the work (trivial_connections.cpp):
// transparent huge pages for the heap on large meshes, and OpenBLAS's idle threads stopped. Both change
// only the speed, never a result. Included by that file only: the program is one translation unit.

#ifndef CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H
#define CGAL_TRIVIAL_CONNECTIONS_PROGRAM_PROCESS_H

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#if defined(__linux__) && defined(__GLIBC__)
#include <dlfcn.h>
#include <unistd.h>
#endif

namespace trivial_connections_program {

// Mesh files from this size on run with huge pages: below it, starting the program a second time costs more
// than the page faults it saves (about 15 ms against some 20 ms per MB of OFF, measured on the machine of
// benchmark/RESULTS.md).
inline constexpr std::uintmax_t huge_page_file_size = std::uintmax_t(1) << 20;

/*
  On Linux with glibc 2.35 or later, the program starts itself again with glibc's malloc asking for transparent
  huge pages (the tunable glibc.malloc.hugetlb=1) when the mesh file has at least huge_page_file_size bytes, the
  kernel grants huge pages on request (transparent_hugepage/enabled is `always` or `madvise`) and the user has
  not set that tunable. Why: on a virtual machine every page fault is a trap to the hypervisor, and the program
  touches its memory once, so 4 KiB faults cost it about a quarter of its time on a 75k-face mesh (0.31 s
  against 0.24 s, see the manual's Performance section). The tunables are read by the dynamic loader only, hence
  the second start. GLIBC_TUNABLES=glibc.malloc.hugetlb=0 keeps the program from doing it. Returns only when
  the program goes on in this process.
*/
inline void restart_with_huge_pages(char** argv, const std::string& mesh)
{
#if defined(__linux__) && defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
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
