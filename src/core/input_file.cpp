// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/input_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include "dform/core/interrupt.h"

namespace dform {

namespace {

Status interruptedReading(const std::string& path) {
  return Status{ErrorCode::Interrupted, path + ": interrupted while waiting to read it"};
}

std::string sizeText(std::size_t bytes) {
  return bytes >= (std::size_t(1) << 20) ? std::to_string(bytes >> 20) + " MiB"
                                         : std::to_string(bytes >> 10) + " KiB";
}

// Reads `fd` to its end, at most one buffer past `maxBytes`, so that a file that grows (or a pipe)
// cannot exhaust memory; `name` is what messages call it. The caller closes `fd`.
Result<std::string> readAll(int fd, const std::string& name, std::size_t maxBytes,
                            std::size_t sizeHint) {
  std::string text;
  text.reserve(sizeHint);
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got == 0) break;
    if (got < 0) {
      if (errno == EINTR) return interruptedReading(name);
      return Status{ErrorCode::InputUnreadable,
                    name + ": read error (" + std::strerror(errno) + ")"};
    }
    text.append(buffer, std::size_t(got));
    if (text.size() > maxBytes)
      return Status{ErrorCode::InputUnreadable,
                    name + ": file is too large (the limit is " + sizeText(maxBytes) + ")"};
  }
  return text;
}

// Standard input read once, whole (up to kMaxInputBytes): a stream can be read only once, and a
// command that reads its input again (a sweep reads its outlines for every start) must see the
// same bytes each time.
Result<std::string> readStandardInput(std::size_t maxBytes) {
  static std::mutex mutex;
  static std::optional<Result<std::string>> whole;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!whole) whole = readAll(STDIN_FILENO, "stdin", kMaxInputBytes, 0);
  if (whole->isOk() && whole->value().size() > maxBytes)
    return Status{ErrorCode::InputUnreadable,
                  "stdin: file is too large (the limit is " + sizeText(maxBytes) + ")"};
  return *whole;
}

// The blocking part of readInputFile: stat, open and read; "-" reads standard input.
Result<std::string> readBlocking(const std::string& path, std::size_t maxBytes) {
  namespace fs = std::filesystem;
  if (path == kStandardInput) return readStandardInput(maxBytes);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  // A missing file (or a path through a regular file) is only not found; anything else (a
  // symbolic-link loop, a folder that may not be searched) is said as the system says it.
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
    return Status{ErrorCode::InputUnreadable, path + ": cannot be read (" + ec.message() + ")"};
  if (!fs::exists(status)) return Status{ErrorCode::InputUnreadable, path + ": no such file"};
  if (fs::is_directory(status))
    return Status{ErrorCode::InputUnreadable, path + ": is a folder, not a file"};
  const std::string limit = "the limit is " + sizeText(maxBytes);
  const std::uintmax_t size = fs::is_regular_file(status) ? fs::file_size(path, ec) : 0;
  if (!ec && size > maxBytes) {
    return Status{ErrorCode::InputUnreadable, path + ": file is too large (" +
                                                  sizeText(std::size_t(size)) + "; " + limit + ")"};
  }
  // POSIX calls rather than a stream, so that an open or a read that a signal interrupts (the
  // CLI's handlers do not restart calls) gives up at once.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == EINTR) return interruptedReading(path);
    return Status{ErrorCode::InputUnreadable,
                  path + ": cannot be opened for reading (" + std::strerror(errno) + ")"};
  }
  Result<std::string> text = readAll(fd, path, maxBytes, std::size_t(size));
  ::close(fd);
  return text;
}

}  // namespace

std::string inputName(const std::string& path) { return path == kStandardInput ? "stdin" : path; }

Result<std::string> readInputFile(const std::string& path, std::size_t maxBytes) {
  // The read runs on a thread of its own while this one polls the interrupt flag: an open or a
  // read can block for as long as a FIFO has no writer or a network mount does not answer, and
  // a signal that came just before the blocking call (or was delivered to another thread) would
  // not interrupt it. Without a thread, the read runs here, where a signal still interrupts a
  // blocked call (EINTR).
  auto result = std::make_shared<std::optional<Result<std::string>>>();
  if (!runWhilePolling([result, path, maxBytes] { *result = readBlocking(path, maxBytes); }))
    return interruptedReading(inputName(path));
  return std::move(**result);
}

}  // namespace dform
