#include "io/outline_reader.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/input_file.h"
#include "core/polyline.h"
#include "io/io_util.h"
#include "io/json_util.h"
#include "io/svg_outline.h"

namespace dform {
namespace {

using io_detail::ClosedLoop;
using io_detail::fmt;
using io_detail::fmtPoint;

/// Consecutive points closer than this are one point: a nanometre is far below any cutting
/// precision and far above double rounding of coordinates up to maxCoordinate.
constexpr double kSamePointMm = 1e-9;

/// An outline whose area is below this fraction of its squared diagonal, or whose points spread
/// across their main direction by less than sqrt(this) of their spread along it, is a line drawn
/// back and forth, not a piece. Relative, so it does not depend on the drawing's scale; the square
/// root keeps it above the eigen solver's rounding.
constexpr double kZeroAreaFraction = 1e-12;

/// Beyond this many outlines the nesting analysis (pairwise) is not worth doing: no piece has it.
constexpr std::size_t kMaxLoops = 10000;

using Vec2 = Eigen::Vector2d;

/// Where segments [a, b] and [c, d], known to touch or cross, meet (an end point if they touch).
Vec2 meetingPoint(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 r = b - a, s = d - c;
  const double denom = r.x() * s.y() - r.y() * s.x();
  if (denom != 0.0) {
    const double t = ((c - a).x() * s.y() - (c - a).y() * s.x()) / denom;
    if (t >= 0.0 && t <= 1.0) return a + t * r;
  }
  // Parallel (collinear overlap) or touching: report an end of one lying on the other.
  for (const Vec2& p : {a, b})
    if (segmentsIntersect(p, p, c, d)) return p;
  for (const Vec2& p : {c, d})
    if (segmentsIntersect(p, p, a, b)) return p;
  return a;
}

struct Box {
  Vec2 lo, hi;
  bool overlaps(const Box& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

Box boundingBox(const Points2& P) {
  return {P.colwise().minCoeff().transpose(), P.colwise().maxCoeff().transpose()};
}

/// Where two closed polylines touch or cross, if they do. Sweep over x as in findSelfIntersection.
std::optional<Vec2> findCrossing(const Points2& A, const Points2& B) {
  struct Edge {
    const Points2* P;
    Eigen::Index i;
    double minX, maxX;
  };
  std::vector<Edge> edges;
  for (const Points2* P : {&A, &B})
    for (Eigen::Index i = 0; i < P->rows(); ++i) {
      const double x0 = (*P)(i, 0), x1 = (*P)((i + 1) % P->rows(), 0);
      edges.push_back({P, i, std::min(x0, x1), std::max(x0, x1)});
    }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& e, const Edge& f) { return e.minX < f.minX; });
  auto ends = [](const Edge& e) {
    return std::make_pair(Vec2(e.P->row(e.i)), Vec2(e.P->row((e.i + 1) % e.P->rows())));
  };
  for (std::size_t k = 0; k < edges.size(); ++k)
    for (std::size_t m = k + 1; m < edges.size() && edges[m].minX <= edges[k].maxX; ++m) {
      if (edges[m].P == edges[k].P) continue;
      const auto [a, b] = ends(edges[k]);
      const auto [c, d] = ends(edges[m]);
      if (segmentsIntersect(a, b, c, d)) return meetingPoint(a, b, c, d);
    }
  return std::nullopt;
}

/// Even-odd ray casting; only used for points known not to lie on the polygon's boundary.
bool insidePolygon(const Vec2& q, const Points2& P) {
  bool inside = false;
  for (Eigen::Index i = 0, j = P.rows() - 1; i < P.rows(); j = i++) {
    const double yi = P(i, 1), yj = P(j, 1);
    if ((yi > q.y()) != (yj > q.y()) &&
        q.x() < (P(j, 0) - P(i, 0)) * (q.y() - yi) / (yj - yi) + P(i, 0))
      inside = !inside;
  }
  return inside;
}

/// Cleans one loop (range check, duplicates removed) and checks it is a simple polygon of
/// positive area; returns it counter-clockwise.
Result<Points2> cleanLoop(const std::string& path, const ClosedLoop& loop,
                          const OutlineReadOptions& options) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": " + loop.label + " " + what};
  };
  if (const auto bad = io_detail::findBadCoordinate(loop.points, options.maxCoordinate))
    return fail("has a coordinate that " +
                io_detail::describeBadCoordinate(loop.points(bad->first, bad->second),
                                                 options.maxCoordinate));
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < loop.points.rows(); ++i)
    if (keep.empty() || (loop.points.row(i) - loop.points.row(keep.back())).norm() > kSamePointMm)
      keep.push_back(i);
  while (keep.size() > 1 &&
         (loop.points.row(keep.back()) - loop.points.row(keep.front())).norm() <= kSamePointMm)
    keep.pop_back();
  Points2 P(Eigen::Index(keep.size()), 2);
  for (std::size_t k = 0; k < keep.size(); ++k) P.row(Eigen::Index(k)) = loop.points.row(keep[k]);
  if (P.rows() < 3) return fail("has fewer than 3 distinct points");
  // Collinear points first (their edges overlap, which is not what "crossing" should mean):
  // the spread across the principal direction is nil.
  const Points2 centred = P.rowwise() - P.colwise().mean();
  const Eigen::Vector2d spread =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(centred.transpose() * centred).eigenvalues();
  if (spread(0) <= kZeroAreaFraction * spread(1)) return fail("has zero area");
  if (const auto hit = findSelfIntersection(P)) {
    const auto [e, f] = *hit;
    const Eigen::Index n = P.rows();
    const Vec2 where = meetingPoint(P.row(e), P.row((e + 1) % n), P.row(f), P.row((f + 1) % n));
    return fail("crosses itself near " + fmtPoint(where.transpose()) + " mm");
  }
  const double diagonal = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  const double area = signedArea(P);
  if (std::abs(area) <= kZeroAreaFraction * diagonal * diagonal) return fail("has zero area");
  if (area < 0.0) P = P.colwise().reverse().eval();
  return P;
}

