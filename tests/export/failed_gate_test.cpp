// SPDX-License-Identifier: GPL-3.0-or-later
// The FAILED GATE stamp is an overlay: a pattern laid out once and marked afterwards keeps every
// path where it was, and the stamp is on every sheet, page, tile and assembly page, clear of the
// pieces, in a colour no profile cuts or scores with.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <functional>

#include "dform/export/exporter.h"
#include "export/internal.h"
#include "synthetic.h"
#include "test_util.h"

namespace dform::test {
namespace {

namespace fs = std::filesystem;

// A profile's pattern: its name, and what the export is asked for.
struct Case {
  const char* what;
  ExportOptions options;
};

std::vector<Case> cases() {
  std::vector<Case> all;
  ExportOptions two = options("laser");  // a sheet too small for both pieces: two sheets
  two.sheetWidthMm = two.sheetHeightMm = 200;
  all.push_back({"laser on two sheets", two});
  ExportOptions tiled = options("print");  // a page smaller than a piece: a page map and tiles
  tiled.page = "120x150mm";
  all.push_back({"print, tiled", tiled});
  all.push_back({"print-and-cut (Silhouette marks)", options("print-and-cut")});
  all.push_back({"print-and-cut-cricut", options("print-and-cut-cricut")});
  ExportOptions bare = options("laser-lightburn");
  bare.title = false;
  all.push_back({"laser-lightburn, no title", bare});
  return all;
}

// One layout written twice: as laid out into `name`-plain, stamped into `name`-marked.
struct Written {
  std::string plain, marked;
  ExportSummary summary;
};

Written writeBoth(const std::string& name, const DForm& model, const ExportOptions& o) {
  Written w;
  const Result<LaidOutExport> laidOut = layOutExport(model, o);
  EXPECT_TRUE(laidOut.isOk()) << name << ": " << laidOut.status().message();
  if (!laidOut.isOk()) return w;
  const LaidOutExport marked = markFailedGate(laidOut.value());
  EXPECT_TRUE(marked.failedGate());
  EXPECT_FALSE(laidOut.value().failedGate()) << "marking leaves the layout it was given as it was";
  EXPECT_EQ(marked.layout.problems(), 0) << marked.layout.example;
  for (const LaidOutExport* one : {&laidOut.value(), &marked}) {
    const Result<PreparedExport> rendered = renderExport(model, *one);
    EXPECT_TRUE(rendered.isOk()) << rendered.status().message();
    if (!rendered.isOk()) return w;
    const std::string dir = freshDir(name + (one == &marked ? "-marked" : "-plain"));
    const Result<ExportSummary> summary = writeExport(rendered.value(), dir);
    EXPECT_TRUE(summary.isOk()) << summary.status().message();
    (one == &marked ? w.marked : w.plain) = dir;
    w.summary = rendered.value().summary;
  }
  return w;
}

// An SVG's text without the stamp: its layer and the description's note.
std::string withoutStamp(std::string svg) {
  const size_t at = svg.find("  <g inkscape:groupmode=\"layer\" inkscape:label=\"FailedGate\"");
  if (at != std::string::npos) {
    const std::string close = "  </g>\n";
    svg.erase(at, svg.find(close, at) + close.size() - at);
  }
  const std::string note = "; FAILED GATE: not for fabrication";
  if (const size_t n = svg.find(note); n != std::string::npos) svg.erase(n, note.size());
  return svg;
}

// The SVG files of an export folder: pattern.svg, assembly.svg and each sheet's.
std::vector<std::string> svgFiles(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".svg") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

Eigen::Vector3d rgb(const std::string& hex) {
  const unsigned long v = std::stoul(hex.substr(1), nullptr, 16);
  return Eigen::Vector3d(double((v >> 16) & 0xFF), double((v >> 8) & 0xFF), double(v & 0xFF)) /
         255.0;
}

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// The stamp's colour in a marked pattern.svg: its layer's stroke.
std::string stampColor(const SvgDoc& svg) {
  for (const SvgPath& path : svg.paths)
    if (path.layer == "FailedGate") return path.stroke;
  ADD_FAILURE() << "no stamp in the SVG";
  return "#000000";
}

// Whether a PDF subpath was drawn in `color` (within the rounding of the content stream).
bool drawnIn(const PdfPath& path, const Eigen::Vector3d& color) {
  return (path.color - color).cwiseAbs().maxCoeff() < 0.01;
}

// A model larger than the print cases' pages, so that print tiles it.
DForm model() { return ellipseCircleDForm(64, 8, 80, 50); }

// `check` on every case's pattern of `m`, laid out once and written plain and stamped into
// `name`-plain and `name`-marked.
void forEachCase(const std::string& name, const DForm& m,
                 const std::function<void(const Case&, const Written&)>& check) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.what);
    const Written w = writeBoth(name, m, c.options);
    if (!w.marked.empty()) check(c, w);  // else writeBoth said why
  }
}

