// One httplib server's accept loop on its own thread, stoppable at any time after start().
#pragma once

#include <atomic>
#include <thread>

namespace httplib {
class Server;
}

namespace dform::studio {

class Listener {
 public:
  /// Runs server.listen_after_bind() on a new thread and returns once it listens (or has ended).
  /// httplib's stop() does nothing before listen has begun: without the wait, a stop right after
  /// start would leave the thread in accept() for good.
  void start(httplib::Server& server);
  /// Waits for the thread to end (after the server's stop()); nothing if it never started.
  void join();

 private:
  std::thread thread_;
  std::atomic<bool> ended_{false};
};

}  // namespace dform::studio
