// SPDX-License-Identifier: GPL-3.0-or-later
// What renderReportHtml needs besides the model, for tests that render report.html of a test model.
#pragma once

#include "dform/report/html_report.h"

namespace dform::test {

/// A minimal report.json (forward, no gate, no iterations) and nothing exported.
inline ReportSources minimalReportSources() {
  ReportSources sources;
  sources.reportPath = "report.json";
  sources.reportJson =
      R"({"mode": "forward", "job": {"piece_a": "a.svg", "piece_b": "b.svg"},
          "tool": {"version": "test"}, "schema_version": 1, "gate": null,
          "metrics": {"L_error": 0.001}, "timings": {"total": 1.0}, "messages": [],
          "solver": {"initial_cost": 1.0, "iterations": [], "termination": "converged",
                     "message": "", "factorisations": 0,
                     "local_global": {"iterations": 0, "initial_energy": 1.0, "final_energy": 1.0}}})";
  return sources;
}

}  // namespace dform::test
