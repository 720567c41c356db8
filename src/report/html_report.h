// report.html: a self-contained page (no external files or scripts) that shows a result's
// verdict, figures, pictures of the shape and its curvature, the flat pattern and the solve.
#pragma once

#include <string>

#include "core/status.h"
#include "core/types.h"

namespace dform {

/// Writes `dir`/report.html (atomically) from `dir`/report.json, `dir`/pattern.svg and
/// `dir`/assembly.svg when they exist,
/// and the model, through the Mustache template `templatesDir`/report/report.html.mustache.
Status writeReportHtml(const std::string& dir, const DForm& model, const std::string& templatesDir);

}  // namespace dform
