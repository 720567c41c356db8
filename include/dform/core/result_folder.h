// SPDX-License-Identifier: GPL-3.0-or-later
// A result folder replaced as one transaction. The new result is written into a fresh hidden
// folder beside it, then swapped in by one rename: a run that fails, is interrupted or is killed
// part way leaves the folder exactly as it was, and files of the earlier result that the new one
// does not produce go with the swap. A lock beside the folder keeps a second run off it meanwhile,
// and a run refuses a folder inside one that another run is replacing. Nothing that appears in the
// folder while the run works is deleted: the swap carries it into the new result and says so.
#pragma once

#include <sys/types.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dform/core/lock_file.h"
#include "dform/core/messages.h"
#include "dform/core/status.h"

namespace dform {

/// A result folder replaced as one transaction (see the file's comment): begin() locks it and opens
/// a staging folder, the result is written there, commit() swaps it in.
class ResultFolder {
 public:
  ResultFolder() = default;
  /// Drops the staging folder when the result was not committed, releases the lock, and
  /// removes the parent folders `begin` created when nothing was committed.
  ~ResultFolder();
  ResultFolder(const ResultFolder&) = delete;
  ResultFolder& operator=(const ResultFolder&) = delete;

  /// Locks `dir` against other dform runs (a hidden `.NAME.dform-lock` in its parent, created
  /// with the parent when missing), checks that no run is replacing a folder `dir` lies in, that
  /// `dir` may be replaced (missing, or a folder holding only regular files named in
  /// `resultFiles`, so that no file of the user's is ever swapped away), removes what runs of
  /// this user killed outright left beside it, notes what the folder holds, and creates the
  /// staging folder. OutputFailed naming the folder or the file in the way (a symbolic link or
  /// someone else's file at the lock or staging path is never followed or removed), or saying
  /// which process holds the lock. `isResultFolder`, when given, names the subfolders that are
  /// the result's too (a sweep's starts): they go with the swap like their locks, but their
  /// contents are the caller's to check (`hold`).
  Status begin(const std::string& dir, const std::set<std::string>& resultFiles,
               const std::function<bool(const std::string&)>& isResultFolder = nullptr);

  /// Locks `dir` as `begin` does and checks that it may be replaced, without staging anything:
  /// a folder that goes with an enclosing result (a sweep's start folder) held against other
  /// runs until this object is destroyed. `begin`'s errors.
  Status hold(const std::string& dir, const std::set<std::string>& resultFiles);

  /// Holds `dir` for reading only (`dform export DIR -o OUT`): a shared lock, so that no run
  /// replaces it meanwhile, without creating anything where the folder's parent is read-only.
  Status read(const std::string& dir);

  /// The folder the new result is written into.
  const std::string& staging() const { return staging_; }

  /// Puts the file `name` of the current result into the staging folder unchanged (a hard link:
  /// files are only ever replaced by rename, never changed in place; a copy where links are not
  /// possible). OutputFailed naming the file.
  Status carryOver(const std::string& name);

  /// `status` with the staging folder's path written as the result folder's, so that a message
  /// names the file the user knows.
  Status named(const Status& status) const;

  /// Flushes the staged files to disk and swaps the staging folder in for the result folder
  /// (one atomic exchange). Of the old result only what `begin` found in it is removed: anything
  /// that appeared in the folder since is moved into the new result, or, where the new result
  /// has an entry of the same name, kept in the old folder renamed `.NAME.dform-kept.PID`; each
  /// such entry is a warning in `sink`. OutputFailed when it cannot: the result folder then
  /// still holds the old result.
  Status commit(MessageSink* sink = nullptr);

  /// A file's or folder's identity: device and inode, and for a file its change time, so that a
  /// file made since under a name (and an inode number) that was freed is not taken for the one
  /// found. A folder's contents are compared one by one instead.
  struct Identity {
    /// The device the entry lies on (st_dev).
    dev_t device = 0;
    /// Its inode number on that device (st_ino).
    ino_t inode = 0;
    long long changedSeconds = 0;      ///< its status change time (st_ctim), seconds; 0: a folder
    long long changedNanoseconds = 0;  ///< the nanoseconds of that time
    /// The same device, inode and change time.
    bool operator==(const Identity& o) const {
      return device == o.device && inode == o.inode && changedSeconds == o.changedSeconds &&
             changedNanoseconds == o.changedNanoseconds;
    }
  };

 private:
  // Locks `dir` (its parent created when missing); its absolute path and its name. Unless
  // `enclosed` (a folder of the result this process replaces), a run replacing a folder `dir`
  // lies in is refused.
  Status lock(const std::string& dir, std::string& absolute, std::string& name,
              bool enclosed = false);
  // OutputFailed naming the first entry of `absolute` (shown as `dir`) that is not a result's.
  static Status checkReplaceable(const std::string& absolute, const std::string& dir,
                                 const std::set<std::string>& resultFiles,
                                 const std::function<bool(const std::string&)>& isResultFolder);
  // Removes this user's killed runs' staging and old folders of `name` in `parent`; refuses one
  // that is a link or not this user's folder.
  static Status removeLeftovers(const std::string& parent, const std::string& name,
                                const std::string& dir);
  // Moves what appeared in `old` since `begin` into the new result; then removes the rest of
  // `old` that `begin` noted, keeping it under a new name when anything is left.
  void retire(const std::string& old, MessageSink* sink);

  std::string dir_;       ///< absolute, symbolic links resolved
  std::string shownDir_;  ///< as the user wrote it, for messages
  std::string staging_, lockPath_;
  std::function<bool(const std::string&)> isResultFolder_;
  std::map<std::string, Identity> found_;  ///< what `begin` found in dir_, by relative path
  LockFile lock_;
  std::vector<std::string>
      createdFolders_;  ///< the lock's missing parents begin made, deepest first
  bool committed_ = false;
};

}  // namespace dform
