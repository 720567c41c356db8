// SPDX-License-Identifier: GPL-3.0-or-later
// Helpers for the export tests: their options, an export read back, a built pattern; readers for
// our SVG (paths with absolute M/L/Z, in layers), pattern.json, binary STL; and running the
// command-line checkers (qpdf, pdfinfo, pdftoppm, node).
#pragma once

#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dform/export/exporter.h"
#include "export/internal.h"

namespace dform::test {

/// The bar for cut and printed lengths, mm.
inline constexpr double kMmTol = 0.1;

using Vec2 = Eigen::Vector2d;
using Polyline = std::vector<Vec2>;

struct SvgPath {
  std::string id, layer, style, fill, stroke;
  double strokeWidth = 0;
  std::vector<Polyline> parts;  ///< subpaths in order
  bool closed = false;
  bool unknownCommand = false;  ///< d used something other than M, L, Z
};

struct SvgDoc {
  std::string width, height, viewBox;  ///< attributes of the root element as written
  std::vector<std::string> layers;     ///< inkscape:label of each layer, in order
  std::vector<SvgPath> paths;          ///< in document order
  const SvgPath* find(const std::string& id) const;
};

SvgDoc readSvg(const std::string& path);
std::string readText(const std::string& path);

/// A subpath drawn on a PDF page, in millimetres from the page's top left corner, y down (the
/// SVG's frame): its points (a curve contributes its end point) and whether it was closed.
struct PdfPath {
  int page = 0;  ///< from 1
  Polyline points;
  bool closed = false;
  Eigen::Vector3d color = Eigen::Vector3d::Zero();  ///< RGB 0..1 it was stroked (or filled) in
  /// The colour space resource it was stroked (or filled) in ("CS1" for "/CS1 CS"), "" for
  /// DeviceRGB (set by RG or rg).
  std::string space;
};
/// Every subpath stroked or filled in the PDF's page content streams (decoded by qpdf), with the
/// transformation matrix (q, Q, cm) applied. Empty, and the test told, when qpdf cannot read it.
std::vector<PdfPath> readPdfPaths(const std::string& pdf);
/// How far the closed subpath of `paths` nearest to the closed polyline `loop` departs from it
/// once their bounding boxes' corners are put together (a page's origin is not the sheet's): the
/// largest distance, in mm, from a point of either to the other line (Cairo merges collinear
/// segments, so the points themselves differ); infinity when no closed subpath has the loop's
/// extent within 1 mm. A scaled or turned drawing of `loop` is as far off as the change moves it.
double closestDrawing(const std::vector<PdfPath>& paths, const Polyline& loop);

/// Options for `profile` with the source tree's templates and the job name "test-job".
ExportOptions options(const std::string& profile = "laser");

/// What exportAll wrote into a fresh folder `name`, read back (empty when it failed, which the
/// test is told).
struct Exported {
  std::string dir;
  ExportSummary summary;
  SvgDoc svg;
  nlohmann::json sidecar;
};
Exported exportTo(const std::string& name, const DForm& model, const ExportOptions& o);

/// The pattern laid out for `model`, no file written (the test is told when it fails).
fab::PatternBuild build(const DForm& model, const ExportOptions& o);

/// An SVG length written in mm ("210mm") as a number; the test fails on another unit.
double parseMm(const std::string& s);

/// A polyline of pattern.json, [[x, y], ...].
Polyline toPolyline(const nlohmann::json& j);

double length(const Polyline& p, bool closed);
/// The length of `piece`'s seam in its flat coordinates (mm): the solved length, not the pattern's.
double solvedPerimeter(const Piece& piece);
/// Arc length along the closed polyline `loop` (from its first point) of the point of `loop`
/// nearest to q, and that distance.
std::pair<double, double> arcLengthOf(const Polyline& loop, const Vec2& q);
bool inside(const Polyline& polygon, const Vec2& q);
/// The 3D seam point at the sheet point q of a piece's seam outline (pattern.json's, in the order
/// of piece.seam): the nearest outline segment i..i+1 and the fraction along it, interpolated
/// between the 3D points of seam[i] and seam[i + 1]. Also returns the distance from q to the
/// outline.
std::pair<Eigen::Vector3d, double> seamPoint3d(const Piece& piece, const Polyline& outline,
                                               const Vec2& q);
/// Where segment [a, b] crosses the closed polyline, if it does (first crossing).
bool crossing(const Polyline& loop, const Vec2& a, const Vec2& b, Vec2* at);

/// check_dxf.py (ezdxf) on an export folder, `extra` its options (--seam A B); its report in *out.
/// A missing python3-ezdxf is exit 2: a failure, never a skip (scripts/install-deps installs it).
int checkDxf(const std::string& dir, std::string* out, const std::string& extra = "");
/// checkDxf passes; its report (the differences measured) goes to the log.
void expectDxfChecks(const std::string& dir, const std::string& extra = "");

/// Whether the text path's first strokes write `words` in `font`: the Hershey strokes of `words`,
/// stroke for stroke and point for point, up to a similarity (position, height and direction).
bool startsWithText(const fab::Path& path, const std::string& words, const fab::StrokeFont& font);

/// Runs a shell command; returns its exit code, output (stdout and stderr) in *out.
int run(const std::string& command, std::string* out = nullptr);
bool haveProgram(const std::string& name);

/// A fresh empty folder under the test's temporary directory.
std::string freshDir(const std::string& name);

}  // namespace dform::test
