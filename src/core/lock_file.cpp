#include "dform/core/lock_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace dform {

namespace {

// Whether `fd` is still the file at `path` (a holder that released it may have removed it).
bool isFileAt(int fd, const std::string& path) {
  struct stat held {
  }, atPath{};
  return ::fstat(fd, &held) == 0 && ::stat(path.c_str(), &atPath) == 0 &&
         held.st_ino == atPath.st_ino && held.st_dev == atPath.st_dev;
}

}  // namespace

LockFile::~LockFile() { release(); }

void LockFile::release() {
  if (fd_ < 0) return;
  // Removed while still held exclusively: a process that opens it meanwhile finds it gone once
  // it has the lock (acquire checks the file) and takes a fresh one. A shared holder removes it
  // only when it can hold it alone; only ever the file this object holds.
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0 && isFileAt(fd_, path_)) ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

Status LockFile::acquire(const std::string& path, bool exclusive, const std::string& what,
                         const std::string& holder) {
  path_ = path;
  for (int attempt = 0; attempt < 8 && fd_ < 0; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      return {ErrorCode::OutputFailed,
              what + ": cannot create " + path + " (" + std::strerror(errno) + ")"};
    if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0) {
      const int error = errno;
      char pid[32] = "";
      const ssize_t got = ::pread(fd, pid, sizeof pid - 1, 0);
      pid[got > 0 ? got : 0] = '\0';
      ::close(fd);
      if (error == EWOULDBLOCK)
        return {
            ErrorCode::OutputFailed,
            what + ": another dform " + holder +
                (pid[0] ? " (process " + std::string(pid) + ")" : "") +
                " is writing this folder; nothing was written (run again when it has finished)"};
      return {ErrorCode::OutputFailed,
              what + ": cannot lock " + path + " (" + std::strerror(error) + ")"};
    }
    if (isFileAt(fd, path))
      fd_ = fd;
    else
      ::close(fd);
  }
  if (fd_ < 0) return {ErrorCode::OutputFailed, what + ": cannot lock " + path};
  if (exclusive) {
    const std::string pid = std::to_string(::getpid());
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0)
      return {ErrorCode::OutputFailed,
              what + ": cannot write " + path + " (" + std::strerror(errno) + ")"};
  }
  return Status::ok();
}

}  // namespace dform
