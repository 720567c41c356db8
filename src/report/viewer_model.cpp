// SPDX-License-Identifier: GPL-3.0-or-later
#include "viewer_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "dform/core/shape_projection.h"

namespace dform {

namespace {

using nlohmann::json;

// Steps per millimetre to round coordinates to: a power of ten, so that they print short, for a
// step below a ten-thousandth of the shape's bounding-box diagonal.
double roundingSteps(const DForm& model) {
  Eigen::RowVector3d lo = model.a.shape.colwise().minCoeff(),
                     hi = model.a.shape.colwise().maxCoeff();
  lo = lo.cwiseMin(model.b.shape.colwise().minCoeff());
  hi = hi.cwiseMax(model.b.shape.colwise().maxCoeff());
  const double size = std::max((hi - lo).norm(), 1e-9);
  return std::pow(10.0, -std::floor(std::log10(size * 1e-4)));
}

}  // namespace

std::string viewerModelJson(const DForm& model, const CurvatureMaps& maps,
                            const std::vector<SeamTick>& ticks) {
  // Divided, not multiplied by a step: 1234 / 100.0 prints as 12.34, 1234 * 0.01 does not.
  const double steps = roundingSteps(model);
  auto coordinates = [&](json& list, const Eigen::Vector3d& p) {
    for (int d = 0; d < 3; ++d) list.push_back(std::round(p(d) * steps) / steps);
  };
  const PointClusters drawn = drawnShapeClusters(model);
  ClusteredFaces kept(drawn.cell);
  json pieces = json::array();
  for (int piece = 0; piece < 2; ++piece) {
    const Piece& p = piece == 0 ? model.a : model.b;
    const Eigen::Index first = piece == 0 ? 0 : model.a.shape.rows();
    // The piece's own vertices, one per cluster its faces use, numbered by first use.
    std::map<int, int> local;
    std::vector<double> defectSum;
    std::vector<int> members;
    json index = json::array();
    for (Eigen::Index f = 0; f < p.F.rows(); ++f) {
      std::array<int, 3> c{};
      for (int k = 0; k < 3; ++k) c[size_t(k)] = drawn.of[size_t(first + p.F(f, k))];
      if (!kept.draws(c)) continue;
      for (int k = 0; k < 3; ++k) {
        const auto [at, added] = local.emplace(c[size_t(k)], int(local.size()));
        if (added) defectSum.push_back(0), members.push_back(0);
        index.push_back(at->second);
      }
    }
    for (Eigen::Index v = 0; v < p.shape.rows(); ++v) {
      const auto at = local.find(drawn.of[size_t(first + v)]);
      if (at == local.end()) continue;  // only on faces that merged away
      defectSum[size_t(at->second)] += maps.piece[piece](v);
      ++members[size_t(at->second)];
    }
    json position = json::array(), curvature = json::array();
    std::vector<int> clusterOf(local.size());
    for (const auto& [cluster, v] : local) clusterOf[size_t(v)] = cluster;
    for (size_t v = 0; v < clusterOf.size(); ++v) {
      coordinates(position, drawn.mean.row(clusterOf[v]).transpose());
      const Eigen::Vector3d c = curvatureColour(defectSum[v] / members[v] / maps.scale);
      long rgb = 0;
      for (int d = 0; d < 3; ++d) rgb = rgb * 256 + std::lround(255.0 * c(d));
      curvature.push_back(rgb);
    }
    const Eigen::Vector3d colour = shadedPieceColour(piece, 1.0);
    pieces.push_back({{"name", p.name},
                      {"colour", {colour.x(), colour.y(), colour.z()}},
                      {"position", position},
                      {"curvature", curvature},
                      {"index", index}});
  }
  json seam = json::array(), tickList = json::array();
  for (int v : model.a.seam) coordinates(seam, model.a.shape.row(v).transpose());
  for (const SeamTick& t : ticks) {
    json at = json::array();
    coordinates(at, t.at);
    tickList.push_back({{"label", t.label}, {"at", at}});
  }
  return json{{"pieces", pieces}, {"seam", seam}, {"ticks", tickList}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

}  // namespace dform
