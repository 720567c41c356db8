// SPDX-License-Identifier: GPL-3.0-or-later
// A sweep's and a batch's rows: the figures measured from a saved result of known shape, the
// gallery's links and text, the starts that were not written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dform/io/model_files.h"
#include "dform/pipeline/sweep.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

// Two square pyramids base to base (an octahedron): the base a 2s x 2s square at z = 0, piece A
// the upper pyramid (apex at z = h), piece B the lower one (apex at z = -h). Its volume is
// 2 * (2s)^2 * h / 3 and its height 2h; its extent in y, 2s, is another number.
DForm octahedron(double s, double h) {
  const double seam[4][2] = {{s, s}, {-s, s}, {-s, -s}, {s, -s}};  // counter-clockwise
  DForm m;
  for (Piece* piece : {&m.a, &m.b}) {
    const bool upper = piece == &m.a;
    piece->name = upper ? "A" : "B";
    piece->flat.resize(5, 2);
    piece->shape.resize(5, 3);
    for (int i = 0; i < 4; ++i) {
      // B lies mirrored on its sheet: its seam runs clockwise there, as a D-Form's B does.
      piece->flat.row(i) << seam[i][0], upper ? seam[i][1] : -seam[i][1];
      piece->shape.row(i) << seam[i][0], seam[i][1], 0;
      piece->seam.push_back(i);
    }
    piece->flat.row(4) << 0, 0;
    piece->shape.row(4) << 0, 0, upper ? h : -h;
    piece->F.resize(4, 3);
    for (int i = 0; i < 4; ++i)
      if (upper)
        piece->F.row(i) << i, (i + 1) % 4, 4;  // outward: up
      else
        piece->F.row(i) << (i + 1) % 4, i, 4;  // outward: down
  }
  return m;
}

struct SavedResult {
  fs::path dir = fs::temp_directory_path() / ("dform_sweep_rows_" + std::to_string(::getpid()));
  explicit SavedResult(const DForm& model) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    EXPECT_TRUE(writeModel(dir.string(), model).isOk());
    std::ofstream(dir / "report.json") << R"({"model": {"name": "exact"}, "timings": {"total": 1.5},
              "gate": {"passed": true, "checks": []}})";
  }
  ~SavedResult() { fs::remove_all(dir); }
};

TEST(SweepRows, TheHeightIsTheZExtentAndTheVolumeEnclosesBothPieces) {
  const double s = 20, h = 7;
  const SavedResult saved(octahedron(s, h));
  const SweepRow row = measureResult(saved.dir.string());
  ASSERT_TRUE(row.solved) << row.reason;
  EXPECT_NEAR(row.heightMm, 2 * h, 1e-12);  // not the y extent, 2s = 40
  const double volume = 2 * (2 * s) * (2 * s) * h / 3;
  EXPECT_NEAR(row.volumeMm3, volume, 1e-9 * volume);  // both pyramids, not A's alone
  EXPECT_EQ(row.model, "exact");
  EXPECT_TRUE(row.passed);
  EXPECT_DOUBLE_EQ(row.seconds, 1.5);
}

TEST(SweepRows, TheGalleryLinksEveryNameAndShowsItsTextAsText) {
  SweepRow odd;
  odd.subfolder = "a#b?c d%e\xe9";
  odd.label = "<script>alert(1)</script> & more";
  odd.reason = "<b>why</b>";
  odd.solved = true;
  odd.model = "<i>exact</i>";
  const std::string html = galleryHtml("sweep <of> \"things\"", {odd});
  EXPECT_NE(html.find("<a href=\"a%23b%3Fc%20d%25e%E9/report.html\">"), std::string::npos) << html;
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt; &amp; more"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;why&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;i&gt;exact&lt;/i&gt;"), std::string::npos);
  EXPECT_NE(html.find("sweep &lt;of&gt; &quot;things&quot;"), std::string::npos);
  for (const char* raw : {"<script>alert", "<b>why", "<i>exact", "<of>"})
    EXPECT_EQ(html.find(raw), std::string::npos) << raw;
}

TEST(SweepRows, StartsThatWereNotWrittenAreNamed) {
  std::vector<SweepRow> rows(4);
  for (int k = 0; k < 4; ++k) rows[std::size_t(k)].subfolder = "start-" + std::to_string(k);
  EXPECT_TRUE(unwrittenStarts("W", rows).isOk());
  rows[2].error = ErrorCode::SolveFailed;  // a start that did not solve is a sweep's finding
  EXPECT_TRUE(unwrittenStarts("W", rows).isOk());
  for (int k : {1, 3}) {
    rows[std::size_t(k)].error = ErrorCode::OutputFailed;
    rows[std::size_t(k)].reason = "W/start-" + std::to_string(k) + ": write failed (disk full?)";
  }
  const Status s = unwrittenStarts("W", rows);
  EXPECT_EQ(s.code(), ErrorCode::OutputFailed);
  EXPECT_EQ(s.message(),
            "W: 2 of 4 starts were not written (start-1, start-3; first: W/start-1: write failed "
            "(disk full?))");
}

}  // namespace
}  // namespace dform
