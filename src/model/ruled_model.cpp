// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/ruled_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"
#include "dform/meshing/triangulate.h"
#include "dform/model/exact_model.h"
#include "dform/ruled/face_locator.h"

namespace dform {

namespace {

// A piece's boundary as the mesher takes it: the outline counter-clockwise, then the hole, and
// for each row of the surface's piece its index among those fixed points.
struct MeshBoundary {
  Points2 outline;
  std::vector<Points2> holes;
  std::vector<int> fixedOfRow;
};

MeshBoundary meshBoundary(const ruled::RuledSurface& surface, int p) {
  const ruled::PieceTriangulation& T = surface.pieces[std::size_t(p)];
  const std::vector<int>& seam = surface.seamRows[std::size_t(p)];
  const std::vector<int>& free = surface.freeRows[std::size_t(p)];
  MeshBoundary out;
  out.fixedOfRow.assign(std::size_t(T.flat().rows()), -1);
  auto take = [&](const std::vector<int>& rows, int first) {
    Points2 P(Eigen::Index(rows.size()), 2);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      P.row(Eigen::Index(k)) = T.flat().row(rows[k]);
      out.fixedOfRow[std::size_t(rows[k])] = first + int(k);
    }
    return P;
  };
  if (!free.empty()) {
    out.outline = take(free, 0);
    out.holes.push_back(take(seam, int(free.size())));
    return out;
  }
  // A disc's seam is its outline: counter-clockwise as it runs on A, the other way round on B.
  std::vector<int> ccw = seam;
  if (signedArea(take(seam, 0)) < 0.0) std::reverse(ccw.begin(), ccw.end());
  out.outline = take(ccw, 0);
  return out;
}

}  // namespace

Result<ruled::RuledSurface> ruledSurface(const RuledPieces& pieces, const std::string paths[2]) {
  ruled::RuledSurface surface;
  const int n = int(pieces.seam.a.rows());
  int vertices = n;
  for (int p = 0; p < 2; ++p) {
    const Points2& seam = p == 0 ? pieces.seam.a : pieces.seam.b;
    const std::optional<Points2>& free = pieces.freeOutline[std::size_t(p)];
    const int m = free ? int(free->rows()) : 0;
    Points2 rows(m + n, 2);
    if (free) rows.topRows(m) = *free;
    rows.bottomRows(n) = seam;
    std::vector<std::pair<int, int>> loops;
    if (free) loops.emplace_back(0, m);
    loops.emplace_back(m, n);
    std::vector<int>& vertex = surface.vertexOf[std::size_t(p)];
    for (int k = 0; k < m; ++k) {
      vertex.push_back(vertices++);
      surface.freeRows[std::size_t(p)].push_back(k);
    }
    for (int k = 0; k < n; ++k) {
      vertex.push_back(k);
      surface.seamRows[std::size_t(p)].push_back(m + k);
    }
    // A crease joins the two samples at its ends (the seam layout samples crease ends).
    std::vector<std::pair<int, int>> creases;
    for (std::size_t c = 0; c < pieces.creases[std::size_t(p)].size(); ++c) {
      const auto& [from, to] = pieces.creases[std::size_t(p)][c];
      Eigen::Index a = 0, b = 0;
      const double da = (rows.rowwise() - from.transpose()).rowwise().norm().minCoeff(&a);
      const double db = (rows.rowwise() - to.transpose()).rowwise().norm().minCoeff(&b);
      // Crease ends are samples, moved off the curve by the seam's chord-loss compensation (kappa
      // h^2 / 24, a small part of a sample spacing h) and by equal chords.
      const double spacing = closedLength(seam) / double(n);
      if (!(da <= 0.1 * spacing && db <= 0.1 * spacing) || a == b)
        return Status(ErrorCode::InputInvalid, paths[p] + ": crease " + std::to_string(c) +
                                                   " does not join two samples of the boundary");
      creases.emplace_back(int(a), int(b));
    }
    Result<Faces> faces = triangulateBoundaryPoints(rows, loops, creases);
    if (!faces.isOk())
      return Status(faces.status().code(), paths[p] + ": " + faces.status().message());
    surface.pieces[std::size_t(p)] = ruled::PieceTriangulation(rows, faces.value(), creases);
  }
  surface.X = Points3::Zero(vertices, 3);
  return surface;
}

Points3 ruledStartOf(const DForm& model, const ruled::RuledSurface& surface) {
  Points3 X = surface.X;
  const Piece* pieces[2] = {&model.a, &model.b};
  for (int p = 0; p < 2; ++p) {
    const std::vector<int>& vertex = surface.vertexOf[std::size_t(p)];
    const std::vector<int>& seamRows = surface.seamRows[std::size_t(p)];
    for (std::size_t k = 0; k < seamRows.size(); ++k)
      X.row(vertex[std::size_t(seamRows[k])]) = pieces[p]->shape.row(pieces[p]->seam[k]);
    const std::vector<int>& freeRows = surface.freeRows[std::size_t(p)];
    if (freeRows.empty()) continue;
    const std::vector<int>& loop = pieces[p]->freeBoundaries.front();
    for (std::size_t k = 0; k < freeRows.size(); ++k)
      X.row(vertex[std::size_t(freeRows[k])]) = pieces[p]->shape.row(loop[k]);
  }
  return X;
}

