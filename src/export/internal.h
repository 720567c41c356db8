// SPDX-License-Identifier: GPL-3.0-or-later
// Internals of the export module, shared by its .cpp files only: the pattern as a drawing (layers
// of polylines in sheet millimetres, y down as in SVG), the stroke font, and the writers.
#pragma once

#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/export/exporter.h"
#include "dform/validate/metrics.h"

namespace dform::fab {

using Vec2 = Eigen::Vector2d;
using Polyline = std::vector<Vec2>;

/// An axis-aligned box (mm); empty until a point is added.
struct Box {
  Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  static Box spanning(const Vec2& lo, const Vec2& hi) {
    Box b;
    b.lo = lo;
    b.hi = hi;
    return b;
  }
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void add(const Polyline& line) {
    for (const Vec2& p : line) add(p);
  }
  double w() const { return hi.x() - lo.x(); }
  double h() const { return hi.y() - lo.y(); }
  /// Whether the closed boxes share a point: two shapes whose boxes do not cannot share area.
  bool overlaps(const Box& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
  }
  /// Whether `o` lies inside this box, with `eps` mm to spare for rounding.
  bool contains(const Box& o, double eps) const {
    return o.lo.x() >= lo.x() - eps && o.lo.y() >= lo.y() - eps && o.hi.x() <= hi.x() + eps &&
           o.hi.y() <= hi.y() + eps;
  }
};

inline Box boxOf(const std::vector<Polyline>& parts) {
  Box b;
  for (const Polyline& part : parts) b.add(part);
  return b;
}

/// One drawn object: one or more polylines under one id (a label is one path of many strokes).
struct Path {
  std::string id;
  std::vector<Polyline> parts;
  bool closed = false;  ///< every part is a closed loop
  /// Filled, no stroke (registration square, piece tint, shaded faces), by the non-zero rule: a
  /// hole winds the other way round, parts of one winding add up.
  bool filled = false;
  std::string fill;  ///< filled: its colour (#RRGGBB) instead of the layer's
  /// Filled and stroked in the fill colour at the layer's width, so that neighbouring shaded faces
  /// meet without the hairline gaps antialiasing leaves between them.
  bool sealed = false;
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
  /// A spot colour's name (a print-and-cut Cut layer for a RIP, "CutContour"): the PDF draws the
  /// layer in that Separation colour space, the SVG names the layer after it. "" = none.
  std::string spot;
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
  /// The area of the page the print may use (page mm): the profile's art region (a Cricut's
  /// Print Then Cut area, inside a Silhouette's marks); empty on a tile or a page map.
  Box printArea;
  /// "sheet" (a sheet or page of the layout), "map" (a tiled piece's page map) or "tile"
  std::string kind = "sheet";
};

/// A tick pair. Both ticks mark one point of the 3D seam: the same seam pair index i and fraction
/// along the edge i..i+1 on both pieces, found from A's arc length `s`.
struct TickInfo {
  int id = 0;
  double s = 0;   ///< arc length along A's seam from seam[0] (mm): the seam parameter
  double sB = 0;  ///< arc length along B's seam of the same seam point (mm)
  Vec2 onA, onB;  ///< where the tick crosses each piece's outline (sheet mm)
};

struct TabInfo {
  int piece = 0;          ///< 0 = A, 1 = B
  double s0 = 0, s1 = 0;  ///< seam parameter (A's arc length, mm) of the fold line's ends
  double width = 0;       ///< tab width (mm)
  Polyline polygon;       ///< the tab (sheet mm), fold line first
  Polyline fold;          ///< the fold line (sheet mm), on the piece outline
};

/// The joint a pattern is made with: the options over the material's preset over the profile's.
struct JointSettings {
  Joint joint = Joint::Glue;
  std::string material;       ///< "" when none was named
  double thicknessMm = 0;     ///< the material's (0: none named)
  double spacingMm = 15;      ///< largest distance between neighbouring holes of a piece (mm)
  double diameterMm = 2;      ///< hole diameter (mm)
  double edgeMm = 3;          ///< seam to hole centre, and to a slot's middle line (mm)
  double slotLengthMm = 7.5;  ///< a tongue's width along the seam (mm): half the spacing unless set
  /// A slot's width (mm): the sheet's thickness (0.3 mm when none is named) and 0.2 mm to slide,
  /// wider than the kerf, which would close a narrower slot's compensated cut loop.
  double slotWidthMm = 0.5;
};

/// The joint settings for `o` and the (resolved) profile.
JointSettings jointSettings(const ExportOptions& o, const Profile& profile);

/// A joint hole. With --joint holes, hole `index` on A and hole `index` on B are a pair at the
/// same seam point; with lace the holes are numbered along the seam, A's even and B's odd.
struct JointHoleInfo {
  int piece = 0;        ///< 0 = A, 1 = B
  int index = 0;        ///< the pair (holes) or the place along the seam (lace)
  double s = 0;         ///< seam parameter (A's arc length, mm) of the hole's seam point
  double own = 0;       ///< the same point's arc length along its own piece's seam (mm)
  Vec2 centre;          ///< sheet mm
  double diameter = 0;  ///< mm
};

/// A tongue of A and its slot in B (--joint slots), both at seam parameter `s`: the tongue's fold
/// line is A's seam from s0 to s1, the slot's middle line lies `edge` inside B's seam, along it.
/// Zipped, the tongue folds back along the seam and through the slot.
struct JointSlotInfo {
  int index = 0;                 ///< the joint's place along the seam (shared with hole pairs)
  double s = 0;                  ///< seam parameter (A's arc length, mm) of the slot's seam point
  double s0 = 0, s1 = 0;         ///< seam parameter of the tongue's fold line's ends
  Polyline tongue;               ///< the tongue (sheet mm), fold line first
  Polyline fold;                 ///< its fold line (sheet mm), on A's outline
  Polyline slot;                 ///< the slot's loop on B (sheet mm)
  Vec2 slotCentre;               ///< sheet mm
  double length = 0, width = 0;  ///< the slot's (mm)
};

/// A crease drawn on the pattern as a fold line.
struct CreaseInfo {
  std::string id;   ///< "A-crease-1-mountain"
  CreaseFold fold;  ///< direction and angle from the solved shape
  Polyline line;    ///< the crease (sheet mm), boundary to boundary
};

/// A fold of the body scored on the pattern (--score-folds), clipped to its piece.
struct ScoredFoldInfo {
  std::string id;               ///< "A-body-fold-3"
  double angleDeg = 0;          ///< the fold angle (degrees)
  std::vector<Polyline> lines;  ///< its parts inside the piece (sheet mm)
};

/// A row of a hinge: its slits and the bending it allows against the shape's.
struct HingeRow {
  std::vector<Polyline> cuts;  ///< straight slits (sheet mm), bridged, clear of the margins
  double pitchMm = 0;          ///< the width of sheet the row bends (its cell across the rows)
  /// The tightest bend it takes with its slits: its cell over its angle (a row without slits,
  /// wholly in the margins, takes none).
  double radiusAllowedMm = 0;
  double radiusNeededMm = 0;  ///< the shape's tightest bending radius in its cell
  double fromMm = 0;          ///< its cell's near side across the hinge, from its first band's
};

/// A body fold a hinge bends along.
struct HingeFoldInfo {
  int index = 0;        ///< into ExportOptions::folds
  Polyline line;        ///< the fold (sheet mm)
  double angleDeg = 0;  ///< its angle
  double radiusMm = 0;  ///< the shape's bending radius there: its band over its angle
  double bandFromMm = 0, bandToMm = 0;  ///< its band across the hinge, as HingeRow::fromMm
  /// The loosest radius the rows with slits across its band allow; 0 where none has slits.
  double radiusAllowedMm = 0;
  double bendDeg = 0;  ///< the angle those rows bend across its band (each its share of it)
  /// Its stretches within the solid margin along the seam (sheet mm): no row has slits beside
  /// them, so the sheet bends there by its own give only, less than the fold.
  std::vector<Polyline> inSeamMargin;
  /// The rows across its band have slits and bend no more loosely than it does: false where the
  /// material cannot bend as tightly (the shape needs less than the material's tightest radius)
  /// or no row beside it has slits.
  bool radiusMet() const { return radiusAllowedMm > 0 && radiusAllowedMm <= radiusMm * (1 + 1e-9); }
};

/// A hinge: rows of cuts across a family of parallel body folds of a piece, parallel to them.
struct HingeInfo {
  std::string id;  ///< "A-hinge-1"; its rows' paths "A-hinge-1-row-03"
  Vec2 direction;  ///< of its folds and rows (sheet, unit)
  std::vector<HingeFoldInfo> folds;
  std::vector<HingeRow> rows;
};

/// The angle a hinge's folds turn in all (degrees).
double hingeTurnDeg(const HingeInfo& hinge);
/// The angle its rows with slits bend at most (degrees): each its pitch over its allowed radius.
double hingeBendDeg(const HingeInfo& hinge);

struct PieceInfo {
  std::string name;
  Polyline outline;  ///< seam polyline in seam order from seam[0] (sheet mm)
  /// Every boundary loop (sheet mm), the outer outline first: the piece's material by the
  /// even-odd rule. Just the seam for a classic piece.
  std::vector<Polyline> boundaries;
  std::vector<Polyline> jointLoops;  ///< its joint holes and slots (sheet mm; among `boundaries`)
  bool seamIsHole = false;           ///< the seam is a hole's loop (anti and demi D-Forms)
  /// The printed tint's loops (sheet mm; holes wind against the outer loops): the cut region grown
  /// by the profile's bleed; empty without a bleed.
  std::vector<Polyline> bleed;
  std::vector<Polyline> cut;       ///< closed outer cut paths (outline with tabs, kerf applied)
  std::vector<Polyline> holeCuts;  ///< closed cut paths of the holes (cut before the outer ones)
  std::vector<CreaseInfo> creases;
  std::vector<ScoredFoldInfo> scoredFolds;  ///< folds scored by --score-folds
  std::vector<HingeInfo> hinges;            ///< kerf-bending cuts where it bends (a rigid sheet)
  double perimeter = 0;                     ///< flat seam length (mm)
  double rotationDeg = 0;                   ///< rotation applied on the sheet (after flipping y)
  int sheet = 0;  ///< the sheet (page) it is on: an index into PatternBuild::sheets
};

/// A part of a nest: which piece of which D-Form (and copy), where it went.
struct NestPartInfo {
  std::string name;    ///< "ellipses-A", its paths' ids' head
  std::string job;     ///< its D-Form's job
  int copy = 1;        ///< which copy of that D-Form (from 1)
  int piece = 0;       ///< 0 = A, 1 = B of its D-Form
  int sheet = 0;       ///< the sheet it is on
  double turnDeg = 0;  ///< the quarter turn past its smallest-box turn it was packed at
};

struct PatternBuild {
  Profile profile;
  double scale = 1.0;  ///< the pattern's scale: 1 true size, else the flat pieces were scaled
  Drawing drawing;
  /// The sheets or pages the pattern is laid out on (canvas mm): one, or one per piece when a
  /// print-and-cut pattern puts each piece on its own page. Every path lies inside one of them.
  std::vector<Box> sheets;
  std::vector<PageView> pages;
  /// The assembly page (how to glue the pieces), the last page of pattern.pdf and assembly.svg.
  Drawing assembly;
  std::vector<PieceInfo> pieces;
  std::vector<TickInfo> ticks;
  std::vector<TabInfo> tabs;
  JointSettings joint;
  std::vector<JointHoleInfo> jointHoles;
  std::vector<JointSlotInfo> jointSlots;
  std::vector<std::string> messages;
  std::vector<std::string> warnings;  ///< what the pattern cannot do as asked (a hinge too stiff)
  double tickSpacing = 0;
  /// A nest's parts (layOutNest), one per piece, in `pieces`' order; empty for one D-Form.
  std::vector<NestPartInfo> nestParts;
  /// Stamped FAILED GATE (stampFailedGate) after a failed quality gate: the stamp is an overlay,
  /// the layout is the same as without it.
  bool failedGate = false;
};

/// The work of a build, counted so that tests can bound it without timing it.
struct BuildWork {
  long ticks = 0;          ///< ticks placed
  long tabCandidates = 0;  ///< tab polygons built and checked (narrowed and split ones too)
  long pairTests = 0;      ///< shape pairs compared (tab-tab, tab-piece, label-label)
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

/// A laid-out pattern as layOutExport keeps it for rendering: the build, the font its labels are
/// written in (the stamp's too) and the options it was laid out with.
struct LaidOutPattern {
  PatternBuild build;
  StrokeFont font;
  ExportOptions options;
};

/// The pattern's own files of a laid-out pattern, rendered in memory: pattern.svg, .dxf, .pdf
/// (with the assembly page when it has one), pattern.json, and each sheet's SVG and DXF when it
/// has more than one; the summary of what they hold.
Result<PreparedExport> renderPattern(const LaidOutExport& laidOut);

/// How many patterns layOutExport has laid out in this process (tests count them).
long patternsLaidOut();

/// The FAILED GATE stamp's text, and the layer that holds it.
inline constexpr const char* kFailedGateText = "FAILED GATE - NOT FOR FABRICATION";
inline constexpr const char* kFailedGateLayer = "FailedGate";

/// Stamps a laid-out pattern FAILED GATE without moving anything (failed_gate.cpp): the text in
/// the free band above (or below) what each sheet, page, tile and the assembly page show, in a
/// colour no profile operation uses, on a layer of its own (first in the drawing: pattern.svg,
/// pattern.dxf, the sheets' files; not printed, since every PDF page gets its own in its overlay)
/// and on the assembly page; "FAILED GATE" in the drawings' descriptions; `failedGate` set.
/// Stamping a stamped pattern changes nothing.
void stampFailedGate(PatternBuild& pattern, const StrokeFont& font);

/// The profile to use for `options` (loaded or the override), the kerf applied.
Result<Profile> resolveProfile(const ExportOptions& options);

/// Lays out the pattern: ticks, tabs, cut paths, placement on the sheet, labels, pages.
/// `work`, when given, counts the work done (also when the build fails).
Result<PatternBuild> buildPattern(const DForm& model, const ExportOptions& options,
                                  const Profile& profile, BuildWork* work = nullptr);

/// How a nest (nest.cpp) lays one D-Form out: both pieces turned `quarterTurns` (0 or 1) quarter
/// turns past their smallest-box turn, and each piece's name (its D-Form's, long) no larger than
/// fits inside it.
struct NestLayout {
  int quarterTurns = 0;
};

/// The pattern of `model` at the options' scale laid out as a nest lays it out; no assembly page.
Result<PatternBuild> buildNestPattern(const DForm& model, const ExportOptions& o,
                                      const Profile& profile, const StrokeFont& font,
                                      const NestLayout& nest);

/// The tick number as printed: one that reads as another number upside down (6, 9, 16, 68, ...)
/// gets a trailing dot.
std::string tickLabel(int k);

/// The pattern's ticks on the 3D seam: the same seam edge and fraction as on A's flat outline.
/// None when that outline is not A's seam vertex for vertex (no numbers rather than wrong ones).
std::vector<SeamTick> seamTicks(const DForm& model, const PatternBuild& pattern);

/// The assembly page's numbered steps for `pattern`: how to cut, start, zip and close it with its
/// tabs and its joint (tape, tabs, hole pairs, lace or tongues and slots).
std::vector<std::string> assemblySteps(const PatternBuild& pattern);

/// The assembly page of a laid-out pattern (A4, or Letter for a Letter profile; mm, y down): the
/// 3D shape with the tick numbers at their seam points, both pieces small with tick 0 and the zip
/// direction, and the numbered steps. Its text is `font`'s.
Drawing assemblyPage(const DForm& model, const PatternBuild& pattern, const ExportOptions& options,
                     const StrokeFont& font);

std::string svgDocument(const Drawing& drawing);
/// The drawing as DXF through dxflib (dxf_writer.cpp): mm, y up (flipped about the drawing's
/// height), layers CUT, SCORE, ENGRAVE (and REGMARKS for print-and-cut marks), every polyline an
/// LWPOLYLINE, closed paths with the closed flag.
std::string dxfDocument(const Drawing& drawing);
/// The part of `drawing` on `sheet` (the paths inside it), moved to the sheet's own origin.
Drawing sheetDrawing(const Drawing& drawing, const Box& sheet);
Result<std::string> pdfDocument(const PatternBuild& pattern);
/// `pdf` (Cairo's) with /ViewerPreferences << /PrintScaling /None >> in its catalog, so that a
/// viewer's print dialog prints at 100 % instead of fitting the page to the paper (pdf_update.cpp,
/// an incremental update: Cairo's bytes stay as they are). Internal when Cairo's output is not
/// laid out as expected.
Result<std::string> withPrintScalingNone(std::string pdf);
/// `pdf` with each page's paths of the pattern's spot-colour layer (Layer::spot, a RIP's
/// CutContour) drawn in that Separation colour space (DeviceCMYK magenta where a device lacks
/// the ink), full tint, at the layer's width; as it is without one.
Result<std::string> withSpotLayers(std::string pdf, const PatternBuild& pattern);
Result<std::string> pngImage(const PatternBuild& pattern, int page, double dpi);
/// Page `page`'s print (its printed layers, no cut line) within its print area, as a PNG at `dpi`
/// with a transparent background and the resolution recorded (pHYs), for a cutter's software that
/// takes the print as an image and cuts round its opaque pixels (Cricut Design Space's Print Then
/// Cut): only the pieces, each clipped to its cut line (a pattern stamped FAILED GATE keeps its
/// stamp).
Result<std::string> printPng(const PatternBuild& pattern, int page, double dpi);
/// Page `page`'s cut line alone, in the frame of printPng's image (mm, its top left at 0, 0).
std::string cutSvg(const PatternBuild& pattern, int page);
std::string sidecarJson(const PatternBuild& pattern, const std::string& jobName);

std::string stlDocument(const DForm& model, bool failedGate);
Result<std::string> gltfDocument(const DForm& model, const ExportOptions& options);

/// Measures the built pattern: paths off the sheet, overlapping tabs, pieces and labels. `work`,
/// when given, counts the shape pairs compared.
LayoutFindings checkLayout(const PatternBuild& pattern, BuildWork* work = nullptr);

/// Checks the indices and sizes of both pieces; InputInvalid naming the problem.
Status checkModel(const DForm& model);

}  // namespace dform::fab
