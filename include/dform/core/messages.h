// SPDX-License-Identifier: GPL-3.0-or-later
// The one channel through which library code talks to people. Library code never prints: it emits
// here; the CLI shows the messages on a terminal and the report keeps them.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace dform {

/// How much a message matters: debug detail, information, a warning, or an error.
enum class Level { Debug, Info, Warning, Error };

/// The level's lower-case name ("debug", "info", "warning", "error").
const char* levelName(Level level);

/// One message of a run: its level and its text, in the library's words.
struct Message {
  /// How much it matters.
  Level level;
  /// What it says; names a setting, never a command-line flag.
  std::string text;
};

/// Collects messages and forwards each to an optional listener (the CLI's terminal printer).
class MessageSink {
 public:
  /// Called with each message as it is emitted.
  using Listener = std::function<void(const Message&)>;

  MessageSink() = default;
  /// A sink that also forwards each message to `listener`.
  explicit MessageSink(Listener listener) : listener_(std::move(listener)) {}

  /// Keeps the message and forwards it to the listener, if any.
  void emit(Level level, std::string text);
  /// emit(Level::Debug, text)
  void debug(std::string text) { emit(Level::Debug, std::move(text)); }
  /// emit(Level::Info, text)
  void info(std::string text) { emit(Level::Info, std::move(text)); }
  /// emit(Level::Warning, text)
  void warning(std::string text) { emit(Level::Warning, std::move(text)); }

  /// Every message emitted so far, in order.
  const std::vector<Message>& messages() const { return messages_; }

 private:
  Listener listener_;
  std::vector<Message> messages_;
};

}  // namespace dform
