// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/job.h"

namespace dform {

std::vector<std::string> Job::inputs() const {
  if (const ForwardJob* forward = std::get_if<ForwardJob>(&run))
    return {forward->pieceA, forward->pieceB};
  return {std::get<InverseJob>(run).curve};
}

int Job::resolution() const {
  return std::visit([](const auto& job) { return job.resolution; }, run);
}

const DForm& solvedModel(const SolvedRun& run) {
  return std::visit([](const auto& r) -> const DForm& { return r.model; }, run);
}

const ModelUsed& solvedModelUsed(const SolvedRun& run) {
  return std::visit([](const auto& r) -> const ModelUsed& { return r.modelUsed; }, run);
}

const Metrics& solvedMetrics(const SolvedRun& run) {
  return std::visit([](const auto& r) -> const Metrics& { return r.metrics; }, run);
}

const Timings& solvedTimings(const SolvedRun& run) {
  return std::visit([](const auto& r) -> const Timings& { return r.timings; }, run);
}

const CurveMatch* solvedCurveMatch(const SolvedRun& run) {
  const InverseRun* inverse = std::get_if<InverseRun>(&run);
  return inverse ? &inverse->curveMatch : nullptr;
}

}  // namespace dform
