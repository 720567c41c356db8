// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's downloads: a saved job (job.json with every setting and the outlines or curve it
// names, which `dform run job.json` reproduces, export included) and an export (the files
// `dform run` writes for that job, made by the pipeline's runAndWrite in a temporary folder),
// each as a stored zip.
#pragma once

#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "dform/core/status.h"
#include "dform/pipeline/job.h"
#include "session.h"

namespace dform::studio {

/// A saved job's files: job.json (every setting of `job`, export options included, its inputs
/// named beside it) and the two outlines it names (forward) or the curve (inverse), as the zip
/// (zip.h storedZip) holds them.
std::vector<std::pair<std::string, std::string>> forwardJobFiles(const PieceInput& a,
                                                                 const PieceInput& b,
                                                                 const Job& job);
std::vector<std::pair<std::string, std::string>> inverseJobFiles(const CurveInput& curve,
                                                                 const Job& job);

/// An export's zip and, where it lacks the cutting files the export asked for, why and what to
/// do, in the studio's words (studioWords): the gate failed without export_anyway, or the pattern
/// could not be laid out (a sheet too small). Empty: the zip holds every file asked for.
struct ExportedZip {
  std::string zip;
  std::string missing;
};

/// An export's files (name, content) and, as ExportedZip's, what it lacks.
struct ExportedFiles {
  std::vector<std::pair<std::string, std::string>> files;
  std::string missing;
};

/// Runs the saved job (`jobFiles` as forwardJobFiles lays them out) with runAndWrite, as its
/// export settings say, into a fresh temporary folder and returns the result folder's files; the
/// folder is removed, and no file nor message names it (report.json names its inputs as the
/// saved job does, beside it). The run's error, in the studio's words, when nothing was written.
/// `cancel`, when set meanwhile, stops the run (Interrupted).
Result<ExportedFiles> exportedFiles(
    const std::vector<std::pair<std::string, std::string>>& jobFiles,
    const std::atomic<bool>* cancel = nullptr);

/// exportedFiles as a zip.
Result<ExportedZip> exportedResult(const std::vector<std::pair<std::string, std::string>>& jobFiles,
                                   const std::atomic<bool>* cancel = nullptr);

/// The print preview of an export: its pattern.json's "pages" (each page or tile: kind, size,
/// origin and window on the canvas) and "sheets", each sheet's SVG ("svg", in the sheets' order),
/// its "scale", "profile" and "failed_gate", and "missing" (ExportedZip's). Without cutting
/// files, "missing" alone; where the run failed, its "error".
nlohmann::json printPreview(const Result<ExportedFiles>& run);

/// printPreview of the export of the job `jobFiles()` makes (exportedFiles); a setting Export
/// refuses (jobFiles' RequestError, a 400 there) is the answer's "error" too: the page asks for a
/// preview as the designer types.
nlohmann::json previewOf(
    const std::function<std::vector<std::pair<std::string, std::string>>()>& jobFiles,
    const std::atomic<bool>* cancel);

}  // namespace dform::studio
