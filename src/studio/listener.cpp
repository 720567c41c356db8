#include "dform/studio/listener.h"

// clang-format off
#include <httplib.h>  // last: its resolv.h defines _res, a name Eigen uses
// clang-format on

namespace dform::studio {

void Listener::start(httplib::Server& server) {
  thread_ = std::thread([this, &server] {
    server.listen_after_bind();
    ended_ = true;
  });
  while (!server.is_running() && !ended_) std::this_thread::yield();
}

void Listener::join() {
  if (thread_.joinable()) thread_.join();
}

}  // namespace dform::studio
