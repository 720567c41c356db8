// SPDX-License-Identifier: GPL-3.0-or-later
// Beside (dform/core/interrupt.h): a computation on a thread of its own, or on the caller's when
// asked to be, that stops with the caller's run and when its result is no longer wanted.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <new>
#include <thread>

#include "dform/core/interrupt.h"

namespace dform {
namespace {

// Polls the stop as the library's loops do, until it is asked for; returns how long it ran.
double runUntilStopped() {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    throwIfInterrupted("the test's loop");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(30)) return 30.0;
  }
}

TEST(Beside, RunsOnAThreadOfItsOwnOrOnTheCallersWhenAsked) {
  for (bool onThread : {true, false}) {
    std::thread::id ranOn;
    Beside<int> beside(onThread, [&] {
      ranOn = std::this_thread::get_id();
      return 42;
    });
    EXPECT_EQ(beside.get(), 42);
    EXPECT_EQ(ranOn == std::this_thread::get_id(), !onThread) << onThread;
  }
}

TEST(Beside, PassesOnWhatTheWorkThrew) {
  Beside<int> beside(true, []() -> int { throw std::bad_alloc(); });
  EXPECT_THROW(beside.get(), std::bad_alloc);
}

// Destroyed before its result is asked for, it stops the work (which polls the stop) and waits
// for it: the work has ended, with Interrupted, when the destructor returns.
TEST(Beside, AResultNoLongerWantedIsStopped) {
  std::atomic<bool> started{false}, ended{false}, interrupted{false};
  {
    Beside<int> beside(true, [&] {
      started = true;
      try {
        runUntilStopped();
      } catch (const Interrupted&) {
        interrupted = true;
      }
      ended = true;
      return 0;
    });
    while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(ended);
  EXPECT_TRUE(interrupted);
}

// The caller's run stopped while it waits: through the caller's own stop flag (ScopedStop) or the
// predicate given; the work is stopped and get() rethrows its Interrupted.
TEST(Beside, TheCallersStopReachesTheWorkWhileTheCallerWaits) {
  for (bool byPredicate : {false, true}) {
    std::atomic<bool> callersStop{false};
    const ScopedStop scope(byPredicate ? nullptr : &callersStop);
    Beside<double> beside(true, runUntilStopped, [&] { return byPredicate && callersStop.load(); });
    std::thread stopper([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      callersStop = true;
    });
    EXPECT_THROW(beside.get(), Interrupted) << byPredicate;
    stopper.join();
  }
}

// The process's stop (interruptFlag: a Ctrl-C) reaches the work on its thread by itself, before
// anyone asks for the result.
TEST(Beside, TheProcesssStopReachesTheWorkByItself) {
  std::atomic<bool> interrupted{false};
  Beside<int> beside(true, [&] {
    try {
      runUntilStopped();
    } catch (const Interrupted&) {
      interrupted = true;
    }
    return 0;
  });
  interruptFlag() = true;
  const auto start = std::chrono::steady_clock::now();
  while (!interrupted && std::chrono::steady_clock::now() - start < std::chrono::seconds(10))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  interruptFlag() = false;
  EXPECT_TRUE(interrupted);
  EXPECT_EQ(beside.get(), 0);
}

}  // namespace
}  // namespace dform