TEST(FailedGate, TheStampMovesNothing) {
  const DForm m = model();
  forEachCase("moves-nothing", m, [&](const Case& c, const Written& w) {
    // Every SVG (pattern, assembly, sheets) is the unmarked one plus the stamp's layer and note.
    const std::vector<std::string> files = svgFiles(w.plain);
    EXPECT_EQ(files, svgFiles(w.marked));
    for (const std::string& file : files) {
      const std::string plain = readText(w.plain + "/" + file);
      const std::string marked = readText(w.marked + "/" + file);
      EXPECT_NE(marked, plain) << file << " is stamped";
      EXPECT_EQ(withoutStamp(marked), plain) << file << ": only the stamp differs";
    }
    // Every cut path's coordinates, exactly.
    const SvgDoc plain = readSvg(w.plain + "/pattern.svg"),
                 marked = readSvg(w.marked + "/pattern.svg");
    int cuts = 0;
    for (const SvgPath& path : plain.paths) {
      if (path.layer != "Cut") continue;
      ++cuts;
      const SvgPath* same = marked.find(path.id);
      ASSERT_NE(same, nullptr) << path.id;
      EXPECT_EQ(same->parts, path.parts) << path.id;
    }
    EXPECT_GE(cuts, 2);
    // pattern.json: the same but for failed_gate.
    nlohmann::json plainJson = nlohmann::json::parse(readText(w.plain + "/pattern.json"));
    nlohmann::json markedJson = nlohmann::json::parse(readText(w.marked + "/pattern.json"));
    EXPECT_FALSE(plainJson["failed_gate"].get<bool>());
    EXPECT_TRUE(markedJson["failed_gate"].get<bool>());
    plainJson.erase("failed_gate");
    markedJson.erase("failed_gate");
    EXPECT_EQ(markedJson, plainJson);
    // Every PDF page draws what it drew, in the same order, and the stamp besides.
    const Eigen::Vector3d color = rgb(stampColor(marked));
    std::vector<PdfPath> plainPdf = readPdfPaths(w.plain + "/pattern.pdf");
    std::vector<PdfPath> markedPdf = readPdfPaths(w.marked + "/pattern.pdf");
    markedPdf.erase(std::remove_if(markedPdf.begin(), markedPdf.end(),
                                   [&](const PdfPath& p) { return drawnIn(p, color); }),
                    markedPdf.end());
    ASSERT_EQ(markedPdf.size(), plainPdf.size());
    for (size_t k = 0; k < plainPdf.size(); ++k) {
      EXPECT_EQ(markedPdf[k].page, plainPdf[k].page);
      EXPECT_EQ(markedPdf[k].points, plainPdf[k].points) << "subpath " << k;
    }
    // The option marks the same layout: a fresh export with it is the stamped one.
    ExportOptions asked = c.options;
    asked.failedGateMark = true;
    const Result<PreparedExport> direct = prepareExport(m, asked);
    ASSERT_TRUE(direct.isOk()) << direct.status().message();
    for (const auto& [name, content] : direct.value().files) {
      if (name == "pattern.svg") {
        EXPECT_EQ(content, readText(w.marked + "/pattern.svg"));
      }
    }
  });
}

