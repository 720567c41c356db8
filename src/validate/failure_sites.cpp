// SPDX-License-Identifier: GPL-3.0-or-later
#include <cmath>

#include "dform/validate/gate.h"
#include "dform/validate/metrics.h"
#include "mesh_measures.h"

namespace dform {

namespace {

// Edges whose |strain| exceeds `limit` (a NaN strain too: it never passes), as vertex pairs.
FailureSites strainedEdges(const DForm& model, const std::string& check, double limit) {
  FailureSites sites{check, FailureSites::Kind::Edges, {}};
  const Piece* pieces[2] = {&model.a, &model.b};
  for (int i = 0; i < 2; ++i)
    for (const EdgeStrain& e : edgeStrains(*pieces[i]))
      if (!(std::abs(e.strain) <= limit))
        sites.items[i].insert(sites.items[i].end(), {e.from, e.to});
  return sites;
}

FailureSites curvedVertices(const DForm& model, double limit) {
  FailureSites sites{"gauss_max_rad", FailureSites::Kind::Vertices, {}};
  const Piece* pieces[2] = {&model.a, &model.b};
  for (int i = 0; i < 2; ++i) {
    const std::vector<bool> away =
        detail::awayFromSeam(*pieces[i], detail::edgeTopology(pieces[i]->F));
    const Eigen::VectorXd defect = detail::angleDefects(pieces[i]->shape, pieces[i]->F);
    for (Eigen::Index v = 0; v < defect.size(); ++v)
      if (away[size_t(v)] && !(std::abs(defect(v)) <= limit)) sites.items[i].push_back(int(v));
  }
  return sites;
}

FailureSites seamGaps(const DForm& model, double limit) {
  FailureSites sites{"seam_gap_mm", FailureSites::Kind::SeamPoints, {}};
  for (size_t k = 0; k < model.a.seam.size() && k < model.b.seam.size(); ++k)
    if (!((model.a.shape.row(model.a.seam[k]) - model.b.shape.row(model.b.seam[k])).norm() <=
          limit))
      sites.items[0].push_back(int(k));
  sites.items[1] = sites.items[0];
  return sites;
}

}  // namespace

std::vector<FailureSites> locateFailures(const DForm& model, const GateReport& report) {
  std::vector<FailureSites> out;
  for (const CheckResult& c : report.checks) {
    if (c.verdict != CheckResult::Verdict::Fail) continue;
    if (c.name == "L_max" || c.name == "L_error")
      out.push_back(strainedEdges(model, c.name, c.limit));
    if (c.name == "gauss_max_rad") out.push_back(curvedVertices(model, c.limit));
    if (c.name == "seam_gap_mm") out.push_back(seamGaps(model, c.limit));
  }
  return out;
}

}  // namespace dform
