// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/exact_model.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "dform/core/constants.h"
#include "dform/core/polyline.h"
#include "dform/exact/body_edges.h"
#include "dform/meshing/triangulate.h"
#include "exact_placement.h"

namespace dform {

namespace {

// The seam of the meshes: every seam point, and between them the places where followed body edges
// cross the seam (the same places on both pieces), in seam order.
class ConformingSeam {
 public:
  ConformingSeam(int n, const std::vector<const exact::BodyEdge*>& edges)
      : crossings_(std::size_t(n)) {
    for (const exact::BodyEdge* edge : edges)
      for (const exact::EdgeRun& run : edge->runs)
        for (const exact::SeamPlace& place : {run.from, run.to})
          if (!place.isSeamPoint()) crossings_[std::size_t(place.chord)].push_back(place.t);
    first_.resize(std::size_t(n) + 1);
    for (int k = 0; k < n; ++k) {
      std::vector<double>& ts = crossings_[std::size_t(k)];
      std::sort(ts.begin(), ts.end());
      // Places closer than kSeamMerge of the chord to a seam point or to each other are one.
      std::vector<double> merged;
      for (double t : ts) {
        if (t <= kSeamMerge || t >= 1.0 - kSeamMerge) continue;
        if (!merged.empty() && t - merged.back() <= kSeamMerge) continue;
        merged.push_back(t);
      }
      ts = std::move(merged);
      first_[std::size_t(k) + 1] = first_[std::size_t(k)] + 1 + int(ts.size());
    }
  }

  /// Places where edges meet the seam closer than this fraction of the chord to a seam point, or
  /// to each other, are merged into one.
  static constexpr double kSeamMerge = 1e-6;

  int size() const { return first_.back(); }
  /// The index in the conforming seam of a place.
  int indexOf(const exact::SeamPlace& place) const {
    const std::vector<double>& ts = crossings_[std::size_t(place.chord)];
    if (place.t <= kSeamMerge) return first_[std::size_t(place.chord)];
    if (place.t >= 1.0 - kSeamMerge) return first_[std::size_t(place.chord) + 1] % size();
    const auto nearest = std::min_element(ts.begin(), ts.end(), [&](double u, double v) {
      return std::abs(u - place.t) < std::abs(v - place.t);
    });
    return first_[std::size_t(place.chord)] + 1 + int(nearest - ts.begin());
  }
  /// The place of index i.
  exact::SeamPlace place(int i) const {
    const int k = int(std::upper_bound(first_.begin(), first_.end(), i) - first_.begin()) - 1;
    const int offset = i - first_[std::size_t(k)];
    return {k, offset == 0 ? 0.0 : crossings_[std::size_t(k)][std::size_t(offset - 1)]};
  }

