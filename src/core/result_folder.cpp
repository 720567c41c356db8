// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/result_folder.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace dform {

using ResultFolderIdentity = ResultFolder::Identity;

namespace {

namespace fs = std::filesystem;

Status outputFailed(const std::string& message) { return {ErrorCode::OutputFailed, message}; }

// Whether `entry` is `prefix` followed by a process id: a staging or old folder of this result
// folder (and not of another folder whose name happens to start the same way).
bool isLeftover(const std::string& entry, const std::string& prefix) {
  if (entry.size() <= prefix.size() || entry.compare(0, prefix.size(), prefix) != 0) return false;
  return entry.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
}

// Forces a file's or a folder's bytes and entries to the disk, so that the renamed folder is
// whole after a power cut too. Best effort: a file system without fsync loses nothing else.
void syncPath(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Whether `entry` is the lock (".NAME.dform-lock") or a killed run's staging or old folder of a
// subfolder NAME that `isResultFolder` accepts: it goes with the folder that holds it.
bool isLockOrLeftoverOf(const std::string& entry,
                        const std::function<bool(const std::string&)>& isResultFolder,
                        bool locksOnly = false) {
  if (entry.size() < 2 || entry[0] != '.') return false;
  for (const char* suffix : {".dform-lock", ".dform-new.", ".dform-old."}) {
    const std::size_t at = entry.rfind(suffix);
    if (at == std::string::npos || at < 2) continue;
    const std::string tail = entry.substr(at + std::strlen(suffix));
    const bool isLock = suffix[7] == 'l';  // ".dform-lock"
    if (locksOnly && !isLock) continue;
    if (isLock ? !tail.empty()
               : tail.empty() || tail.find_first_not_of("0123456789") != std::string::npos)
      continue;
    if (isResultFolder(entry.substr(1, at - 1))) return true;
  }
  return false;
}

// The file system's identity of `path` itself (a link is not followed); false when it is gone.
bool identityOf(const fs::path& path, ResultFolderIdentity& id, bool& isFolder) {
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return false;
  isFolder = S_ISDIR(status.st_mode);
  id = {status.st_dev, status.st_ino, isFolder ? 0 : (long long)status.st_ctim.tv_sec,
        isFolder ? 0 : (long long)status.st_ctim.tv_nsec};
  return true;
}

// Every entry under `root`/`relative`, links not followed, by its path relative to `root`.
void noteEntries(const fs::path& root, const fs::path& relative,
                 std::map<std::string, ResultFolderIdentity>& found) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(root / relative, ec)) {
    const fs::path name = relative / entry.path().filename();
    ResultFolderIdentity id;
    bool isFolder = false;
    if (!identityOf(entry.path(), id, isFolder)) continue;
    found[name.string()] = id;
    if (isFolder) noteEntries(root, name, found);
  }
}

// A message naming `path` in the way of a hidden file of dform's.
std::string inTheWay(const std::string& dir, const fs::path& path) {
  return dir + ": " + path.string() +
         " is in the way (a symbolic link, or not a folder this user's dform runs made); "
         "nothing was written (remove it if no dform run is using it)";
}

}  // namespace

ResultFolder::~ResultFolder() {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  lock_.release();
  // A run that put nothing in place leaves no folder it created for its lock either.
  if (!committed_)
    for (const std::string& made : createdFolders_) fs::remove(made, ec);
}

Status ResultFolder::lock(const std::string& dir, std::string& absolute, std::string& name,
                          bool enclosed) {
  std::error_code ec;
  fs::path path = fs::absolute(dir, ec).lexically_normal();
  if (path.has_parent_path() && path.filename().empty()) path = path.parent_path();  // "out/"
  // A symbolic link to a folder: the folder it names is replaced, the link kept.
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    const fs::path target = fs::canonical(path, ec);
    if (ec)
      return outputFailed(dir + ": a symbolic link that leads nowhere (" + ec.message() + ")");
    path = target;
  }
  name = path.filename().string();
  if (name.empty() || name == "." || name == ".." || path == path.root_path())
    return outputFailed(dir + ": cannot be used as a result folder (it is replaced as a whole)");
  // A folder inside one that another run swaps away would go with it.
  if (!enclosed)
    if (Status s = checkNoEnclosingRun(path.string(), dir); !s.isOk()) return s;
  const fs::path parent = path.parent_path();
  for (fs::path missing = parent; !missing.empty() && !fs::exists(fs::symlink_status(missing, ec));
       missing = missing.parent_path()) {
    createdFolders_.push_back(missing.string());  // deepest first
    if (missing == missing.root_path()) break;
  }
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent))
    return outputFailed(dir + ": cannot create the output folder (" +
                        (ec ? ec.message() : std::string("Not a directory")) + ")");
  absolute = path.string();
  lockPath_ = (parent / ("." + name + ".dform-lock")).string();
  return lock_.acquire(lockPath_, true, dir);
}

