// SPDX-License-Identifier: GPL-3.0-or-later
#include "server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <list>

// Last: glibc's resolv.h, which it includes, defines _res, a name Eigen's headers use.
#include <httplib.h>

namespace dform::studio {

using Clock = std::chrono::steady_clock;

namespace {

// Bytes of a chunked body's framing (its chunk sizes and line ends) let through beyond the
// body's limit: a body cut at the limit still reaches it whatever its chunks.
constexpr std::size_t kFramingBytes = std::size_t(64) << 10;
// An event stream whose client reads nothing is closed once this much waits for it.
constexpr std::size_t kMaxUnsentStreamBytes = std::size_t(4) << 20;
// An event stream that sent nothing for this long sends a comment, as a sign of life to a
// client that times out a silent connection.
constexpr auto kStreamKeepAlive = std::chrono::seconds(1);

int millisecondsUntil(Clock::time_point when) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(when - Clock::now());
  return int(std::clamp<long long>(left.count(), 0, 60000));
}

bool waitFor(int fd, short events, std::chrono::milliseconds timeout) {
  pollfd p{fd, events, 0};
  int got;
  while ((got = ::poll(&p, 1, int(timeout.count()))) < 0 && errno == EINTR) {
  }
  return got > 0;
}

}  // namespace

// httplib's request parsing and routing, called on a socket this server owns.
class Routes : public httplib::Server {
 public:
  using httplib::Server::process_request;
};

struct Connection {
  int fd = -1;
  long id = 0;                 ///< unique: a busy connection is found again by it
  Clock::time_point deadline;  ///< waiting: when it is dropped
  std::string head;            ///< the request line and headers, read at once when admitted
  std::size_t headUsed = 0;    ///< of `head`, what the parser has taken
  std::size_t headBytes = 0;   ///< how long the head is (found by peeking before admitting)
  bool partialHead = false;    ///< waiting with part of its head: its low-water mark is raised
  std::size_t budget = 0;      ///< bytes past the head the request may still read
  std::size_t bodyLimit = 0;   ///< what admitBody() lets it read
  bool bodyAdmitted = false, tooLarge = false, closeAfter = false;
  std::shared_ptr<std::atomic<bool>> gone;
  std::function<bool(std::string&)> pump;  ///< set: an event stream
  std::string outbox;                      ///< an event stream's bytes not yet sent
  Clock::time_point lastSent;
  // Shut down before it is closed: a worker's connection may be in the accepting thread's poll
  // set, which holds the socket open past close() until that poll returns (up to a stream tick),
  // and its client would wait that long for the end of an answer that closes the connection.
  ~Connection() {
    if (fd < 0) return;
    ::shutdown(fd, SHUT_RDWR);
    ::close(fd);
  }
};

namespace {

thread_local Connection* current = nullptr;

// A socket as httplib's parser reads and writes it: reads never go past what the request may
// read (its head until the guard admits its body, then the body's limit), and block at most the
// read timeout each.
class ConnectionStream : public httplib::Stream {
 public:
  ConnectionStream(Connection& c, const ServerLimits& limits) : c_(c), limits_(limits) {}

  bool is_readable() const override {
    return c_.headUsed < c_.head.size() || waitFor(c_.fd, POLLIN, limits_.readTimeout);
  }
  bool is_writable() const override { return waitFor(c_.fd, POLLOUT, limits_.writeTimeout); }

  ssize_t read(char* ptr, size_t size) override {
    if (c_.headUsed < c_.head.size()) {
      const std::size_t n = std::min(size, c_.head.size() - c_.headUsed);
      std::memcpy(ptr, c_.head.data() + c_.headUsed, n);
      c_.headUsed += n;
      return ssize_t(n);
    }
    if (c_.budget == 0) {
      c_.tooLarge = c_.bodyAdmitted;
      return -1;
    }
    if (!waitFor(c_.fd, POLLIN, limits_.readTimeout)) return -1;
    ssize_t n;
    while ((n = ::recv(c_.fd, ptr, std::min(size, c_.budget), 0)) < 0 && errno == EINTR) {
    }
    if (n > 0) c_.budget -= std::size_t(n);
    return n;
  }

