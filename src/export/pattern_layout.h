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

// Where a sheet's title block goes: under its pieces, in a column beside them, or nowhere (the
// pieces and the block do not fit).
enum class TitleAt { Below, Aside, None };

// One sheet (or page) of the layout and what is on it.
struct SheetPlan {
  Box box;                   // on the canvas (mm); the sheets lie side by side
  std::vector<int> pieces;   // the pieces on it (0 = A, 1 = B)
  Vec2 size = Vec2::Zero();  // the extent of those pieces, from the region's top-left corner (mm)
  TitleAt title = TitleAt::Below;
  bool tiled = false;           // a piece larger than the page, tiled across pages (print)
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
  double textH = 0, lineH = 0;  // the title lines' capital height and line pitch (mm)
  bool tabbed = false;          // the pattern has tabs: a title line says how they fold
  double titleBlock = 0;        // the title block's height with its margin from the pieces
  std::string scaleNote;        // the line stating a scale other than 1, on every sheet; or ""
  std::string pageName;         // empty for a material sheet
  std::string sheetWord;        // "sheet" or "page"
  double pageW = 0, pageH = 0;
  bool mayTurnPage = false, mayTile = false;
  double tileW = 0, tileH = 0, overlap = 0;  // a tile's window and the windows' overlap (mm)

  // The area of a W x H sheet or page (its top-left corner at `at`) that the pieces and the title
  // lines may use.
  Box artRegion(double W, double H, const Vec2& at = Vec2::Zero()) const;
  // Where a sheet's title block goes when the pieces on it take `size` of its region `r`: under
  // them (a margin apart) where the region is tall enough, else in a column to their right, its
  // lines reading upwards; None when neither fits (or the pieces do not).
  TitleAt titleAt(const Vec2& size, const Box& r) const;
  // Whether pieces (and tabs) of extent `size` fit a W x H sheet, with their title block beside
  // them unless `withTitle` is false (the title lines then go on a page of their own).
  bool fits(const Vec2& size, double W, double H, bool withTitle = true) const;
  // Whether they fit a page or sheet alone, turned where the page may turn, title or not.
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
Result<Arrangement> arrange(const SheetFit& fit, const std::vector<Polyline> cuts[2],
                            const std::string names[2], std::vector<std::string>& messages);

// Piece p on the sheet: its outline, material, cut paths, tint and creases.
PieceInfo placedPiece(const FlatPieces& flat, int p, const std::vector<Polyline>& cuts,
                      const std::vector<Polyline>& holeCuts, const Placement& place,
                      const Arrangement& a, double bleedMm);

// Each piece's ticks and tick numbers, name and crease letters, and messages for the labels left
// out.
void drawPieceLabels(const FlatPieces& flat, const Placement place[2], const Profile& profile,
                     const StrokeFont& font, DrawingBuilder& b, PatternBuild& out, BuildWork& work);

// Crease fold lines: the profile's fold style, dashed by the fold's direction.
void drawCreases(const std::vector<PieceInfo>& pieces, const Profile& profile, DrawingBuilder& b);

// The body's folds of at least o.scoreFoldsDeg through piece p (o.folds, flat mm), placed on the
// sheet and clipped to the piece's material; none without --score-folds.
std::vector<ScoredFoldInfo> scoredFolds(const ExportOptions& o, int p, const Placement& place,
                                        const PieceInfo& info);

// The scored folds as solid lines on the score layer (and the cutter's score pass).
void drawScoredFolds(const std::vector<PieceInfo>& pieces, DrawingBuilder& b);

// The cut paths, every hole before any outer cut (inner cuts first); then the printed tint.
void drawCuts(const std::vector<PieceInfo>& pieces, const std::string names[2],
              const Profile& profile, DrawingBuilder& b);

// The scale as a percentage of true size, to a tenth ("73.4 %").
std::string percentText(double scale);

// What the title lines of a pattern's sheets say: its pieces, options, scale and seam length.
struct TitleText {
  const FlatPieces& flat;
  const ExportOptions& o;
  std::string scaleText, perimeterText;
  const StrokeFont& font;
};

// A title block: its lines run along `along` from `start`, each the next one across, in
// `length` mm; `v` is how far across the lines so far reach.
struct TitleBlock {
  Vec2 along, across, start;
  double length = 0;
  double v = 0;
};

// The title lines of sheet k (of `sheets`), unless --no-title, into `layer`: the title, the note
// and the legends for creases and tabs.
void drawTitleLines(size_t k, size_t sheets, const SheetPlan& plan, const SheetFit& fit,
                    const TitleText& text, Layer& layer, TitleBlock& block);

// The title lines and, where the profile has one, the 50 mm calibration bar after them.
void drawTitleBlock(size_t k, size_t sheets, const SheetPlan& plan, const SheetFit& fit,
                    const TitleText& text, Layer& layer, TitleBlock& block);

// Title lines (and the calibration bar) under each sheet's pieces or in a column beside them;
// those of a tiled piece go on its page map, those that do not fit beside the pieces on a cover
// page before the sheet's. The registration marks in each sheet's corners.
void drawSheetFurniture(const std::vector<SheetPlan>& plans, const SheetFit& fit,
                        const TitleText& text, DrawingBuilder& b);

// The drawing's title and description (SVG <title> and <desc>, PDF title).
void describe(Drawing& drawing, const ExportOptions& o, const Profile& profile, double scale,
              const std::string& perimeterText);

// The pages: one per sheet; a tiled piece gets a page map (with its sheet's title lines), then
// its tiles.
void addPages(const std::vector<SheetPlan>& plans, const SheetFit& fit, const TitleText& text,
              PatternBuild& out);

// "an A4", "a Letter": the page's name with its article.
std::string aPage(const std::string& pageName);

}  // namespace dform::fab
