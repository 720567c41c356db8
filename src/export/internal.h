// Internals of the export module, shared by its .cpp files only: the pattern as a drawing (layers
// of polylines in sheet millimetres, y down as in SVG), the stroke font, and the writers.
#pragma once

#include <string>
#include <vector>

#include "core/status.h"
#include "core/types.h"
#include "export/exporter.h"
#include "validate/metrics.h"

namespace dform::fab {

using Vec2 = Eigen::Vector2d;
using Polyline = std::vector<Vec2>;

/// One drawn object: one or more polylines under one id (a label is one path of many strokes).
struct Path {
  std::string id;
  std::vector<Polyline> parts;
  bool closed = false;       ///< every part is a closed loop
  bool filled = false;       ///< filled with the layer colour, no stroke (registration square)
  bool dashed = false;       ///< drawn with the layer's dash pattern, or with `dash` when it is set
  std::vector<double> dash;  ///< dashed: on/off lengths (mm) instead of the layer's (a fold style)
};

/// An Inkscape layer: one operation, one colour, one stroke width.
struct Layer {
  std::string name;        ///< "Cut", "Score", "Engrave", "Print", "Regmarks", ...
  std::string color;       ///< #RRGGBB
  double widthMm = 0.025;  ///< stroke width (mm)
  double dashMm = 3.0;     ///< dash and gap length for dashed paths (mm)
  bool printed = true;     ///< drawn in the PDF and PNG (a print-and-cut Cut layer is not)
  std::vector<Path> paths;
};

/// The whole pattern on its canvas, in mm with y pointing down.
struct Drawing {
  double width = 0, height = 0;
  std::vector<Layer> layers;
  std::string title;        ///< SVG <title>, PDF title
  std::string description;  ///< SVG <desc>: profile, job, units
};

/// One PDF page: the canvas window shown on it plus page furniture (tiling marks, header).
struct PageView {
  double width = 0, height = 0;  ///< page size (mm)
  Vec2 origin{0, 0};             ///< canvas point drawn at the page's (0, 0)
  double clipX0 = 0, clipY0 = 0, clipX1 = 0, clipY1 = 0;  ///< page area the canvas shows (mm)
  std::vector<Layer> overlay;                             ///< drawn in page coordinates, unclipped
};

struct TickInfo {
  int id = 0;
  double s = 0;   ///< seam arc length from seam[0] (mm)
  Vec2 onA, onB;  ///< where the tick crosses each piece's outline (sheet mm)
};

struct TabInfo {
  int piece = 0;          ///< 0 = A, 1 = B
  double s0 = 0, s1 = 0;  ///< seam arc length of the fold line's ends (mm)
  double width = 0;       ///< tab width (mm)
  Polyline polygon;       ///< the tab (sheet mm), fold line first
  Polyline fold;          ///< the fold line (sheet mm), on the piece outline
};

/// A crease drawn on the pattern as a fold line.
struct CreaseInfo {
  std::string id;   ///< "A-crease-1-mountain"
  CreaseFold fold;  ///< direction and angle from the solved shape
  Polyline line;    ///< the crease (sheet mm), boundary to boundary
};

struct PieceInfo {
  std::string name;
  Polyline outline;  ///< seam polyline in seam order from seam[0] (sheet mm)
  /// Every boundary loop (sheet mm), the outer outline first: the piece's material by the
  /// even-odd rule. Just the seam for a classic piece.
  std::vector<Polyline> boundaries;
  bool seamIsHole = false;         ///< the seam is a hole's loop (anti and demi D-Forms)
  std::vector<Polyline> cut;       ///< closed outer cut paths (outline with tabs, kerf applied)
  std::vector<Polyline> holeCuts;  ///< closed cut paths of the holes (cut before the outer ones)
  std::vector<CreaseInfo> creases;
  double perimeter = 0;    ///< flat seam length (mm)
  double rotationDeg = 0;  ///< rotation applied on the sheet (after flipping y)
};

struct PatternBuild {
  Profile profile;
  Drawing drawing;
  std::vector<PageView> pages;
  std::vector<PieceInfo> pieces;
  std::vector<TickInfo> ticks;
  std::vector<TabInfo> tabs;
  std::vector<std::string> messages;
  double tickSpacing = 0;
};

/// A Hershey single-stroke font (.jhf), glyphs for ASCII 32..126.
class StrokeFont {
 public:
  static Result<StrokeFont> load(const std::string& path);
  /// The strokes of `text`, centred on `center`, baseline along the unit vector `dir` (sheet
  /// coordinates, y down), capital height `height` mm.
  std::vector<Polyline> layout(const std::string& text, const Vec2& center, const Vec2& dir,
                               double height) const;
  /// Width of `text` at capital height `height` (mm).
  double width(const std::string& text, double height) const;

 private:
  struct Glyph {
    int left = 0, right = 0;
    std::vector<std::vector<Vec2>> strokes;  ///< font units, y down
  };
  const Glyph& glyph(char c) const;
  std::vector<Glyph> glyphs_;
};

/// The profile to use for `options` (loaded or the override), the kerf applied.
Result<Profile> resolveProfile(const ExportOptions& options);

/// Lays out the pattern: ticks, tabs, cut paths, placement on the sheet, labels, pages.
Result<PatternBuild> buildPattern(const DForm& model, const ExportOptions& options,
                                  const Profile& profile);

std::string svgDocument(const Drawing& drawing);
Result<std::string> pdfDocument(const PatternBuild& pattern);
Result<std::string> pngImage(const PatternBuild& pattern, int page, double dpi);
std::string sidecarJson(const PatternBuild& pattern, const std::string& jobName);

std::string stlDocument(const DForm& model, bool failedGate);
Result<std::string> gltfDocument(const DForm& model, const ExportOptions& options);

/// Measures the built pattern: paths off the sheet, overlapping tabs, pieces and labels.
LayoutFindings checkLayout(const PatternBuild& pattern);

/// Checks the indices and sizes of both pieces; InputInvalid naming the problem.
Status checkModel(const DForm& model);

}  // namespace dform::fab