Status ResultFolder::hold(const std::string& dir, const std::set<std::string>& resultFiles) {
  std::string absolute, name;
  // (Held by the run that replaces the folder it lies in: that run's own lock is no refusal.)
  if (Status s = lock(dir, absolute, name, true); !s.isOk()) return s;
  return checkReplaceable(absolute, dir, resultFiles, nullptr);
}

Status ResultFolder::read(const std::string& dir) {
  std::error_code ec;
  fs::path path = fs::canonical(dir, ec);
  if (ec) return {ErrorCode::InputUnreadable, dir + ": no such result folder"};
  if (path == path.root_path()) return Status::ok();
  lockPath_ = (path.parent_path() / ("." + path.filename().string() + ".dform-lock")).string();
  return lock_.acquireForReading(lockPath_, dir);
}

Status ResultFolder::checkReplaceable(
    const std::string& absolute, const std::string& dir, const std::set<std::string>& resultFiles,
    const std::function<bool(const std::string&)>& isResultFolder) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(absolute, ec);
  if (!fs::exists(status)) return Status::ok();
  if (!fs::is_directory(status)) return outputFailed(dir + ": exists and is not a folder");
  for (const fs::directory_entry& entry : fs::directory_iterator(absolute, ec)) {
    const std::string entryName = entry.path().filename().string();
    // An earlier version's temporary file ("report.json.tmp.123") is a result's too.
    const std::string stem = entryName.substr(0, entryName.find(".tmp."));
    const fs::file_status entryStatus = entry.symlink_status(ec);
    if (isResultFolder && fs::is_directory(entryStatus) && isResultFolder(entryName)) continue;
    if (isResultFolder && isLockOrLeftoverOf(entryName, isResultFolder)) continue;
    if (!resultFiles.count(stem) || !fs::is_regular_file(entryStatus))
      return outputFailed((fs::path(dir) / entryName).string() +
                          ": is not part of a dform result, and the result folder is "
                          "replaced as a whole; nothing was written (use an empty or new "
                          "folder)");
  }
  if (ec) return outputFailed(dir + ": cannot be read (" + ec.message() + ")");
  return Status::ok();
}

Status ResultFolder::removeLeftovers(const std::string& parent, const std::string& name,
                                     const std::string& dir) {
  // Staging and old folders of runs killed outright (SIGKILL, a second Ctrl-C, a power cut): no
  // run is using them while we hold the lock. Only this user's own folders are removed.
  std::error_code ec;
  const std::string stagingPrefix = "." + name + ".dform-new.",
                    oldPrefix = "." + name + ".dform-old.";
  for (const fs::directory_entry& entry : fs::directory_iterator(parent, ec)) {
    const std::string entryName = entry.path().filename().string();
    if (!isLeftover(entryName, stagingPrefix) && !isLeftover(entryName, oldPrefix)) continue;
    struct stat status {};
    if (::lstat(entry.path().c_str(), &status) != 0) continue;
    if (!S_ISDIR(status.st_mode) || status.st_uid != ::geteuid())
      return outputFailed(inTheWay(dir, entry.path()));
    fs::remove_all(entry.path(), ec);
  }
  return Status::ok();
}

Status ResultFolder::begin(const std::string& dir, const std::set<std::string>& resultFiles,
                           const std::function<bool(const std::string&)>& isResultFolder) {
  std::string absolute, name;
  if (Status s = lock(dir, absolute, name); !s.isOk()) return s;
  const fs::path parent = fs::path(absolute).parent_path();
  if (Status s = removeLeftovers(parent.string(), name, dir); !s.isOk()) return s;
  if (Status s = checkReplaceable(absolute, dir, resultFiles, isResultFolder); !s.isOk()) return s;
  dir_ = absolute;
  shownDir_ = dir;
  while (shownDir_.size() > 1 && shownDir_.back() == '/') shownDir_.pop_back();
  isResultFolder_ = isResultFolder;
  noteEntries(dir_, "", found_);
  const fs::path staging = parent / ("." + name + ".dform-new." + std::to_string(::getpid()));
  // A fresh folder of our own: anything at its path now (a link planted there) is refused.
  if (::mkdir(staging.c_str(), 0777) != 0) {
    if (errno == EEXIST) return outputFailed(inTheWay(dir, staging));
    return outputFailed(dir + ": cannot write in " + parent.string() + " (" + std::strerror(errno) +
                        ")");
  }
  staging_ = staging.string();
  return Status::ok();
}

Status ResultFolder::carryOver(const std::string& name) {
  const fs::path from = fs::path(dir_) / name, to = fs::path(staging_) / name;
  if (::link(from.c_str(), to.c_str()) == 0) {
    // The link changed the file's change time: it is still the file begin found.
    ResultFolderIdentity id;
    bool isFolder = false;
    if (found_.count(name) && identityOf(from, id, isFolder)) found_[name] = id;
    return Status::ok();
  }
  std::error_code ec;
  if (fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec)) return Status::ok();
  return outputFailed((fs::path(shownDir_) / name).string() +
                      ": cannot be kept in the new result (" + ec.message() + ")");
}

