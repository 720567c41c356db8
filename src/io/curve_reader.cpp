// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/io/curve_reader.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "dform/core/file_hash.h"
#include "dform/core/input_file.h"
#include "dform/core/polyline.h"
#include "flatten.h"
#include "io_util.h"
#include "json_util.h"
#include "obj_format.h"

namespace dform {
namespace {

using io_detail::fmt;
using io_detail::fmtPoint;
using Vec3 = Eigen::Vector3d;

/// Distinct points a seam needs: fewer cannot bound a meaningful surface (a curve through 4
/// points is at best a skew quadrilateral).
constexpr Eigen::Index kMinDistinctPoints = 5;

/// Points, and segments, closer than this fraction of the curve length count as touching: far
/// below any physical meaning, far above double rounding.
constexpr double kTouchFraction = 1e-9;

/// Distance between segments [p1, q1] and [p2, q2] (Ericson, Real-Time Collision Detection 5.1.9),
/// and the midpoint of the closest pair.
std::pair<double, Vec3> segmentDistance(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                        const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a == 0.0 && e == 0.0) {
    s = t = 0.0;
  } else if (a == 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e == 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom != 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  const Vec3 c1 = p1 + s * d1, c2 = p2 + t * d2;
  return {(c1 - c2).norm(), 0.5 * (c1 + c2)};
}

/// Where two non-adjacent segments of the closed curve come within `eps`, if they do. Sweeps
/// along the axis of largest extent so only segments overlapping there are compared.
std::optional<Vec3> findNearSelfIntersection(const Points3& P, double eps) {
  const Eigen::Index n = P.rows();
  const Eigen::Vector3d extent = P.colwise().maxCoeff() - P.colwise().minCoeff();
  Eigen::Index axis = 0;
  extent.maxCoeff(&axis);
  Eigen::MatrixXd lo(n, 3), hi(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    lo.row(i) = P.row(i).cwiseMin(P.row((i + 1) % n)).array() - eps;
    hi.row(i) = P.row(i).cwiseMax(P.row((i + 1) % n)).array() + eps;
  }
  std::vector<Eigen::Index> order(std::size_t(n), 0);
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return lo(a, axis) < lo(b, axis); });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Eigen::Index i = order[k];
    for (std::size_t m = k + 1; m < order.size() && lo(order[m], axis) <= hi(i, axis); ++m) {
      const Eigen::Index j = order[m];
      const Eigen::Index gap = std::abs(i - j);
      if (gap <= 1 || gap == n - 1) continue;  // neighbours share a point by construction
      if ((lo.row(i).array() > hi.row(j).array()).any() ||
          (lo.row(j).array() > hi.row(i).array()).any())
        continue;
      const auto [distance, where] =
          segmentDistance(P.row(i), P.row((i + 1) % n), P.row(j), P.row((j + 1) % n));
      if (distance <= eps) return where;
    }
  }
  return std::nullopt;
}

Eigen::Index countDistinct(const Points3& P) {
  std::vector<std::array<double, 3>> rows;
  for (Eigen::Index i = 0; i < P.rows(); ++i) rows.push_back({P(i, 0), P(i, 1), P(i, 2)});
  std::sort(rows.begin(), rows.end());
  return Eigen::Index(std::unique(rows.begin(), rows.end()) - rows.begin());
}

/// Checks a closed curve (no repeated closing point). `pointName(i)` names row i in messages.
template <typename PointName>
Status validateCurve(const std::string& path, const Points3& P, const CurveReadOptions& options,
                     PointName pointName) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": " + what};
  };
  if (std::size_t(P.rows()) > options.maxPoints)
    return io_detail::tooManyPoints(path, "the curve has", options.maxPoints);
  if (const auto bad = io_detail::findBadCoordinate(P, options.maxCoordinate))
    return fail(
        pointName(bad->first) + " has a coordinate that " +
        io_detail::describeBadCoordinate(P(bad->first, bad->second), options.maxCoordinate));
  if (const double size =
          P.rows() > 0 ? (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm() : 0.0;
      P.rows() > 0 && size < io_detail::kMinShapeSizeMm)
    return fail("the curve is " + fmt(size) + " mm across; seam curves must be at least " +
                fmt(io_detail::kMinShapeSizeMm) +
                " mm across (the diagonal of their bounding box)");
  if (countDistinct(P) < kMinDistinctPoints)
    return fail("the curve has fewer than " + std::to_string(kMinDistinctPoints) +
                " distinct points");
  const double eps = kTouchFraction * closedLength(P);
  const Eigen::Index n = P.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index j = (i + 1) % n;
    if ((P.row(j) - P.row(i)).norm() <= eps)
      return fail(pointName(i) + " and " + pointName(j) + " are the same point " +
                  fmtPoint(P.row(i)));
  }
  if (const auto where = findNearSelfIntersection(P, eps))
    return fail("the curve crosses or touches itself near " + fmtPoint(where->transpose()) + " mm");
  return Status::ok();
}

