// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace dform {

Status writeFileAtomically(const std::string& path, const std::string& content) {
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  // O_EXCL | O_NOFOLLOW: a file or link someone else put at the temporary path is never written
  // through or truncated.
  const int fd =
      ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) {
    if (errno == EEXIST)
      return {ErrorCode::OutputFailed,
              temporary + ": is in the way (a file or symbolic link dform did not make); " +
                  "nothing was written (remove it)"};
    return {ErrorCode::OutputFailed, path + ": cannot write (" + std::strerror(errno) + ")"};
  }
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += std::size_t(n);
  }
  const bool closed = ::close(fd) == 0;
  if (written < content.size() || !closed) {
    ::unlink(temporary.c_str());
    return {ErrorCode::OutputFailed, path + ": write failed (disk full?)"};
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    return {ErrorCode::OutputFailed, path + ": cannot rename into place (" + reason + ")"};
  }
  return Status::ok();
}

}  // namespace dform