  ssize_t write(const char* ptr, size_t size) override {
    if (c_.pump) return ssize_t(size);  // an event stream writes its own answer
    std::size_t sent = 0;
    while (sent < size) {
      if (!waitFor(c_.fd, POLLOUT, limits_.writeTimeout)) return -1;
      const ssize_t n = ::send(c_.fd, ptr + sent, size - sent, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return -1;
      sent += std::size_t(n);
    }
    return ssize_t(size);
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    address(::getpeername, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    address(::getsockname, ip, port);
  }
  // httplib answers 500 for a socket number past select()'s FD_SETSIZE; this server polls, so
  // any number will do and none past it is shown.
  socket_t socket() const override { return c_.fd < FD_SETSIZE ? c_.fd : 0; }

 private:
  void address(int (*get)(int, sockaddr*, socklen_t*), std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t size = sizeof a;
    ip.clear();
    port = 0;
    if (get(c_.fd, reinterpret_cast<sockaddr*>(&a), &size) != 0) return;
    char text[INET6_ADDRSTRLEN] = "";
    if (a.ss_family == AF_INET) {
      const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
      port = ntohs(v4->sin_port);
    } else if (a.ss_family == AF_INET6) {
      const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
      ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
      port = ntohs(v6->sin6_port);
    }
    ip = text;
  }

  Connection& c_;
  const ServerLimits& limits_;
};

// A listening socket on a loopback address, non-blocking; -1 when it cannot be had.
int listenOn(const char* host, int family, int port) {
  const int fd = ::socket(family, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return -1;
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_storage a{};
  socklen_t size = 0;
  if (family == AF_INET) {
    auto* v4 = reinterpret_cast<sockaddr_in*>(&a);
    v4->sin_family = AF_INET;
    v4->sin_port = htons(uint16_t(port));
    ::inet_pton(AF_INET, host, &v4->sin_addr);
    size = sizeof *v4;
  } else {
    ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &yes, sizeof yes);
    auto* v6 = reinterpret_cast<sockaddr_in6*>(&a);
    v6->sin6_family = AF_INET6;
    v6->sin6_port = htons(uint16_t(port));
    ::inet_pton(AF_INET6, host, &v6->sin6_addr);
    size = sizeof *v6;
  }
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), size) != 0 || ::listen(fd, 512) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

int boundPort(int fd) {
  sockaddr_storage a{};
  socklen_t size = sizeof a;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &size) != 0) return -1;
  return a.ss_family == AF_INET ? ntohs(reinterpret_cast<sockaddr_in*>(&a)->sin_port)
                                : ntohs(reinterpret_cast<sockaddr_in6*>(&a)->sin6_port);
}

// How long the request line and headers waiting on `fd` are: 0 while they have not all arrived
// (`buffered`: the bytes of them that have), -1 when the client has closed the connection (or it
// failed). At `maxBytes` without their end the request is admitted as it is, for the parser to
// refuse.
long headLength(int fd, std::size_t maxBytes, std::size_t& buffered) {
  std::string peeked(maxBytes, '\0');
  ssize_t n;
  while ((n = ::recv(fd, peeked.data(), maxBytes, MSG_PEEK | MSG_DONTWAIT)) < 0 && errno == EINTR) {
  }
  buffered = n > 0 ? std::size_t(n) : 0;
  if (n == 0) return -1;
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK ? 0 : -1;
  peeked.resize(std::size_t(n));
  const std::size_t end = peeked.find("\r\n\r\n");
  if (end != std::string::npos) return long(end + 4);
  return std::size_t(n) >= maxBytes ? long(n) : 0;
}

// The bytes the socket must hold before poll() calls it readable. Bytes left unread keep a
// socket readable, so a head that arrived in part is polled again only once more of it comes
// (a low-water mark past what is there), not at every turn of the loop; a worker reads with
// the usual mark of 1.
void setLowWater(int fd, std::size_t bytes) {
  const int mark = int(bytes);
  ::setsockopt(fd, SOL_SOCKET, SO_RCVLOWAT, &mark, sizeof mark);
}

