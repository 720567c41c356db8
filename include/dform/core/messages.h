// The one channel through which library code talks to people. Library code never prints: it emits
// here; the CLI shows the messages on a terminal and the report keeps them.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace dform {

enum class Level { Debug, Info, Warning, Error };

const char* levelName(Level level);

struct Message {
  Level level;
  std::string text;
};

/// Collects messages and forwards each to an optional listener (the CLI's terminal printer).
class MessageSink {
 public:
  using Listener = std::function<void(const Message&)>;

  MessageSink() = default;
  explicit MessageSink(Listener listener) : listener_(std::move(listener)) {}

  void emit(Level level, std::string text);
  void debug(std::string text) { emit(Level::Debug, std::move(text)); }
  void info(std::string text) { emit(Level::Info, std::move(text)); }
  void warning(std::string text) { emit(Level::Warning, std::move(text)); }

  const std::vector<Message>& messages() const { return messages_; }

 private:
  Listener listener_;
  std::vector<Message> messages_;
};

}  // namespace dform
