// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/lock_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace dform {

namespace {

Status lockFailed(const std::string& message) { return {ErrorCode::OutputFailed, message}; }

// Whether `fd` is still the file at `path` itself (a holder that released it may have removed
// it, or something else may stand at the path now).
bool isFileAt(int fd, const std::string& path) {
  struct stat held {
  }, atPath{};
  return ::fstat(fd, &held) == 0 && ::lstat(path.c_str(), &atPath) == 0 &&
         held.st_ino == atPath.st_ino && held.st_dev == atPath.st_dev;
}

// The process id an exclusive holder wrote into the lock file ("" when there is none).
std::string holderPid(int fd) {
  char pid[32] = "";
  const ssize_t got = ::pread(fd, pid, sizeof pid - 1, 0);
  pid[got > 0 ? got : 0] = '\0';
  const std::string text = pid;
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos ? text : "";
}

std::string busy(const std::string& what, const std::string& holder, const std::string& pid) {
  return what + ": another dform " + holder + (pid.empty() ? "" : " (process " + pid + ")") +
         " is writing this folder; nothing was written (run again when it has finished)";
}

// Why a path in the way of a lock cannot be used: a link or something that is not a file.
std::string lockInTheWay(const std::string& what, const std::string& path) {
  struct stat status {};
  const bool link = ::lstat(path.c_str(), &status) == 0 && S_ISLNK(status.st_mode);
  return what + ": " + path + (link ? " is a symbolic link" : " is not a regular file") +
         " where dform keeps its lock; nothing was written (remove it if no dform run is "
         "using the folder)";
}

// Opens the lock file at `path`, never through a symbolic link: a new one (`created`) or the
// one there (read-only: a file this process did not make is never written). -1 with errno set.
int openLock(const std::string& path, bool& created) {
  created = false;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd >= 0) {
    created = true;
    return fd;
  }
  if (errno != EEXIST) return -1;
  // O_NONBLOCK: a FIFO planted at the path must not block the open.
  return ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
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
  return take(path, exclusive, what, holder, false);
}

Status LockFile::acquireForReading(const std::string& path, const std::string& what) {
  return take(path, false, what, "run", true);
}

Status LockFile::take(const std::string& path, bool exclusive, const std::string& what,
                      const std::string& holder, bool mayGoWithout) {
  path_ = path;
  for (int attempt = 0; attempt < 8 && fd_ < 0; ++attempt) {
    bool created = false;
    const int fd = openLock(path, created);
    if (fd < 0) {
      const int error = errno;
      if (error == ENOENT) continue;  // removed by its holder between the two opens
      if (error == ELOOP) return lockFailed(lockInTheWay(what, path));
      if (mayGoWithout && (error == EACCES || error == EROFS || error == EPERM))
        return Status::ok();
      return lockFailed(what + ": cannot create " + path + " (" + std::strerror(error) + ")");
    }
    struct stat status {};
    if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
      ::close(fd);
      return lockFailed(lockInTheWay(what, path));
    }
    if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) != 0) {
      const int error = errno;
      const std::string pid = holderPid(fd);
      ::close(fd);
      if (error == EWOULDBLOCK) return lockFailed(busy(what, holder, pid));
      return lockFailed(what + ": cannot lock " + path + " (" + std::strerror(error) + ")");
    }
    if (!isFileAt(fd, path)) {
      ::close(fd);
      continue;
    }
    // An exclusive holder names itself in a file of its own: the stale file of a killed holder
    // (locked now, so no one uses it) is removed and the lock made afresh.
    if (exclusive && !created && ::unlink(path.c_str()) == 0) {
      ::close(fd);
      continue;
    }
    fd_ = fd;
    if (exclusive && created) {
      const std::string pid = std::to_string(::getpid());
      if (::pwrite(fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
        return lockFailed(what + ": cannot write " + path + " (" + std::strerror(errno) + ")");
    }
  }
  if (fd_ < 0) return lockFailed(what + ": cannot lock " + path);
  return Status::ok();
}

Status checkNoEnclosingRun(const std::string& dir, const std::string& what) {
  namespace fs = std::filesystem;
  const fs::path path = fs::path(dir).lexically_normal();
  for (fs::path folder = path.parent_path(); folder.has_filename() && folder != folder.root_path();
       folder = folder.parent_path()) {
    const std::string lock =
        (folder.parent_path() / ("." + folder.filename().string() + ".dform-lock")).string();
    const int fd = ::open(lock.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) continue;
    struct stat status {};
    const bool busyNow = ::fstat(fd, &status) == 0 && S_ISREG(status.st_mode) &&
                         ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    const std::string pid = busyNow ? holderPid(fd) : "";
    ::close(fd);
    if (busyNow)
      return lockFailed(what + ": " + folder.string() + " is being replaced by another dform run" +
                        (pid.empty() ? "" : " (process " + pid + ")") +
                        ", which would swap this folder away; nothing was written (run "
                        "again when it has finished, or choose a folder outside it)");
  }
  return Status::ok();
}

}  // namespace dform
