// The studio's downloads: a saved job (job.json with the outlines or curve it names, which
// `dform run job.json` reproduces) and an export (the files `dform run` writes for that job,
// made by the pipeline's runAndWrite in a temporary folder), each as a stored zip.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "dform/core/status.h"
#include "dform/pipeline/inverse_pipeline.h"
#include "session.h"

namespace dform::studio {

/// The zip of job.json and the two outline files it names (forward).
std::string savedForwardJob(const PieceInput& a, const PieceInput& b,
                            const ForwardSettings& settings);

/// The zip of job.json and the curve file it names (inverse).
std::string savedInverseJob(const CurveInput& curve, const InverseSettings& settings,
                            bool forceClosed);

/// What "Export" asks for: the pattern's options as the command line spells them.
struct ExportRequest {
  std::string profile = "laser", page, sheet, scale;
  bool exportAnyway = false;
};

ExportRequest exportRequestFrom(const nlohmann::json& request);

/// Runs the saved job (forward or inverse, `jobZipFiles` as savedForwardJob lays them out) with
/// runAndWrite into a fresh temporary folder and returns the zip of the result folder's files;
/// the folder is removed. The run's error (a bad profile, a failed gate without exportAnyway
/// still writes the result) when nothing was written. `cancel`, when set meanwhile, stops the run
/// (Interrupted).
Result<std::string> exportedResult(const std::vector<std::pair<std::string, std::string>>& jobFiles,
                                   const ExportRequest& request,
                                   const std::atomic<bool>* cancel = nullptr);

/// The files of savedForwardJob / savedInverseJob before zipping.
std::vector<std::pair<std::string, std::string>> forwardJobFiles(const PieceInput& a,
                                                                 const PieceInput& b,
                                                                 const ForwardSettings& settings);
std::vector<std::pair<std::string, std::string>> inverseJobFiles(const CurveInput& curve,
                                                                 const InverseSettings& settings,
                                                                 bool forceClosed);

}  // namespace dform::studio
