// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_FILE_CONTENTS_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_FILE_CONTENTS_H

#include <CGAL/disable_warnings.h>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>

namespace CGAL {
namespace Trivial_connections {
namespace internal {
namespace io {

// The whole content of a file, read in one go: mapped into memory where POSIX mmap is available (no copy),
// else read into a buffer. `ok()` is false if the file could not be read (the caller then falls back to
// CGAL's reader, which reports the problem).
class File_contents
{
public:
  explicit File_contents(const std::string& path)
  {
#if defined(__unix__) || defined(__APPLE__)
    const int fd = ::open(path.c_str(), O_RDONLY);
    if(fd >= 0) {
      struct stat st;
      if(::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
        int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
        flags |= MAP_POPULATE; // fault all pages in at once
#endif
        void* p = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, flags, fd, 0);
        if(p != MAP_FAILED) {
          m_map = p;
          m_data = static_cast<const char*>(p);
          m_size = std::size_t(st.st_size);
          m_ok = true;
        }
      }
      ::close(fd);
      if(m_ok)
        return;
    }
#endif
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if(file == nullptr)
      return;
    bool ok = std::fseek(file, 0, SEEK_END) == 0;
    const long size = ok ? std::ftell(file) : -1L;
    ok = ok && size >= 0 && std::fseek(file, 0, SEEK_SET) == 0;
    if(ok) {
      m_buffer.reset(new char[std::size_t(size) + 1]);
      ok = size == 0 || std::fread(m_buffer.get(), 1, std::size_t(size), file) == std::size_t(size);
      m_data = m_buffer.get();
      m_size = std::size_t(size);
    }
    std::fclose(file);
    m_ok = ok;
  }
  ~File_contents()
  {
#if defined(__unix__) || defined(__APPLE__)
    if(m_map != nullptr)
      ::munmap(m_map, m_size);
#endif
  }
  File_contents(const File_contents&) = delete;
  File_contents& operator=(const File_contents&) = delete;

  bool ok() const { return m_ok; }
  const char* begin() const { return m_data; }
  const char* end() const { return m_data + m_size; }

private:
  bool m_ok = false;
  void* m_map = nullptr;
  std::unique_ptr<char[]> m_buffer;
  const char* m_data = nullptr;
  std::size_t m_size = 0;
};

} // namespace io
} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#include <CGAL/enable_warnings.h>

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_INTERNAL_FILE_CONTENTS_H
