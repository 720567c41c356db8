// SPDX-License-Identifier: GPL-3.0-or-later
// Internals of the pattern build shared by its stage files: the flat pieces as every stage reads
// them, their cut paths (pattern.cpp), the sheet or page and what fits on it (sheet_fit.cpp), the
// arrangement of the pieces on sheets (arrangement.cpp), the drawing of pieces, creases and cuts
// (pattern_drawing.cpp), each sheet's title block and marks (title_block.cpp) and the pages
// (tiling.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pattern_parts.h"

namespace dform::fab {

// Cricut Print Then Cut: 6.75 x 9.25 in (the long-standing safe maximum on Letter).
inline constexpr double kCricutW = 6.75 * 25.4, kCricutH = 9.25 * 25.4;
// Silhouette type-1 marks: 10 mm from the edges, 5 mm square, 20 mm L arms, 0.3 mm lines (the
// artwork's clearance from them is the profile's registration_clear_mm).
inline constexpr double kRegInset = 10.0, kRegSquare = 5.0, kRegArm = 20.0, kRegLine = 0.3;
// Tiles: each page shows a window of the pattern inside a 10 mm margin, under a 12 mm header.
inline constexpr double kTileMargin = 10.0, kTileHeader = 12.0;
// More pages than this is no print job anyone assembles by hand (500 A4 pages are 31 m^2 of
// paper): such a pattern is refused before it is drawn, as one too large for its sheet is.
inline constexpr long kMaxTiles = 500;

// The layout turns pieces in steps of this many degrees; 90 is a multiple, so a piece's turn plus
// a quarter turn is a step too.
inline constexpr int kTurnStepDeg = 2;

// A piece's material in its flat frame: every boundary loop, the outer outline first (even-odd).
std::vector<Polyline> materialLoops(const Piece& piece);

// The model's two pieces in their flat frames, as every stage of a build reads them.
struct FlatPieces {
  const Piece* piece[2];
  const Seam seams[2];
  const std::string names[2];
  const std::vector<Polyline> material[2];
  bool creased = false;

  explicit FlatPieces(const DForm& model)
      : piece{&model.a, &model.b},
        seams{Seam(model.a), Seam(model.b)},
        names{model.a.name.empty() ? "A" : model.a.name, model.b.name.empty() ? "B" : model.b.name},
        material{materialLoops(model.a), materialLoops(model.b)},
        creased(!model.a.creases.empty() || !model.b.creases.empty()) {}
};

struct TitleText;

// A title block: its lines run along `along` from `start`, each the next one across, in
// `length` mm; `v` is how far across the lines so far reach.
struct TitleBlock {
  Vec2 along = Vec2::Zero(), across = Vec2::Zero(), start = Vec2::Zero();
  double length = 0;
  double v = 0;
};

// Where a sheet's title block goes and what it holds: the full block (title, note, legends, scale
// note and the 50 mm bar) or, where that finds no room, the mark every cut sheet carries (the
// 50 mm bar beside the job's name, and the scale in words where it is not 1), at text height `h`,
// in a free rectangle of the sheet's art region.
struct TitlePlace {
  bool placed = false;
  bool full = true;
  double h = 0;
  TitleBlock block;
};

// One sheet (or page) of the layout and what is on it.
struct SheetPlan {
  Box box;                   // on the canvas (mm); the sheets lie side by side
  std::vector<int> pieces;   // the pieces on it (0 = A, 1 = B)
  Vec2 size = Vec2::Zero();  // the extent of those pieces, from the region's top-left corner (mm)
  TitlePlace title;          // none on a tiled piece's sheet (its page map has it)
  bool tiled = false;        // a piece larger than the page, tiled across pages (print)
  long tilesX = 1, tilesY = 1;  // its pages: columns and rows
};

// The sheet or page the pattern is laid out on and what fits on it: the region a sheet's pieces
// and title lines may use, where the title block goes, and the tiles of a piece too large for a
// page.
struct SheetFit {
  const Profile* profile = nullptr;
  bool* tooLargeOut = nullptr;  // set when the pattern fails because a piece does not fit
  double m = 0;                 // the profile's margin (mm)
  double edge = 0;              // drawn outside a piece's cut line
  double textH = 0;             // the title lines' capital height (mm), where room allows
  bool tabbed = false;          // the pattern has tabs: a title line says how they fold
  double titleBlock = 0;        // the full title block's depth with its margin from the pieces
  double scale = 1.0;           // the pattern's scale
  std::string scaleNote;        // the line stating a scale other than 1, on every sheet; or ""
  std::string pageName;         // empty for a material sheet
  std::string sheetWord;        // "sheet" or "page"
  double pageW = 0, pageH = 0;
  bool mayTurnPage = false, mayTile = false;
  double tileW = 0, tileH = 0, overlap = 0;  // a tile's window and the windows' overlap (mm)

