// SPDX-License-Identifier: GPL-3.0-or-later
// An advisory lock file (flock) that keeps a second dform process off a folder: exclusive for a
// run that writes the folder alone, shared for processes that may work side by side (the shards
// of one batch, readers of a result) but not beside an exclusive holder. A lock file whose holder
// was killed is taken over (the kernel drops a dead process's flock); the last holder removes the
// file. The file is never opened through a symbolic link and never written unless this process
// created it: a lock path that someone else's link or file occupies is refused, not followed.
#pragma once

#include <string>

#include "dform/core/status.h"

namespace dform {

/// An advisory lock file held by this process (see the file's comment): exclusive or shared,
/// released by release() or the destructor.
class LockFile {
 public:
  LockFile() = default;
  /// Releases the lock; removes the file when no other process holds it.
  ~LockFile();
  LockFile(const LockFile&) = delete;
  LockFile& operator=(const LockFile&) = delete;

  /// Takes the lock at `path` (created when missing) without waiting. An exclusive holder writes
  /// its process id into a file it created (a stale file of a killed holder is removed and made
  /// afresh). OutputFailed when another process holds it: "`what`: another dform `holder`
  /// (process N) is writing this folder; nothing was written", when `path` is a symbolic link or
  /// not a regular file, or when the file cannot be created or locked.
  Status acquire(const std::string& path, bool exclusive, const std::string& what,
                 const std::string& holder = "run");

  /// A shared lock for a process that only reads the folder: as acquire(path, false, ...), but
  /// where the lock file cannot be made (a read-only folder) the folder is read without one
  /// (ok, held() false): no dform process can be writing where this one cannot.
  Status acquireForReading(const std::string& path, const std::string& what);

  /// Releases the lock now (the destructor's work); nothing when none is held.
  void release();

  /// Whether this object holds a lock now.
  bool held() const { return fd_ >= 0; }

 private:
  Status take(const std::string& path, bool exclusive, const std::string& what,
              const std::string& holder, bool mayGoWithout);

  std::string path_;
  int fd_ = -1;
};

/// OutputFailed when a dform run holds the lock of a folder that `dir` lies in (`dir` would be
/// swapped away with it): "`what`: FOLDER is being replaced by another dform run (process N);
/// nothing was written". Only lock files that exist are looked at; none is created.
Status checkNoEnclosingRun(const std::string& dir, const std::string& what);

}  // namespace dform
