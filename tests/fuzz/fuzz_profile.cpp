// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzzes the export-profile reader. A profile it accepts must be one the exporter can draw with.
#include <cmath>

#include "dform/export/exporter.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  using namespace dform;
  const Result<Profile> profile = fuzz::parseChecked(data, size, "profile.json", parseProfileJson);
  if (!profile.isOk()) return 0;
  const Profile& p = profile.value();
  for (const double width : {p.cutWidthMm, p.scoreWidthMm, p.engraveWidthMm})
    fuzz::require(std::isfinite(width) && width > 0.0, "an accepted stroke width is unusable");
  fuzz::require(p.page.empty() || p.page == "A4" || p.page == "Letter", "an unknown page", p.page);
  return 0;
}
