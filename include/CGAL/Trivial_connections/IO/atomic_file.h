// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_IO_ATOMIC_FILE_H
#define CGAL_TRIVIAL_CONNECTIONS_IO_ATOMIC_FILE_H

#include <CGAL/Trivial_connections/exceptions.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace CGAL {
namespace Trivial_connections {
/*!
\ingroup PkgTrivialConnectionsIO
Writes a function's output to a file through a stream.
*/
using File_writer = std::function<void(std::ostream&)>;

namespace internal {
namespace io {

inline std::string errno_suffix(int err)
{
  return err != 0 ? std::string(": ") + std::strerror(err) : std::string();
}

// A name for a temporary file next to `target` (same directory, so that std::rename does not cross file
// systems), not yet used by any file.
inline std::filesystem::path temporary_path_for(const std::filesystem::path& target)
{
  static std::atomic<unsigned long> counter{0};
  std::random_device device;
  std::mt19937_64 random(
    (std::uint64_t(device()) << 32) ^ std::uint64_t(device()) ^
    std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()) ^ counter.fetch_add(1));
  const std::filesystem::path directory = target.parent_path();
  for(int attempt = 0; attempt < 100; ++attempt) {
    const std::string name =
      "." + target.filename().string() + ".tmp" + std::to_string(random() % 1000000000ull);
    const std::filesystem::path candidate = directory.empty() ? std::filesystem::path(name) : directory / name;
    std::error_code ec;
    if(!std::filesystem::exists(candidate, ec) && !ec)
      return candidate;
  }
  throw Invalid_input(Error_code::io_error, "cannot find a free temporary file name next to '" +
                                              target.string() + "'");
}

inline void remove_quietly(const std::filesystem::path& p)
{
  std::error_code ec;
  std::filesystem::remove(p, ec);
}

// Writes `writer`'s output to a new temporary file next to `target`; returns its path.
// On failure the temporary file is removed and Invalid_input(io_error) (or the writer's exception) is thrown.
inline std::filesystem::path write_temporary(const std::filesystem::path& target, const File_writer& writer)
{
  if(target.empty())
    throw Invalid_input(Error_code::io_error, "empty output file name");
  std::error_code ec;
  if(std::filesystem::is_directory(target, ec))
    throw Invalid_input(Error_code::io_error, "cannot write '" + target.string() + "': it is a directory");
  const std::filesystem::path directory = target.parent_path();
  if(!directory.empty() && !std::filesystem::is_directory(directory, ec))
    throw Invalid_input(Error_code::io_error, "cannot write '" + target.string() + "': directory '" +
                                                directory.string() + "' does not exist");

  const std::filesystem::path temporary = temporary_path_for(target);
  errno = 0;
  std::ofstream os(temporary, std::ios::out | std::ios::trunc);
  if(!os) {
    const int err = errno;
    remove_quietly(temporary);
    throw Invalid_input(Error_code::io_error, "cannot write '" + target.string() + "'" + errno_suffix(err));
  }
  try {
    writer(os);
    os.flush();
    if(!os)
      throw Invalid_input(Error_code::io_error, "error while writing '" + target.string() + "'" +
                                                  errno_suffix(errno));
    os.close();
    if(os.fail())
      throw Invalid_input(Error_code::io_error, "error while closing '" + target.string() + "'" +
                                                  errno_suffix(errno));
  } catch(...) {
    if(os.is_open())
      os.close();
    remove_quietly(temporary);
    throw;
  }
  return temporary;
}

} // namespace io
} // namespace internal

/*!
\ingroup PkgTrivialConnectionsIO
Writes several files together, completely or not at all. Every file is first written by its writer to a
temporary file in the target's directory; the streams are flushed and checked. Only when all of them
succeeded are the temporary files renamed over the targets (`std::rename`, atomic on POSIX file systems).
If anything fails before the renames (a writer throws, a directory does not exist, a target is a
directory, the disk is full), every temporary file is removed, no target is touched, and the exception is
propagated (`Invalid_input` with `Error_code::io_error` for input/output failures; with several failures,
the one of the first file in the list).

With `concurrently == true` the writers run at the same time, each on its own thread (the first one on the
calling thread): they must then not modify anything they share. The result is the same as with
`concurrently == false`, only faster when formatting the files takes time.

A rename can still fail in the final phase (e.g. the directory was removed meanwhile): the remaining
temporary files are then removed and `Invalid_input(io_error)` is thrown; targets renamed before stay written.
\param files the files to write, in order: pairs of a target path and the `File_writer` that writes its
       whole content to the stream it is given
\param concurrently whether the writers run at the same time on separate threads
\pre the targets are pairwise different
*/
inline void write_files_atomically(const std::vector<std::pair<std::string, File_writer>>& files,
                                   bool concurrently = false)
{
  std::vector<std::filesystem::path> temporaries;
  temporaries.reserve(files.size());
  if(concurrently && files.size() > 1) {
    std::vector<std::filesystem::path> written(files.size());
    std::vector<std::exception_ptr> failure(files.size());
    auto write = [&](std::size_t i) {
      try {
        written[i] = internal::io::write_temporary(std::filesystem::path(files[i].first), files[i].second);
      } catch(...) {
        failure[i] = std::current_exception();
      }
    };
    std::vector<std::thread> threads;
    try {
      for(std::size_t i = 1; i < files.size(); ++i)
        threads.emplace_back(write, i);
    } catch(...) { // no thread could be started: write the remaining files here
      for(std::size_t i = threads.size() + 1; i < files.size(); ++i)
        write(i);
    }
    write(0);
    for(std::thread& t : threads)
      t.join();
    for(std::size_t i = 0; i < files.size(); ++i)
      if(failure[i]) {
        for(const auto& t : written)
          if(!t.empty())
            internal::io::remove_quietly(t);
        std::rethrow_exception(failure[i]);
      }
    temporaries = std::move(written);
  } else {
    try {
      for(const auto& f : files)
        temporaries.push_back(internal::io::write_temporary(std::filesystem::path(f.first), f.second));
    } catch(...) {
      for(const auto& t : temporaries)
        internal::io::remove_quietly(t);
      throw;
    }
  }
  for(std::size_t i = 0; i < files.size(); ++i) {
    errno = 0;
    if(std::rename(temporaries[i].string().c_str(), files[i].first.c_str()) != 0) {
      const int err = errno;
      for(std::size_t j = i; j < files.size(); ++j)
        internal::io::remove_quietly(temporaries[j]);
      throw Invalid_input(Error_code::io_error,
                          "cannot move the new '" + files[i].first + "' into place" + internal::io::errno_suffix(err));
    }
  }
}

/*!
\ingroup PkgTrivialConnectionsIO
Writes one file completely or not at all (see `write_files_atomically()`).
\param path the target file
\param writer writes the whole content of the file to the stream it is given
*/
inline void write_file_atomically(const std::string& path, const File_writer& writer)
{
  write_files_atomically({{path, writer}});
}

} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_IO_ATOMIC_FILE_H