TEST(FailedGate, TheStampIsOnEveryPageSheetAndTileClearOfThePieces) {
  forEachCase("everywhere", model(), [](const Case& c, const Written& w) {
    const SvgDoc svg = readSvg(w.marked + "/pattern.svg");
    const std::string color = stampColor(svg);
    // Every page of pattern.pdf: the sheets (or a tiled piece's map and tiles), then assembly.
    const int pages = w.summary.pages + 1;
    std::vector<int> stampStrokes(size_t(pages) + 1, 0), plainStrokes(size_t(pages) + 1, 0);
    for (const PdfPath& p : readPdfPaths(w.marked + "/pattern.pdf"))
      if (drawnIn(p, rgb(color))) ++stampStrokes.at(size_t(p.page));
    for (const PdfPath& p : readPdfPaths(w.plain + "/pattern.pdf"))
      if (drawnIn(p, rgb(color))) ++plainStrokes.at(size_t(p.page));
    for (int page = 1; page <= pages; ++page) {
      EXPECT_GE(stampStrokes[size_t(page)], 30) << "page " << page << " of " << pages;
      EXPECT_EQ(plainStrokes[size_t(page)], 0) << "page " << page;
    }
    if (std::string(c.what) == "print, tiled") {
      EXPECT_GT(pages, 4) << "a map and its tiles";
    }
    // Every sheet of pattern.svg has one stamp, inside it and clear of everything on it.
    const nlohmann::json sidecar = nlohmann::json::parse(readText(w.marked + "/pattern.json"));
    if (c.options.sheetWidthMm == 200) {
      EXPECT_EQ(sidecar["sheets"].size(), 2u);
    }
    std::vector<const SvgPath*> stamps;
    for (const SvgPath& path : svg.paths)
      if (path.layer == "FailedGate") stamps.push_back(&path);
    ASSERT_EQ(stamps.size(), sidecar["sheets"].size());
    for (size_t k = 0; k < stamps.size(); ++k) {
      const nlohmann::json& sheet = sidecar["sheets"][k];
      const Vec2 lo = toPolyline(nlohmann::json::array({sheet["origin"]})).front();
      const Vec2 hi = lo + Vec2(sheet["width"].get<double>(), sheet["height"].get<double>());
      fab::Box box;
      for (const Polyline& part : stamps[k]->parts) box.add(part);
      EXPECT_TRUE(fab::Box::spanning(lo, hi).contains(box, 1e-9)) << stamps[k]->id;
      EXPECT_GE(box.w(), 40.0) << "readable across the sheet";
      for (const SvgPath& other : svg.paths) {
        if (other.layer == "FailedGate") continue;
        fab::Box drawn;
        for (const Polyline& part : other.parts) drawn.add(part);
        EXPECT_FALSE(drawn.overlaps(box)) << stamps[k]->id << " over " << other.id;
      }
    }
    // Each sheet's own SVG has its stamp; the assembly page has one.
    for (size_t k = 1; sidecar["sheets"].size() > 1 && k <= sidecar["sheets"].size(); ++k) {
      const SvgDoc sheet = readSvg(w.marked + "/" + sheetFileName(int(k), "svg"));
      EXPECT_EQ(std::count_if(sheet.paths.begin(), sheet.paths.end(),
                              [](const SvgPath& p) { return p.layer == "FailedGate"; }),
                1)
          << "sheet " << k;
    }
    EXPECT_NE(readSvg(w.marked + "/assembly.svg").find("assembly-failed-gate"), nullptr);
    // The DXF: the stamp on a layer of its own, every other entity as the SVG has it.
    EXPECT_NE(readText(w.marked + "/pattern.dxf").find("FAILED-GATE"), std::string::npos);
    expectDxfChecks(w.marked);
  });
}

TEST(FailedGate, TheStampIsInNoColourAProfileCutsOrScoresWith) {
  const DForm m = model();
  std::vector<std::string> profiles = listProfiles(DFORM_TEMPLATES_DIR);
  ASSERT_GE(profiles.size(), 8u);
  for (const std::string& name : profiles) {
    ExportOptions o = options(name);
    o.scaleToFit = true;
    const Result<Profile> profile = loadProfile(name, DFORM_TEMPLATES_DIR);
    ASSERT_TRUE(profile.isOk()) << profile.status().message();
    // A profile whose cut colour is the usual stamp's gets another.
    for (bool clash : {false, true}) {
      Profile p = profile.value();
      if (clash) p.cutColor = "#ff9933";
      o.profileOverride = p;
      o.useProfileOverride = true;
      const Result<LaidOutExport> laidOut = layOutExport(m, o);
      ASSERT_TRUE(laidOut.isOk()) << name << ": " << laidOut.status().message();
      const LaidOutExport marked = markFailedGate(laidOut.value());
      const fab::Layer& stamp = marked.pattern->build.drawing.layers[0];
      ASSERT_EQ(stamp.name, "FailedGate");
      for (const std::string& operation : {p.cutColor, p.scoreColor, p.engraveColor})
        EXPECT_NE(upper(stamp.color), upper(operation)) << name << (clash ? " (clash)" : "");
      // Nor a pure colour a laser maps to an operation (Epilog, LightBurn's first layers).
      for (const char* pure :
           {"#FF0000", "#00FF00", "#0000FF", "#000000", "#00FFFF", "#FFFF00", "#FF00FF", "#00E000"})
        EXPECT_NE(upper(stamp.color), pure) << name;
    }
  }
}

}  // namespace
}  // namespace dform::test
