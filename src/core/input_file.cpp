#include "core/input_file.h"

#include <filesystem>
#include <fstream>
#include <system_error>

namespace dform {

namespace {

std::string sizeText(std::size_t bytes) {
  return bytes >= (std::size_t(1) << 20) ? std::to_string(bytes >> 20) + " MiB"
                                         : std::to_string(bytes >> 10) + " KiB";
}

}  // namespace

Result<std::string> readInputFile(const std::string& path, std::size_t maxBytes) {
  namespace fs = std::filesystem;
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
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status{ErrorCode::InputUnreadable, path + ": cannot be opened for reading"};
  std::string text;
  text.reserve(std::size_t(size));
  // Read at most one buffer past the limit, so a file that grows (or a pipe) cannot exhaust memory.
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, std::size_t(in.gcount()));
    if (text.size() > maxBytes)
      return Status{ErrorCode::InputUnreadable, path + ": file is too large (" + limit + ")"};
  }
  if (in.bad()) return Status{ErrorCode::InputUnreadable, path + ": read error"};
  return text;
}

}  // namespace dform