/// Turns closed loops into one piece: the outermost loop is the outline, loops directly inside it
/// are holes; loops side by side, crossing, or islands inside holes are errors.
Result<Shape2> assembleShape(const std::string& path, const std::vector<ClosedLoop>& loops,
                             const OutlineReadOptions& options) {
  if (loops.empty()) return Status{ErrorCode::InputInvalid, path + ": no closed outline found"};
  if (loops.size() > kMaxLoops)
    return Status{ErrorCode::InputInvalid, path + ": " + std::to_string(loops.size()) +
                                               " closed outlines; expected one piece"};
  std::vector<Points2> clean;
  for (const ClosedLoop& loop : loops) {
    Result<Points2> P = cleanLoop(path, loop, options);
    if (!P.isOk()) return P.status();
    clean.push_back(std::move(P).value());
  }
  std::vector<double> areas;
  std::vector<Box> boxes;
  for (const Points2& P : clean) {
    areas.push_back(signedArea(P));
    boxes.push_back(boundingBox(P));
  }
  std::vector<std::size_t> order(clean.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return areas[a] > areas[b]; });

  // Depth of each loop in the containment tree; larger loops come first, so the last container
  // found is the innermost one.
  std::vector<int> depth(clean.size(), 0);
  int pieces = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    for (std::size_t m = 0; m < k; ++m) {
      const std::size_t j = order[m];
      if (!boxes[i].overlaps(boxes[j])) continue;
      if (const auto where = findCrossing(clean[i], clean[j]))
        return Status{ErrorCode::InputInvalid, path + ": " + loops[i].label + " and " +
                                                   loops[j].label + " touch or cross near " +
                                                   fmtPoint(where->transpose()) + " mm"};
      if (insidePolygon(clean[i].row(0).transpose(), clean[j])) depth[i] = depth[j] + 1;
    }
    pieces += depth[i] % 2 == 0;
  }
  if (pieces > 1)
    return Status{ErrorCode::InputInvalid,
                  path + ": " + std::to_string(pieces) + " separate outlines; expected one piece"};
  Shape2 shape;
  for (std::size_t i : order) {
    Outline2 outline{std::move(clean[i]), path};
    if (depth[i] == 0)
      shape.outer = std::move(outline);
    else
      shape.holes.push_back(std::move(outline));
  }
  return shape;
}