 private:
  std::vector<std::vector<double>> crossings_;
  std::vector<int> first_{0};
};

}  // namespace

namespace {

// The lines a piece's mesh follows: each run of a followed body edge through the piece, from one
// row of the conforming seam to another, with points about `edge` apart; and each line's fold.
struct PieceLines {
  std::vector<InteriorLine> lines;
  std::vector<double> folds;                  ///< radians
  std::vector<std::pair<int, int>> places;    ///< each line's ends in the conforming seam
  std::vector<const exact::BodyEdge*> edges;  ///< the body edge each line follows
  std::vector<std::pair<double, double>>
      along;                    ///< how far along its edge each line's ends are, mm
  std::vector<double> spacing;  ///< how far apart each line's points are to be, mm
};

// Whether the run between seam places i and j cuts off places of the seam (one or more, between
// i and j going one way round) that all lie within kSliver of the run's length from it: the face
// between them is a sliver whose corners at i and j are under 1e-3 rad, which no mesh draws
// without triangles that thin. The fold is not followed: the triangles beside the seam there
// cross it within that sliver (an edge of length l across a fold of angle theta at distance d
// from its end is shorter by about theta^2 d / (2 l) of l). A body edge along a straight stretch
// of the seam is such a run wherever the outline is drawn to a precision: rounded, the stretch's
// points lie a little off the edge; so is one along a nearly straight stretch (the flat side of a
// superellipse).
constexpr double kSliver = 1e-3;

bool hugsTheSeam(const Points2& outline, const std::vector<int>& rowOf, int i, int j) {
  const int N = int(rowOf.size());
  for (const auto& [from, to] : {std::pair{i, j}, std::pair{j, i}}) {
    const Eigen::Vector2d p = outline.row(rowOf[std::size_t(from)]),
                          q = outline.row(rowOf[std::size_t(to)]);
    const Eigen::Vector2d u = (q - p).normalized();
    const double off = kSliver * (q - p).norm();
    bool within = (from + 1) % N != to;
    for (int m = (from + 1) % N; within && m != to; m = (m + 1) % N) {
      const Eigen::Vector2d d = outline.row(rowOf[std::size_t(m)]).transpose() - p;
      within = std::abs(u.x() * d.y() - u.y() * d.x()) < off && u.dot(d) > 0.0 &&
               u.dot(d) < (q - p).norm();
    }
    if (within) return true;
  }
  return false;
}

// Lines that leave a place of the seam within kSliver (radians) of another line or of the seam
// there bound a face of the body whose corner there is under the validator's degenerate angle:
// a needle (two body edges from one seam point to neighbouring points of a straight side nearly
// in line with them) that no mesh draws without a triangle that thin. Of the two, the gentler
// fold is not followed (a line beside the seam is not followed): its needle is narrower than
// kSliver times its length, and the triangles across it read the fold as those across a fold
// that hugs the seam do.
void withoutNeedles(PieceLines& out, const Points2& outline) {
  const int N = int(outline.rows());
  std::vector<bool> kept(out.lines.size(), true);
  for (bool dropped = true; dropped;) {
    dropped = false;
    std::vector<std::vector<std::pair<double, int>>> at(static_cast<std::size_t>(N));
    for (std::size_t l = 0; l < out.lines.size(); ++l)
      if (kept[l])
        for (const auto& [v, w] : {std::pair{out.lines[l].from, out.lines[l].to},
                                   std::pair{out.lines[l].to, out.lines[l].from}}) {
          const Eigen::Vector2d p = outline.row(v), next = outline.row((v + 1) % N);
          const Eigen::Vector2d u = next - p, d = outline.row(w).transpose() - p;
          at[std::size_t(v)].emplace_back(std::atan2(u.x() * d.y() - u.y() * d.x(), u.dot(d)),
                                          int(l));
        }
    for (int v = 0; v < N && !dropped; ++v) {
      std::vector<std::pair<double, int>>& here = at[std::size_t(v)];
      if (here.empty()) continue;
      const Eigen::Vector2d p = outline.row(v), next = outline.row((v + 1) % N),
                            prev = outline.row((v + N - 1) % N);
      const Eigen::Vector2d u = next - p, d = prev - p;
      here.emplace_back(0.0, -1);  // the seam both ways
      here.emplace_back(std::atan2(u.x() * d.y() - u.y() * d.x(), u.dot(d)), -1);
      std::sort(here.begin(), here.end());
      for (std::size_t k = 0; k + 1 < here.size() && !dropped; ++k) {
        if (here[k + 1].first - here[k].first >= kSliver) continue;
        const int a = here[k].second, b = here[k + 1].second;
        if (a < 0 && b < 0) continue;
        const int gentler = a < 0                                                   ? b
                            : b < 0                                                 ? a
                            : out.folds[std::size_t(a)] < out.folds[std::size_t(b)] ? a
                                                                                    : b;
        kept[std::size_t(gentler)] = false;
        dropped = true;
      }
    }
  }
  PieceLines left;
  for (std::size_t l = 0; l < out.lines.size(); ++l) {
    if (!kept[l]) continue;
    left.lines.push_back(std::move(out.lines[l]));
    left.folds.push_back(out.folds[l]);
    left.places.push_back(out.places[l]);
    left.edges.push_back(out.edges[l]);
    left.along.push_back(out.along[l]);
    left.spacing.push_back(out.spacing[l]);
  }
  out = std::move(left);
}

// A seam place turning by less than this (radians) makes, with its two neighbours, a triangle
// whose smallest angle is about half that: within a factor of 5 of the validator's degenerate
// angle (1e-3).
constexpr double kNearlyStraight = 1e-2;

// How far apart the points inside the run from place i to place j are, mm: `edge`, or, where the
// run cuts off a nearly straight stretch of seam (a place in it turning by under kNearlyStraight:
// a fold near the flattest point of a superellipse, or across the rim of a disc glued to a
// square's corner at n = 1000) lying closer to it than half of `edge` (no lattice point of the
// mesher fits between them), that stretch's distance from the run but no less than its places'
// spacing. With the run's two ends alone the mesher could only join the stretch's places to each
// other, in triangles of three nearly collinear places whose angles go to zero where the seam is
// straightest; with points across from them, the smallest angle there is the run's angle with
// the seam at its ends (kept above kSliver by withoutNeedles).
double runSpacing(const Points2& outline, const std::vector<int>& rowOf, int i, int j,
                  double edge) {
  const int N = int(rowOf.size());
  const auto at = [&](int m) -> Eigen::Vector2d { return outline.row(rowOf[std::size_t(m)]); };
  const Eigen::Vector2d p = at(i), u = (at(j) - p).normalized();
  double spacing = edge;
  for (const auto& [from, to] : {std::pair{i, j}, std::pair{j, i}}) {
    double farthest = 0.0, seamLength = (at((from + 1) % N) - at(from)).norm();
    double leastTurn = kPi;
    int places = 0;
    for (int m = (from + 1) % N; m != to; m = (m + 1) % N) {
      const Eigen::Vector2d d = at(m) - p, back = at(m) - at((m + N - 1) % N),
                            ahead = at((m + 1) % N) - at(m);
      farthest = std::max(farthest, std::abs(u.x() * d.y() - u.y() * d.x()));
      leastTurn = std::min(
          leastTurn,
          std::abs(std::atan2(back.x() * ahead.y() - back.y() * ahead.x(), back.dot(ahead))));
      seamLength += ahead.norm();
      ++places;
    }
    if (places == 0 || leastTurn >= kNearlyStraight) continue;
    const double across = std::max(farthest, seamLength / double(places + 1));
    if (across < 0.5 * edge) spacing = std::min(spacing, across);
  }
  return spacing;
}

// Two lines leaving one place of the seam a small angle alpha apart, with points s1 < s2 apart,
// make a triangle there whose smallest angle is about alpha s1 / (s2 - s1): the point s1 along the
// one, joined to the point s2 along the other (seen: 8.6e-4 rad, lines 0.006 rad apart with points
// 0.8 and 5.6 mm out, at a fold beside the flat side of a superellipse at n = 1000). Where that
// angle would be under kNearlyStraight, both lines take the smaller spacing, so that their points
// pair off across the wedge and its triangles' smallest angle is about alpha.
void evenWedges(PieceLines& out, const Points2& outline) {
  // Each place's lines, with the far end of each.
  std::map<int, std::vector<std::pair<std::size_t, int>>> at;
  for (std::size_t l = 0; l < out.lines.size(); ++l) {
    at[out.lines[l].from].emplace_back(l, out.lines[l].to);
    at[out.lines[l].to].emplace_back(l, out.lines[l].from);
  }
  for (bool evened = true; evened;) {
    evened = false;
    for (const auto& [place, lines] : at)
      for (std::size_t i = 0; i < lines.size(); ++i)
        for (std::size_t j = i + 1; j < lines.size(); ++j) {
          const auto [a, endA] = lines[i];
          const auto [b, endB] = lines[j];
          const Eigen::Vector2d p = outline.row(place), u = outline.row(endA).transpose() - p,
                                v = outline.row(endB).transpose() - p;
          const double alpha = std::abs(std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)));
          const double near = std::min(out.spacing[a], out.spacing[b]),
                       far = std::max(out.spacing[a], out.spacing[b]);
          if (!(near < far) || alpha * near >= kNearlyStraight * (far - near)) continue;
          out.spacing[a] = out.spacing[b] = near;
          evened = true;
        }
  }
}

