// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/forward/coarse_to_fine.h"

#include <array>

#include "dform/core/polyline.h"
#include "dform/meshing/triangulate.h"
#include "dform/model/run_control.h"
#include "dform/model/transfer.h"

namespace dform {

namespace {

// Both pieces remeshed on m of their n seam points (the same ones, so that the pairs stay
// paired), with interior edges as long as the coarse seam's.
Result<std::array<Piece, 2>> coarserPieces(const Piece& a, const Piece& b, int m) {
  const int n = int(a.seam.size());
  std::array<Piece, 2> coarse;
  const Piece* fine[2] = {&a, &b};
  for (int p = 0; p < 2; ++p) {
    // The mesher takes the outline counter-clockwise: A's seam order, B's reversed.
    std::vector<int> rowOf(std::size_t(m), 0);
    Points2 outline(m, 2);
    for (int k = 0; k < m; ++k) {
      rowOf[std::size_t(k)] = p == 0 ? k : (m - k) % m;
      outline.row(rowOf[std::size_t(k)]) =
          fine[p]->flat.row(fine[p]->seam[std::size_t(long(k) * n / m)]);
    }
    TriangulateOptions meshOptions;
    meshOptions.targetEdgeLength = closedLength(outline) / double(m);
    Result<FlatMesh> mesh = triangulateDomain(outline, {}, meshOptions);
    if (!mesh.isOk()) return mesh.status();
    Piece& out = coarse[std::size_t(p)];
    out.name = fine[p]->name;
    out.flat = std::move(mesh.value().V);
    out.F = std::move(mesh.value().F);
    out.seam = std::move(rowOf);
  }
  return coarse;
}

}  // namespace

namespace detail {

ForwardSettings levelSettings(ForwardSettings settings, bool finest, long vertices) {
  if (!finest) {
    settings.solver.maxIterations = std::min(settings.solver.maxIterations, kCoarseIterations);
    settings.constraintRounds = 0;
  }
  relaxOnlyIfLarge(vertices, settings.solver, settings.relaxation);
  return settings;
}

}  // namespace detail

ForwardResult solveMeshedCoarseToFine(const Piece& a, const Piece& b,
                                      const ForwardSettings& settings) {
  const bool discs = a.freeBoundaries.empty() && b.freeBoundaries.empty();
  const std::vector<int> levels = detail::seamLevels(int(a.seam.size()), discs);
  ForwardResult solved;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const bool finest = level + 1 == levels.size();
    std::array<Piece, 2> pieces;
    if (finest) {
      pieces = {a, b};
    } else {
      Result<std::array<Piece, 2>> coarse = coarserPieces(a, b, levels[level]);
      if (!coarse.isOk()) continue;  // a coarse level is only a start: the next one does without it
      pieces = std::move(coarse).value();
    }
    const bool haveCoarser = solved.model.a.shape.rows() > 0;
    for (Piece& piece : pieces) piece.shape.resize(0, 3);  // from the pillow, or:
    if (haveCoarser) startFromCoarser(solved.model, pieces[0], pieces[1]);
    solved = solveForward(
        pieces[0], pieces[1],
        detail::levelSettings(settings, finest, pieces[0].flat.rows() + pieces[1].flat.rows()));
    if (finest || solved.summary.usable()) continue;
    solved = ForwardResult{};  // a failed coarse level starts nothing: the next one starts from the
                               // pillow
  }
  return solved;
}

}  // namespace dform
