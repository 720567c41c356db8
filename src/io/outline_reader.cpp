// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/io/outline_reader.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>

#include "crease_lines.h"
#include "dform/core/file_hash.h"
#include "dform/core/input_file.h"
#include "dform/core/polyline.h"
#include "io_util.h"
#include "json_util.h"
#include "svg_outline.h"

namespace dform {
namespace {

using io_detail::DrawnLine;
using io_detail::fmt;
using io_detail::fmtPoint;

/// An outline whose area is below this fraction of its squared diagonal, or whose points spread
/// across their main direction by less than sqrt(this) of their spread along it, is a line drawn
/// back and forth, not a piece. Relative, so it does not depend on the drawing's scale; the square
/// root keeps it above the eigen solver's rounding.
constexpr double kZeroAreaFraction = 1e-12;

using io_detail::kMinShapeSizeMm;

/// Beyond this many outlines the nesting analysis (pairwise) is not worth doing: no piece has it.
constexpr std::size_t kMaxLoops = 10000;

using Vec2 = Eigen::Vector2d;

struct Box {
  Vec2 lo, hi;
  bool overlaps(const Box& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

Box boundingBox(const Points2& P) {
  return {P.colwise().minCoeff().transpose(), P.colwise().maxCoeff().transpose()};
}

/// Where two closed polylines touch or cross, if they do.
std::optional<Vec2> crossingPoint(const Points2& A, const Points2& B) {
  const auto edges = findCrossing(A, B);
  if (!edges) return std::nullopt;
  const auto [i, j] = *edges;
  return segmentsMeetingPoint(A.row(i), A.row((i + 1) % A.rows()), B.row(j),
                              B.row((j + 1) % B.rows()));
}

/// Cleans one loop (range check, duplicates removed) and checks it is a simple polygon of
/// positive area; returns it counter-clockwise.
Result<Points2> cleanLoop(const std::string& path, const DrawnLine& loop,
                          const OutlineReadOptions& options) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": " + loop.label + " " + what};
  };
  if (const auto bad = io_detail::findBadCoordinate(loop.points, options.maxCoordinate))
    return fail("has a coordinate that " +
                io_detail::describeBadCoordinate(loop.points(bad->first, bad->second),
                                                 options.maxCoordinate));
  Points2 P = io_detail::dropRepeatedPoints(loop.points, true);
  if (P.rows() < 3) return fail("has fewer than 3 distinct points");
  if (const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
      size < kMinShapeSizeMm)
    return fail("is " + fmt(size) + " mm across; outlines and holes must be at least " +
                fmt(kMinShapeSizeMm) + " mm across (the diagonal of their bounding box)");
  // Collinear points first (their edges overlap, which is not what "crossing" should mean):
  // the spread across the principal direction is nil.
  const Points2 centred = P.rowwise() - P.colwise().mean();
  const Eigen::Vector2d spread =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(centred.transpose() * centred).eigenvalues();
  if (spread(0) <= kZeroAreaFraction * spread(1)) return fail("has zero area");
  if (const auto hit = findSelfIntersection(P)) {
    const auto [e, f] = *hit;
    const Eigen::Index n = P.rows();
    const Vec2 where =
        segmentsMeetingPoint(P.row(e), P.row((e + 1) % n), P.row(f), P.row((f + 1) % n));
    return fail("crosses itself near " + fmtPoint(where.transpose()) + " mm");
  }
  const double diagonal = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  const double area = signedArea(P);
  if (std::abs(area) <= kZeroAreaFraction * diagonal * diagonal) return fail("has zero area");
  // Turned counter-clockwise about its first point: start fractions are measured from the point
  // the path was drawn from, whichever way it was drawn.
  if (area < 0.0)
    P.bottomRows(P.rows() - 1) = P.bottomRows(P.rows() - 1).colwise().reverse().eval();
  return P;
}

/// Turns closed loops into one piece: the outermost loop is the outline, loops directly inside it
/// are holes; loops side by side, crossing, or islands inside holes are errors.
Result<Shape2> assembleShape(const std::string& path, const std::vector<DrawnLine>& loops,
                             const OutlineReadOptions& options) {
  if (loops.empty()) return Status{ErrorCode::InputInvalid, path + ": no closed outline found"};
  if (loops.size() > kMaxLoops)
    return Status{ErrorCode::InputInvalid, path + ": " + std::to_string(loops.size()) +
                                               " closed outlines; expected one piece"};
  std::vector<Points2> clean;
  for (const DrawnLine& loop : loops) {
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
      if (const auto where = crossingPoint(clean[i], clean[j]))
        return Status{ErrorCode::InputInvalid, path + ": " + loops[i].label + " and " +
                                                   loops[j].label + " touch or cross near " +
                                                   fmtPoint(where->transpose()) + " mm"};
      if (insidePolygon(clean[j], clean[i].row(0).transpose())) depth[i] = depth[j] + 1;
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

/// Reads a JSON list of 2D points scaled to mm, as an open line.
Result<Points2> jsonLine(const std::string& path, const nlohmann::json& list,
                         const std::string& what, double scale) {
  Result<Eigen::MatrixXd> rows = io_detail::jsonPointList(path, list, what, 2, scale);
  if (!rows.isOk()) return rows.status();
  return Points2(rows.value());
}

/// Reads a JSON outline list scaled to mm; a repeated closing point is dropped.
Result<Points2> jsonLoop(const std::string& path, const nlohmann::json& list,
                         const std::string& what, double scale) {
  Result<Points2> P = jsonLine(path, list, what, scale);
  if (P.isOk() && P.value().rows() > 1 && P.value().row(0) == P.value().row(P.value().rows() - 1))
    P.value().conservativeResize(P.value().rows() - 1, 2);
  return P;
}

/// {"points": [[x, y], ...], "units": "mm", "holes": [[[x, y], ...], ...],
///  "creases": [[[x, y], ...], ...]} or a bare point list.
Result<io_detail::Drawing> readJsonDrawing(const std::string& path, const std::string& text,
                                           std::size_t maxPoints) {
  const Result<nlohmann::json> parsed = io_detail::parseJson(path, text, maxPoints, 2);
  if (!parsed.isOk()) return parsed.status();
  const nlohmann::json& doc = parsed.value();
  if (doc.is_object() && !doc.contains("points"))
    return Status{ErrorCode::InputUnreadable, path + ": JSON object has no \"points\" list"};
  if (Status s = io_detail::onlyKnownKeys(path, doc, {"points", "units", "holes", "creases"});
      !s.isOk())
    return s;
  const Result<double> scale = io_detail::jsonUnitScale(path, doc);
  if (!scale.isOk()) return scale.status();
  io_detail::Drawing drawing;
  Result<Points2> outline =
      jsonLoop(path, doc.is_object() ? doc["points"] : doc, "the outline", scale.value());
  if (!outline.isOk()) return outline.status();
  drawing.loops.push_back({std::move(outline).value(), "the outline"});
  for (const char* key : {"holes", "creases"}) {
    if (!doc.is_object() || !doc.contains(key)) continue;
    const nlohmann::json& lists = doc[key];
    if (!lists.is_array())
      return Status{ErrorCode::InputUnreadable,
                    path + ": \"" + key + "\" is not a list of point lists"};
    const bool holes = std::string(key) == "holes";
    for (std::size_t k = 0; k < lists.size(); ++k) {
      const std::string name = (holes ? "hole " : "crease ") + std::to_string(k + 1);
      Result<Points2> P = holes ? jsonLoop(path, lists[k], name, scale.value())
                                : jsonLine(path, lists[k], name, scale.value());
      if (!P.isOk()) return P.status();
      // fitCreases names a crease "crease <label>".
      (holes ? drawing.loops : drawing.creases)
          .push_back({std::move(P).value(), holes ? name : std::to_string(k + 1)});
    }
  }
  return drawing;
}

}  // namespace

Result<Shape2> parseOutline(std::string text, const std::string& source,
                            const OutlineReadOptions& options) {
  if (!(options.flattenTolerance > 0.0) || !(options.maxCoordinate > 0.0) ||
      !(options.closeTolerance >= 0.0))
    return Status{ErrorCode::Usage, source +
                                        ": the flatten tolerance and coordinate limit must be "
                                        "positive, the closing tolerance not negative"};
  std::string ext = io_detail::lowerExtension(source);
  if (ext != "svg" && ext != "json") {  // sniff the content of files without a known extension
    const auto first = text.find_first_not_of(" \t\r\n\xef\xbb\xbf");
    const char c = first == std::string::npos ? '\0' : text[first];
    ext = c == '<' ? "svg" : (c == '{' || c == '[') ? "json" : "";
  }
  if (ext.empty()) return Status{ErrorCode::InputUnreadable, source + ": not an SVG or JSON file"};
  Result<io_detail::Drawing> drawing =
      ext == "svg" ? io_detail::readSvgDrawing(source, std::move(text), options)
                   : readJsonDrawing(source, text, options.maxPoints);
  if (!drawing.isOk()) return drawing.status();
  Result<Shape2> shape = assembleShape(source, drawing.value().loops, options);
  if (!shape.isOk()) return shape;
  if (Status s = io_detail::fitCreases(source, drawing.value().creases, options, shape.value());
      !s.isOk())
    return s;
  return shape;
}

Result<Shape2> checkOutline(const Shape2& shape, const std::string& name,
                            const OutlineReadOptions& options) {
  std::vector<DrawnLine> loops{{shape.outer.points, "the outline"}};
  for (std::size_t k = 0; k < shape.holes.size(); ++k)
    loops.push_back({shape.holes[k].points, "hole " + std::to_string(k + 1)});
  Result<Shape2> checked = assembleShape(name, loops, options);
  if (!checked.isOk()) return checked;
  for (std::size_t k = 0; k < shape.creases.size(); ++k)
    checked.value().creases.push_back({shape.creases[k].points, shape.creases[k].label.empty()
                                                                    ? std::to_string(k + 1)
                                                                    : shape.creases[k].label});
  if (Status s = io_detail::checkFittedCreases(name, checked.value(), options); !s.isOk()) return s;
  checked.value().outer.source = shape.outer.source;
  for (Outline2& hole : checked.value().holes) hole.source = shape.outer.source;
  checked.value().sha256 = shape.sha256;
  return checked;
}

Result<Shape2> readOutline(const std::string& path, const OutlineReadOptions& options) {
  Result<std::string> text = readInputFile(path);
  if (!text.isOk()) return text.status();
  std::string sha256 = sha256Hex(text.value());
  Result<Shape2> shape = parseOutline(std::move(text).value(), inputName(path), options);
  if (shape.isOk()) shape.value().sha256 = std::move(sha256);
  return shape;
}

}  // namespace dform