PieceLines pieceLines(const std::vector<const exact::BodyEdge*>& followed, int piece,
                      const ConformingSeam& seam, const std::vector<int>& rowOf,
                      const Points2& outline, double edge) {
  PieceLines out;
  const int N = seam.size();
  std::map<std::pair<int, int>, std::size_t> seen;
  for (const exact::BodyEdge* body : followed)
    for (const exact::EdgeRun& run : body->runs) {
      if (run.piece != piece) continue;
      const int i = seam.indexOf(run.from), j = seam.indexOf(run.to);
      // Merged into one place, or along the seam between neighbouring places: nothing to
      // follow.
      if (i == j || (i + 1) % N == j || (j + 1) % N == i) continue;
      InteriorLine line;
      line.from = rowOf[std::size_t(i)];
      line.to = rowOf[std::size_t(j)];
      if (hugsTheSeam(outline, rowOf, i, j)) continue;
      const auto key = std::minmax(line.from, line.to);
      if (const auto it = seen.find(key); it != seen.end()) {
        out.folds[it->second] = std::max(out.folds[it->second], body->fold);
        continue;
      }
      seen[key] = out.lines.size();
      out.lines.push_back(std::move(line));
      out.folds.push_back(body->fold);
      out.places.emplace_back(i, j);
      out.edges.push_back(body);
      out.along.emplace_back(run.fromLength, run.toLength);
      out.spacing.push_back(runSpacing(outline, rowOf, i, j, edge));
    }
  withoutNeedles(out, outline);
  evenWedges(out, outline);
  for (std::size_t l = 0; l < out.lines.size(); ++l) {
    InteriorLine& line = out.lines[l];
    Points2 ends(2, 2);
    ends << outline.row(line.from), outline.row(line.to);
    const int segments = std::max(1, int(std::lround(openLength(ends) / out.spacing[l])));
    line.interior = resampleOpen(ends, segments).middleRows(1, segments - 1);
  }
  return out;
}