/// Drops a repeated closing point, or reports the curve open unless options.forceClosed.
Status closeCurve(const std::string& path, Points3& P, bool closedByIndex,
                  const CurveReadOptions& options) {
  const Eigen::Index n = P.rows();
  if (n >= 2 && (closedByIndex || P.row(0) == P.row(n - 1))) {
    P.conservativeResize(n - 1, 3);
    return Status::ok();
  }
  if (options.forceClosed || n < 2) return Status::ok();
  return Status{ErrorCode::InputInvalid, path + ": the curve is open (its end is " +
                                             fmt((P.row(n - 1) - P.row(0)).norm()) +
                                             " mm from its start; close it or read it as closed)"};
}

Result<Curve3> readObjCurve(const std::string& path, const std::string& text,
                            const CurveReadOptions& options) {
  const Result<io_detail::ObjData> parsed = io_detail::parseObj(path, text, options.maxPoints);
  if (!parsed.isOk()) return parsed.status();
  const io_detail::ObjData& obj = parsed.value();
  if (obj.lines.empty())
    return Status{
        ErrorCode::InputInvalid,
        path + (obj.faces.empty() ? ": has no polyline ('l' element)"
                                  : ": has faces but no polyline ('l' element); expected a curve")};
  if (obj.lines.size() > 1)
    return Status{ErrorCode::InputInvalid, path + ": has " + std::to_string(obj.lines.size()) +
                                               " polylines ('l' elements); expected one"};
  std::vector<int> indices = obj.lines[0].indices;
  Points3 P(Eigen::Index(indices.size()), 3);
  for (std::size_t k = 0; k < indices.size(); ++k)
    P.row(Eigen::Index(k)) = obj.vertices[std::size_t(indices[k])].transpose();
  const Status closed = closeCurve(path, P, indices.front() == indices.back(), options);
  if (!closed.isOk()) return closed;
  const Status valid = validateCurve(path, P, options, [&](Eigen::Index i) {
    return "polyline point " + std::to_string(i + 1) + " (vertex " +
           std::to_string(indices[std::size_t(i)] + 1) + ")";
  });
  if (!valid.isOk()) return valid;
  return Curve3{std::move(P), path, {}};
}

/// Closed piecewise cubic Bezier: 3k control points p0 c c p1 c c ... the last segment ends at p0.
Result<Points3> flattenClosedBezier(const std::string& path, const Eigen::MatrixXd& control,
                                    const CurveReadOptions& options) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": " + what};
  };
  const Eigen::Index count = control.rows();
  if (count < 3 || count % 3 != 0)
    return fail("\"bezier\" needs 3 control points per segment (p0 c1 c2 p1 c1 c2 ...); found " +
                std::to_string(count));
  if (const auto bad = io_detail::findBadCoordinate(control, options.maxCoordinate))
    return fail(
        "Bezier control point " + std::to_string(bad->first + 1) + " has a coordinate that " +
        io_detail::describeBadCoordinate(control(bad->first, bad->second), options.maxCoordinate));
  std::vector<Vec3> points = {control.row(0).transpose()};
  for (Eigen::Index s = 0; s < count / 3; ++s) {
    std::vector<Vec3> segment;
    for (Eigen::Index k = 0; k < 4; ++k)
      segment.push_back(control.row((3 * s + k) % count).transpose());
    if (std::all_of(segment.begin(), segment.end(), [&](const Vec3& p) { return p == segment[0]; }))
      return fail("Bezier segment " + std::to_string(s + 1) + " has zero length");
    if (!io_detail::appendBezier(segment, options.flattenTolerance, points))
      return fail("Bezier segment " + std::to_string(s + 1) + " needs more than " +
                  fmt(io_detail::kMaxStepsPerCurve) + " points at a flatten tolerance of " +
                  fmt(options.flattenTolerance) + " mm");
    // The first and last points are the same until the last one is dropped below.
    if (points.size() > options.maxPoints + 1)
      return io_detail::tooManyPoints(path, "the flattened curve has", options.maxPoints);
  }
  points.pop_back();  // the last segment returns to p0
  Points3 P(Eigen::Index(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) P.row(Eigen::Index(i)) = points[i].transpose();
  return P;
}

