// SPDX-License-Identifier: GPL-3.0-or-later
// report.html's interactive 3D view in headless Chromium (SwiftShader WebGL): the script runs
// without a console error, and its first view, screenshot, matches a reference this test rasterises
// itself from the model with the still pictures' camera: the same silhouette, A and B where they
// should be, the curvature colours where they should be, the tick numbers at their seam points.
#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "cli/text_files.h"
#include "dform/core/shape_projection.h"
#include "dform/report/html_report.h"
#include "dform/report/views.h"
#include "dform/validate/metrics.h"
#include "headless_chromium.h"
#include "minimal_report.h"
#include "models.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using test::readText;

constexpr int kWidth = 800, kHeight = 480;  // the window: the view fills it (#view3d)
constexpr int kBar = 40;                    // the buttons along its bottom, left out of the count

// A tall disphenoid (both pieces in the first view) with B puffed out, the more the farther from
// its seam: B is coloured by curvature, A white.
DForm curvedModel() {
  DForm model = test::tetraDForm(10, 40.0, 0.45);
  Piece& b = model.b;
  Eigen::VectorXd fromSeam(b.flat.rows());
  for (Eigen::Index v = 0; v < b.flat.rows(); ++v) {
    fromSeam(v) = std::numeric_limits<double>::infinity();
    for (int s : b.seam)
      fromSeam(v) = std::min(fromSeam(v), (b.flat.row(v) - b.flat.row(s)).norm());
  }
  for (Eigen::Index v = 0; v < b.flat.rows(); ++v)
    b.shape.row(v) *= 1.0 + 0.2 * std::sin(0.5 * M_PI * fromSeam(v) / fromSeam.maxCoeff());
  return model;
}

// The viewer's first view of `model` in a canvas of width x height pixels: ShapeCamera(30, 25)
// about the bounding box's centre, its half diagonal nine tenths of half the shorter side.
struct Projection {
  Projection(const DForm& model, int width, int height) : width(width), height(height) {
    const Eigen::RowVector3d lo =
        model.a.shape.colwise().minCoeff().cwiseMin(model.b.shape.colwise().minCoeff());
    const Eigen::RowVector3d hi =
        model.a.shape.colwise().maxCoeff().cwiseMax(model.b.shape.colwise().maxCoeff());
    centre = 0.5 * (lo + hi).transpose();
    scale = 0.45 * std::min(width, height) / (0.5 * (hi - lo).norm());
  }
  Eigen::Vector2d pixel(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d s = camera.screen(p - centre);
    return {0.5 * width + scale * s.x(), 0.5 * height - scale * s.y()};
  }
  int width, height;
  ShapeCamera camera{30, 25};
  Eigen::Vector3d centre;
  double scale = 1;
};

// What each pixel of the window should show: -1 background, else the piece (0 A, 1 B), and the
// curvature colour's t there.
struct Reference {
  std::vector<int> piece = std::vector<int>(size_t(kWidth * kHeight), -1);
  std::vector<double> t = std::vector<double>(size_t(kWidth * kHeight), 0.0);
};

