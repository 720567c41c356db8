// SPDX-License-Identifier: GPL-3.0-or-later
// Opening the studio's page in the user's browser without showing its token to other users: a
// command line is visible to every local user (ps, /proc), so xdg-open is given a file that only
// this user can read, which sends the browser on to the address with its token.
#pragma once

#include <string>

namespace dform::cli {

class PrivateOpener {
 public:
  PrivateOpener() = default;
  /// Removes the file and its folder.
  ~PrivateOpener();
  PrivateOpener(const PrivateOpener&) = delete;
  PrivateOpener& operator=(const PrivateOpener&) = delete;

  /// Writes a page that redirects to `url` into a new folder only this user may enter
  /// ($XDG_RUNTIME_DIR, else the temporary folder; mode 0700, the file 0600) and starts
  /// `xdg-open FILE` (found on the PATH) without waiting for it. False when there is no xdg-open or
  /// the file cannot be written: the printed address is then all there is.
  bool open(const std::string& url);

  /// The page written (empty before open()).
  const std::string& file() const { return file_; }

 private:
  std::string folder_, file_;
};

}  // namespace dform::cli
