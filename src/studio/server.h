// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's HTTP server: cpp-httplib's request parsing and routing, behind a connection budget
// of its own that no client can use up (docs/studio.md, "Connections").
//
// One thread accepts connections and holds each until its request line and headers have arrived
// whole (a deadline, the oldest dropped beyond a cap), so a worker is only ever given a request it
// can read without waiting on the network; until the guard lets a request in, the worker reads
// nothing past its headers. Workers answer one request at a time and hand an idle keep-alive
// connection back. An event stream leaves its worker at once: the same thread writes every open
// stream (the oldest closed beyond a cap). A request body is counted as it arrives, chunked or not,
// and cut off at the limit. A client that closes its connection while its request is handled sets
// that request's `clientGone()` flag, which the studio's solves and exports poll.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

// Declared by httplib.h, which stays in the .cpp files (it defines _res, a name Eigen uses).
namespace httplib {
class Server;
}

namespace dform::studio {

struct ServerLimits {
  int workers = 16;              ///< requests handled at once
  std::size_t maxWaiting = 256;  ///< connections waiting for their request; the oldest dropped
  std::size_t maxStreams = 128;  ///< open event streams; the oldest closed beyond
  std::size_t maxHeaderBytes = 16384;               ///< request line and headers
  std::size_t maxBodyBytes = std::size_t(8) << 20;  ///< a request's body (its chunks' data)
  std::chrono::milliseconds requestDeadline{3000};  ///< from accepting to the headers' end
  std::chrono::milliseconds idleDeadline{5000};     ///< a keep-alive connection between requests
  std::chrono::milliseconds readTimeout{5000};      ///< one read of an admitted request's body
  std::chrono::milliseconds writeTimeout{5000};     ///< one write of an answer
  std::chrono::milliseconds streamTick{500};        ///< event streams polled for news at least
};

struct Connection;
class Routes;

class Server {
 public:
  explicit Server(ServerLimits limits = {});
  ~Server();  ///< stop()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// Where the requests' handlers are set: its pre-routing handler, routes, error and exception
  /// handlers answer every request (it never listens itself).
  httplib::Server& routes();

  /// Binds 127.0.0.1 on `port` (0: any free one) and ::1 on the same port where the machine has
  /// IPv6; the port, or -1 when it is taken.
  int bindLoopback(int port);
  /// Starts the accepting thread and the workers.
  void start();
  /// Stops accepting, closes every connection (open streams end), sets every running request's
  /// clientGone() flag and waits for the workers.
  void stop();
  /// Wakes the accepting thread to poll the event streams now (new events were queued).
  void wake();

  // Called by a request's handler, on the worker that answers it:
  /// The request may read a body (up to the limit): the guard let it in.
  static void admitBody();
  /// The connection closes after this answer (the rest of a refused request is never read).
  static void closeAfterAnswer();
  /// Whether the request's body was cut off at the limit (its answer is then 413).
  static bool bodyTooLarge();
  /// Set once the request's client closes its connection before its answer.
  static std::shared_ptr<std::atomic<bool>> clientGone();
  /// Makes the connection an event stream once the handler returns (the handler's own answer is
  /// not sent): "200 text/event-stream" and then whatever `pump` appends, called on the accepting
  /// thread at each wake() and every streamTick; `pump` returns false to end the stream.
  static void streamEvents(std::function<bool(std::string& out)> pump);

  /// Connections waiting for their request, and open event streams, now (for tests).
  std::size_t waiting() const { return waitingCount_.load(); }
  std::size_t streams() const { return streamCount_.load(); }
  /// How many times the accepting thread has woken so far (for tests: a connection that waits
  /// for the rest of its request wakes it only when more arrives).
  std::size_t turns() const { return turnCount_.load(); }

 private:
  struct Loop;  ///< the accepting thread's connections and steps (server.cpp)
  void accepting();
  void working();
  void answer(std::unique_ptr<Connection> connection);
  void handBack(std::unique_ptr<Connection> connection);

  std::unique_ptr<Routes> routes_;
  ServerLimits limits_;
  int listeners_[2] = {-1, -1};
  int wakePipe_[2] = {-1, -1};
  std::atomic<bool> stopping_{false};
  bool started_ = false, stopped_ = false;
  std::thread acceptor_;
  std::vector<std::thread> workers_;

  std::mutex mutex_;  ///< guards the queues below
  std::condition_variable ready_;
  std::deque<std::unique_ptr<Connection>> admitted_;   ///< headers whole, for a worker
  std::vector<std::unique_ptr<Connection>> returned_;  ///< from workers: idle or streams
  std::vector<Connection*> busy_;                      ///< being answered by a worker
  std::atomic<std::size_t> waitingCount_{0}, streamCount_{0}, turnCount_{0};
};

}  // namespace dform::studio
