// SPDX-License-Identifier: GPL-3.0-or-later
// A studio on a free loopback port for a test, and a client that talks to it as the page does.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "dform/io/outline_reader.h"
#include "dform/studio/studio.h"
#include "studio/outlines.h"

// clang-format off
#include <httplib.h>  // last: its resolv.h defines _res, a name Eigen uses
// clang-format on

namespace dform::test {

class StudioClient {
 public:
  explicit StudioClient(const StudioOptions& options = {}) {
    Result<std::unique_ptr<Studio>> started = Studio::start(options);
    if (!started.isOk()) ADD_FAILURE() << started.status().message();
    studio_ = std::move(started).value();
    client_ = std::make_unique<httplib::Client>("127.0.0.1", studio_->port());
    client_->set_read_timeout(180);
  }
  Studio& studio() { return *studio_; }
  httplib::Client& raw() { return *client_; }
  httplib::Headers headers() const { return {{"X-Dform-Token", studio_->token()}}; }
  /// The token's cookie as the page sets it (the page and its assets are asked with it).
  std::string cookie() const {
    return "dform_studio_" + std::to_string(studio_->port()) + "=" + studio_->token();
  }

  std::pair<int, nlohmann::json> post(const std::string& path, const nlohmann::json& body) {
    auto r = client_->Post(path.c_str(), headers(), body.dump(), "application/json");
    if (!r) return {0, nullptr};
    nlohmann::json parsed = nlohmann::json::parse(r->body, nullptr, false);
    return {r->status, parsed};
  }
  std::string session() {
    auto r = post("/api/session", nlohmann::json::object());
    EXPECT_EQ(r.first, 200);
    return r.second.value("session", "");
  }

 private:
  std::unique_ptr<Studio> studio_;
  std::unique_ptr<httplib::Client> client_;
};

/// Reads a session's event stream on a thread of its own.
class EventReader {
 public:
  EventReader(StudioClient& c, const std::string& session)
      : client_("127.0.0.1", c.studio().port()), headers_(c.headers()) {
    client_.set_read_timeout(5);
    thread_ = std::thread([this, session] {
      while (!stop_) {
        // A reconnect (after a read timeout on a loaded machine) resumes after the last event
        // seen, as a browser's EventSource does, so no event is lost between two connections.
        httplib::Headers headers = headers_;
        if (lastId_ >= 0) headers.emplace("Last-Event-ID", std::to_string(lastId_));
        client_.Get(("/api/events?session=" + session).c_str(), headers,
                    [this](const httplib::Response&) {
                      std::lock_guard<std::mutex> lock(mutex_);
                      open_ = true;
                      changed_.notify_all();
                      return true;
                    },
                    [this](const char* data, std::size_t n) {
                      std::lock_guard<std::mutex> lock(mutex_);
                      buffer_.append(data, n);
                      for (std::size_t end; (end = buffer_.find("\n\n")) != std::string::npos;) {
                        read(buffer_.substr(0, end));
                        buffer_.erase(0, end + 2);
                      }
                      changed_.notify_all();
                      return !stop_.load();
                    });
      }
    });
    std::unique_lock<std::mutex> lock(mutex_);  // the stream is open before anything is asked
    changed_.wait_for(lock, std::chrono::seconds(60), [this] { return open_; });
  }
  ~EventReader() {
    stop_ = true;
    client_.stop();
    thread_.join();
  }
  /// The first event of `type` (null on timeout).
  nlohmann::json waitFor(const std::string& type, std::chrono::seconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    nlohmann::json found;
    changed_.wait_for(lock, timeout, [&] {
      for (const auto& e : events_)
        if (e.value("type", "") == type) return found = e, true;
      return false;
    });
    return found;
  }
  std::vector<nlohmann::json> seen() {
    std::lock_guard<std::mutex> lock(mutex_);
    return events_;
  }

 private:
  // One SSE message: its "id: n" line and its "data: {...}" line (comments start with ':').
  void read(const std::string& message) {
    std::size_t from = 0;
    while (from < message.size()) {
      std::size_t to = message.find('\n', from);
      if (to == std::string::npos) to = message.size();
      const std::string line = message.substr(from, to - from);
      if (line.rfind("id: ", 0) == 0) lastId_ = std::stol(line.substr(4));
      if (line.rfind("data: ", 0) == 0) events_.push_back(nlohmann::json::parse(line.substr(6)));
      from = to + 1;
    }
  }

  httplib::Client client_;
  httplib::Headers headers_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::string buffer_;
  bool open_ = false;
  long lastId_ = -1;
  std::vector<nlohmann::json> events_;
  std::thread thread_;
};

inline std::string decodeBase64(const nlohmann::json& text) {
  const std::string in = text.get<std::string>();
  std::string bytes;
  int bits = 0;
  std::uint32_t value = 0;  // unsigned: the shifted-out high bits wrap instead of overflowing
  for (char ch : in) {
    const auto pos =
        std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/").find(ch);
    if (pos == std::string::npos) break;
    value = (value << 6) | std::uint32_t(pos);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes += char((value >> bits) & 0xFF);
    }
  }
  return bytes;
}

inline std::vector<double> decodeDoubles(const nlohmann::json& text) {
  const std::string bytes = decodeBase64(text);
  std::vector<double> out(bytes.size() / sizeof(double));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(double));
  return out;
}

inline std::vector<std::uint32_t> decodeIndices(const nlohmann::json& text) {
  const std::string bytes = decodeBase64(text);
  std::vector<std::uint32_t> out(bytes.size() / sizeof(std::uint32_t));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(std::uint32_t));
  return out;
}

/// The studio's built-in starting ellipse of semi-axes a, b, read as the studio reads it.
inline Shape2 startEllipse(double a, double b, const std::string& name) {
  return parseOutline(studio::parametricOutline("ellipse", {{"a", a}, {"b", b}}), name).value();
}

}  // namespace dform::test