// The head without its Accept-Encoding lines. cpp-httplib compresses a text answer (the page,
// its scripts and styles) for a client that accepts brotli or gzip; between two processes on one
// machine that only costs time (docs/studio.md, "Connections").
void acceptNoContentCoding(std::string& head) {
  static const std::string name = "accept-encoding:";
  const auto sameLetter = [](char lower, char c) {
    return lower == std::tolower(static_cast<unsigned char>(c));
  };
  std::size_t lineEnd = head.find("\r\n");  // the request line stays
  while (lineEnd != std::string::npos) {
    const std::size_t start = lineEnd + 2;
    const std::size_t end = head.find("\r\n", start);
    if (end == std::string::npos || end == start) return;  // no more header lines
    if (end - start >= name.size() &&
        std::equal(name.begin(), name.end(), head.begin() + long(start), sameLetter))
      head.erase(start, end + 2 - start);
    else
      lineEnd = end;
  }
}

}  // namespace

Server::Server(ServerLimits limits) : routes_(std::make_unique<Routes>()), limits_(limits) {
  if (::pipe2(wakePipe_, O_CLOEXEC | O_NONBLOCK) != 0) wakePipe_[0] = wakePipe_[1] = -1;
}

Server::~Server() {
  stop();
  for (int fd : {listeners_[0], listeners_[1], wakePipe_[0], wakePipe_[1]})
    if (fd >= 0) ::close(fd);
}

httplib::Server& Server::routes() { return *routes_; }

int Server::bindLoopback(int port) {
  listeners_[0] = listenOn("127.0.0.1", AF_INET, port);
  if (listeners_[0] < 0) return -1;
  const int bound = boundPort(listeners_[0]);
  listeners_[1] = listenOn("::1", AF_INET6, bound);  // where the machine has IPv6
  return bound;
}

void Server::start() {
  if (started_) return;
  started_ = true;
  acceptor_ = std::thread([this] { accepting(); });
  for (int k = 0; k < limits_.workers; ++k) workers_.emplace_back([this] { working(); });
}

void Server::stop() {
  if (stopped_) return;
  stopped_ = true;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    for (Connection* c : busy_) c->gone->store(true);
  }
  wake();
  ready_.notify_all();
  if (acceptor_.joinable()) acceptor_.join();
  for (std::thread& t : workers_) t.join();
  const std::lock_guard<std::mutex> lock(mutex_);
  admitted_.clear();
  returned_.clear();
}

void Server::wake() {
  if (wakePipe_[1] < 0) return;
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(wakePipe_[1], &byte, 1);  // full: a wake is pending
}

void Server::admitBody() {
  if (!current || current->bodyAdmitted) return;
  current->bodyAdmitted = true;
  current->budget = current->bodyLimit;
}

void Server::closeAfterAnswer() {
  if (current) current->closeAfter = true;
}

bool Server::bodyTooLarge() { return current && current->tooLarge; }

std::shared_ptr<std::atomic<bool>> Server::clientGone() {
  return current ? current->gone : std::make_shared<std::atomic<bool>>(false);
}

void Server::streamEvents(std::function<bool(std::string&)> pump) {
  if (current) current->pump = std::move(pump);
}

// The accepting thread's state and steps: new connections wait here until their request's head
// has arrived (then a worker answers it), idle keep-alive connections until their next request,
// event streams for as long as they are open; running requests are watched for their client
// closing. Only the accepting thread touches it.
struct Server::Loop {
  explicit Loop(Server& server) : s(server) {}
  Server& s;
  std::list<std::unique_ptr<Connection>> waiting, streams;
  long nextId = 0;
  std::vector<pollfd> polled;
  std::size_t firstWaiting = 0, firstStream = 0, firstBusy = 0;
  std::vector<long> busyIds;