Result<Curve3> readJsonCurve(const std::string& path, const std::string& text,
                             const CurveReadOptions& options) {
  const Result<nlohmann::json> parsed = io_detail::parseJson(path, text, options.maxPoints, 3);
  if (!parsed.isOk()) return parsed.status();
  const nlohmann::json& doc = parsed.value();
  const Result<double> scale = io_detail::jsonUnitScale(path, doc);
  if (!scale.isOk()) return scale.status();
  const bool bezier = doc.is_object() && doc.contains("bezier");
  if (doc.is_object() && !bezier && !doc.contains("points"))
    return Status{ErrorCode::InputUnreadable,
                  path + ": JSON object has no \"points\" or \"bezier\" list"};
  if (Status s = io_detail::onlyKnownKeys(path, doc, {"points", "bezier", "units"}); !s.isOk())
    return s;
  const nlohmann::json& list = doc.is_object() ? doc[bezier ? "bezier" : "points"] : doc;
  const Result<Eigen::MatrixXd> rows =
      io_detail::jsonPointList(path, list, bezier ? "\"bezier\"" : "\"points\"", 3, scale.value());
  if (!rows.isOk()) return rows.status();
  Points3 P;
  if (bezier) {
    Result<Points3> flat = flattenClosedBezier(path, rows.value(), options);
    if (!flat.isOk()) return flat.status();
    P = std::move(flat).value();
  } else {
    P = rows.value();
    const Status closed = closeCurve(path, P, false, options);
    if (!closed.isOk()) return closed;
  }
  const Status valid = validateCurve(path, P, options, [&](Eigen::Index i) {
    return (bezier ? "flattened point " : "point ") + std::to_string(i + 1);
  });
  if (!valid.isOk()) return valid;
  return Curve3{std::move(P), path, {}};
}

}  // namespace

namespace {

/// The format named by the extension of `source`, or InputUnreadable.
Result<std::string> curveFormat(const std::string& source) {
  const std::string ext = io_detail::lowerExtension(source);
  if (ext != "obj" && ext != "json")
    return Status{ErrorCode::InputUnreadable, source + ": unknown file type" +
                                                  (ext.empty() ? "" : " '." + ext + "'") +
                                                  "; expected .obj or .json"};
  return ext;
}

}  // namespace

Result<Curve3> parseCurve(const std::string& text, const std::string& source,
                          const CurveReadOptions& options) {
  if (!(options.flattenTolerance > 0.0) || !(options.maxCoordinate > 0.0))
    return Status{ErrorCode::Usage,
                  source + ": the flatten tolerance and coordinate limit must be positive"};
  Result<std::string> format = curveFormat(source);
  if (!format.isOk()) {  // a source without a known extension (stdin, a curve in memory): sniffed
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return format.status();
    // An OBJ file opens with a comment, a vertex, an object or a group line.
    const std::string opening = text.substr(first, 2);
    if (text[first] == '{')
      format = std::string("json");
    else if (opening[0] == '#' || opening == "v " || opening == "o " || opening == "g ")
      format = std::string("obj");
    else
      return format.status();
  }
  return format.value() == "obj" ? readObjCurve(source, text, options)
                                 : readJsonCurve(source, text, options);
}

Result<Curve3> checkCurve(const Curve3& curve, const std::string& name,
                          const CurveReadOptions& options) {
  CurveReadOptions closed = options;  // a curve in memory is closed by its type
  closed.forceClosed = true;
  Points3 P = curve.points;
  if (Status s = closeCurve(name, P, false, closed); !s.isOk()) return s;
  const Status valid = validateCurve(
      name, P, options, [](Eigen::Index i) { return "point " + std::to_string(i + 1); });
  if (!valid.isOk()) return valid;
  return Curve3{std::move(P), curve.source, curve.sha256};
}

Result<Curve3> readCurve(const std::string& path, const CurveReadOptions& options) {
  // The type is checked first: a wrong file is named as such without being read. Standard input
  // has no name to tell: its content is sniffed.
  if (path != kStandardInput)
    if (const Result<std::string> format = curveFormat(path); !format.isOk())
      return format.status();
  const Result<std::string> text = readInputFile(path);
  if (!text.isOk()) return text.status();
  Result<Curve3> curve = parseCurve(text.value(), inputName(path), options);
  if (curve.isOk()) curve.value().sha256 = sha256Hex(text.value());
  return curve;
}

}  // namespace dform
