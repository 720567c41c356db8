// An advisory lock file (flock) that keeps a second dform process off a folder: exclusive for a
// run that writes the folder alone, shared for processes that may work side by side (the shards
// of one batch) but not beside an exclusive holder. A lock file whose holder was killed is taken
// over (the kernel drops a dead process's flock); the last holder removes the file.
#pragma once

#include <string>

#include "dform/core/status.h"

namespace dform {

class LockFile {
 public:
  LockFile() = default;
  /// Releases the lock; removes the file when no other process holds it.
  ~LockFile();
  LockFile(const LockFile&) = delete;
  LockFile& operator=(const LockFile&) = delete;

  /// Takes the lock at `path` (created when missing) without waiting. An exclusive holder writes
  /// its process id into the file. OutputFailed when another process holds it: "`what`: another
  /// dform `holder` (process N) is writing this folder; nothing was written", or when the file
  /// cannot be created or locked.
  Status acquire(const std::string& path, bool exclusive, const std::string& what,
                 const std::string& holder = "run");

  /// Releases the lock now (the destructor's work); nothing when none is held.
  void release();

  bool held() const { return fd_ >= 0; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace dform
