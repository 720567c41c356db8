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

namespace {

Result<PreparedExport> renderOrThrow(const DForm& model, const LaidOutExport& laidOut) {
  if (!laidOut.pattern) return Status(ErrorCode::Internal, "renderExport: nothing laid out");
  const fab::PatternBuild& pat = laidOut.pattern->build;
  ExportOptions options = laidOut.pattern->options;
  options.failedGateMark = pat.failedGate;  // the previews' names and header say so too
  auto pdf = fab::pdfDocument(pat);
  if (!pdf.isOk()) return pdf.status();
  if (interruptRequested()) return stopped();
  auto gltf = fab::gltfDocument(model, options);
  if (!gltf.isOk()) return gltf.status();
  if (interruptRequested()) return stopped();
  PreparedExport prepared;
  prepared.files = {
      {"pattern.svg", fab::svgDocument(pat.drawing)},
      {"pattern.dxf", fab::dxfDocument(pat.drawing)},
      {"pattern.pdf", pdf.value()},
      {"assembly.svg", fab::svgDocument(pat.assembly)},
      {"pattern.json", fab::sidecarJson(pat, options.jobName)},
      {"dform.stl", fab::stlDocument(model, pat.failedGate)},
      {options.gltfBinary ? "dform.glb" : "dform.gltf", gltf.value()},
  };
  // A pattern on several sheets (pages): each also alone, at its own size, for the machine, as
  // SVG and as DXF.
  if (pat.sheets.size() > 1)
    for (size_t k = 0; k < pat.sheets.size(); ++k) {
      const fab::Drawing sheet = fab::sheetDrawing(pat.drawing, pat.sheets[k]);
      prepared.files.emplace_back(sheetFileName(int(k) + 1, "svg"), fab::svgDocument(sheet));
      prepared.files.emplace_back(sheetFileName(int(k) + 1, "dxf"), fab::dxfDocument(sheet));
    }
  prepared.layout = laidOut.layout;
  prepared.ticks = laidOut.ticks;
  ExportSummary& summary = prepared.summary;
  summary.messages = pat.messages;
  summary.profile = pat.profile.name;
  summary.perimeterA = pat.pieces[0].perimeter;
  summary.perimeterB = pat.pieces[1].perimeter;
  summary.sheetWidthMm = pat.drawing.width;
  summary.sheetHeightMm = pat.drawing.height;
  summary.ticks = int(pat.ticks.size());
  summary.tabs = int(pat.tabs.size());
  summary.creases = int(pat.pieces[0].creases.size() + pat.pieces[1].creases.size());
  summary.jointHoles = int(pat.jointHoles.size());
  summary.jointSlots = int(pat.jointSlots.size());
  summary.pages = int(pat.pages.size());
  summary.triangles = int(model.a.F.rows() + model.b.F.rows());
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
          sheetFileName(2, "dxf")};
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