Reference rasterise(const DForm& model) {
  Reference r;
  const Projection view(model, kWidth, kHeight);
  const CurvatureMaps maps = curvatureMaps(model);
  std::vector<double> depth(r.piece.size(), std::numeric_limits<double>::infinity());
  for (int piece = 0; piece < 2; ++piece) {
    const Piece& p = piece == 0 ? model.a : model.b;
    for (Eigen::Index f = 0; f < p.F.rows(); ++f) {
      Eigen::Vector2d c[3];
      double z[3], t[3];
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d q = p.shape.row(p.F(f, k)).transpose();
        c[k] = view.pixel(q);
        z[k] = view.camera.screen(q).z();
        t[k] = maps.piece[piece](p.F(f, k)) / maps.scale;
      }
      const double det =
          (c[1] - c[0]).x() * (c[2] - c[0]).y() - (c[1] - c[0]).y() * (c[2] - c[0]).x();
      if (std::abs(det) < 1e-12) continue;
      const int x0 = std::max(0, int(std::floor(std::min({c[0].x(), c[1].x(), c[2].x()}))));
      const int x1 = std::min(kWidth - 1, int(std::ceil(std::max({c[0].x(), c[1].x(), c[2].x()}))));
      const int y0 = std::max(0, int(std::floor(std::min({c[0].y(), c[1].y(), c[2].y()}))));
      const int y1 =
          std::min(kHeight - 1, int(std::ceil(std::max({c[0].y(), c[1].y(), c[2].y()}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d w = Eigen::Vector2d(x + 0.5, y + 0.5) - c[0];
          const double b1 = (w.x() * (c[2] - c[0]).y() - w.y() * (c[2] - c[0]).x()) / det;
          const double b2 = ((c[1] - c[0]).x() * w.y() - (c[1] - c[0]).y() * w.x()) / det;
          if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
          const size_t at = size_t(y * kWidth + x);
          const double there = (1 - b1 - b2) * z[0] + b1 * z[1] + b2 * z[2];
          if (there >= depth[at]) continue;
          depth[at] = there;
          r.piece[at] = piece;
          r.t[at] = (1 - b1 - b2) * t[0] + b1 * t[1] + b2 * t[2];
        }
    }
  }
  return r;
}

// A screenshot's pixels (0xRRGGBB), row by row; empty when it cannot be read.
std::vector<unsigned> readPng(const fs::path& path, int& width, int& height) {
  cairo_surface_t* image = cairo_image_surface_create_from_png(path.c_str());
  std::vector<unsigned> pixels;
  if (cairo_surface_status(image) == CAIRO_STATUS_SUCCESS) {
    width = cairo_image_surface_get_width(image);
    height = cairo_image_surface_get_height(image);
    const int stride = cairo_image_surface_get_stride(image);
    const unsigned char* data = cairo_image_surface_get_data(image);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        pixels.push_back(reinterpret_cast<const uint32_t*>(data + y * stride)[x] & 0xffffff);
  }
  cairo_surface_destroy(image);
  return pixels;
}

// The view's background, rgb(228, 238, 246): no shaded surface colour comes within 3 of it in
// every channel (its green exceeds its red by 10; a white, blue or red surface's never does, and
// piece B's by 18 or more only where it is dark).
bool background(unsigned rgb) {
  const int r = int(rgb >> 16), g = int((rgb >> 8) & 255), b = int(rgb & 255);
  return std::abs(r - 228) <= 3 && std::abs(g - 238) <= 3 && std::abs(b - 246) <= 3;
}

// A pixel's warmth, whatever its shade: +1 warm (red over blue), -1 cool, 0 neutral (grey).
int warmth(unsigned rgb) {
  const double r = rgb >> 16, b = rgb & 255, top = std::max({r, b, double((rgb >> 8) & 255), 1.0});
  const double w = (r - b) / top;
  return w > 0.1 ? 1 : w < -0.1 ? -1 : 0;
}

class ViewerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::chromiumInstalled())
      GTEST_SKIP() << "chromium is not installed (scripts/install-deps --browser installs it)";
    dir_ = test::freshTestFolder("dform_viewer");
  }
  void TearDown() override {
    if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
  }

  // report.html of `model` with `ticks` into the folder; the page's text.
  std::string writeReport(const DForm& model, const std::vector<SeamTick>& ticks) {
    ReportSources sources = test::minimalReportSources();
    sources.seamTicks = ticks;
    const Result<std::string> html = renderReportHtml(sources, model, DFORM_TEMPLATES_DIR);
    EXPECT_TRUE(html.isOk()) << html.status().message();
    std::ofstream(dir_ / "report.html") << html.value();
    return html.value();
  }

  // Chromium on report.html + `hash` with `action`; its output. Fails on any console message.
  std::string chromium(const std::string& action, const std::string& hash) {
    const fs::path out = dir_ / "out.txt", log = dir_ / "chromium.log";
    const int code = test::runChromium(
        action + " --window-size=" + std::to_string(kWidth) + "," + std::to_string(kHeight),
        "file://" + (dir_ / "report.html").string() + hash, (dir_ / "profile").string(),
        out.string(), log.string());
    EXPECT_EQ(code, 0) << readText(log);
    EXPECT_EQ(readText(log).find("CONSOLE"), std::string::npos) << readText(log);
    return readText(out);
  }

  // The screenshot of report.html + `hash`, compared with `reference` pixel by pixel above the
  // buttons: the surface's pixels where the reference has the surface (and no others), and their
  // warmth (+1 warm, -1 cool, 0 neutral) as `expected` says for the reference's piece and t there,
  // judged for each warmth apart, so that a small coloured region counts as much as a large white
  // one. `skip`: no expectation at that pixel. Returns how many pixels of each warmth were
  // compared.
  std::array<long, 3> compareScreenshot(
      const std::string& hash, const Reference& reference,
      const std::function<int(int piece, double t, bool& skip)>& expected) {
    const fs::path png = dir_ / ("screenshot-" + hash.substr(1) + ".png");
    chromium("--screenshot=" + png.string(), hash);
    int width = 0, height = 0;
    const std::vector<unsigned> shot = readPng(png, width, height);
    std::array<long, 3> compared{0, 0, 0}, agreeing{0, 0, 0};
    EXPECT_EQ(width, kWidth);
    EXPECT_EQ(height, kHeight);
    if (width != kWidth || height != kHeight) return compared;
    long both = 0, either = 0;
    for (int y = 0; y < kHeight - kBar; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const size_t at = size_t(y * kWidth + x);
        const bool drawn = !background(shot[at]), expectedDrawn = reference.piece[at] >= 0;
        both += drawn && expectedDrawn;
        either += drawn || expectedDrawn;
        bool skip = false;
        if (!drawn || !expectedDrawn) continue;
        const int want = expected(reference.piece[at], reference.t[at], skip);
        if (skip) continue;
        ++compared[size_t(want + 1)];
        agreeing[size_t(want + 1)] += warmth(shot[at]) == want;
      }
    EXPECT_GT(double(both) / double(either), 0.93) << hash << ": the silhouettes differ";
    for (size_t w = 0; w < 3; ++w) {
      if (compared[w] == 0) continue;
      EXPECT_GT(double(agreeing[w]) / double(compared[w]), 0.9)
          << hash << ": the colours differ where they should be of warmth " << int(w) - 1 << " ("
          << compared[w] << " pixels)";
    }
    return compared;
  }

  fs::path dir_;
};

