// SPDX-License-Identifier: GPL-3.0-or-later
// 1000 random and malformed requests over loopback (bounded: each with a short timeout) leave
// the studio serving; under the sanitizer build this also finds memory errors on those paths.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <iterator>
#include <random>

#include "studio_client.h"

namespace dform {
namespace {

using nlohmann::json;

// Raw bytes to the port: whatever the HTTP parser makes of them.
void sendRaw(int port, const std::string& bytes) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  timeval timeout{1, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(std::uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    static_cast<void>(::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL));
    ::shutdown(fd, SHUT_WR);
    char buffer[4096];
    while (::recv(fd, buffer, sizeof buffer, 0) > 0) {
    }
  }
  ::close(fd);
}

TEST(StudioSoak, ThousandRandomAndMalformedRequestsLeaveItServing) {
  StudioOptions options;
  options.maxUploadBytes = 256 * 1024;
  test::StudioClient c(options);
  c.raw().set_read_timeout(10);
  const std::string session = c.session();
  std::mt19937 random(20261127);  // fixed: the same requests every run
  auto pick = [&](int n) { return int(random() % unsigned(n)); };
  auto junk = [&](int length) {
    std::string s;
    for (int i = 0; i < length; ++i) s += char(random() & 0xFF);
    return s;
  };
  const char* paths[] = {
      "/api/solve", "/api/outline", "/api/parametric", "/api/strip",  "/api/curve", "/api/inverse",
      "/api/job",   "/api/session", "/api/events",     "/api/settle", "/",          "/studio.js",
      "/x"};
  const json bodies[] = {
      {{"session", session}, {"seq", 1}, {"start_b", 0.2}, {"resolution", 24}},
      {{"session", session},
       {"piece", "a"},
       {"name", "x.svg"},
       {"text", "<svg><path d='M 0 0 L 10'/></svg>"}},
      {{"session", session},
       {"piece", "b"},
       {"name", "x.json"},
       {"text", "{\"points\": [[0,0],[1e308,0],[0,1]]}"}},
      {{"session", session}, {"piece", "c"}, {"kind", "ellipse"}},
      {{"session", session},
       {"piece", "a"},
       {"kind", "lobed"},
       {"values", {{"lobes", -1e9}, {"amplitude", "x"}}}},
      {{"session", session}, {"name", "c.obj"}, {"text", "v 0 0 0\nv 1 1 1\nl 1 2 1\n"}},
      {{"session", session}, {"seq", "x"}},
      {{"session", session}, {"resolution", 1e9}},
      {{"session", session}, {"starts", 1000}},
      {{"session", nullptr}},
  };
  int answered = 0;
  for (int i = 0; i < 1000; ++i) {
    const int kind = pick(5);
    if (kind == 0) {  // raw garbage or a broken request line
      const std::string garbage[] = {
          junk(pick(200)), "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n" + junk(50),
          "POST /api/solve HTTP/1.1\r\nContent-Length: 99999999\r\n\r\n{",
          "GET /" + std::string(9000, 'a') + " HTTP/1.1\r\n\r\n"};
      sendRaw(c.studio().port(), garbage[pick(4)]);
      continue;
    }
    httplib::Headers headers = pick(4) ? c.headers() : httplib::Headers{};
    if (pick(6) == 0) headers.emplace("Origin", "http://evil.example");
    const std::string path = paths[pick(int(std::size(paths)))];
    std::string body = kind == 1 ? junk(pick(300)) : bodies[pick(10)].dump();
    if (kind == 2 && !body.empty()) body.resize(std::size_t(pick(int(body.size()))));  // cut short
    if (path == "/api/events" || path == "/" || path == "/studio.js" || path == "/x") {
      if (path == "/api/events") continue;  // a stream: covered by the session tests
      if (c.raw().Get(path.c_str(), headers)) ++answered;
    } else if (c.raw().Post(path.c_str(), headers, body,
                            kind == 3 ? "text/plain" : "application/json")) {
      ++answered;
    }
  }
  EXPECT_GT(answered, 500);
  auto alive = c.post("/api/session", json::object());
  EXPECT_EQ(alive.first, 200);
  auto solve = c.post("/api/solve", {{"session", session}, {"seq", 9}});
  EXPECT_EQ(solve.first, 200);
  EXPECT_FALSE(solve.second.contains("error")) << solve.second;
}

}  // namespace
}  // namespace dform
