// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/shape_projection.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

#include "dform/core/constants.h"
#include "dform/core/interrupt.h"

namespace dform {

ShapeCamera::ShapeCamera(double azimuthDeg, double elevationDeg) {
  const double az = azimuthDeg * kPi / 180.0, el = elevationDeg * kPi / 180.0;
  R_ = (Eigen::AngleAxisd(el, Eigen::Vector3d::UnitX()) *
        Eigen::AngleAxisd(-az, Eigen::Vector3d::UnitZ()))
           .toRotationMatrix();
}

Eigen::Vector3d ShapeCamera::depthAxis() const { return R_.row(1).transpose(); }

Eigen::Vector3d ShapeCamera::screen(const Eigen::Vector3d& p) const {
  // Screen: x right, y up = rotated (x, z); depth = rotated y.
  const Eigen::Vector3d q = R_ * p;
  return {q.x(), q.z(), q.y()};
}

double drawingCell(double area, Eigen::Index faces) {
  // A grid of cell c leaves about 2 S / c^2 faces on a surface of area S.
  if (double(faces) <= kDrawnFaces || !(area > 0)) return 0.0;
  return std::sqrt(2.0 * area / kDrawnFaces);
}

PointClusters clusterPoints(const Eigen::MatrixXd& points, double cell) {
  PointClusters clusters;
  clusters.cell = cell;
  if (!(cell > 0)) {
    clusters.of.resize(size_t(points.rows()));
    std::iota(clusters.of.begin(), clusters.of.end(), 0);
    clusters.mean = points;
    return clusters;
  }
  std::map<std::array<long, 3>, int> cellCluster;  // ordered: the same clusters on every machine
  std::vector<Eigen::VectorXd> sums;
  std::vector<int> members;
  for (Eigen::Index v = 0; v < points.rows(); ++v) {
    if (v % kPollInterval == 0) throwIfInterrupted("the pictures");
    std::array<long, 3> key{};
    for (Eigen::Index d = 0; d < points.cols() && d < 3; ++d)
      key[size_t(d)] = long(std::floor(points(v, d) / cell));
    const auto [at, added] = cellCluster.emplace(key, int(sums.size()));
    if (added) sums.emplace_back(Eigen::VectorXd::Zero(points.cols())), members.push_back(0);
    clusters.of.push_back(at->second);
    sums[size_t(at->second)] += points.row(v).transpose();
    ++members[size_t(at->second)];
  }
  clusters.mean.resize(Eigen::Index(sums.size()), points.cols());
  for (size_t c = 0; c < sums.size(); ++c)
    clusters.mean.row(Eigen::Index(c)) = sums[c].transpose() / double(members[c]);
  return clusters;
}

bool ClusteredFaces::draws(std::array<int, 3> clusters) {
  if (!merged_) return true;
  std::sort(clusters.begin(), clusters.end());
  return clusters[0] != clusters[1] && clusters[1] != clusters[2] && drawn_.insert(clusters).second;
}

PointClusters drawnShapeClusters(const DForm& model) {
  Eigen::MatrixXd points(model.a.shape.rows() + model.b.shape.rows(), 3);
  points << model.a.shape, model.b.shape;
  double area = 0;
  for (const Piece* p : {&model.a, &model.b})
    for (Eigen::Index f = 0; f < p->F.rows(); ++f) {
      const Eigen::Vector3d p0 = p->shape.row(p->F(f, 0)).transpose();
      area += 0.5 * (p->shape.row(p->F(f, 1)).transpose() - p0)
                        .cross(p->shape.row(p->F(f, 2)).transpose() - p0)
                        .norm();
    }
  return clusterPoints(points, drawingCell(area, model.a.F.rows() + model.b.F.rows()));
}

std::vector<SeenFace> paintersFaces(const DForm& model, const ShapeCamera& camera) {
  return paintersFaces(model, camera, drawnShapeClusters(model));
}

std::vector<SeenFace> paintersFaces(const DForm& model, const ShapeCamera& camera,
                                    const PointClusters& drawn) {
  const Eigen::Vector3d light = Eigen::Vector3d(-0.4, 0.5, 1.0).normalized();  // screen frame
  // A closed surface (no free boundary; faces wind outward) hides every face turned away from
  // the viewer behind one turned towards it: those need no drawing. An open one shows both sides.
  const bool closed = model.a.freeBoundaries.empty() && model.b.freeBoundaries.empty();
  const Eigen::Vector3d away = camera.depthAxis();
  const Piece* pieces[2] = {&model.a, &model.b};
  ClusteredFaces kept(drawn.cell);
  std::vector<SeenFace> faces;
  for (int piece = 0; piece < 2; ++piece) {
    const Piece& p = *pieces[piece];
    const Eigen::Index first = piece == 0 ? 0 : model.a.shape.rows();
    for (Eigen::Index f = 0; f < p.F.rows(); ++f) {
      if (f % kPollInterval == 0) throwIfInterrupted("the pictures");
      // Turned away or not by the face as solved: a face drawn on clusters may tip over.
      const Eigen::Vector3d p0 = p.shape.row(p.F(f, 0)).transpose();
      const Eigen::Vector3d outward =
          (p.shape.row(p.F(f, 1)).transpose() - p0).cross(p.shape.row(p.F(f, 2)).transpose() - p0);
      if (closed && outward.dot(away) > 0) continue;
      std::array<int, 3> c{};
      for (int k = 0; k < 3; ++k) c[size_t(k)] = drawn.of[size_t(first + p.F(f, k))];
      if (!kept.draws(c)) continue;
      Eigen::Vector3d s[3];
      for (int k = 0; k < 3; ++k) s[k] = camera.screen(drawn.mean.row(c[size_t(k)]).transpose());
      SeenFace seen;
      seen.piece = piece;
      seen.face = int(f);
      for (int k = 0; k < 3; ++k) {
        seen.corners[size_t(k)] = s[k].head<2>();
        seen.cornerDepths[size_t(k)] = s[k].z();
      }
      seen.depth = (s[0].z() + s[1].z() + s[2].z()) / 3.0;
      const Eigen::Vector3d n = (s[1] - s[0]).cross(s[2] - s[0]);
      const double lit = n.norm() > 0 ? std::abs(n.normalized().dot(light)) : 0.0;
      seen.shade = 0.35 + 0.65 * lit;
      faces.push_back(seen);
    }
  }
  // Far (large depth) first; ties by piece and face, so the order is the same on every machine.
  std::sort(faces.begin(), faces.end(), [](const SeenFace& a, const SeenFace& b) {
    if (a.depth != b.depth) return a.depth > b.depth;
    return a.piece != b.piece ? a.piece < b.piece : a.face < b.face;
  });
  return faces;
}

Eigen::Vector3d shadedPieceColour(int piece, double shade) {
  return piece == 0 ? Eigen::Vector3d(0.98, 0.72, 0.45) * shade
                    : Eigen::Vector3d(0.50, 0.70, 0.95) * shade;
}

}  // namespace dform
