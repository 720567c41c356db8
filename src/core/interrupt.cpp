// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/interrupt.h"

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

namespace dform {

namespace {

// Constant-initialised, so a signal arriving before main() finds it ready.
std::atomic<bool> flag{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler sets the flag");

}  // namespace

std::atomic<bool>& interruptFlag() { return flag; }

thread_local const std::atomic<bool>* detail::threadStop = nullptr;

bool runWhilePolling(std::function<void()> work) {
  struct Pending {
    std::mutex mutex;
    std::condition_variable done;
    bool finished = false;
  };
  auto pending = std::make_shared<Pending>();
  // Shared, so that it is still here to run on this thread when no thread can be started.
  auto task = std::make_shared<std::function<void()>>(std::move(work));
  try {
    std::thread([pending, task] {
      (*task)();
      const std::lock_guard<std::mutex> lock(pending->mutex);
      pending->finished = true;
      pending->done.notify_one();
    }).detach();
  } catch (const std::system_error&) {
    (*task)();
    return true;
  }
  // 20 ms: far below what a person notices, and a few hundred wake-ups over a long wait.
  constexpr std::chrono::milliseconds kPoll{20};
  std::unique_lock<std::mutex> lock(pending->mutex);
  while (!pending->done.wait_for(lock, kPoll, [&] { return pending->finished; }))
    if (interruptRequested()) return false;
  return true;
}

}  // namespace dform