  // Polls everything at once until something happens, a waiting connection's deadline or the
  // streams' tick.
  void poll() {
    polled.assign(1, {s.wakePipe_[0], POLLIN, 0});
    for (int fd : s.listeners_)
      if (fd >= 0) polled.push_back({fd, POLLIN, 0});
    firstWaiting = polled.size();
    for (const auto& c : waiting) polled.push_back({c->fd, POLLIN | POLLRDHUP, 0});
    firstStream = polled.size();
    for (const auto& c : streams)
      polled.push_back({c->fd, short(POLLIN | POLLRDHUP | (c->outbox.empty() ? 0 : POLLOUT)), 0});
    firstBusy = polled.size();
    busyIds.clear();
    {
      const std::lock_guard<std::mutex> lock(s.mutex_);
      for (Connection* c : s.busy_) {
        polled.push_back({c->fd, POLLRDHUP, 0});
        busyIds.push_back(c->id);
      }
    }
    Clock::time_point next = Clock::now() + s.limits_.streamTick;
    for (const auto& c : waiting) next = std::min(next, c->deadline);
    ::poll(polled.data(), polled.size(), millisecondsUntil(next));
    char drained[64];
    while (::read(s.wakePipe_[0], drained, sizeof drained) > 0) {
    }
  }

  // Running requests whose client has gone: their flag is set, the worker carries on.
  void watchBusy() {
    for (std::size_t k = firstBusy; k < polled.size(); ++k) {
      if (!(polled[k].revents & (POLLRDHUP | POLLHUP | POLLERR))) continue;
      const std::lock_guard<std::mutex> lock(s.mutex_);
      for (Connection* c : s.busy_)
        if (c->id == busyIds[k - firstBusy]) c->gone->store(true);
    }
  }

  // Waiting connections: admitted once their head is whole, dropped when they close (a client
  // that stopped sending in the middle of its head never finishes it) or their time is up. (The
  // poll list's waiting part is in the list's order.)
  void admitWaiting() {
    std::size_t k = firstWaiting;
    for (auto it = waiting.begin(); it != waiting.end() && k < firstStream; ++k) {
      const short revents = polled[k].revents;
      std::size_t buffered = 0;
      long head = revents ? headLength((*it)->fd, s.limits_.maxHeaderBytes, buffered) : 0;
      if (head == 0 && (revents & (POLLRDHUP | POLLHUP | POLLERR))) head = -1;
      if (head == 0 && buffered > 0) {
        setLowWater((*it)->fd, buffered + 1);
        (*it)->partialHead = true;
      }
      if (head > 0) {
        if ((*it)->partialHead) setLowWater((*it)->fd, 1);
        (*it)->partialHead = false;
        (*it)->headBytes = std::size_t(head);
        {
          const std::lock_guard<std::mutex> lock(s.mutex_);
          s.admitted_.push_back(std::move(*it));
        }
        s.ready_.notify_one();
        it = waiting.erase(it);
      } else if (head < 0 || Clock::now() >= (*it)->deadline) {
        it = waiting.erase(it);
      } else {
        ++it;
      }
    }
  }

