#include "model/exact_model.h"

#include <algorithm>
#include <cmath>

#include "core/polyline.h"
#include "meshing/triangulate.h"

namespace dform {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// A smoothly curved body of n seam points folds by up to about 3 x 360/n degrees between
// neighbouring faces (measured on ellipse pairs and an ellipse with a circle, n = 100 to 400:
// 10.4, 5.2 and 2.6 degrees); a real crease keeps its angle as n grows (a square's corners
// against a circle: 66 degrees). Twice that margin, and never below 20 degrees.
double foundCreaseRadians(long n) { return std::max(20.0, 6.0 * 360.0 / double(n)) * kDegree; }

}  // namespace

Result<DForm> exactDForm(exact::SeamPolygons polygons, double targetEdge, const std::string paths[2],
                         ModelUsed& used) {
  const Eigen::Index n = polygons.a.rows();
  used.chordMoveMm = exact::equalizeChords(polygons);
  Result<exact::ExactGluing> glued = exact::glue(polygons);
  if (!glued.isOk()) return glued.status();
  const exact::ExactGluing& g = glued.value();
  used.doublyCovered = g.doublyCovered;
  used.conePoints = g.doublyCovered ? 0 : g.triangulation.vertexCount();
  used.newtonSteps = g.embedding.iterations;
  used.maxCurvature = g.embedding.maxCurvature;
  const std::vector<exact::FoundCrease> folds = exact::findCreases(g, foundCreaseRadians(n));
  DForm model;
  Piece* pieces[2] = {&model.a, &model.b};
  for (int p = 0; p < 2; ++p) {
    // The mesher takes the outline counter-clockwise: A's seam order, B's reversed.
    const Points2& side = p == 0 ? g.seam.a : g.seam.b;
    std::vector<int> rowOf(n);
    Points2 outline(n, 2);
    for (Eigen::Index k = 0; k < n; ++k) {
      rowOf[k] = p == 0 ? int(k) : int((n - k) % n);
      outline.row(rowOf[k]) = side.row(k);
    }
    std::vector<InteriorLine> lines;
    std::vector<const exact::FoundCrease*> kept;
    for (const exact::FoundCrease& fold : folds) {
      if (fold.piece != p) continue;
      InteriorLine line;
      line.from = rowOf[fold.from];
      line.to = rowOf[fold.to];
      Points2 ends(2, 2);
      ends << outline.row(line.from), outline.row(line.to);
      const int segments = std::max(1, int(std::lround(openLength(ends) / targetEdge)));
      line.interior = resampleOpen(ends, segments).middleRows(1, segments - 1);
      lines.push_back(std::move(line));
      kept.push_back(&fold);
    }
    TriangulateOptions meshOptions;
    meshOptions.targetEdgeLength = targetEdge;
    Result<FlatMesh> mesh = triangulateDomain(outline, {}, meshOptions, lines);
    if (!mesh.isOk()) return Status(mesh.status().code(), paths[p] + ": " + mesh.status().message());
    Piece& out = *pieces[p];
    out.name = p == 0 ? "A" : "B";
    out.flat = std::move(mesh.value().V);
    out.F = std::move(mesh.value().F);
    out.seam = rowOf;
    out.creases = std::move(mesh.value().lines);
    out.shape = exact::placeOnBody(g, p, out.flat);
    if (!out.shape.allFinite())
      return Status(ErrorCode::SolveFailed, paths[p] + ": a mesh vertex could not be placed on the exact D-Form");
    for (std::size_t c = 0; c < kept.size(); ++c)
      used.creases.push_back({p, int(c), kept[c]->angle / kDegree,
                              (outline.row(rowOf[kept[c]->from]) - outline.row(rowOf[kept[c]->to])).norm()});
  }
  // Seam partners are one point of the body; placed from either side they differ by rounding.
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    model.b.shape.row(model.b.seam[k]) = model.a.shape.row(model.a.seam[k]);
  // Every mesh edge on the body is a chord of a path as long as the flat edge, so never longer
  // than it: a longer one means a vertex was placed off its spot, and the result is not used
  // (auto then makes the shape with the paper model).
  for (int p = 0; p < 2; ++p) {
    const Piece& piece = *pieces[p];
    double longest = 0.0;
    for (Eigen::Index f = 0; f < piece.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int i = piece.F(f, c), j = piece.F(f, (c + 1) % 3);
        const double flat = (piece.flat.row(i) - piece.flat.row(j)).norm();
        longest = std::max(longest, (piece.shape.row(i) - piece.shape.row(j)).norm() / flat - 1.0);
      }
    // 1e-4: the seam polygons were moved by up to ~1e-6 of an edge to equal chords, and placing
    // a vertex rounds; a misplaced vertex is off by a good part of an edge (seen: 174 %).
    if (longest > 1e-4)
      return Status(ErrorCode::SolveFailed, paths[p] + ": a mesh vertex was placed off the exact D-Form (an edge came "
                                                      "out longer than it is flat, by " + std::to_string(100 * longest) + " %)");
  }
  return model;
}

}  // namespace dform
