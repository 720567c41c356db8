// exportAll: every output rendered to memory first, then each file written atomically, so that a
// failed run leaves no half-written file.
#include "export/exporter.h"

#include <filesystem>

#include "core/atomic_file.h"
#include "core/interrupt.h"
#include "export/internal.h"

namespace dform {

namespace {

namespace fs = std::filesystem;

Status checkFolder(const std::string& outDir) {
  std::error_code ec;
  if (!fs::is_directory(outDir, ec))
    return {ErrorCode::OutputFailed, outDir + ": the output folder does not exist"};
  return Status::ok();
}

}  // namespace

Status checkExportOptions(const ExportOptions& o) {
  if (!(o.tickSpacingMm >= 1.0))
    return Status{ErrorCode::Usage, "tick spacing must be at least 1 mm"};
  if (!(o.tabWidthMm >= 0 && o.tabWidthMm <= 50))
    return Status{ErrorCode::Usage, "tab width must be between 0 and 50 mm"};
  if (!(o.tabAngleDeg >= 15 && o.tabAngleDeg <= 90))
    return Status{ErrorCode::Usage, "tab angle must be between 15 and 90 degrees"};
  if (!(o.tabGapMm >= 0) || !(o.tabMaxLengthMm > 0) || !(o.tabMaxTurnDeg > 0))
    return Status{ErrorCode::Usage, "tab gap, length and turn limits must be positive"};
  if (!(o.scale >= 0.05 && o.scale <= 20))
    return Status{ErrorCode::Usage, "scale must be between 0.05 (5%) and 20"};
  return Status::ok();
}

Result<PreparedExport> prepareExport(const DForm& model, const ExportOptions& options) {
  auto profile = fab::resolveProfile(options);
  if (!profile.isOk()) return profile.status();
  // Each stage takes seconds on a fine mesh (420k triangles: the pattern with its assembly page
  // 4 s, the PDF 4 s): a stop asked for meanwhile is honoured between them.
  const Status stopped(ErrorCode::Interrupted, "interrupted during the export");
  auto pattern = fab::buildPattern(model, options, profile.value());
  if (!pattern.isOk()) return pattern.status();
  const fab::PatternBuild& pat = pattern.value();
  if (interruptRequested()) return stopped;
  auto pdf = fab::pdfDocument(pat);
  if (!pdf.isOk()) return pdf.status();
  if (interruptRequested()) return stopped;
  auto gltf = fab::gltfDocument(model, options);
  if (!gltf.isOk()) return gltf.status();
  if (interruptRequested()) return stopped;
  PreparedExport prepared;
  prepared.files = {
      {"pattern.svg", fab::svgDocument(pat.drawing)},
      {"pattern.dxf", fab::dxfDocument(pat.drawing)},
      {"pattern.pdf", pdf.value()},
      {"assembly.svg", fab::svgDocument(pat.assembly)},
      {"pattern.json", fab::sidecarJson(pat, options.jobName)},
      {"dform.stl", fab::stlDocument(model, options.failedGateMark)},
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
  prepared.layout = fab::checkLayout(pat);
  prepared.ticks = fab::seamTicks(model, pat);
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
  summary.pages = int(pat.pages.size());
  summary.triangles = int(model.a.F.rows() + model.b.F.rows());
  return prepared;
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
  return {"pattern.svg",           "pattern.dxf",           "pattern.pdf",
          "assembly.svg",          "pattern.json",          "dform.stl",
          "dform.glb",             "dform.gltf",            sheetFileName(1, "svg"),
          sheetFileName(2, "svg"), sheetFileName(1, "dxf"), sheetFileName(2, "dxf")};
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
  auto png = fab::pngImage(pattern.value(), page, dpi);
  if (!png.isOk()) return png.status();
  return writeFileAtomically(pngPath, png.value());
}

}  // namespace dform