TEST_F(ViewerTest, FirstViewMatchesTheReferenceInPieceAndCurvatureColours) {
  const DForm model = curvedModel();
  const Reference reference = rasterise(model);
  // The reference itself: A warm and B cool in sight, A's curvature coloured, B's white.
  writeReport(model, {});
  const std::string dom = chromium("--dump-dom", "#view3d");
  std::smatch status;
  ASSERT_TRUE(std::regex_search(dom, status, std::regex("data-viewer=\"([^\"]*)\"")))
      << dom.substr(0, 500);
  EXPECT_EQ(status[1].str(), "ok triangles=" + std::to_string(model.a.F.rows() + model.b.F.rows()) +
                                 " ticks=0 colours=curvature");

  // Enough of each kind in sight that a view without them fails: A and B; white and red.
  const std::array<long, 3> pieces = compareScreenshot(
      "#view3d-pieces", reference, [](int piece, double, bool&) { return piece == 0 ? 1 : -1; });
  EXPECT_GT(pieces[0], 2000);
  EXPECT_GT(pieces[2], 2000);
  const std::array<long, 3> curvature =
      compareScreenshot("#view3d", reference, [](int, double t, bool& skip) {
        skip = std::abs(t) > 0.02 && std::abs(t) < 0.25;  // between white and clearly coloured
        return t >= 0.25 ? 1 : t <= -0.25 ? -1 : 0;
      });
  EXPECT_GT(curvature[1], 2000);
  EXPECT_GT(curvature[2], 2000);
}

TEST_F(ViewerTest, TickNumbersSitAtTheirSeamPoints) {
  const DForm model = test::tetraDForm(10);
  std::vector<SeamTick> ticks;
  const size_t n = model.a.seam.size();
  for (int k = 0; k < 4; ++k)
    ticks.push_back({k, k == 3 ? "9." : std::to_string(k),
                     model.a.shape.row(model.a.seam[size_t(k) * n / 4]).transpose()});
  writeReport(model, ticks);
  const std::string dom = chromium("--dump-dom", "#view3d");
  EXPECT_NE(dom.find("ticks=4 "), std::string::npos);
  // --dump-dom lays the page out in a window shorter than --window-size: the canvas says how big.
  std::smatch size;
  ASSERT_TRUE(std::regex_search(
      dom, size, std::regex("id=\"viewer-canvas\" width=\"([0-9]+)\" height=\"([0-9]+)\"")));
  const Projection view(model, std::stoi(size[1]), std::stoi(size[2]));
  const std::regex label(
      "<span class=\"[a-z]*\" style=\"left: ([-0-9.]+)px; top: ([-0-9.]+)px;\">([^<]*)</span>");
  size_t found = 0;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), label); it != std::sregex_iterator();
       ++it, ++found) {
    ASSERT_LT(found, ticks.size());
    EXPECT_EQ((*it)[3].str(), ticks[found].label);
    const Eigen::Vector2d expected = view.pixel(ticks[found].at);
    EXPECT_NEAR(std::stod((*it)[1]), expected.x(), 1.0) << ticks[found].label;
    EXPECT_NEAR(std::stod((*it)[2]), expected.y(), 1.0) << ticks[found].label;
  }
  EXPECT_EQ(found, ticks.size()) << dom.substr(dom.find("viewer-labels"), 800);
}

TEST_F(ViewerTest, WithoutWebGlANoteTakesItsPlaceAndTheStillPicturesStay) {
  writeReport(test::tetraDForm(4), {});
  const std::string dom = chromium("--disable-webgl --dump-dom", "");
  EXPECT_NE(dom.find("class=\"viewer no-webgl\" data-viewer=\"no-webgl\""), std::string::npos);
  EXPECT_NE(dom.find("id=\"viewer-fallback\""), std::string::npos);
  EXPECT_NE(dom.find("<figcaption>from the front, above</figcaption>"), std::string::npos);
}

TEST_F(ViewerTest, AScriptErrorIsReportedAndFailsTheConsoleCheck) {
  // The same page with a model the script cannot read: its status says so and Chromium logs it.
  std::string html = writeReport(test::tetraDForm(4), {});
  const std::string start = "<script type=\"application/json\" id=\"viewer-model\">";
  html.insert(html.find(start) + start.size(), "{");
  std::ofstream(dir_ / "report.html") << html;
  const fs::path out = dir_ / "dom.html", log = dir_ / "chromium.log";
  test::runChromium("--dump-dom", "file://" + (dir_ / "report.html").string(),
                    (dir_ / "profile").string(), out.string(), log.string());
  EXPECT_NE(readText(out).find("data-viewer=\"error: "), std::string::npos);
  EXPECT_NE(readText(log).find("CONSOLE"), std::string::npos);
}

}  // namespace
}  // namespace dform