// ---- JSON -------------------------------------------------------------------------------------

/// Reads a JSON outline list scaled to mm; a repeated closing point is dropped.
Result<Points2> jsonLoop(const std::string& path, const nlohmann::json& list,
                         const std::string& what, double scale) {
  Result<Eigen::MatrixXd> rows = io_detail::jsonPointList(path, list, what, 2, scale);
  if (!rows.isOk()) return rows.status();
  Points2 P = rows.value();
  if (P.rows() > 1 && P.row(0) == P.row(P.rows() - 1)) P.conservativeResize(P.rows() - 1, 2);
  return P;
}

/// {"points": [[x, y], ...], "units": "mm", "holes": [[[x, y], ...], ...]} or a bare point list.
Result<std::vector<ClosedLoop>> readJsonLoops(const std::string& path, const std::string& text,
                                              std::size_t maxPoints) {
  const Result<nlohmann::json> parsed = io_detail::parseJson(path, text, maxPoints);
  if (!parsed.isOk()) return parsed.status();
  const nlohmann::json& doc = parsed.value();
  if (doc.is_object() && !doc.contains("points"))
    return Status{ErrorCode::InputUnreadable, path + ": JSON object has no \"points\" list"};
  const Result<double> scale = io_detail::jsonUnitScale(path, doc);
  if (!scale.isOk()) return scale.status();
  std::vector<std::pair<const nlohmann::json*, std::string>> lists = {
      {doc.is_object() ? &doc["points"] : &doc, "the outline"}};
  if (doc.is_object() && doc.contains("holes")) {
    const nlohmann::json& holes = doc["holes"];
    if (!holes.is_array())
      return Status{ErrorCode::InputUnreadable, path + ": \"holes\" is not a list of point lists"};
    for (std::size_t h = 0; h < holes.size(); ++h)
      lists.emplace_back(&holes[h], "hole " + std::to_string(h + 1));
  }
  std::vector<ClosedLoop> loops;
  std::size_t points = 0;
  for (const auto& [list, name] : lists) {
    Result<Points2> P = jsonLoop(path, *list, name, scale.value());
    if (!P.isOk()) return P.status();
    points += std::size_t(P.value().rows());
    if (points > maxPoints) return io_detail::tooManyPoints(path, "the outlines have", maxPoints);
    loops.push_back({std::move(P).value(), name});
  }
  return loops;
}

}  // namespace

Result<Shape2> parseShape(std::string text, const std::string& source,
                          const OutlineReadOptions& options) {
  if (!(options.flattenTolerance > 0.0) || !(options.maxCoordinate > 0.0))
    return Status{ErrorCode::Usage,
                  source + ": the flatten tolerance and coordinate limit must be positive"};
  std::string ext = io_detail::lowerExtension(source);
  if (ext != "svg" && ext != "json") {  // sniff the content of files without a known extension
    const auto first = text.find_first_not_of(" \t\r\n\xef\xbb\xbf");
    const char c = first == std::string::npos ? '\0' : text[first];
    ext = c == '<' ? "svg" : (c == '{' || c == '[') ? "json" : "";
  }
  if (ext.empty()) return Status{ErrorCode::InputUnreadable, source + ": not an SVG or JSON file"};
  Result<std::vector<ClosedLoop>> loops =
      ext == "svg" ? io_detail::readSvgLoops(source, std::move(text), options)
                   : readJsonLoops(source, text, options.maxPoints);
  if (!loops.isOk()) return loops.status();
  return assembleShape(source, loops.value(), options);
}

Result<Shape2> readShape(const std::string& path, const OutlineReadOptions& options) {
  Result<std::string> text = readInputFile(path);
  if (!text.isOk()) return text.status();
  return parseShape(std::move(text).value(), path, options);
}

}  // namespace dform
