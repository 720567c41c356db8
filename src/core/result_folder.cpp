#include "dform/core/result_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace dform {

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
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Whether `entry` is the lock (".NAME.dform-lock") or a killed run's staging or old folder of a
// subfolder NAME that `isResultFolder` accepts: it goes with the folder that holds it.
bool isLockOrLeftoverOf(const std::string& entry,
                        const std::function<bool(const std::string&)>& isResultFolder) {
  if (entry.size() < 2 || entry[0] != '.') return false;
  for (const char* suffix : {".dform-lock", ".dform-new.", ".dform-old."}) {
    const std::size_t at = entry.rfind(suffix);
    if (at == std::string::npos || at < 2) continue;
    const std::string tail = entry.substr(at + std::strlen(suffix));
    const bool isLock = suffix[6] == 'l';
    if (isLock ? !tail.empty()
               : tail.empty() || tail.find_first_not_of("0123456789") != std::string::npos)
      continue;
    if (isResultFolder(entry.substr(1, at - 1))) return true;
  }
  return false;
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

Status ResultFolder::lock(const std::string& dir, std::string& absolute, std::string& name) {
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
  if (Status s = lock(dir, absolute, name); !s.isOk()) return s;
  return checkReplaceable(absolute, dir, resultFiles, nullptr);
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

Status ResultFolder::begin(const std::string& dir, const std::set<std::string>& resultFiles,
                           const std::function<bool(const std::string&)>& isResultFolder) {
  std::string absolute, name;
  if (Status s = lock(dir, absolute, name); !s.isOk()) return s;
  const fs::path parent = fs::path(absolute).parent_path();
  const std::string pid = std::to_string(::getpid());

  // Staging and old folders of runs killed outright (SIGKILL, a second Ctrl-C, a power cut):
  // no run is using them while we hold the lock.
  std::error_code ec;
  const std::string stagingPrefix = "." + name + ".dform-new.",
                    oldPrefix = "." + name + ".dform-old.";
  for (const fs::directory_entry& entry : fs::directory_iterator(parent, ec)) {
    const std::string entryName = entry.path().filename().string();
    if (isLeftover(entryName, stagingPrefix) || isLeftover(entryName, oldPrefix))
      fs::remove_all(entry.path(), ec);
  }
  if (Status s = checkReplaceable(absolute, dir, resultFiles, isResultFolder); !s.isOk()) return s;
  dir_ = absolute;
  shownDir_ = dir;
  while (shownDir_.size() > 1 && shownDir_.back() == '/') shownDir_.pop_back();
  staging_ = (parent / (stagingPrefix + pid)).string();
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec) {
    const std::string reason = ec.message();
    staging_.clear();
    return outputFailed(dir + ": cannot write in " + parent.string() + " (" + reason + ")");
  }
  return Status::ok();
}

Status ResultFolder::carryOver(const std::string& name) const {
  const fs::path from = fs::path(dir_) / name, to = fs::path(staging_) / name;
  if (::link(from.c_str(), to.c_str()) == 0) return Status::ok();
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

Status ResultFolder::commit() {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_, ec))
    syncPath(entry.path());
  syncPath(staging_);
  const fs::path parent = fs::path(dir_).parent_path();
  const fs::file_status old = fs::status(dir_, ec);
  if (!fs::exists(old)) {
    if (std::rename(staging_.c_str(), dir_.c_str()) != 0)
      return outputFailed(shownDir_ + ": cannot put the result in place (" + std::strerror(errno) +
                          ")");
  } else {
    fs::permissions(staging_, old.permissions(), ec);  // the folder keeps its permissions
    // One atomic exchange: at every instant the path holds the old result or the new one.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) != 0) {
      if (errno != EINVAL && errno != ENOSYS)
        return outputFailed(shownDir_ + ": cannot put the result in place (" +
                            std::strerror(errno) + ")");
      // A file system without the exchange: the old result moves aside, the new one in (a run
      // killed between the two leaves the old one beside the path, named .NAME.dform-old.PID).
      const std::string aside = (parent / ("." + fs::path(dir_).filename().string() +
                                           ".dform-old." + std::to_string(::getpid())))
                                    .string();
      if (std::rename(dir_.c_str(), aside.c_str()) != 0)
        return outputFailed(shownDir_ + ": cannot put the result in place (" +
                            std::strerror(errno) + ")");
      if (std::rename(staging_.c_str(), dir_.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::rename(aside.c_str(), dir_.c_str());
        return outputFailed(shownDir_ + ": cannot put the result in place (" + reason + ")");
      }
      staging_ = aside;
    }
  }
  syncPath(parent);
  committed_ = true;
  // staging_ now names the old result (or nothing): removed, the lock released by the destructor.
  fs::remove_all(staging_, ec);
  staging_.clear();
  return Status::ok();
}

}  // namespace dform
