// SPDX-License-Identifier: GPL-3.0-or-later
// The process's request to stop a run. Signals are process-wide, so the flag is too: the command
// line's SIGINT/SIGTERM handler sets it (an application embedding dform sets it to cancel a run),
// and the long loops and file reads of every stage poll it.
#pragma once

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <future>
#include <string>
#include <system_error>

#include "dform/core/status.h"

namespace dform {

/// The one flag of the process. Lock-free, so that a signal handler may set it.
std::atomic<bool>& interruptFlag();

namespace detail {
/// The stop flag of the run on this thread besides the process's (ScopedStop), or null.
extern thread_local const std::atomic<bool>* threadStop;
}  // namespace detail

/// Whether a stop has been requested: interruptFlag() is set, or the flag of the run on this
/// thread (ScopedStop) is.
inline bool interruptRequested() {
  return interruptFlag().load(std::memory_order_relaxed) ||
         (detail::threadStop && detail::threadStop->load(std::memory_order_relaxed));
}

/// While it lives, `flag` (when not null) stops the runs of this thread as interruptFlag() stops
/// every run: a server's request whose client went away stops inside its long loops as the
/// command line's Ctrl-C does, without stopping the requests beside it. Threads the run starts
/// are not covered (their callers poll on this thread: runWhilePolling). Scopes nest.
class ScopedStop {
 public:
  /// Makes `flag` (when not null) this thread's stop flag until the scope ends.
  explicit ScopedStop(const std::atomic<bool>* flag) : outer_(detail::threadStop) {
    if (flag) detail::threadStop = flag;
  }
  ~ScopedStop() { detail::threadStop = outer_; }
  ScopedStop(const ScopedStop&) = delete;
  ScopedStop& operator=(const ScopedStop&) = delete;

 private:
  const std::atomic<bool>* outer_;
};

/// Thrown by throwIfInterrupted from inside a long set-up (a triangulation, a matrix assembly)
/// that has no status to return: the entry point of the run's stage (solveDForm, solvePieces,
/// triangulateDomain) catches it and returns ErrorCode::Interrupted, so no half-built value is
/// ever used. Only ever thrown while a stop is requested.
class Interrupted : public std::exception {
 public:
  /// A stop during `stage` (a static string).
  explicit Interrupted(const char* stage) : stage_(stage) {}
  /// "interrupted"
  const char* what() const noexcept override { return "interrupted"; }
  /// The stage that was stopped, as a run's message names it ("the meshing", "the solve").
  const char* stage() const { return stage_; }

 private:
  const char* stage_;
};

/// The Interrupted status of a run or a step that stopped at `stage` ("the solve", "the meshing",
/// "the figures"): the one wording of a stop, whether it was polled or thrown.
inline Status interruptedDuring(const std::string& stage) {
  return Status(ErrorCode::Interrupted, "interrupted during " + stage);
}

/// Throws Interrupted(stage) when a stop has been requested. Cheap (one relaxed load): loops poll
/// it every few thousand iterations, so that any run stops within a fraction of a second.
inline void throwIfInterrupted(const char* stage) {
  if (interruptRequested()) throw Interrupted(stage);
}

/// How often a loop over a fine mesh's elements (faces, vertices, candidate pairs) polls: once per
/// this many, a few milliseconds of work, so that a stop during the figures or the pictures of a
/// 400k-vertex result is seen at once, not after the seconds they take.
constexpr int kPollInterval = 4096;

/// Runs `work` on a thread of its own while this one polls interruptRequested() every 20 ms, for
/// a call that may block or run for seconds and cannot be stopped from outside (an open or read
/// of a FIFO or a silent network mount, CHOLMOD's analysis). Returns true once `work` has run,
/// false on a stop: the thread is then left to finish on its own, so `work` must own (or share)
/// everything it touches; the process is stopping meanwhile. Without a thread to be had (a
/// process or memory limit) `work` runs here.
bool runWhilePolling(std::function<void()> work);

/// A computation run on a thread of its own while the caller works on (the ruled engine's starts
/// and its ways round a mesh, Levenberg-Marquardt's set-up during the relaxation), where asked and
/// where a thread can be started; otherwise it runs on the caller's thread when get() asks for
/// it, so the result never depends on which. The thread heeds the process's stop, and stops when
/// the caller's run is stopped while the caller waits in get() (interruptRequested() on the
/// caller's thread, or `stopAsked`), and when its result is no longer wanted: a Beside destroyed
/// before get() stops it and waits for it. `work` must not outlive what it captures: the
/// destructor waits for the thread.
template <typename T>
class Beside {
 public:
  /// Starts `work` on a thread when `onThread`.
  Beside(
      bool onThread, std::function<T()> work,
      std::function<bool()> stopAsked = [] { return false; })
      : work_(std::move(work)), stopAsked_(std::move(stopAsked)) {
    if (!onThread) return;
    try {
      future_ = std::async(std::launch::async, [this] {
        const ScopedStop stop(&unwanted_);
        return work_();
      });
    } catch (const std::system_error&) {
    }
  }
  /// Stops the thread, unless it has finished, and waits for it (future_ is destroyed next).
  ~Beside() { unwanted_ = true; }
  Beside(const Beside&) = delete;
  Beside& operator=(const Beside&) = delete;

  /// The result, once only; rethrows what `work` threw (Interrupted, std::bad_alloc).
  T get() {
    if (!future_.valid()) return work_();
    // 20 ms: runWhilePolling's pace, far below what a person notices.
    while (future_.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready)
      if (interruptRequested() || stopAsked_()) unwanted_ = true;
    return future_.get();
  }

 private:
  std::atomic<bool> unwanted_{false};
  std::function<T()> work_;
  std::function<bool()> stopAsked_;
  std::future<T> future_;
};

}  // namespace dform
