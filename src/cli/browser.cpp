// SPDX-License-Identifier: GPL-3.0-or-later
#include "browser.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <thread>
#include <vector>

extern char** environ;

namespace dform::cli {

namespace {

namespace fs = std::filesystem;

// A folder of this user's only, for the page: $XDG_RUNTIME_DIR where it is one.
fs::path privateBase() {
  const char* runtime = std::getenv("XDG_RUNTIME_DIR");
  struct stat status {};
  if (runtime && *runtime && ::stat(runtime, &status) == 0 && S_ISDIR(status.st_mode) &&
      status.st_uid == ::geteuid() && (status.st_mode & 077) == 0)
    return runtime;
  std::error_code ec;
  return fs::temp_directory_path(ec);
}

// `url` escaped for an HTML attribute (it holds letters, digits and ":/?=." only; escaped all
// the same).
std::string attribute(const std::string& url) {
  std::string out;
  for (const char c : url) {
    if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else if (c == '<')
      out += "&lt;";
    else
      out += c;
  }
  return out;
}

}  // namespace

PrivateOpener::~PrivateOpener() {
  if (!file_.empty()) ::unlink(file_.c_str());
  if (!folder_.empty()) ::rmdir(folder_.c_str());
}

bool PrivateOpener::open(const std::string& url) {
  std::string pattern = (privateBase() / "dform-studio-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) return false;  // mode 0700
  folder_ = pattern;
  const std::string page = folder_ + "/open.html";
  const int fd = ::open(page.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  file_ = page;
  const std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>dform studio</title>"
      "<meta http-equiv=\"refresh\" content=\"0;url=" +
      attribute(url) + "\"></head><body><a href=\"" + attribute(url) +
      "\">dform studio</a></body></html>\n";
  const bool written = ::write(fd, html.data(), html.size()) == ssize_t(html.size());
  if (::close(fd) != 0 || !written) return false;
  // The browser's output is not the studio's; the path is an argument, never shell text.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<char*> argv = {const_cast<char*>("xdg-open"), file_.data(), nullptr};
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, "xdg-open", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  std::thread([pid] { ::waitpid(pid, nullptr, 0); }).detach();  // no zombie left
  return true;
}

}  // namespace dform::cli
