// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/validate/metrics.h"

#include <Eigen/Geometry>
#include <cassert>
#include <cmath>
#include <limits>

#include "dform/core/constants.h"
#include "dform/core/interrupt.h"
#include "dform/core/polyline.h"
#include "dform/exact/aligned_distance.h"
#include "mesh_measures.h"

namespace dform {

namespace {

// An edge's strain from its flat length L and 3D length Lh (EdgeStrain). A zero-length flat edge
// is reported by the degenerate count; its strain is infinite unless the 3D edge is zero too.
double strainOf(double L, double Lh) {
  return L > 0.0 ? (Lh - L) / L : (Lh > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
}

// Adds one piece's edges to the L_error sums and the L_max maximum. Each undirected edge counts
// once; L is its flat length, Lh its 3D length.
void addEdgeLengths(const Piece& p, const detail::EdgeTopology& topology, double& sumSqDiff,
                    double& sumSqFlat, double& maxRel) {
  for (const auto& e : topology.edges) {
    const double L = (p.flat.row(e[0]) - p.flat.row(e[1])).norm();
    const double Lh = (p.shape.row(e[0]) - p.shape.row(e[1])).norm();
    sumSqDiff += (Lh - L) * (Lh - L);
    sumSqFlat += L * L;
    const double rel = std::abs(strainOf(L, Lh));
    if (std::isnan(rel) || rel > maxRel) maxRel = rel;  // std::max would skip a NaN; once NaN, kept
  }
}

// Angle defect per vertex of a piece's 3D shape; NaN on the boundary, the seam and the creases,
// where the sheet may turn and the defect is not curvature.
Eigen::VectorXd interiorDefects(const Piece& p, const detail::EdgeTopology& topology) {
  Eigen::VectorXd defect = detail::angleDefects(p.shape, p.F);
  const std::vector<bool> onBoundary = detail::boundaryOrCreaseVertices(p, topology);
  for (Eigen::Index v = 0; v < defect.size(); ++v)
    if (onBoundary[size_t(v)]) defect(v) = std::numeric_limits<double>::quiet_NaN();
  return defect;
}

// Adds one piece's |angle defect| at interior vertices.
void addDefects(const Piece& p, const detail::EdgeTopology& topology, double& maxAbs,
                double& sumAbs, int& count) {
  for (double d : interiorDefects(p, topology)) {
    if (std::isnan(d)) continue;
    maxAbs = std::max(maxAbs, std::abs(d));
    sumAbs += std::abs(d);
    ++count;
  }
}

// A piece's 3D seam, row k for seam point k.
Points3 seamShape(const Piece& p) {
  Points3 out(Eigen::Index(p.seam.size()), 3);
  for (std::size_t k = 0; k < p.seam.size(); ++k) out.row(Eigen::Index(k)) = p.shape.row(p.seam[k]);
  return out;
}

}  // namespace

std::vector<EdgeStrain> edgeStrains(const Piece& piece) {
  std::vector<EdgeStrain> out;
  for (const auto& e : detail::edgeTopology(piece.F).edges)
    out.push_back({e[0], e[1],
                   strainOf((piece.flat.row(e[0]) - piece.flat.row(e[1])).norm(),
                            (piece.shape.row(e[0]) - piece.shape.row(e[1])).norm())});
  return out;
}

Eigen::VectorXd curvatureMap(const Piece& piece) {
  return interiorDefects(piece, detail::edgeTopology(piece.F)).unaryExpr([](double d) {
    return std::isnan(d) ? 0.0 : d;
  });
}

const char* foldDirectionName(FoldDirection direction) {
  return direction == FoldDirection::Mountain ? "mountain" : "valley";
}

std::vector<CreaseFold> creaseFolds(const Piece& piece) {
  if (piece.creases.empty()) return {};  // most pieces: no edge table to build
  const detail::EdgeTopology topology = detail::edgeTopology(piece.F);
  auto corner = [&](int v) -> Eigen::Vector3d { return piece.shape.row(v).transpose(); };
  auto unitNormal = [&](int f) {
    const Eigen::Vector3d a = corner(piece.F(f, 0));
    return Eigen::Vector3d(
        (corner(piece.F(f, 1)) - a).cross(corner(piece.F(f, 2)) - a).normalized());
  };
  // Whether face f runs from u to v (then it lies on the edge's left in the flat layout).
  auto runs = [&](int f, int u, int v) {
    for (int k = 0; k < 3; ++k)
      if (piece.F(f, k) == u && piece.F(f, (k + 1) % 3) == v) return true;
    return false;
  };
  std::vector<CreaseFold> folds;
  for (const std::vector<int>& crease : piece.creases) {
    CreaseFold fold;
    double weighted = 0.0, weight = 0.0;
    bool first = true;
    for (size_t k = 0; k + 1 < crease.size(); ++k) {
      const int u = crease[k], v = crease[k + 1];
      const double length = (piece.flat.row(u) - piece.flat.row(v)).norm();
      fold.lengthMm += length;
      const int e = detail::edgeIndex(topology, u, v);
      if (e < 0 || topology.faces[size_t(e)][1] < 0) continue;
      auto [f, g] = topology.faces[size_t(e)];
      if (!runs(f, u, v)) std::swap(f, g);
      // With f on the left of u -> v, the fold is convex seen from the faces' outward side (a
      // mountain) when g's normal turns about u -> v the positive way from f's.
      const Eigen::Vector3d nf = unitNormal(f), ng = unitNormal(g);
      const Eigen::Vector3d along = (corner(v) - corner(u)).normalized();
      const double angle = std::atan2(nf.cross(ng).dot(along), nf.dot(ng)) * 180.0 / kPi;
      fold.minAngleDeg = first ? angle : std::min(fold.minAngleDeg, angle);
      fold.maxAngleDeg = first ? angle : std::max(fold.maxAngleDeg, angle);
      first = false;
      weighted += length * angle;
      weight += length;
    }
    const double mean = weight > 0.0 ? weighted / weight : 0.0;
    fold.direction = mean >= 0.0 ? FoldDirection::Mountain : FoldDirection::Valley;
    fold.angleDeg = std::abs(mean);
    folds.push_back(fold);
  }
  return folds;
}

Metrics computeMetrics(const DForm& model, const ReferenceSeam& exactBody) {
  assert(model.a.seam.size() == model.b.seam.size() && "seam partners come in pairs");
  Metrics m;
  double sumSqDiff = 0.0, sumSqFlat = 0.0, sumAbsDefect = 0.0;
  int interiorCount = 0;
  for (const Piece* p : {&model.a, &model.b}) {
    throwIfInterrupted("the figures");
    assert(p->flat.rows() == p->shape.rows() && "flat and 3D layouts share their vertices");
    const detail::EdgeTopology topology = detail::edgeTopology(p->F);
    addEdgeLengths(*p, topology, sumSqDiff, sumSqFlat, m.lengthErrorMax);
    addDefects(*p, topology, m.gaussMax, sumAbsDefect, interiorCount);
    for (int f = 0; f < p->F.rows(); ++f) m.flipped2d += detail::isFlippedFlat(p->flat, p->F, f);
    // Folded over: across an interior edge whose two flat triangles are both counter-clockwise
    // (flat dihedral 0), the 3D unit normals have a negative dot product (a turn of more than 90
    // degrees); each triangle counts once. Crease edges may fold sharply and are not looked at.
    // Details in mesh_measures.cpp.
    m.flipped3d +=
        detail::countFolded(p->flat, p->shape, p->F, topology, detail::creaseEdges(*p, topology));
    m.degenerate2d += detail::countDegenerate(detail::lift(p->flat), p->F, topology);
    m.degenerate3d += detail::countDegenerate(p->shape, p->F, topology);
  }
  m.lengthError = sumSqFlat > 0.0 ? std::sqrt(sumSqDiff / sumSqFlat) : 0.0;
  m.gaussMean = interiorCount > 0 ? sumAbsDefect / interiorCount : 0.0;

  const std::vector<int>& sa = model.a.seam;
  const std::vector<int>& sb = model.b.seam;
  double sumGap = 0.0;
  for (size_t i = 0; i < sa.size(); ++i) {
    const double gap = (model.a.shape.row(sa[i]) - model.b.shape.row(sb[i])).norm();
    sumGap += gap;
    m.seamGapMm = std::max(m.seamGapMm, gap);
  }
  m.seamLengthAMm = detail::seamLength(model.a.flat, sa);
  m.seamLengthBMm = detail::seamLength(model.b.flat, sb);
  m.seamLength3dMm = detail::seamLength(model.a.shape, sa);
  if (!sa.empty() && m.seamLength3dMm > 0.0)
    m.seamError = (sumGap / double(sa.size())) / m.seamLength3dMm;
  if (exactBody.points.rows() > 0) {
    const exact::AlignedDistance d = exact::alignedDistance(exactBody.points, seamShape(model.a));
    m.exactDistanceRmsRel = d.rmsRel;
    m.exactDistanceMaxRel = d.maxRel;
  } else {
    m.exactNote = exactBody.note;
  }
  return m;
}

CurveMatch computeCurveMatch(const DForm& model, const Curve3& target,
                             const ReferenceSeam& zippedAgain) {
  const std::vector<int>& sa = model.a.seam;
  const std::vector<int>& sb = model.b.seam;
  assert(sa.size() == sb.size() && size_t(target.points.rows()) == sa.size() &&
         "the target curve has one point per seam pair");
  CurveMatch match;
  double sum = 0.0;  // Eq. 7: both boundaries' distances in one vector of 2n entries
  for (size_t i = 0; i < sa.size(); ++i) {
    const double da = (model.a.shape.row(sa[i]) - target.points.row(Eigen::Index(i))).norm();
    const double db = (model.b.shape.row(sb[i]) - target.points.row(Eigen::Index(i))).norm();
    sum += da + db;
    match.curveDistanceMaxMm = std::max({match.curveDistanceMaxMm, da, db});
  }
  const double curveLength = closedLength(target.points);
  if (!sa.empty() && curveLength > 0.0)
    match.curveError = (sum / (2.0 * double(sa.size()))) / curveLength;
  if (zippedAgain.points.rows() > 0) {
    const exact::AlignedDistance d = exact::alignedDistance(target.points, zippedAgain.points);
    match.roundtripRmsRel = d.rmsRel;
    match.roundtripMaxRel = d.maxRel;
  }
  match.roundtripNote = zippedAgain.note;
  return match;
}

}  // namespace dform