// The point a distance `along` from the first end of a body edge: on its straight segment in
// 3D.
Eigen::Vector3d onEdge(const exact::ExactGluing& g, const exact::BodyEdge& edge, double along) {
  const Eigen::Vector3d p = g.vertices.row(g.vertexOfSeam[std::size_t(edge.from)]).transpose();
  const Eigen::Vector3d q = g.vertices.row(g.vertexOfSeam[std::size_t(edge.to)]).transpose();
  return p + (along / edge.length) * (q - p);
}

// Where each place of the conforming seam is on the body, where the body tells it: its cone
// points, and the places its followed edges pass (crossings of the seam, flat seam points).
std::vector<std::optional<Eigen::Vector3d>> seamOnBody(
    const exact::ExactGluing& g, const ConformingSeam& seam,
    const std::vector<const exact::BodyEdge*>& followed) {
  std::vector<std::optional<Eigen::Vector3d>> out(std::size_t(seam.size()));
  for (int i = 0; i < seam.size(); ++i) {
    const exact::SeamPlace place = seam.place(i);
    if (place.isSeamPoint() && g.vertexOfSeam[std::size_t(place.chord)] >= 0)
      out[std::size_t(i)] = g.vertices.row(g.vertexOfSeam[std::size_t(place.chord)]).transpose();
  }
  for (const exact::BodyEdge* edge : followed)
    for (const exact::EdgeRun& run : edge->runs)
      for (const auto& [place, along] :
           {std::pair{run.from, run.fromLength}, std::pair{run.to, run.toLength}}) {
        std::optional<Eigen::Vector3d>& at = out[std::size_t(seam.indexOf(place))];
        if (!at) at = onEdge(g, *edge, along);
      }
  return out;
}

}  // namespace

double foundCreaseRadians(long n) { return std::max(20.0, 6.0 * 360.0 / double(n)) * kDegree; }

