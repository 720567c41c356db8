// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/report/views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dform/core/piece_loops.h"
#include "dform/core/shape_projection.h"
#include "dform/validate/metrics.h"
#include "svg_text.h"

namespace dform {

namespace {

using svg::hexColour;
using svg::number;

std::string divergingColour(double t) {
  const Eigen::Vector3d c = curvatureColour(t);
  return hexColour(c.x(), c.y(), c.z());
}

// A piece's creases as SVG polylines through `pixel(v)` ("x,y"), styled by their fold as on the
// printed pattern: a valley dashed, a mountain dash-dot, each in its own colour.
template <class Pixel>
std::string creaseLines(const Piece& piece, Pixel pixel) {
  const std::vector<CreaseFold> folds = creaseFolds(piece);
  std::string svg;
  for (size_t k = 0; k < folds.size(); ++k) {
    const bool mountain = folds[k].direction == FoldDirection::Mountain;
    std::string points;
    for (int v : piece.creases[k]) points += pixel(v) + " ";
    svg += "<polyline points='" + points + "' fill='none' class='crease " +
           foldDirectionName(folds[k].direction) + "' stroke='" +
           (mountain ? "#b03a2e" : "#1f5fa8") + "' stroke-width='1.4' stroke-dasharray='" +
           (mountain ? "6,3,1.5,3" : "4,3") + "'/>";
  }
  return svg;
}

}  // namespace

CurvatureMaps curvatureMaps(const DForm& model) {
  CurvatureMaps c;
  c.piece[0] = curvatureMap(model.a);
  c.piece[1] = curvatureMap(model.b);
  const double top = std::max(c.piece[0].cwiseAbs().maxCoeff(), c.piece[1].cwiseAbs().maxCoeff());
  // Never below 1e-3 rad (a 20th of the default gate's limit): on an exactly developable shape
  // the defects are rounding noise, which must stay white rather than be stretched to full colour.
  c.scale = std::max(top, 1e-3);
  return c;
}

Eigen::Vector3d curvatureColour(double t) {
  t = std::clamp(t, -1.0, 1.0);
  return t >= 0 ? Eigen::Vector3d(1.0, 1.0 - 0.8 * t, 1.0 - 0.8 * t)
                : Eigen::Vector3d(1.0 + 0.8 * t, 1.0 + 0.8 * t, 1.0);
}

double curvatureScale(const DForm& model) { return curvatureMaps(model).scale; }

std::string shapeSvg(const DForm& model, const View& view, const CurvatureMaps* maps) {
  const ShapeCamera camera(view.azimuthDeg, view.elevationDeg);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Piece* p : {&model.a, &model.b})
    for (Eigen::Index i = 0; i < p->shape.rows(); ++i) {
      const Eigen::Vector3d s = camera.screen(p->shape.row(i).transpose());
      lo = lo.cwiseMin(s.head<2>());
      hi = hi.cwiseMax(s.head<2>());
    }
  const double margin = 8.0;
  const double scale = (view.widthPx - 2 * margin) / std::max(hi.x() - lo.x(), 1e-9);
  const double height = (hi.y() - lo.y()) * scale + 2 * margin;
  auto pixel = [&](const Eigen::Vector2d& s) {
    return Eigen::Vector2d(margin + (s.x() - lo.x()) * scale,
                           height - margin - (s.y() - lo.y()) * scale);
  };
  auto toScreen = [&](const Eigen::Vector3d& p) { return camera.screen(p).head<2>().eval(); };
  const CurvatureMaps measured = view.curvature && !maps ? curvatureMaps(model) : CurvatureMaps{};
  const CurvatureMaps& K = maps ? *maps : measured;

  std::string svg = svg::open(view.widthPx, height);
  for (const SeenFace& face : paintersFaces(model, camera)) {
    const Piece& p = face.piece == 0 ? model.a : model.b;
    std::string points;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d q = pixel(face.corners[size_t(k)]);
      points += number(q.x()) + "," + number(q.y()) + (k < 2 ? " " : "");
    }
    std::string fill;
    if (view.curvature) {
      const Eigen::VectorXd& k = K.piece[face.piece];
      const auto f = face.face;
      fill = divergingColour((k(p.F(f, 0)) + k(p.F(f, 1)) + k(p.F(f, 2))) / 3.0 / K.scale);
    } else {
      const Eigen::Vector3d c = shadedPieceColour(face.piece, face.shade);
      fill = hexColour(c.x(), c.y(), c.z());
    }
    svg += "<polygon points='" + points + "' fill='" + fill + "' stroke='" + fill +
           "' stroke-width='0.4'/>";
  }
  // The seam, on top: it is the ridge where the two pieces meet.
  std::string seam;
  for (int v : model.a.seam) {
    const Eigen::Vector2d q = pixel(toScreen(model.a.shape.row(v).transpose()));
    seam += number(q.x()) + "," + number(q.y()) + " ";
  }
  svg += "<polygon points='" + seam +
         "' fill='none' stroke='#c2185b' stroke-width='1.2' stroke-opacity='0.8'/>";
  for (const Piece* p : {&model.a, &model.b})  // the creases, on top like the seam
    svg += creaseLines(*p, [&](int v) {
      const Eigen::Vector2d q = pixel(toScreen(p->shape.row(v).transpose()));
      return number(q.x()) + "," + number(q.y());
    });
  return svg + "</svg>";
}

