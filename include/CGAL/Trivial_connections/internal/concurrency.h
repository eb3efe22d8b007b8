// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_CONCURRENCY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_CONCURRENCY_H

#include <future>
#include <system_error>
#include <thread>

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// Starts `task` on a second thread when the machine has more than one core (and the thread can be made);
// otherwise the task runs in the caller's thread when its result is asked for. Either way the future's
// get() returns the result or rethrows the task's exception, and its destructor waits for the task, so a
// task may use anything that outlives the future. Defining CGAL_TRIVIAL_CONNECTIONS_NO_THREADS keeps
// everything in the caller's thread.
template <class Task>
auto concurrently(const Task& task) -> std::future<decltype(task())>
{
#ifndef CGAL_TRIVIAL_CONNECTIONS_NO_THREADS
  if(std::thread::hardware_concurrency() > 1) {
    try {
      return std::async(std::launch::async, task);
    } catch(const std::system_error&) {
      // no thread available: run it later in this one
    }
  }
#endif
  return std::async(std::launch::deferred, task);
}

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_CONCURRENCY_H