Result<DForm> exactDForm(exact::SeamPolygons polygons, double targetEdge,
                         const std::string paths[2], ModelUsed& used) {
  const Eigen::Index n = polygons.a.rows();
  used.chordMoveMm = exact::equalizeChords(polygons);
  Result<exact::ExactGluing> glued = exact::glue(polygons);
  if (!glued.isOk()) return glued.status();
  exact::ExactGluing& g = glued.value();
  used.doublyCovered = g.doublyCovered;
  used.precisionMm = exact::seamPrecision(g.seam);
  if (g.doublyCovered) {
    used.pouch = g.pouch == exact::ExactGluing::Pouch::Thin ? "thin" : "congruent";
    used.flatDeviationMm = g.flatDeviation;
    used.thicknessMm = g.thickness;
  }
  used.conePoints = g.doublyCovered ? 0 : g.triangulation.vertexCount();
  used.newtonSteps = g.embedding.iterations;
  used.maxCurvature = g.embedding.maxCurvature;
  Result<std::vector<exact::BodyEdge>> traced = exact::traceBodyEdges(g);
  if (!traced.isOk()) return traced.status();
  exact::fitBodyToEdges(g, traced.value());
  std::vector<const exact::BodyEdge*> followed;
  for (const exact::BodyEdge& edge : traced.value())
    if (edge.fold >= kFollowedFold && !edge.runs.empty()) followed.push_back(&edge);
  const ConformingSeam seam(int(n), followed);
  const int N = seam.size();
  const std::vector<std::optional<Eigen::Vector3d>> onBody =
      g.doublyCovered ? std::vector<std::optional<Eigen::Vector3d>>{}
                      : seamOnBody(g, seam, followed);
  const double creaseAngle = foundCreaseRadians(n);
  DForm model;
  Piece* pieces[2] = {&model.a, &model.b};
  std::vector<std::optional<Eigen::Vector3d>> known[2];
  std::vector<std::vector<int>> walls[2];
  for (int p = 0; p < 2; ++p) {
    // The mesher takes the outline counter-clockwise: A's seam order, B's reversed.
    std::vector<int> rowOf(static_cast<std::size_t>(N));
    Points2 outline(N, 2);
    for (int k = 0; k < N; ++k) {
      rowOf[std::size_t(k)] = p == 0 ? k : (N - k) % N;
      outline.row(rowOf[std::size_t(k)]) = exact::seamPlacePoint(g, p, seam.place(k)).transpose();
    }
    const PieceLines lines = pieceLines(followed, p, seam, rowOf, outline, targetEdge);
    TriangulateOptions meshOptions;
    meshOptions.targetEdgeLength = targetEdge;
    Result<FlatMesh> mesh = triangulateDomain(outline, {}, meshOptions, lines.lines);
    if (!mesh.isOk())
      return Status(ErrorCode::SolveFailed, paths[p] + ": the body's folds could not be meshed: " +
                                                mesh.status().message());
    Piece& out = *pieces[p];
    out.name = p == 0 ? "A" : "B";
    out.flat = std::move(mesh.value().V);
    out.F = std::move(mesh.value().F);
    out.seam = rowOf;
    for (std::size_t l = 0; l < lines.lines.size(); ++l) {
      const InteriorLine& line = lines.lines[l];
      const auto seamPointAt = [&](int i) {
        return seam.place(i).isSeamPoint() ? seam.place(i).chord : -1;
      };
      used.folds.push_back({p, line.from, line.to, seamPointAt(lines.places[l].first),
                            seamPointAt(lines.places[l].second), lines.edges[l]->from,
                            lines.edges[l]->to, lines.folds[l],
                            lines.folds[l] > creaseAngle ? int(out.creases.size()) : -1});
      if (lines.folds[l] <= creaseAngle) continue;
      used.creases.push_back({p, int(out.creases.size()), lines.folds[l] / kDegree,
                              (outline.row(line.from) - outline.row(line.to)).norm()});
      out.creases.push_back(mesh.value().lines[l]);
    }
    // Congruent pieces fold flat onto each other: the body is the doubly covered piece.
    if (g.doublyCovered) {
      out.shape = exact::placeOnBody(g, p, out.flat);
      continue;
    }
    known[p].resize(std::size_t(out.flat.rows()));
    for (int k = 0; k < N; ++k)
      known[p][std::size_t(rowOf[std::size_t(k)])] = onBody[std::size_t(k)];
    for (std::size_t l = 0; l < lines.lines.size(); ++l) {
      const std::vector<int>& line = mesh.value().lines[l];
      const Eigen::Vector2d from = out.flat.row(line.front()), to = out.flat.row(line.back());
      const auto [fromAlong, toAlong] = lines.along[l];
      for (std::size_t k = 1; k + 1 < line.size(); ++k) {
        const double share = (out.flat.row(line[k]).transpose() - from).norm() / (to - from).norm();
        known[p][std::size_t(line[k])] =
            onEdge(g, *lines.edges[l], fromAlong + share * (toAlong - fromAlong));
      }
    }
    walls[p] = mesh.value().lines;
    walls[p].push_back(mesh.value().boundary);
    walls[p].back().push_back(mesh.value().boundary.front());
  }
  if (!g.doublyCovered && !placeBothOnFaces(g, pieces, known, walls))
    return Status(ErrorCode::SolveFailed, "a mesh vertex could not be placed on the exact D-Form");
  // Seam partners are one point of the body; placed from either side they differ by rounding.
  for (std::size_t k = 0; k < model.a.seam.size(); ++k)
    model.b.shape.row(model.b.seam[k]) = model.a.shape.row(model.a.seam[k]);
  // A longer edge means a vertex was placed off its spot, and the result is not used (auto then
  // makes the shape with the paper model). 1e-4: the seam polygons were moved by up to ~1e-6 of
  // an edge to equal chords, and placing a vertex rounds; a misplaced vertex is off by a good
  // part of an edge (seen: 174 %).
  for (int p = 0; p < 2; ++p)
    if (const double longest = longestStretch(*pieces[p]); longest > 1e-4)
      return Status(ErrorCode::SolveFailed,
                    paths[p] +
                        ": a mesh vertex was placed off the exact D-Form (an edge came "
                        "out longer than it is flat, by " +
                        std::to_string(100 * longest) + " %)");
  return model;
}

}  // namespace dform
