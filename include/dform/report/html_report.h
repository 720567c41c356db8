// SPDX-License-Identifier: GPL-3.0-or-later
// report.html: a self-contained page (no external files or scripts) that shows a result's
// verdict, figures, pictures of the shape and its curvature, the flat pattern and the solve.
#pragma once

#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

/// What report.html shows besides the model, all in memory: report.json's text, the exported
/// pattern's and assembly sheet's SVG and the pattern's ticks on the seam (empty: none was
/// exported).
struct ReportSources {
  std::string reportJson;           ///< report.json's text
  std::string reportPath;           ///< where report.json is (or will be), named in errors
  std::string patternSvg;           ///< pattern.svg's text; empty when no pattern was exported
  std::string assemblySvg;          ///< assembly.svg's text; empty when no pattern was exported
  std::vector<SeamTick> seamTicks;  ///< the pattern's numbered ticks on the 3D seam
};

/// report.html's text, rendered through the Mustache template
/// `templatesDir`/report/report.html.mustache. InputUnreadable when reportJson is not JSON.
Result<std::string> renderReportHtml(const ReportSources& sources, const DForm& model,
                                     const std::string& templatesDir);

}  // namespace dform