  // The area of a W x H sheet or page (its top-left corner at `at`) that the pieces and the title
  // lines may use.
  Box artRegion(double W, double H, const Vec2& at = Vec2::Zero()) const;
  // The least room (mm, a margin included) the mark takes beside a sheet's pieces: the bar's row
  // (or the job's name) and the scale's line where it is not 1, at the smallest title height.
  double markRoom() const;
  // Whether pieces (and tabs) of extent `size` fit a W x H sheet, title block aside.
  bool fits(const Vec2& size, double W, double H) const;
  // Whether they fit a page or sheet alone, turned where the page may turn, title block aside.
  bool fitsSomeWay(const Vec2& size) const;
  // `what` (`contents`) fits the sheet in none of the arrangements tried, of extents `sizes`:
  // the message gives the sheet size needed by the arrangement that needs the least enlargement.
  Status tooLarge(const std::string& what, const std::vector<Vec2>& sizes,
                  const std::string& contents) const;
  // Tiling: the columns and rows of pages that show a piece of extent `size` with the margins
  // (its title block goes on its page map); neighbouring windows overlap by tileOverlapMm.
  Vec2 tiledExtent(const Vec2& size) const;
  std::pair<long, long> tileGrid(const Vec2& size) const;
  Status tooManyTiles(long tiles) const;
};

// The sheet or page for the options and profile, and its title block's height for a pattern at
// `scale`. `tooLargeOut` is the build's flag for failing because a piece does not fit.
Result<SheetFit> sheetFit(const ExportOptions& o, const Profile& profile, bool creased,
                          double scale, bool& tooLargeOut);

// Fails, before any tick or tab is made, when a piece's bare outline fits no sheet (or, tiled,
// needs too many pages).
Status checkOutlinesFit(const SheetFit& fit, const FlatPieces& flat);

// Flat frame -> sheet without the translation: flip y, then turn by `deg` degrees.
Eigen::Matrix2d flipRotate(double deg);

// A piece's extent on the sheet turned by `deg`: the box of its paths grown by `edge`, what sticks
// out of the outline (the ticks, kTickOut, or a printed bleed).
Box extentAt(const std::vector<Polyline>& paths, double deg, double edge);

struct CutPaths {
  std::vector<Polyline> outer;  // counter-clockwise in the flat frame
  std::vector<Polyline> holes;  // clockwise
};

// Piece p's closed cut paths (flat frame): its seam and free boundaries with its tabs merged in,
// and its joint holes (`jointHoles`, flat frame, clockwise); offset by half the kerf `kerf`.
CutPaths pieceCutPaths(const FlatPieces& flat, int p, const std::vector<FlatTab>& tabs,
                       const std::vector<Polyline>& jointHoles, double kerf);

// A piece's printed tint (flat frame; holes wind against the outer loops): its cut region grown
// by `bleed`.
std::vector<Polyline> bleedLoops(const std::vector<Polyline>& outer,
                                 const std::vector<Polyline>& holes, double bleed);

// Where each piece goes: its turn, its extent, the top-left corner of that extent, and the
// sheets (pages) they are on.
struct Arrangement {
  double rot[2] = {0, 0};
  Box box[2];
  Vec2 corner[2];
  std::vector<SheetPlan> plans;
};

// Pieces are packed on as few sheets (pages) as hold them: both on one where they fit together,
// else each on its own, else (print) tiled across pages.
// `quarterTurns` 0 or 1 turns both pieces that many quarter turns past their smallest-box turn
// (a nest lays each piece out both ways); -1 lets the arrangement choose.
Result<Arrangement> arrange(const SheetFit& fit, const std::vector<Polyline> cuts[2],
                            const std::string names[2], const TitleText& text,
                            std::vector<std::string>& messages, int quarterTurns = -1);

// Piece p on the sheet: its outline, material, cut paths, tint and creases.
PieceInfo placedPiece(const FlatPieces& flat, int p, const std::vector<Polyline>& cuts,
                      const std::vector<Polyline>& holeCuts, const Placement& place,
                      const Arrangement& a, double bleedMm);

// Each piece's ticks and tick numbers, name and crease letters, and messages for the labels left
// out.
// `fitNames`: each name no wider than fits in its piece (a nest's long names); else as tall as
// the room at the roomiest point allows.
void drawPieceLabels(const FlatPieces& flat, const Placement place[2], const Profile& profile,
                     const StrokeFont& font, DrawingBuilder& b, PatternBuild& out, BuildWork& work,
                     bool fitNames = false);

// Crease fold lines: the profile's fold style, dashed by the fold's direction.
void drawCreases(const std::vector<PieceInfo>& pieces, const Profile& profile, DrawingBuilder& b);

// The body's folds of at least o.scoreFoldsDeg through piece p (o.folds, flat mm at true size,
// drawn at `scale`) but its creases (drawn as crease lines), placed on the sheet and clipped to the
// piece's material; none without --score-folds.
std::vector<ScoredFoldInfo> scoredFolds(const ExportOptions& o, int p, const Placement& place,
                                        double scale, const PieceInfo& info);

// Piece p's hinges (hinges.cpp): rows of bridged slits parallel to the body's folds (o.folds, flat
// frame) of at least 2 degrees, spaced so that each row bends by the material's row angle over a
// cell no wider than that angle times the shape's bending radius there (never narrower than the
// material's row pitch), a solid margin inside the seam (past the joint holes `jointLoops`), free
// edges, holes and the piece's `labels` (convex footprints on the sheet); placed on the sheet by
// `place`. The folds are drawn at true size, the pieces at `scale`.
std::vector<HingeInfo> hingesOf(const ExportOptions& o, int p, const FlatPieces& flat,
                                const std::vector<Polyline>& jointLoops, const JointSettings& joint,
                                const MaterialPreset& material, const Placement& place,
                                double scale, const std::vector<Polyline>& labels);

// The hinges' slits in the Cut layer, before the holes and outer cuts.
void drawHinges(const std::vector<PieceInfo>& pieces, DrawingBuilder& b);

// Each piece's hinges where `o` asks for them (unset: where the material's preset does), clear of
// the labels drawn so far, drawn (drawHinges); a message for each hinge whose rows cannot let the
// sheet bend as tightly as the shape does.
void addHinges(const ExportOptions& o, const FlatPieces& flat,
               const std::vector<Polyline> jointLoops[2], const Placement place[2], double scale,
               DrawingBuilder& b, PatternBuild& out);

// The scored folds as solid lines on the score layer (and the cutter's score pass).
void drawScoredFolds(const std::vector<PieceInfo>& pieces, DrawingBuilder& b);

// The cut paths, every hole before any outer cut (inner cuts first); then the printed tint.
void drawCuts(const std::vector<PieceInfo>& pieces, const std::string names[2],
              const Profile& profile, DrawingBuilder& b);

// The scale as a percentage of true size, to a tenth ("73.4 %").
std::string percentText(double scale);

// What the title lines of a pattern's sheets say: what it is ("D-Form A + B"), its pieces'
// names, its options, scale and seam length ("seam 607.3 mm").
struct TitleText {
  const ExportOptions& o;
  std::string what, scaleText, perimeterText;
  std::vector<std::string> names;  // the pieces' names, as the sheets' notes name them
  bool creased = false;            // a crease is drawn: the legend line says how to read it
  const StrokeFont& font;
};

// Title lines: their pitch (x capital height), the calibration bar's row (its 3 mm end ticks and a
// label up to 4 mm tall centred 1.5 mm above the bar, 4 mm down the row), where the bar's label
// starts (the 50 mm bar and a 4 mm gap), and the smallest capital height a title line is set at
// where room is short (small, still legible printed and engraved).
inline constexpr double kTitlePitch = 1.7, kBarRow = 5.0, kBarLabelAt = 54.0, kMinTitleH = 1.5;

// One title line: its id and its words.
struct TitleLine {
  std::string id, words;
};

// The lines of sheet k's (of `sheets`, with piece `piece` first on it) title block: the full
// block (title, note, legends for creases and tabs, the scale in words) or the mark's (the job's
// name and "print at 100%" over the bar, the scale in a short line where it is not 1).
std::vector<TitleLine> titleLines(size_t k, size_t sheets, int piece, bool full,
                                  const SheetFit& fit, const TitleText& text);

// The calibration bar's label: "50 mm - print at 100% (actual size)" in the full block, "50 mm"
// in the mark (whose line above it names the job and says so).
std::string barLabel(bool full, const SheetFit& fit);

// The rectangles of `region` clear of every box of `taken` grown by `gap` (those spanned by the
// boxes' and the region's edges): the one under everything across the whole region first, then
// the column right of everything (where the block has always gone), then the rest.
std::vector<Box> freeRectangles(const Box& region, const std::vector<Box>& taken, double gap);

// Where sheet k's title block goes beside the pieces' extents `taken` in its art region: the full
// block (unless the title is off) at the largest height that fits, else the mark; in the first
// free rectangle that holds it, reading along or up. Not placed when not even the mark fits.
TitlePlace placeTitle(const Box& region, const std::vector<Box>& taken, size_t k, size_t sheets,
                      int piece, const SheetFit& fit, const TitleText& text);

// Whether title place `a` is better than `b`: placed, then full, then larger.
bool betterTitle(const TitlePlace& a, const TitlePlace& b);

// Sheet k's title block (full or the mark) at capital height h, and where the profile has one,
// the 50 mm calibration bar after it, into `layer` along `block`.
void drawTitleBlock(size_t k, size_t sheets, int piece, bool full, double h, const SheetFit& fit,
                    const TitleText& text, Layer& layer, TitleBlock& block);

// Each sheet's title block where its plan put it (a tiled piece's goes on its page map), and the
// registration marks in each sheet's corners.
void drawSheetFurniture(const std::vector<SheetPlan>& plans, const SheetFit& fit,
                        const TitleText& text, DrawingBuilder& b);

// The drawing's title and description (SVG <title> and <desc>, PDF title).
void describe(Drawing& drawing, const ExportOptions& o, const Profile& profile, double scale,
              const std::string& perimeterText);

// The pages: one per sheet; a tiled piece gets a page map (with its sheet's title lines), then
// its tiles. A message for each sheet whose title lines found no room beside its pieces.
void addPages(const std::vector<SheetPlan>& plans, const SheetFit& fit, const TitleText& text,
              PatternBuild& out);

// "an A4", "a Letter": the page's name with its article.
std::string aPage(const std::string& pageName);

}  // namespace dform::fab
