// SPDX-License-Identifier: GPL-3.0-or-later
// exportAll: the pattern laid out once, stamped FAILED GATE when asked (an overlay: nothing moves),
// every output rendered to memory, then each file written atomically, so that a failed run leaves
// no half-written file.
#include "dform/export/exporter.h"

#include <atomic>
#include <filesystem>

#include "dform/core/atomic_file.h"
#include "dform/core/interrupt.h"
#include "internal.h"
#include "pattern_parts.h"

namespace dform {

namespace {

namespace fs = std::filesystem;

Status checkFolder(const std::string& outDir) {
  std::error_code ec;
  if (!fs::is_directory(outDir, ec))
    return {ErrorCode::OutputFailed, outDir + ": the output folder does not exist"};
  return Status::ok();
}

std::atomic<long> layoutsMade{0};

// Each stage takes seconds on a fine mesh (420k triangles: the pattern with its assembly page
// 4 s, the PDF 4 s): a stop asked for meanwhile is honoured between them.
Status stopped() { return interruptedDuring("the export"); }

}  // namespace

Status checkExportOptions(const ExportOptions& o) {
  // The values the layout cannot work with at all (a tick spacing of 0 would never end): the
  // export's own guard for a caller that did not go through the settings table, which checks
  // the same ranges for a user.
  if (!(o.tickSpacingMm >= kMinTickSpacingMm))
    return Status{ErrorCode::Usage, mention(Setting::TickSpacing) + " must be at least " +
                                        fab::formatMm(kMinTickSpacingMm) + " mm"};
  if (!(o.tabWidthMm >= 0 && o.tabWidthMm <= kMaxTabWidthMm))
    return Status{ErrorCode::Usage, mention(Setting::TabWidth) + " must be between 0 and " +
                                        fab::formatMm(kMaxTabWidthMm) + " mm"};
  if (!(o.scale >= kMinPatternScale && o.scale <= kMaxPatternScale))
    return Status{ErrorCode::Usage, mention(Setting::Scale) + " must be between " +
                                        fab::formatMm(kMinPatternScale) + " and " +
                                        fab::formatMm(kMaxPatternScale)};
  if (!(o.tabAngleDeg >= 15 && o.tabAngleDeg <= 90))
    return Status{ErrorCode::Usage, "tab angle must be between 15 and 90 degrees"};
  if (!(o.tabGapMm >= 0) || !(o.tabMaxLengthMm > 0) || !(o.tabMaxTurnDeg > 0))
    return Status{ErrorCode::Usage, "tab gap, length and turn limits must be positive"};
  // A rigid sheet neither folds a tongue back through a slot nor bends without a hinge; a hinge
  // needs the material's bending figures.
  const std::optional<MaterialPreset> material = materialNamed(o.material);
  if (material && material->hinge && o.joint == Joint::Slots)
    return Status{ErrorCode::Usage,
                  mention(Setting::Joint) + " slots: " + o.material + " (" +
                      fab::formatMm(material->thicknessMm) +
                      " mm) cannot fold its tongues back through the slots; join it with holes"};
  if (o.hinge.value_or(false) && !(material && material->hingeRowMm > 0))
    return Status{ErrorCode::Usage, mention(Setting::Hinge) +
                                        ": kerf-bending cuts are for a rigid sheet material (" +
                                        rigidMaterials() + "), got " +
                                        (o.material.empty() ? std::string("none") : o.material)};
  // The holes' sizes as the pattern will use them (a material's, or the defaults, where unset),
  // against each other; each alone is in its range (the settings table).
  const fab::JointSettings j = fab::jointSettings(o, Profile{});
  if (!(j.edgeMm >= j.diameterMm))
    return Status{ErrorCode::Usage, mention(Setting::HoleEdge) +
                                        " must be at least the hole diameter (" +
                                        fab::formatMm(j.diameterMm) + " mm)"};
  if (!(j.spacingMm >= 2 * j.diameterMm))
    return Status{ErrorCode::Usage, mention(Setting::HoleSpacing) +
                                        " must be at least twice the hole diameter (" +
                                        fab::formatMm(2 * j.diameterMm) + " mm)"};
  if (o.slotLengthMm && !(*o.slotLengthMm <= j.spacingMm - j.diameterMm))
    return Status{ErrorCode::Usage, mention(Setting::SlotLength) +
                                        " must be at most the hole spacing less a hole diameter (" +
                                        fab::formatMm(j.spacingMm - j.diameterMm) + " mm)"};
  return Status::ok();
}

Status checkProfileOptions(const ExportOptions& options) {
  const Result<Profile> profile = fab::resolveProfile(options);
  return profile.isOk() ? Status::ok() : profile.status();
}

long fab::patternsLaidOut() { return layoutsMade.load(); }

bool LaidOutExport::failedGate() const { return pattern && pattern->build.failedGate; }

namespace {

Result<LaidOutExport> layOutOrThrow(const DForm& model, const ExportOptions& options) {
  auto profile = fab::resolveProfile(options);
  if (!profile.isOk()) return profile.status();
  ++layoutsMade;
  auto pattern = fab::buildPattern(model, options, profile.value());
  if (!pattern.isOk()) return pattern.status();
  if (interruptRequested()) return stopped();
  auto font = fab::StrokeFont::load(options.fontPath);  // read by the build already: it loads
  if (!font.isOk()) return font.status();
  LaidOutExport laidOut;
  laidOut.layout = fab::checkLayout(pattern.value());
  laidOut.ticks = fab::seamTicks(model, pattern.value());
  laidOut.pattern = std::make_shared<const fab::LaidOutPattern>(
      fab::LaidOutPattern{std::move(pattern.value()), std::move(font.value()), options});
  return laidOut;
}

}  // namespace

// A stop inside the layout's or the rendering's pictures (they poll the stop flag and throw) ends
// the export as a stop between its steps does.
Result<LaidOutExport> layOutExport(const DForm& model, const ExportOptions& options) {
  try {
    return layOutOrThrow(model, options);
  } catch (const Interrupted&) {
    return stopped();
  }
}

LaidOutExport markFailedGate(const LaidOutExport& laidOut) {
  if (!laidOut.pattern || laidOut.failedGate()) return laidOut;
  auto marked = std::make_shared<fab::LaidOutPattern>(*laidOut.pattern);
  fab::stampFailedGate(marked->build, marked->font);
  LaidOutExport out = laidOut;
  out.pattern = std::move(marked);
  return out;
}

Result<PreparedExport> fab::renderPattern(const LaidOutExport& laidOut) {
  if (!laidOut.pattern) return Status(ErrorCode::Internal, "renderPattern: nothing laid out");
  const fab::PatternBuild& pat = laidOut.pattern->build;
  auto pdf = fab::pdfDocument(pat);
  if (!pdf.isOk()) return pdf.status();
  if (interruptRequested()) return stopped();
  PreparedExport prepared;
  prepared.files = {
      {"pattern.svg", fab::svgDocument(pat.drawing)},
      {"pattern.dxf", fab::dxfDocument(pat.drawing)},
      {"pattern.pdf", pdf.value()},
      {"pattern.json", fab::sidecarJson(pat, laidOut.pattern->options.jobName)},
  };
  // A pattern on several sheets (pages): each also alone, at its own size, for the machine, as
  // SVG and as DXF.
  if (pat.sheets.size() > 1)
    for (size_t k = 0; k < pat.sheets.size(); ++k) {
      const fab::Drawing sheet = fab::sheetDrawing(pat.drawing, pat.sheets[k]);
      prepared.files.emplace_back(sheetFileName(int(k) + 1, "svg"), fab::svgDocument(sheet));
      prepared.files.emplace_back(sheetFileName(int(k) + 1, "dxf"), fab::dxfDocument(sheet));
    }
  // For a cutter's software that takes the print as an image: each page's print as a PNG and its
  // cut line alone as an SVG of the same frame.
  if (pat.profile.printPngDpi > 0)
    for (size_t k = 0, sheet = 0; k < pat.pages.size(); ++k) {
      if (pat.pages[k].kind != "sheet") continue;
      auto png = fab::printPng(pat, int(k), pat.profile.printPngDpi);
      if (!png.isOk()) return png.status();
      ++sheet;
      prepared.files.emplace_back(printSheetFileName(int(sheet), "png"), png.value());
      prepared.files.emplace_back(printSheetFileName(int(sheet), "svg"), fab::cutSvg(pat, int(k)));
    }
  prepared.layout = laidOut.layout;
  prepared.ticks = laidOut.ticks;
  ExportSummary& summary = prepared.summary;
  summary.messages = pat.messages;
  summary.warnings = pat.warnings;
  summary.profile = pat.profile.name;
  if (pat.pieces.size() == 2) {
    summary.perimeterA = pat.pieces[0].perimeter;
    summary.perimeterB = pat.pieces[1].perimeter;
  }
  summary.sheetWidthMm = pat.drawing.width;
  summary.sheetHeightMm = pat.drawing.height;
  summary.ticks = int(pat.ticks.size());
  summary.tabs = int(pat.tabs.size());
  for (const fab::PieceInfo& piece : pat.pieces) summary.creases += int(piece.creases.size());
  summary.jointHoles = int(pat.jointHoles.size());
  summary.jointSlots = int(pat.jointSlots.size());
  summary.pages = int(pat.pages.size());
  summary.pieces = int(pat.pieces.size());
  summary.sheets = int(pat.sheets.size());
  return prepared;
}

namespace {

Result<PreparedExport> renderOrThrow(const DForm& model, const LaidOutExport& laidOut) {
  if (!laidOut.pattern) return Status(ErrorCode::Internal, "renderExport: nothing laid out");
  const fab::PatternBuild& pat = laidOut.pattern->build;
  ExportOptions options = laidOut.pattern->options;
  options.failedGateMark = pat.failedGate;  // the previews' names and header say so too
  Result<PreparedExport> prepared = fab::renderPattern(laidOut);
  if (!prepared.isOk()) return prepared;
  auto gltf = fab::gltfDocument(model, options);
  if (!gltf.isOk()) return gltf.status();
  if (interruptRequested()) return stopped();
  std::vector<std::pair<std::string, std::string>>& files = prepared.value().files;
  files.insert(files.begin() + 3, {"assembly.svg", fab::svgDocument(pat.assembly)});
  files.insert(files.begin() + 5, {"dform.stl", fab::stlDocument(model, pat.failedGate)});
  files.insert(files.begin() + 6, {options.gltfBinary ? "dform.glb" : "dform.gltf", gltf.value()});
  prepared.value().summary.triangles = int(model.a.F.rows() + model.b.F.rows());
  return prepared;
}

}  // namespace

Result<PreparedExport> renderExport(const DForm& model, const LaidOutExport& laidOut) {
  try {
    return renderOrThrow(model, laidOut);
  } catch (const Interrupted&) {
    return stopped();
  }
}

Result<PreparedExport> prepareExport(const DForm& model, const ExportOptions& options) {
  Result<LaidOutExport> laidOut = layOutExport(model, options);
  if (!laidOut.isOk()) return laidOut.status();
  return renderExport(model,
                      options.failedGateMark ? markFailedGate(laidOut.value()) : laidOut.value());
}

Result<ExportSummary> writeExport(const PreparedExport& prepared, const std::string& outDir) {
  if (Status s = checkFolder(outDir); !s.isOk()) return s;
  ExportSummary summary = prepared.summary;
  for (const auto& [name, content] : prepared.files) {
    const std::string path = (fs::path(outDir) / name).string();
    if (Status s = writeFileAtomically(path, content); !s.isOk()) return s;
    summary.files.push_back(path);
  }
  return summary;
}

std::vector<std::string> exportFileNames() {
  // A D-Form has two pieces, so a pattern takes at most two sheets.
  return {"pattern.svg",
          "pattern.dxf",
          "pattern.pdf",
          "assembly.svg",
          "pattern.json",
          "dform.stl",
          "dform.glb",
          "dform.gltf",
          sheetFileName(1, "svg"),
          sheetFileName(2, "svg"),
          sheetFileName(1, "dxf"),
          sheetFileName(2, "dxf"),
          printSheetFileName(1, "png"),
          printSheetFileName(2, "png"),
          printSheetFileName(1, "svg"),
          printSheetFileName(2, "svg")};
}

Result<ExportSummary> exportAll(const DForm& model, const ExportOptions& options,
                                const std::string& outDir) {
  if (Status s = checkFolder(outDir); !s.isOk()) return s;
  Result<PreparedExport> prepared = prepareExport(model, options);
  if (!prepared.isOk()) return prepared.status();
  return writeExport(prepared.value(), outDir);
}

Status renderPatternPng(const DForm& model, const ExportOptions& options,
                        const std::string& pngPath, double dpi, int page) {
  auto profile = fab::resolveProfile(options);
  if (!profile.isOk()) return profile.status();
  auto pattern = fab::buildPattern(model, options, profile.value());
  if (!pattern.isOk()) return pattern.status();
  if (options.failedGateMark) {
    auto font = fab::StrokeFont::load(options.fontPath);
    if (!font.isOk()) return font.status();
    fab::stampFailedGate(pattern.value(), font.value());
  }
  auto png = fab::pngImage(pattern.value(), page, dpi);
  if (!png.isOk()) return png.status();
  return writeFileAtomically(pngPath, png.value());
}

}  // namespace dform
