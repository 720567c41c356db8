// SPDX-License-Identifier: GPL-3.0-or-later
// Headless Chromium for the tests that open a page dform wrote (Debian's `chromium`).
#pragma once

#include <cstdlib>
#include <string>

namespace dform::test {

inline bool chromiumInstalled() { return std::system("command -v chromium >/dev/null 2>&1") == 0; }

/// Runs headless Chromium on `url` with `action` ("--dump-dom", "--screenshot=PATH", plus e.g.
/// "--window-size=W,H"): stdout into `out`, stderr into `log`, where every console message of the
/// page appears as a line with "CONSOLE". WebGL runs on SwiftShader, opted into: without
/// --enable-unsafe-swiftshader Chromium falls back to it with a deprecation warning on the
/// console. Returns the shell's exit status.
inline int runChromium(const std::string& action, const std::string& url,
                       const std::string& profileDir, const std::string& out,
                       const std::string& log) {
  const std::string command =
      "chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "
      "--enable-logging=stderr --v=0 --user-data-dir=" +
      profileDir + " " + action + " '" + url + "' >" + out + " 2>" + log;
  return std::system(command.c_str());
}

}  // namespace dform::test
