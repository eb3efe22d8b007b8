// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers

#ifndef CGAL_TRIVIAL_CONNECTIONS_INTERNAL_CONCURRENCY_H
#define CGAL_TRIVIAL_CONNECTIONS_INTERNAL_CONCURRENCY_H

#include <condition_variable>
#include <exception>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>

#if defined(__linux__)
#include <sched.h>
#endif

namespace CGAL {
namespace Trivial_connections {
namespace internal {

// The cores this thread may run on: its affinity on Linux (taskset, a container's cpuset, a batch worker's share
// of the machine), where std::thread::hardware_concurrency() counts every core online; a second thread on the
// same core only takes turns with the first.
inline unsigned usable_cores()
{
#if defined(__linux__) && defined(CPU_COUNT)
  cpu_set_t set;
  CPU_ZERO(&set);
  if(sched_getaffinity(0, sizeof(set), &set) == 0)
    return unsigned(CPU_COUNT(&set));
#endif
  return std::thread::hardware_concurrency();
}

// Starts `task` on a second thread when this thread may run on more than one core (and the thread can be made);
// otherwise the task runs in the caller's thread when its result is asked for. Either way the future's
// get() returns the result or rethrows the task's exception, and its destructor waits for the task, so a
// task may use anything that outlives the future. Defining CGAL_TRIVIAL_CONNECTIONS_NO_THREADS keeps
// everything in the caller's thread.
template <class Task>
auto concurrently(const Task& task) -> std::future<decltype(task())>
{
#ifndef CGAL_TRIVIAL_CONNECTIONS_NO_THREADS
  if(usable_cores() > 1) {
    try {
      return std::async(std::launch::async, task);
    } catch(const std::system_error&) {
      // no thread available: run it later in this one
    }
  }
#endif
  return std::async(std::launch::deferred, task);
}

/*
  One thread kept for the second half of many short steps (a refinement round has several): starting a thread costs
  30-50 us on the machines of benchmark/RESULTS.md, about 7 % of femur's refinement (33 threads), while waking one
  costs a few. The thread starts at the first step, when this thread may run on more than one core (and it can be
  made); otherwise, or with CGAL_TRIVIAL_CONNECTIONS_NO_THREADS, both parts run in the caller's thread. The parts of
  one step must not race; an exception of either is rethrown once both are done.
*/
class Second_thread
{
public:
  Second_thread() = default;
  Second_thread(const Second_thread&) = delete;
  Second_thread& operator=(const Second_thread&) = delete;
  ~Second_thread()
  {
    if(!m_thread.joinable())
      return;
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_stop = true;
    }
    m_wake.notify_one();
    m_thread.join();
  }

  // `here()` in the caller's thread while `there()` runs on the kept one
  template <class Here, class There>
  void together(const Here& here, const There& there)
  {
    if(!started()) {
      here();
      there();
      return;
    }
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_task = [&there] { there(); };
      m_done = false;
      m_error = nullptr;
    }
    m_wake.notify_one();
    std::exception_ptr error;
    try {
      here();
    } catch(...) {
      error = std::current_exception();
    }
    std::unique_lock<std::mutex> lock(m_mutex);
    m_finished.wait(lock, [this] { return m_done; });
    if(!error)
      error = m_error;
    if(error)
      std::rethrow_exception(error);
  }

  // f(0, half) here and f(half, count) on the kept thread, half = count / 2; with results, both of them (first
  // half first)
  template <class F>
  auto on_two_halves(std::size_t count, const F& f)
  {
    using Result = decltype(f(std::size_t(0), std::size_t(0)));
    const std::size_t half = count / 2;
    if constexpr(std::is_void_v<Result>)
      together([&] { f(0, half); }, [&] { f(half, count); });
    else {
      std::optional<Result> first, second;
      together([&] { first.emplace(f(0, half)); }, [&] { second.emplace(f(half, count)); });
      return std::make_pair(std::move(*first), std::move(*second));
    }
  }

private:
  bool started()
  {
#ifdef CGAL_TRIVIAL_CONNECTIONS_NO_THREADS
    return false;
#else
    if(m_thread.joinable())
      return true;
    if(m_refused || usable_cores() < 2)
      return false;
    try {
      m_thread = std::thread([this] { serve(); });
      return true;
    } catch(const std::system_error&) {
      m_refused = true; // no thread available: every step in the caller's thread
      return false;
    }
#endif
  }

  void serve()
  {
    std::unique_lock<std::mutex> lock(m_mutex);
    for(;;) {
      m_wake.wait(lock, [this] { return m_stop || bool(m_task); });
      if(m_stop)
        return; // together() waits for its task: none is left
      std::function<void()> task = std::move(m_task);
      m_task = nullptr;
      lock.unlock();
      std::exception_ptr error;
      try {
        task();
      } catch(...) {
        error = std::current_exception();
      }
      lock.lock();
      m_error = error;
      m_done = true;
      m_finished.notify_one();
    }
  }

  std::thread m_thread;
  std::mutex m_mutex;
  std::condition_variable m_wake, m_finished;
  std::function<void()> m_task;
  std::exception_ptr m_error;
  bool m_done = false, m_stop = false, m_refused = false;
};

} // namespace internal
} // namespace Trivial_connections
} // namespace CGAL

#endif // CGAL_TRIVIAL_CONNECTIONS_INTERNAL_CONCURRENCY_H
