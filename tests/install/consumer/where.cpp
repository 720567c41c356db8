// SPDX-License-Identifier: GPL-3.0-or-later
// Prints the templates folder the installed dform libraries read (export profiles, gate presets,
// the report page), as a program linked to them finds it: scripts/check-package runs it from /
// without DFORM_TEMPLATES and expects the one the Debian package installs.
#include <dform/pipeline/run.h>

#include <cstdio>

int main() {
  const dform::Result<std::string> found = dform::templatesDir();
  if (!found.isOk()) return std::fprintf(stderr, "%s\n", found.status().message().c_str()), 1;
  std::printf("%s\n", found.value().c_str());
  return 0;
}
