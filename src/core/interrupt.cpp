#include "core/interrupt.h"

namespace dform {

namespace {

// Constant-initialised, so a signal arriving before main() finds it ready.
std::atomic<bool> flag{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler sets the flag");

}  // namespace

std::atomic<bool>& interruptFlag() { return flag; }

}  // namespace dform
