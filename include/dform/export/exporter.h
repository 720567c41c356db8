// SPDX-License-Identifier: GPL-3.0-or-later
// Fabrication export of a solved D-Form: cut-ready flat patterns (SVG written by our own writer,
// DXF through dxflib, PDF through Cairo) with seam tick marks and glue tabs, and 3D previews
// (binary STL, glTF 2.0).
// Works on any DForm (forward or inverse modelling); it never looks at the solver.
// What each file holds, the profiles and the error codes: docs/export.md.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"

namespace dform {

namespace fab {
struct LaidOutPattern;  // export-internal (export/internal.h)
}

/// What kind of machine a profile is for.
enum class ProfileKind {
  Laser,        ///< hairline strokes, one colour per operation (cut, score, engrave)
  Print,        ///< visible line weights for paper and scissors, tiled across pages if needed
  PrintAndCut,  ///< printed artwork plus a cut layer, with the cutter's registration marks
};

/// How the fold line between a piece and its glue tab is drawn.
enum class FoldStyle {
  Score,       ///< a solid line in the score colour (laser score pass, pen)
  Dashed,      ///< a dashed printed line (visual only; cutters ignore dashes)
  Perforated,  ///< real cut segments in the cut layer, for card stock on a blade or laser
};

/// Registration marks for print-and-cut.
enum class Registration {
  None,
  Silhouette,  ///< Silhouette "type 1": 5 mm square and two 20 mm L-marks, 0.3 mm lines
  Cricut,      ///< no marks (Design Space adds its own); artwork within the 6.75 x 9.25 in area
};

/// Which piece gets the glue tabs.
enum class TabSide {
  A,          ///< every tab on piece A
  B,          ///< every tab on piece B
  Alternate,  ///< tabs alternate between A and B along the seam
  None,       ///< no tabs: the pieces are glued edge to edge (or taped)
};

/// The side's name in profiles and on the command line: "a", "b", "alternate", "none".
const char* tabSideName(TabSide side);

/// The side called `name` (as tabSideName writes it), or nullopt.
std::optional<TabSide> tabSideNamed(const std::string& name);

/// Every side's name, in the order of TabSide.
std::vector<std::string> tabSideNames();

/// Where a tick's number is printed.
enum class TickNumbers {
  Face,  ///< inside the piece, beside its tick (seen on the finished D-Form)
  Tabs,  ///< on the glue tab over the tick, where it has one (hidden once glued), else the face
  Both,  ///< on the tab and on the face
};

/// The place's name in profiles and on the command line: "face", "tabs", "both".
const char* tickNumbersName(TickNumbers numbers);

/// The place called `name` (as tickNumbersName writes it), or nullopt.
std::optional<TickNumbers> tickNumbersNamed(const std::string& name);
/// Every place's name, in the order of TickNumbers.
std::vector<std::string> tickNumbersNames();

/// How the pieces are joined along the seam.
enum class Joint {
  Glue,   ///< glue tabs (or edge to edge): paper and card
  Holes,  ///< matched hole pairs on A and B at the same seam points: ties, rivets, stitches
  Lace,   ///< lacing holes, B's halfway between A's along the seam: a zigzag lace
  /// tongues on A through slots in B where both seams are straight enough, hole pairs elsewhere:
  /// stiff sheets joined without ties
  Slots,
};

/// The joint's name in profiles and on the command line: "glue", "holes", "lace", "slots".
const char* jointName(Joint joint);

/// The joint called `name` (as jointName writes it), or nullopt.
std::optional<Joint> jointNamed(const std::string& name);

/// Every joint's name, in the order of Joint.
std::vector<std::string> jointNames();

/// A sheet material (--material): its thickness and the joint it is usually made with.
struct MaterialPreset {
  std::string name;           ///< "paper", "card", "polypropylene", "plywood"
  double thicknessMm = 0;     ///< nominal thickness (mm)
  Joint joint = Joint::Glue;  ///< the joint a sheet of it is usually made with
  double holeSpacingMm = 15;  ///< holes and lace: largest distance between neighbouring holes (mm)
  double holeDiameterMm = 2;  ///< holes and lace: the holes' diameter (mm)
  double holeEdgeMm = 3;      ///< holes and lace: seam to hole centre (mm)
  /// Kerf-bending (living-hinge) cuts where the shape bends, by default: a sheet too stiff to
  /// bend to the D-Form without them.
  bool hinge = false;
  /// The hinge's rows of cuts: no closer than this (mm, centre to centre: the links between rows
  /// about as wide as the sheet is thick, and a kerf), each row bending by at most
  /// hingeRowDeg degrees; so the tightest radius the hinge allows is hingeRowMm / hingeRowDeg.
  double hingeRowMm = 0;
  double hingeRowDeg = 0;  ///< the most one row of hinge cuts bends (degrees)
};

/// The preset called `name`, or nullopt; materialNames lists them ("paper, card, ...").
std::optional<MaterialPreset> materialNamed(const std::string& name);
/// Every preset's name, comma-separated, for messages ("paper, card, polypropylene, plywood").
std::string materialNames();
/// Every preset's name, in materialNames' order.
std::vector<std::string> materialPresetNames();

/// The ranges of the user's export options (the settings table checks them, pipeline/settings.h;
/// a profile's kerf_mm is held to the same range).
constexpr double kMaxKerfMm = 5;            ///< the cutter's kerf (mm), from 0
constexpr double kMaxTabWidthMm = 50;       ///< glue tab width (mm), from 0
constexpr double kMinTickSpacingMm = 1;     ///< seam length between numbered ticks (mm)
constexpr double kMinPatternScale = 0.05;   ///< the pattern's scale (5 %) ...
constexpr double kMaxPatternScale = 20;     ///< ... to 20 times true size
constexpr double kMinHoleDiameterMm = 0.5;  ///< joint holes' diameter (mm) ...
constexpr double kMaxHoleDiameterMm = 20;   ///< ... up to this
constexpr double kMaxHoleEdgeMm = 50;       ///< seam to hole centres (mm), from the diameter
constexpr double kMaxHoleSpacingMm = 1000;  ///< between holes (mm), from twice the diameter
constexpr double kMinSlotLengthMm = 2;      ///< a tongue's width (mm), to spacing - diameter

/// The presets of sheets too stiff to bend without a hinge ("plywood").
std::string rigidMaterials();

/// A machine profile, read from `templates/profiles/<name>.json` (see docs/export.md). Every field
/// has a default; a profile file may leave any field out.
struct Profile {
  std::string name = "laser";             ///< the profile's name
  std::string source;                     ///< the file it was read from, for messages
  std::string description;                ///< one line for people
  ProfileKind kind = ProfileKind::Laser;  ///< what the profile's machine does: cut, print, or both
  std::string cutColor = "#FF0000";       ///< cut operation colour, #RRGGBB
  std::string scoreColor = "#0000FF";     ///< score / fold / tick colour, #RRGGBB
  std::string engraveColor = "#000000";   ///< labels colour, #RRGGBB
  double cutWidthMm = 0.025;              ///< stroke width of cut lines (mm)
  double scoreWidthMm = 0.025;            ///< stroke width of score lines and ticks (mm)
  double engraveWidthMm = 0.025;          ///< stroke width of single-stroke labels (mm)
  FoldStyle fold = FoldStyle::Score;  ///< how fold lines are drawn (score, perforated, dashed...)
  double perforationCutMm = 1.0;      ///< perforated fold: length of each cut (mm)
  double perforationGapMm = 1.0;      ///< perforated fold: length of each bridge (mm)
  double dashMm = 3.0;                ///< dashed fold: dash and gap length (mm)
  double marginMm = 5.0;  ///< clear margin at the sheet/page edges and between pieces (mm)
  std::string page;       ///< "" = the sheet from ExportOptions; a page name (pageSizeMm) otherwise
  bool tile = false;      ///< page profiles: tile a pattern larger than a page
  double tileOverlapMm = 10.0;                     ///< overlap between neighbouring tiles (mm)
  Registration registration = Registration::None;  ///< the cutter's marks, for print-and-cut
  /// Silhouette: clear space (mm) between the artwork and the marks' inner edges (the square's
  /// far side, 15 mm from the edges), so the artwork keeps 15 mm + this from every page edge.
  double registrationClearMm = 5.0;
  bool calibrationBar = false;  ///< draw a 50 mm calibration bar with "print at 100%"
  /// Print-and-cut: each piece is printed as a tint (fillColorA, fillColorB) reaching this far
  /// outside its cut line, so that a cut a little off its line leaves no white edge; 0 = no tint.
  /// While it is on, the outline is not printed on the cut line, where an off cut would show it.
  double bleedMm = 0.0;
  /// Print-and-cut for a RIP (Roland VersaWorks, Mimaki RasterLink): the cut line is written into
  /// pattern.pdf as this spot colour (a Separation colour space, e.g. "CutContour"), which the RIP
  /// sends to the cutter and does not print; the SVG's cut layer is named after it. "" = none.
  std::string cutSpotColor;
  /// Print-and-cut: each page's print also written as a PNG at this resolution (dots per inch,
  /// 72 to 1200), transparent around the print, with the cut outline alone as an SVG of the same
  /// frame (Cricut Design Space); 0 = none.
  double printPngDpi = 0;
  std::string fillColorA = "#FFE6CC";  ///< piece A's tint, #RRGGBB (the 3D preview's A)
  std::string fillColorB = "#CCE6FF";  ///< piece B's tint, #RRGGBB (the 3D preview's B)
  double labelHeightMm = 3.0;          ///< cap height of tick numbers (mm); piece names are 3x
  /// The cutter's kerf (mm, the width of material the beam removes): cut paths are offset by
  /// half of it away from the material, so that the parts come out at their drawn size.
  double kerfMm = 0.0;
  TabSide tabs = TabSide::A;                ///< which piece gets the glue tabs
  TickNumbers numbers = TickNumbers::Face;  ///< where the ticks' numbers are printed
  Joint joint = Joint::Glue;  ///< how the pieces are joined (a material or --joint overrides)
};

/// Reads a profile: `nameOrPath` is a profile name (looked up as
/// `<templatesDir>/profiles/<name>.json`) or a path to a .json file. Usage when the name is
/// unknown (the message lists the known ones), InputUnreadable when the file is missing or not
/// JSON, InputInvalid naming the file and field when a field is unknown, mistyped or out of range.
Result<Profile> loadProfile(const std::string& nameOrPath, const std::string& templatesDir);

/// A profile from the text of its file; `source` names it in messages. The same codes as
/// loadProfile, except that an empty name stays empty (loadProfile names it after the file).
Result<Profile> parseProfileJson(const std::string& text, const std::string& source);

/// The profile names found in `<templatesDir>/profiles/`, sorted.
std::vector<std::string> listProfiles(const std::string& templatesDir);

/// The size (width, height in mm, portrait) of a page called `name`: "A4", "A3", "Letter",
/// "Tabloid", or "WxH" with a unit mm, cm or in ("200x300mm"), in any case ("a4", "200x300MM");
/// nullopt for anything else.
std::optional<std::pair<double, double>> pageSizeMm(const std::string& name);

/// A page name as pageSizeMm reads it, spelt the one way: "a4" -> "A4", "200X300MM" ->
/// "200x300mm".
std::string pageName(const std::string& name);

/// The file of sheet `sheet` (1-based) alone, written when a pattern takes more than one sheet or
/// page: "pattern-sheet-1.svg" for (1, "svg"), "pattern-sheet-1.dxf" for (1, "dxf").
std::string sheetFileName(int sheet, const std::string& extension);

/// A print-and-cut profile with print_png_dpi: sheet (page) `sheet`'s print as an image,
/// "print-sheet-1.png" for (1, "png"), and its cut line alone, "cut-sheet-1.svg" for (1, "svg").
std::string printSheetFileName(int sheet, const std::string& extension);

/// A fold of the solved body through a flat piece (report.json's model.folds), to score.
struct FoldToScore {
  int piece = 0;                                   ///< 0 = A, 1 = B
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< one end in the piece's flat frame (mm)
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    ///< the other end
  double angleDeg = 0;                             ///< fold angle (degrees; 0 = flat)
  bool crease = false;  ///< a found crease (drawn as the piece's crease line, never scored)
};

/// What an export makes and how: the profile, the sheet or page, the glue tabs, ticks, joint,
/// hinge and scale, and the folds to score. Lengths in mm, angles in degrees.
struct ExportOptions {
  std::string profile = "laser";    ///< profile name or path to a profile .json
  std::string templatesDir;         ///< folder holding profiles/ (the CLI passes the install path)
  Profile profileOverride;          ///< used instead of loading when useProfileOverride is set
  bool useProfileOverride = false;  ///< use profileOverride (tests, callers that built one)
  double sheetWidthMm = 600;        ///< material sheet width (mm); page profiles use their page
  double sheetHeightMm = 400;       ///< material sheet height (mm)
  /// The sheet size was asked for (--sheet): a page profile refuses it rather than ignore it.
  bool sheetGiven = false;
  /// Page profiles: the page (a pageSizeMm name) instead of the profile's; "" = the profile's.
  std::string page;
  double tickSpacingMm = 20;       ///< seam arc length between numbered ticks (mm)
  double tabWidthMm = 6;           ///< glue tab width (mm); 0 = no tabs
  double tabAngleDeg = 45;         ///< angle of the tab ends against the fold line (degrees)
  double tabMaxTurnDeg = 25;       ///< max turning of the seam along one tab (degrees)
  double tabMaxLengthMm = 40;      ///< max length of one tab along the seam (mm)
  double tabGapMm = 1.5;           ///< gap between neighbouring tabs along the seam (mm)
  std::optional<TabSide> tabSide;  ///< which piece gets the glue tabs; unset: the profile's
  /// Where the ticks' numbers go (the face, the glue tabs, both); unset: the profile's.
  std::optional<TickNumbers> numbers;
  /// The cutter's kerf (mm, 0 to 5; cut paths move half of it); unset: the profile's.
  std::optional<double> kerfMm;
  /// --joint: how the pieces are joined; unset: the material's, else the profile's. With holes,
  /// lace or slots the glue tabs are off unless tabSide asks for them (slots: on B only, since
  /// A's seam carries the tongues).
  std::optional<Joint> joint;
  std::string material;  ///< --material: a materialNamed preset; "" none
  /// Joint holes (mm): the largest distance between neighbouring holes (or slots) on a piece along
  /// the seam, the holes' diameter and the distance from the seam to their centres (slots': to
  /// their middle line); unset: the material's, else 15, 2 and 3.
  std::optional<double> holeSpacingMm;
  std::optional<double> holeDiameterMm;  ///< the joint holes' diameter (mm); see holeSpacingMm
  std::optional<double> holeEdgeMm;      ///< seam to the holes' centres (mm); see holeSpacingMm
  /// --slot-length: a tongue's width along the seam (mm), its slot that and a clearance; unset:
  /// half the hole spacing. A tongue and its slot sit where a hole pair would.
  std::optional<double> slotLengthMm;
  /// --score-folds: every fold of `folds` of at least this angle (degrees) becomes an optional
  /// score line on its piece (SCORE layer, pattern.json); unset: none.
  std::optional<double> scoreFoldsDeg;
  std::vector<FoldToScore> folds;  ///< the body's folds; empty when the model knows none
  /// Kerf-bending cuts across each piece where the solved shape bends, parallel to the body's
  /// folds (`folds`); unset: the material's (on for plywood).
  std::optional<bool> hinge;
  std::string jobName = "dform";  ///< printed in the title line and file metadata
  bool title = true;              ///< the title block and notes on each sheet (--no-title: none)
  /// Scale of the pattern (1 = true size): the pieces are scaled, tabs, ticks and labels keep
  /// their size; the scale is printed in the title line and written in pattern.json.
  double scale = 1.0;
  /// When the pieces do not fit at `scale`, use the largest smaller scale (to 0.1 %) at which
  /// they do, and say so (--scale fit).
  bool scaleToFit = false;
  /// prepareExport, exportAll, renderPatternPng: stamp every output FAILED GATE (markFailedGate)
  bool failedGateMark = false;
  /// Optional per-vertex Gaussian curvature of A for the glTF's COLOR_0, in any unit (the map is
  /// scaled by its 95th percentile), e.g. validate's curvatureMap (angle defect, radians).
  std::vector<double> curvatureA;
  std::vector<double> curvatureB;  ///< the same for B
  bool gltfBinary = true;          ///< dform.glb (true) or dform.gltf with embedded buffer
  std::string fontPath = "/usr/share/hershey-fonts/futural.jhf";  ///< Hershey single-stroke font
};

/// Checks the option values that do not depend on the model or the profile and that the settings
/// table does not (the tabs' angle, gap and limits, and the joint sizes against each other: a
/// hole's edge distance and spacing against its diameter, a slot's length against the spacing),
/// and guards the layout against values it cannot work with (a tick spacing, tab width or scale
/// outside the ranges above): Usage with a one-line message naming the setting otherwise. Every
/// export checks them; a caller may check them before it has a model.
Status checkExportOptions(const ExportOptions& options);

/// The options against their profile (options.profile, or the override), before anything is
/// solved: Usage for a kerf on a profile cut by hand, glue tabs where slots' tongues go, or a
/// profile that cannot be read.
Status checkProfileOptions(const ExportOptions& options);

/// What an export wrote: its files, notes and warnings, the canvas, and the layout's checks.
struct ExportSummary {
  std::vector<std::string> files;     ///< every file written, full paths
  std::vector<std::string> messages;  ///< notes for the user (dropped tabs, perimeter mismatch)
  /// What the pattern cannot do as asked: a hinge's folds bending more tightly than the material
  std::vector<std::string> warnings;
  std::string profile;       ///< the profile's name
  double perimeterA = 0;     ///< piece A's flat seam length (mm)
  double perimeterB = 0;     ///< piece B's flat seam length (mm)
  double sheetWidthMm = 0;   ///< the pattern canvas's width (mm)
  double sheetHeightMm = 0;  ///< the pattern canvas's height (mm)
  int ticks = 0;             ///< tick pairs
  int tabs = 0;              ///< glue tabs on both pieces
  int creases = 0;           ///< crease fold lines on both pieces
  int jointHoles = 0;        ///< joint holes on both pieces
  int jointSlots = 0;        ///< tongue and slot pairs (--joint slots)
  int pages = 0;      ///< pattern pages (more than 1 when tiled or one piece per page); the PDF has
                      ///< the assembly page after them
  int triangles = 0;  ///< triangles in the STL (both pieces)
  int pieces = 0;     ///< pieces on the sheets (2, or a nest's)
  int sheets = 0;     ///< sheets (pages) the pieces are laid out on
};

/// What the layout check measured on the laid-out pattern (the fabrication part of the quality
/// gate): every count is 0 on a pattern fit to cut.
struct LayoutFindings {
  int outsideSheet = 0;       ///< drawn paths with a point off the sheet
  int overlappingTabs = 0;    ///< pairs of glue tabs sharing area
  int tabsOverPieces = 0;     ///< (tab, piece) pairs sharing area
  int overlappingPieces = 0;  ///< pairs of pieces whose cut paths share area
  int labelsOutside = 0;      ///< labels not wholly inside their piece's outline
  int overlappingLabels = 0;  ///< pairs of labels whose footprints (convex hulls) share area
  /// (title block or calibration bar line, piece or registration mark) pairs sharing area
  int titleOverlaps = 0;
  /// Closed cut loops beyond one per boundary loop of each piece (its outline and its holes): a
  /// glue tab or a sliver the cutter would cut free of its piece
  int extraCutLoops = 0;
  std::string example;  ///< the first problem found, in words; empty when none
  /// The number of problems of every kind together; 0 for a pattern that can be cut as laid out.
  int problems() const {
    return outsideSheet + overlappingTabs + tabsOverPieces + overlappingPieces + labelsOutside +
           overlappingLabels + titleOverlaps + extraCutLoops;
  }
};

/// A pattern laid out (sheets, the pieces' arrangement, ticks, tabs, labels, title block, pages
/// and tiles, the assembly page) and checked, not yet rendered. Everything geometric is decided
/// here; marking it FAILED GATE afterwards moves nothing. Cheap to copy: the pattern is shared.
struct LaidOutExport {
  std::shared_ptr<const fab::LaidOutPattern> pattern;  ///< the layout, its font and options
  LayoutFindings layout;        ///< the layout check (a stamp, added later, is not part of it)
  std::vector<SeamTick> ticks;  ///< the pattern's numbered ticks on the 3D seam
  bool failedGate() const;      ///< stamped by markFailedGate
};

/// Lays out the pattern of `model` and checks the layout, once; nothing is rendered. The same
/// errors as exportAll except the folder's and the renderers'.
Result<LaidOutExport> layOutExport(const DForm& model, const ExportOptions& options);

/// The same layout stamped "FAILED GATE - NOT FOR FABRICATION" as an overlay: on every sheet of
/// pattern.svg and pattern.dxf (a layer of its own, first), every page and tile of pattern.pdf
/// and the assembly page, in the free margin above (or below) what each shows and in a colour no
/// profile cuts or scores with; the STL header, the glTF names and pattern.json's `failed_gate`
/// say so when rendered. Nothing moves: every other path is as laid out. `laidOut` is unchanged.
LaidOutExport markFailedGate(const LaidOutExport& laidOut);

/// Every output rendered in memory, not yet written, with the layout check of its pattern.
struct PreparedExport {
  std::vector<std::pair<std::string, std::string>> files;  ///< file name -> content
  ExportSummary summary;                                   ///< `files` still empty
  LayoutFindings layout;                                   ///< the layout's checks of the pattern
  std::vector<SeamTick> ticks;  ///< the pattern's numbered ticks on the 3D seam
};

/// Renders everything exportAll writes from a laid-out pattern of `model` (the model it was laid
/// out from: the STL and glTF previews are drawn from its meshes). OutputFailed when Cairo fails,
/// Usage for curvature arrays of the wrong size.
Result<PreparedExport> renderExport(const DForm& model, const LaidOutExport& laidOut);

/// layOutExport, markFailedGate when options.failedGateMark, then renderExport. The same errors
/// as exportAll except the folder's.
Result<PreparedExport> prepareExport(const DForm& model, const ExportOptions& options);

/// Writes a prepared export into `outDir` (which must exist), each file atomically.
Result<ExportSummary> writeExport(const PreparedExport& prepared, const std::string& outDir);

/// The names of every file an export may write (for removing a previous run's).
std::vector<std::string> exportFileNames();

/// prepareExport then writeExport. Writes into `outDir` (which must exist): pattern.svg,
/// pattern.dxf (mm, y up, layers CUT/SCORE/ENGRAVE), pattern.pdf (one page per tile, or per
/// piece, then the assembly page), assembly.svg (the assembly page alone), pattern.json (sidecar:
/// outlines, ticks, tabs in sheet mm), dform.stl and dform.glb (or dform.gltf), and with two
/// sheets each alone (pattern-sheet-k.svg/.dxf). Each file is written atomically. Usage for a
/// bad option or a sheet too small (the message gives the size needed), InputInvalid for a model
/// that cannot be exported, OutputFailed for an unwritable folder, and loadProfile's codes.
Result<ExportSummary> exportAll(const DForm& model, const ExportOptions& options,
                                const std::string& outDir);

/// One D-Form of a nest (layOutNest): its model, the job its pieces are labelled with, how many
/// copies of it to cut, and its body's folds (for score lines).
struct NestItem {
  const DForm* model = nullptr;    ///< the solved D-Form, owned by the caller
  std::string jobName;             ///< the job's name, printed on its pieces
  int copies = 1;                  ///< how many copies of it to cut, at least 1
  std::vector<FoldToScore> folds;  ///< its body's folds, for score lines; empty when none
};

/// Every piece of `items` (each D-Form `copies` times) on as few sheets of the options' sheet (a
/// page profile: its page) as hold them, `kerf + 1` mm apart, each turned by a quarter where that
/// packs better, labelled with its D-Form ("ellipses-A", a later copy "ellipses-copy2-A"); each
/// sheet with the mark (the options' job name over the 50 mm bar) and the title lines where they
/// fit; checked by the layout check. Usage when a piece fits the sheet at neither turn, or for
/// no items or a copy count below 1; the errors of layOutExport.
Result<LaidOutExport> layOutNest(const std::vector<NestItem>& items, const ExportOptions& options);

/// A laid-out nest's files in memory: pattern.svg, pattern.dxf, pattern.pdf (a page per sheet),
/// pattern.json (with `nest`: each part's job, copy, piece and sheet), and each sheet's SVG and
/// DXF when there is more than one.
Result<PreparedExport> renderNest(const LaidOutExport& laidOut);

/// Renders the pattern's page `page` (0-based; tiles of a print profile are pages, and the page
/// after the last is the assembly page) to a PNG at
/// `dpi` pixels per inch, white background, hairlines drawn at least one pixel wide.
Status renderPatternPng(const DForm& model, const ExportOptions& options,
                        const std::string& pngPath, double dpi = 96, int page = 0);

}  // namespace dform