Result<DForm> ruledDForm(const ruled::RuledSurface& surface, double targetEdge,
                         const std::string paths[2], ModelUsed& used) {
  const std::vector<ruled::SurfaceEdge> edges = surface.edges();
  const int n = int(surface.seamRows[0].size());
  const double creaseAngle = foundCreaseRadians(n);
  DForm model;
  Piece* pieces[2] = {&model.a, &model.b};
  for (int p = 0; p < 2; ++p) {
    const ruled::PieceTriangulation& T = surface.pieces[std::size_t(p)];
    const MeshBoundary boundary = meshBoundary(surface, p);
    // The lines the mesh follows: drawn creases, and chords folded by kFollowedFold or more.
    std::vector<InteriorLine> lines;
    std::vector<double> folds;
    std::vector<bool> drawn;
    for (const ruled::SurfaceEdge& e : edges) {
      if (e.piece != p || e.kind == ruled::EdgeKind::Boundary) continue;
      const double fold = ruled::dihedral(surface.X.row(e.i), surface.X.row(e.j),
                                          surface.X.row(e.k), surface.X.row(e.l));
      const bool crease = e.kind == ruled::EdgeKind::Crease;
      if (!crease && std::abs(fold) < kFollowedFold) continue;
      const int from = T.tail(e.halfedge), to = T.head(e.halfedge);
      Points2 ends(2, 2);
      ends << T.flat().row(from), T.flat().row(to);
      const int segments = std::max(1, int(std::lround(openLength(ends) / targetEdge)));
      lines.push_back({boundary.fixedOfRow[std::size_t(from)], boundary.fixedOfRow[std::size_t(to)],
                       resampleOpen(ends, segments).middleRows(1, segments - 1)});
      folds.push_back(fold);
      drawn.push_back(crease);
    }
    TriangulateOptions options;
    options.targetEdgeLength = targetEdge;
    Result<FlatMesh> mesh = triangulateDomain(boundary.outline, boundary.holes, options, lines);
    if (!mesh.isOk())
      return Status(
          ErrorCode::SolveFailed,
          paths[p] + ": the surface's folds could not be meshed: " + mesh.status().message());
    Piece& out = *pieces[p];
    out.name = p == 0 ? "A" : "B";
    out.flat = std::move(mesh.value().V);
    out.F = std::move(mesh.value().F);
    for (int row : surface.seamRows[std::size_t(p)])
      out.seam.push_back(boundary.fixedOfRow[std::size_t(row)]);
    if (!surface.freeRows[std::size_t(p)].empty()) {
      out.freeBoundaries.emplace_back();
      for (int row : surface.freeRows[std::size_t(p)])
        out.freeBoundaries.back().push_back(boundary.fixedOfRow[std::size_t(row)]);
    }
    for (std::size_t l = 0; l < lines.size(); ++l) {
      const std::vector<int>& line = mesh.value().lines[l];
      const bool crease = drawn[l] || std::abs(folds[l]) > creaseAngle;
      const int index = crease ? int(out.creases.size()) : -1;
      const auto seamPointAt = [&](int vertex) {
        const auto it = std::find(out.seam.begin(), out.seam.end(), vertex);
        return it == out.seam.end() ? -1 : int(it - out.seam.begin());
      };
      used.folds.push_back({p, line.front(), line.back(), seamPointAt(line.front()),
                            seamPointAt(line.back()), seamPointAt(line.front()),
                            seamPointAt(line.back()), std::abs(folds[l]), index});
      if (!crease) continue;
      if (!drawn[l])
        used.creases.push_back({p, index, std::abs(folds[l]) / kDegree,
                                (out.flat.row(line.front()) - out.flat.row(line.back())).norm()});
      out.creases.push_back(line);
    }
    // Every vertex on the surface's face that holds it (vertices on a fold are on both faces
    // beside it, which meet there).
    const Faces faces = T.faces();
    const ruled::FaceLocator locator(T.flat(), faces);
    const std::vector<int>& vertex = surface.vertexOf[std::size_t(p)];
    out.shape.resize(out.flat.rows(), 3);
    for (Eigen::Index v = 0; v < out.flat.rows(); ++v) {
      Eigen::Vector3d bary;
      const int f = locator.locate(out.flat.row(v).transpose(), bary);
      if (f < 0 || bary.minCoeff() < -1e-6)
        return Status(ErrorCode::SolveFailed,
                      paths[p] + ": a mesh vertex lies in no triangle of the ruled surface");
      Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
      for (int c = 0; c < 3; ++c) x += bary[c] * surface.X.row(vertex[std::size_t(faces(f, c))]);
      out.shape.row(v) = x;
    }
  }
  // The seam's rows are surface vertices: exactly where the surface has them, the same on both.
  for (int p = 0; p < 2; ++p)
    for (int k = 0; k < n; ++k) {
      const int row = surface.seamRows[std::size_t(p)][std::size_t(k)];
      pieces[p]->shape.row(pieces[p]->seam[std::size_t(k)]) =
          surface.X.row(surface.vertexOf[std::size_t(p)][std::size_t(row)]);
    }
  return model;
}

}  // namespace dform