std::string flatCurvatureSvg(const DForm& model, double widthPx, const CurvatureMaps* maps,
                             const std::vector<FlatFold>& folds) {
  // Lay A and B side by side with a gap of a tenth of the larger piece.
  Eigen::RowVector2d loA = model.a.flat.colwise().minCoeff(),
                     hiA = model.a.flat.colwise().maxCoeff();
  Eigen::RowVector2d loB = model.b.flat.colwise().minCoeff(),
                     hiB = model.b.flat.colwise().maxCoeff();
  const double gap = 0.1 * std::max((hiA - loA).maxCoeff(), (hiB - loB).maxCoeff());
  const double totalW = (hiA.x() - loA.x()) + gap + (hiB.x() - loB.x());
  const double totalH = std::max(hiA.y() - loA.y(), hiB.y() - loB.y());
  const double margin = 8.0;
  const double scale = (widthPx - 2 * margin) / std::max(totalW, 1e-9);
  const double height = totalH * scale + 2 * margin;
  const CurvatureMaps measured = maps ? CurvatureMaps{} : curvatureMaps(model);
  const CurvatureMaps& K = maps ? *maps : measured;
  std::string svg = svg::open(widthPx, height);
  // A fine mesh is drawn on about kDrawnFaces faces (core/shape_projection.h), with one cell for
  // both pieces.
  double area = 0;
  for (const Piece* p : {&model.a, &model.b})
    for (Eigen::Index f = 0; f < p->F.rows(); ++f) {
      const Eigen::RowVector2d u = p->flat.row(p->F(f, 1)) - p->flat.row(p->F(f, 0));
      const Eigen::RowVector2d v = p->flat.row(p->F(f, 2)) - p->flat.row(p->F(f, 0));
      area += 0.5 * std::abs(u.x() * v.y() - u.y() * v.x());
    }
  const double cell = drawingCell(area, model.a.F.rows() + model.b.F.rows());
  for (int piece = 0; piece < 2; ++piece) {
    const Piece& p = piece == 0 ? model.a : model.b;
    const Eigen::RowVector2d origin = piece == 0 ? loA : loB;
    const double offset = piece == 0 ? 0.0 : (hiA.x() - loA.x()) + gap;
    auto pixelAt = [&](const Eigen::RowVector2d& at) {
      const Eigen::RowVector2d q = at - origin;
      return number(margin + (q.x() + offset) * scale) + "," +
             number(height - margin - q.y() * scale);
    };
    auto pixel = [&](Eigen::Index v) { return pixelAt(p.flat.row(v)); };
    const PointClusters drawn = clusterPoints(p.flat, cell);
    ClusteredFaces kept(cell);
    const Eigen::VectorXd& k = K.piece[piece];
    for (Eigen::Index f = 0; f < p.F.rows(); ++f) {
      std::array<int, 3> c{};
      for (int j = 0; j < 3; ++j) c[size_t(j)] = drawn.of[size_t(p.F(f, j))];
      if (!kept.draws(c)) continue;
      const std::string fill =
          divergingColour((k(p.F(f, 0)) + k(p.F(f, 1)) + k(p.F(f, 2))) / 3.0 / K.scale);
      svg += "<polygon points='" + pixelAt(drawn.mean.row(c[0])) + " " +
             pixelAt(drawn.mean.row(c[1])) + " " + pixelAt(drawn.mean.row(c[2])) + "' fill='" +
             fill + "' stroke='" + fill + "' stroke-width='0.4'/>";
    }
    // Every boundary loop outlined (the seam, the free outlines and holes; a hole has no
    // triangles, so it stays empty), then the creases.
    for (const std::vector<int>& loop : boundaryLoops(p)) {
      std::string outline;
      for (int v : loop) outline += pixel(v) + " ";
      svg += "<polygon points='" + outline + "' fill='none' stroke='#333' stroke-width='1'/>";
    }
    // The body's folds under the creases: gentle ones barely there, found creases stronger.
    for (const FlatFold& fold : folds)
      if (fold.piece == piece)
        svg += "<line class='fold " + std::string(fold.crease ? "steep" : "gentle") + "' x1='" +
               number(margin + (fold.from.x() - origin.x() + offset) * scale) + "' y1='" +
               number(height - margin - (fold.from.y() - origin.y()) * scale) + "' x2='" +
               number(margin + (fold.to.x() - origin.x() + offset) * scale) + "' y2='" +
               number(height - margin - (fold.to.y() - origin.y()) * scale) + "' stroke='#333' " +
               (fold.crease ? "stroke-opacity='0.7' stroke-width='1'"
                            : "stroke-opacity='0.3' stroke-width='0.5'") +
               "/>";
    svg += creaseLines(p, [&](int v) { return pixel(v); });
  }
  return svg + "</svg>";
}

}  // namespace dform
