// Copyright (c) 2026 CGAL Trivial Connections contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : CGAL Trivial Connections developers
//
// Progress callbacks, logging and Ctrl-C in long calls: the library's progress named parameter, forwarded to Python.
// A part of the one translation unit python/trivial_connections_module.cpp (which includes the headers and defines
// the types they use, in its order): not a header to include elsewhere.

#ifndef TRIVIAL_CONNECTIONS_PYTHON_PROGRESS_H
#define TRIVIAL_CONNECTIONS_PYTHON_PROGRESS_H

namespace {

// ---- progress, logging and Ctrl-C during long calls ------------------------------------------------------

// What the progress callback of one call reports to: the user's callable (or None) and the logger
// "trivial_connections". The callback the library gets holds a pointer to it, so that copying the callback
// (the library does, without the GIL) copies no Python object; it lives as long as the call.
struct Progress_context
{
  std::string call; // "Solver()", "solve()", ...
  py::object callable, logger;
  std::chrono::steady_clock::time_point phase_start;

  Progress_context(std::string c, py::object f) : call(std::move(c)), callable(std::move(f))
  {
    if(!callable.is_none() && !PyCallable_Check(callable.ptr()))
      throw py::type_error("progress must be a callable progress(phase, fraction) or None, got " +
                           std::string(py::repr(callable)));
    logger = py::module_::import("logging").attr("getLogger")("trivial_connections");
  }

  // Called by the library between phases and iterations, on the calling thread, without the GIL: takes it,
  // raises a pending KeyboardInterrupt (or whatever a signal handler raised) by throwing, which aborts the C++
  // call; logs the phase (INFO when it starts and ends, DEBUG in between); calls the user's callable, whose
  // exception aborts the call too.
  TC::Progress_callback callback()
  {
    Progress_context* self = this;
    return [self](TC::Phase phase, double fraction) {
      py::gil_scoped_acquire gil;
      if(PyErr_CheckSignals() != 0)
        throw py::error_already_set();
      const char* name = TC::phase_name(phase);
      const auto now = std::chrono::steady_clock::now();
      if(fraction <= 0)
        self->phase_start = now;
      const int level = (fraction <= 0 || fraction >= 1) ? 20 : 10; // logging.INFO, logging.DEBUG
      if(self->logger.attr("isEnabledFor")(level).cast<bool>()) {
        if(fraction <= 0)
          self->logger.attr("log")(level, "%s %s: started", self->call, name);
        else if(fraction >= 1)
          self->logger.attr("log")(level, "%s %s: done in %.3f s", self->call, name,
                                   std::chrono::duration<double>(now - self->phase_start).count());
        else
          self->logger.attr("log")(level, "%s %s: %.0f %%", self->call, name, 100 * fraction);
      }
      if(!self->callable.is_none())
        self->callable(name, fraction);
    };
  }
};

}  // namespace

#endif // TRIVIAL_CONNECTIONS_PYTHON_PROGRESS_H
