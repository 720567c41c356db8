// A result folder replaced as one transaction. The new result is written into a fresh hidden
// folder beside it, then swapped in by one rename: a run that fails, is interrupted or is killed
// part way leaves the folder exactly as it was, and files of the earlier result that the new one
// does not produce go with the swap. A lock beside the folder keeps a second run off it meanwhile.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "dform/core/lock_file.h"
#include "dform/core/status.h"

namespace dform {

class ResultFolder {
 public:
  ResultFolder() = default;
  /// Drops the staging folder when the result was not committed, releases the lock, and
  /// removes the parent folders `begin` created when nothing was committed.
  ~ResultFolder();
  ResultFolder(const ResultFolder&) = delete;
  ResultFolder& operator=(const ResultFolder&) = delete;

  /// Locks `dir` against other dform runs (a hidden `.NAME.dform-lock` in its parent, created
  /// with the parent when missing), checks that it may be replaced (missing, or a folder holding
  /// only regular files named in `resultFiles`, so that no file of the user's is ever swapped
  /// away), removes what runs killed outright left beside it, and creates the staging folder.
  /// OutputFailed naming the folder or the file in the way, or saying which process holds the
  /// lock. `isResultFolder`, when given, names the subfolders that are the result's too (a
  /// sweep's starts): they go with the swap like their locks, but their contents are the
  /// caller's to check (`hold`).
  Status begin(const std::string& dir, const std::set<std::string>& resultFiles,
               const std::function<bool(const std::string&)>& isResultFolder = nullptr);

  /// Locks `dir` as `begin` does and checks that it may be replaced, without staging anything:
  /// a folder that goes with an enclosing result (a sweep's start folder) held against other
  /// runs until this object is destroyed. `begin`'s errors.
  Status hold(const std::string& dir, const std::set<std::string>& resultFiles);

  /// The folder the new result is written into.
  const std::string& staging() const { return staging_; }

  /// Puts the file `name` of the current result into the staging folder unchanged (a hard link:
  /// files are only ever replaced by rename, never changed in place; a copy where links are not
  /// possible). OutputFailed naming the file.
  Status carryOver(const std::string& name) const;

  /// `status` with the staging folder's path written as the result folder's, so that a message
  /// names the file the user knows.
  Status named(const Status& status) const;

  /// Flushes the staged files to disk and swaps the staging folder in for the result folder
  /// (one atomic exchange; the old result is then removed). OutputFailed when it cannot: the
  /// result folder then still holds the old result.
  Status commit();

 private:
  // Locks `dir` (its parent created when missing); its absolute path and its name.
  Status lock(const std::string& dir, std::string& absolute, std::string& name);
  // OutputFailed naming the first entry of `absolute` (shown as `dir`) that is not a result's.
  static Status checkReplaceable(const std::string& absolute, const std::string& dir,
                                 const std::set<std::string>& resultFiles,
                                 const std::function<bool(const std::string&)>& isResultFolder);

  std::string dir_;       ///< absolute, symbolic links resolved
  std::string shownDir_;  ///< as the user wrote it, for messages
  std::string staging_, lockPath_;
  LockFile lock_;
  std::vector<std::string>
      createdFolders_;  ///< the lock's missing parents begin made, deepest first
  bool committed_ = false;
};

}  // namespace dform