Status ResultFolder::named(const Status& status) const {
  if (status.isOk() || staging_.empty()) return status;
  std::string message = status.message();
  for (std::size_t at = 0; (at = message.find(staging_, at)) != std::string::npos;
       at += shownDir_.size())
    message.replace(at, staging_.size(), shownDir_);
  return {status.code(), message};
}

void ResultFolder::retire(const std::string& old, MessageSink* sink) {
  const auto warn = [&](const std::string& text) {
    if (sink) sink->warning(text);
  };
  // What appeared since begin (a new name, or a name now on another file) is moved into the new
  // result under its name, where that is free.
  std::vector<std::string> appeared;
  const std::function<void(const fs::path&)> walk = [&](const fs::path& relative) {
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(old) / relative, ec)) {
      const fs::path name = relative / entry.path().filename();
      Identity id;
      bool isFolder = false;
      if (!identityOf(entry.path(), id, isFolder)) continue;
      const auto noted = found_.find(name.string());
      if (noted != found_.end() && noted->second == id) {
        if (isFolder) walk(name);
      } else if (!(relative.empty() && isResultFolder_ && !isFolder &&
                   isLockOrLeftoverOf(name.string(), isResultFolder_, true))) {
        appeared.push_back(name.string());  // (a lock of a held start folder is the run's own)
      }
    }
  };
  walk("");
  for (const std::string& name : appeared) {
    const fs::path from = fs::path(old) / name, to = fs::path(dir_) / name;
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0)
      warn((fs::path(shownDir_) / name).string() + ": appeared while dform was writing " +
           shownDir_ + "; kept in the new result");
  }
  // The old result as begin found it, deepest first; the run's own start locks with it.
  for (auto it = found_.rbegin(); it != found_.rend(); ++it) {
    const fs::path path = fs::path(old) / it->first;
    Identity id;
    bool isFolder = false;
    if (identityOf(path, id, isFolder) && id == it->second)
      isFolder ? ::rmdir(path.c_str()) : ::unlink(path.c_str());
  }
  std::error_code ec;
  if (isResultFolder_)
    for (const fs::directory_entry& entry : fs::directory_iterator(old, ec))
      if (isLockOrLeftoverOf(entry.path().filename().string(), isResultFolder_, true) &&
          entry.is_regular_file(ec))
        ::unlink(entry.path().c_str());
  if (::rmdir(old.c_str()) == 0 || errno == ENOENT) return;
  // Something is left: what appeared under a name the new result has too. Kept, not deleted.
  const fs::path parent = fs::path(dir_).parent_path();
  const fs::path kept = parent / ("." + fs::path(dir_).filename().string() + ".dform-kept." +
                                  std::to_string(::getpid()));
  if (::renameat2(AT_FDCWD, old.c_str(), AT_FDCWD, kept.c_str(), RENAME_NOREPLACE) == 0)
    warn(shownDir_ + ": what appeared in it while dform was writing it, under names the new " +
         "result has too, is kept in " + kept.string());
  else
    warn(shownDir_ + ": what appeared in it while dform was writing it is kept in " + old);
}

Status ResultFolder::commit(MessageSink* sink) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_, ec))
    syncPath(entry.path());
  syncPath(staging_);
  const fs::path parent = fs::path(dir_).parent_path();
  struct stat old {};
  if (::lstat(dir_.c_str(), &old) != 0) {
    // Never onto a folder that appeared meanwhile (that one is exchanged below instead; a plain
    // rename, where the file system has no RENAME_NOREPLACE, replaces only an empty one).
    int moved = ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_NOREPLACE);
    if (moved != 0 && (errno == EINVAL || errno == ENOSYS))
      moved = std::rename(staging_.c_str(), dir_.c_str());
    if (moved == 0) {
      syncPath(parent);
      committed_ = true;
      staging_.clear();
      return Status::ok();
    }
    if (errno != EEXIST && errno != ENOTEMPTY)
      return outputFailed(shownDir_ + ": cannot put the result in place (" + std::strerror(errno) +
                          ")");
    ::lstat(dir_.c_str(), &old);
  }
  ::chmod(staging_.c_str(), old.st_mode & 07777);  // the folder keeps its permissions
  // One atomic exchange: at every instant the path holds the old result or the new one.
  std::string retired = staging_;
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS)
      return outputFailed(shownDir_ + ": cannot put the result in place (" + std::strerror(errno) +
                          ")");
    // A file system without the exchange: the old result moves aside, the new one in (a run
    // killed between the two leaves the old one beside the path, named .NAME.dform-old.PID).
    retired = (parent / ("." + fs::path(dir_).filename().string() + ".dform-old." +
                         std::to_string(::getpid())))
                  .string();
    if (std::rename(dir_.c_str(), retired.c_str()) != 0)
      return outputFailed(shownDir_ + ": cannot put the result in place (" + std::strerror(errno) +
                          ")");
    if (std::rename(staging_.c_str(), dir_.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      std::rename(retired.c_str(), dir_.c_str());
      return outputFailed(shownDir_ + ": cannot put the result in place (" + reason + ")");
    }
  }
  syncPath(parent);
  committed_ = true;
  staging_.clear();
  retire(retired, sink);
  return Status::ok();
}

}  // namespace dform