  // One stream: what its client sends is read and dropped (its closing ends the stream), news
  // appended, and as much sent as the socket takes. False when it is to be closed.
  static bool serveStream(Connection& c, short revents) {
    if (revents & (POLLIN | POLLRDHUP | POLLHUP | POLLERR)) {
      char sink[512];
      const ssize_t n = ::recv(c.fd, sink, sizeof sink, MSG_DONTWAIT);
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR))
        return false;
    }
    std::string news;
    if (!c.pump(news)) return false;
    c.outbox += news;
    if (c.outbox.empty() && Clock::now() - c.lastSent > kStreamKeepAlive) c.outbox = ": alive\n\n";
    while (!c.outbox.empty()) {
      const ssize_t n = ::send(c.fd, c.outbox.data(), c.outbox.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
      if (n <= 0) {
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) break;
        return false;
      }
      c.outbox.erase(0, std::size_t(n));
      c.lastSent = Clock::now();
    }
    return c.outbox.size() <= kMaxUnsentStreamBytes;  // a client that reads nothing is dropped
  }

  void serveStreams() {
    std::size_t k = firstStream;
    for (auto it = streams.begin(); it != streams.end(); ++k) {
      const short revents = k < firstBusy ? polled[k].revents : 0;  // a stream opened since polls
      it = serveStream(**it, revents) ? std::next(it) : streams.erase(it);
    }
  }

  // Connections the workers are done with: idle ones wait for their next request, streams open
  // (the oldest closed beyond the cap).
  void takeReturned() {
    std::vector<std::unique_ptr<Connection>> back;
    {
      const std::lock_guard<std::mutex> lock(s.mutex_);
      back.swap(s.returned_);
    }
    for (auto& c : back) {
      if (c->pump) {
        c->outbox =
            "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\n"
            "Connection: close\r\n\r\n";
        c->lastSent = Clock::now();
        streams.push_back(std::move(c));
        while (streams.size() > s.limits_.maxStreams) streams.pop_front();
      } else {
        c->deadline = Clock::now() + s.limits_.idleDeadline;
        waiting.push_back(std::move(c));
      }
    }
  }

  // New connections, each given the request deadline; beyond the cap the oldest waiting one is
  // dropped, so that no number of connections that send nothing keeps a client out.
  void acceptNew() {
    for (int listener : s.listeners_) {
      if (listener < 0) continue;
      for (int accepted = 0; accepted < 64; ++accepted) {
        const int fd = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd < 0) {
          if ((errno == EMFILE || errno == ENFILE) && !waiting.empty()) {
            waiting.pop_front();  // out of descriptors: the oldest waiting makes room
            continue;
          }
          break;
        }
        const int yes = 1;  // an answer's last partial segment is not held back (Nagle)
        ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
        auto c = std::make_unique<Connection>();
        c->fd = fd;
        c->id = ++nextId;
        c->deadline = Clock::now() + s.limits_.requestDeadline;
        waiting.push_back(std::move(c));
        while (waiting.size() > s.limits_.maxWaiting) waiting.pop_front();
      }
    }
  }

  void run() {
    while (!s.stopping_) {
      poll();
      ++s.turnCount_;
      if (s.stopping_) break;
      watchBusy();
      admitWaiting();
      serveStreams();
      takeReturned();
      acceptNew();
      s.waitingCount_ = waiting.size();
      s.streamCount_ = streams.size();
    }
    s.waitingCount_ = 0;
    s.streamCount_ = 0;
  }
};

void Server::accepting() { Loop(*this).run(); }

void Server::working() {
  for (;;) {
    std::unique_ptr<Connection> c;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [&] { return stopping_ || !admitted_.empty(); });
      if (stopping_) return;
      c = std::move(admitted_.front());
      admitted_.pop_front();
      c->gone = std::make_shared<std::atomic<bool>>(false);
      busy_.push_back(c.get());
    }
    wake();  // the accepting thread watches it for its client closing
    answer(std::move(c));
  }
}

void Server::answer(std::unique_ptr<Connection> c) {
  // The head is in the socket's buffer whole: read at once, then parsed from memory.
  c->head.assign(c->headBytes, '\0');
  ssize_t got;
  while ((got = ::recv(c->fd, c->head.data(), c->headBytes, MSG_WAITALL)) < 0 && errno == EINTR) {
  }
  c->head.resize(got > 0 ? std::size_t(got) : 0);
  acceptNoContentCoding(c->head);
  c->headUsed = 0;
  c->budget = 0;
  c->bodyLimit = limits_.maxBodyBytes + kFramingBytes;
  c->bodyAdmitted = c->tooLarge = c->closeAfter = false;
  bool closed = true, answered = false;
  if (!c->head.empty()) {
    current = c.get();
    ConnectionStream stream(*c, limits_);
    closed = false;
    answered = routes_->process_request(stream, false, closed, nullptr);
    current = nullptr;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    busy_.erase(std::find(busy_.begin(), busy_.end(), c.get()));
  }
  if (c->pump || (answered && !closed && !c->closeAfter && !c->tooLarge && !stopping_))
    handBack(std::move(c));
}

void Server::handBack(std::unique_ptr<Connection> c) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) return;
    returned_.push_back(std::move(c));
  }
  wake();
}

}  // namespace dform::studio
