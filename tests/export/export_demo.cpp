// SPDX-License-Identifier: GPL-3.0-or-later
// export_demo: writes the synthetic D-Form's pattern for every profile, and the variants' (an anti
// D-Form, a demi D-Form, creased pieces), and renders the docs pictures
// (scripts/render-docs-export), or times exportAll (docs/export.md).
//   export_demo render OUT_DIR IMAGES_DIR
//   export_demo bench OUT_DIR [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dform/export/exporter.h"
#include "models.h"
#include "synthetic.h"

namespace {

int fail(const dform::Status& s) {
  std::fprintf(stderr, "export_demo: %s\n", s.message().c_str());
  return 1;
}

dform::ExportOptions baseOptions() {
  dform::ExportOptions o;
  o.templatesDir = DFORM_TEMPLATES_DIR;
  o.jobName = "demo";
  return o;
}

int render(const std::string& outDir, const std::string& imagesDir) {
  namespace fs = std::filesystem;
  enum class Model { Ellipses, Anti, Demi, Creased };
  struct Job {
    std::string profile, image;
    double sheetW, sheetH, scale;
    std::optional<dform::TabSide> tabs;  // unset: the profile's
    Model model = Model::Ellipses;
    bool assembly = false;  // the assembly page rather than the first page
  };
  const std::vector<Job> jobs = {
      {"laser", "export-laser", 400, 250, 1.0, {}},
      {"laser-ponoko", "export-laser-ponoko", 400, 250, 1.0, {}},
      {"laser-lightburn", "export-laser-lightburn", 400, 250, 1.0, {}},
      {"laser-card", "export-laser-card", 400, 250, 1.0, {}},
      {"print", "export-print", 0, 0, 1.0, {}},
      {"print", "export-print-tiled", 0, 0, 2.0, {}},
      {"print-and-cut", "export-print-and-cut", 0, 0, 0.6, {}},
      {"print-and-cut-cricut", "export-print-and-cut-cricut", 0, 0, 0.7, {}},
      {"laser", "export-laser-anti", 300, 180, 1.0, {}, Model::Anti},
      {"laser", "export-laser-demi", 300, 180, 1.0, dform::TabSide::Alternate, Model::Demi},
      {"print", "export-print-creases", 0, 0, 1.0, {}, Model::Creased},
      {"print", "export-assembly", 0, 0, 1.0, {}, Model::Ellipses, true},
  };
  auto model = [](const Job& job) {
    namespace t = dform::test;
    switch (job.model) {
      case Model::Anti: return t::annulusDForm(60, 25, 64, 6);
      case Model::Demi: return t::demiDForm(60, 30, 64, 6);
      case Model::Creased: {
        const dform::Piece a =
            t::foldedSquare(12, 84.0, {{4, 0, 4, 12, 40.0}, {6, 0, 12, 6, -60.0}});
        return dform::DForm{a, t::mirroredCopy(a, "B")};
      }
      case Model::Ellipses: break;
    }
    return t::ellipseCircleDForm(64, 8, 80 * job.scale, 50 * job.scale, 30 * job.scale);
  };
  for (const Job& job : jobs) {
    const dform::DForm m = model(job);
    dform::ExportOptions o = baseOptions();
    o.profile = job.profile;
    o.tabSide = job.tabs;
    if (job.sheetW > 0) {
      o.sheetWidthMm = job.sheetW;
      o.sheetHeightMm = job.sheetH;
    }
    const std::string dir = (fs::path(outDir) / job.image).string();
    fs::create_directories(dir);
    auto summary = dform::exportAll(m, o, dir);
    if (!summary.isOk()) return fail(summary.status());
    const std::string png = (fs::path(imagesDir) / (job.image + ".png")).string();
    const int page = job.assembly ? summary.value().pages : 0;  // the assembly page comes last
    if (auto s = dform::renderPatternPng(m, o, png, 60, page); !s.isOk()) return fail(s);
    std::printf("%-22s %d page(s), %d ticks, %d tabs, %d creases -> %s\n", job.profile.c_str(),
                summary.value().pages, summary.value().ticks, summary.value().tabs,
                summary.value().creases, png.c_str());
  }
  return 0;
}

int bench(const std::string& outDir, int repeats) {
  const dform::DForm model = dform::test::ellipseCircleDForm(64, 8);
  dform::ExportOptions o = baseOptions();
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    auto summary = dform::exportAll(model, o, outDir);
    const auto t1 = std::chrono::steady_clock::now();
    if (!summary.isOk()) return fail(summary.status());
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  std::printf(
      "exportAll, laser profile, %d triangles, %d repeats: min %.1f ms, median %.1f ms, max %.1f "
      "ms\n",
      int(model.a.F.rows() + model.b.F.rows()), repeats, ms.front(), ms[ms.size() / 2], ms.back());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "render" && argc == 4) return render(argv[2], argv[3]);
  if (mode == "bench" && argc >= 3) return bench(argv[2], argc > 3 ? std::stoi(argv[3]) : 21);
  std::fprintf(
      stderr,
      "usage: export_demo render OUT_DIR IMAGES_DIR | export_demo bench OUT_DIR [REPEATS]\n");
  return 2;
}
