// SPDX-License-Identifier: GPL-3.0-or-later
// A run's pattern is laid out once: the layout the gate judges is the one written, and a run that
// fails its gate (on the layout alone, or on a figure) gets the FAILED GATE stamp as an overlay on
// that layout, not a second layout. `dform export` of a saved result likewise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dform/export/exporter.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/run.h"
#include "dform/pipeline/saved_result.h"
#include "export/internal.h"
#include "shipped_samples.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

std::string fileText(const fs::path& path) {
  std::ostringstream s;
  s << std::ifstream(path, std::ios::binary).rdbuf();
  return s.str();
}

// The lines of an SVG but its stamp's layer and its description (which notes the stamp).
std::vector<std::string> unstampedLines(const std::string& svg) {
  std::vector<std::string> lines;
  std::istringstream in(svg);
  bool inStamp = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("inkscape:label=\"FailedGate\"") != std::string::npos) inStamp = true;
    if (!inStamp && line.find("<desc>") == std::string::npos) lines.push_back(line);
    if (inStamp && line == "  </g>") inStamp = false;
  }
  return lines;
}

class FailedGateRun : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dform-failed-gate-run-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    job_.pieceA = test::samplePath("forward/ellipses-a.svg");
    job_.pieceB = test::samplePath("forward/ellipses-b.svg");
    job_.resolution = 30;
    ASSERT_NO_FATAL_FAILURE(solve());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Solves job_ into run_.
  void solve() {
    Result<Shape2> a = readOutline(job_.pieceA), b = readOutline(job_.pieceB);
    ASSERT_TRUE(a.isOk() && b.isOk());
    MessageSink sink;
    Result<ForwardRun> run = makeDForm(a.value(), b.value(), job_, sink);
    ASSERT_TRUE(run.isOk()) << run.status().message();
    run_ = run.value();
  }

  // Writes the run into `name` as `dform forward` does, counting the patterns laid out.
  WrittenResult write(const std::string& name, const ExportSettings& exporting, long* layouts) {
    OutputOptions output;
    output.outDir = (dir_ / name).string();
    const Result<RunSettings> settings = checkOutput(exporting);
    EXPECT_TRUE(settings.isOk()) << settings.status().message();
    MessageSink sink;
    const long before = fab::patternsLaidOut();
    Job job(job_);
    job.exporting = exporting;
    const Result<WrittenResult> written =
        writeResult(job, SolvedRun(run_), output, settings.value(), sink);
    *layouts = fab::patternsLaidOut() - before;
    EXPECT_TRUE(written.isOk()) << written.status().message();
    return written.isOk() ? written.value() : WrittenResult{};
  }

  // The pattern of the run's model laid out with `output`'s options and no mark, into `name`.
  std::string unmarked(const std::string& name, const ExportSettings& exporting) {
    const Result<RunSettings> settings = checkOutput(exporting);
    EXPECT_TRUE(settings.isOk()) << settings.status().message();
    ExportOptions options = *settings.value().exporting;
    options.jobName = "ellipses-a";  // the run's: its first input's name
    const fs::path plain = dir_ / name;
    fs::create_directories(plain);
    const Result<ExportSummary> exported = exportAll(run_.model, options, plain.string());
    EXPECT_TRUE(exported.isOk()) << exported.status().message();
    return fileText(plain / "pattern.svg");
  }

  fs::path dir_;
  ForwardJob job_;
  ForwardRun run_;
};

TEST_F(FailedGateRun, AFailedLayoutIsLaidOutOnceAndStampedAsItIs) {
  // Piece names wider than the pieces: their labels stick out, the layout check counts them,
  // and every other check passes.
  run_.model.a.name = "A-piece-whose-name-is-far-wider-than-the-piece-itself";
  run_.model.b.name = "B-piece-whose-name-is-far-wider-than-the-piece-itself";
  ExportSettings output;
  output.exportAnyway = true;
  long layouts = 0;
  const WrittenResult written = write("layout", output, &layouts);
  ASSERT_TRUE(written.gate.has_value());
  const GateReport& gate = *written.gate;
  const CheckResult* layout = gate.find("pattern_layout");
  ASSERT_NE(layout, nullptr);
  ASSERT_EQ(layout->verdict, CheckResult::Verdict::Fail) << layout->detail;
  for (const CheckResult& check : gate.checks) {
    if (check.name != "pattern_layout") {
      EXPECT_NE(check.verdict, CheckResult::Verdict::Fail) << check.name << ": " << check.detail;
    }
  }
  EXPECT_EQ(layouts, 1) << "judged and stamped on one layout";

  // Written stamped, and but for the stamp the pattern an unmarked export lays out.
  const fs::path out = dir_ / "layout";
  const std::string svg = fileText(out / "pattern.svg");
  EXPECT_NE(svg.find("inkscape:label=\"FailedGate\""), std::string::npos);
  EXPECT_TRUE(nlohmann::json::parse(fileText(out / "pattern.json"))["failed_gate"].get<bool>());
  const std::string plain = unmarked("layout-plain", output);
  EXPECT_EQ(plain.find("FailedGate"), std::string::npos);
  EXPECT_EQ(unstampedLines(svg), unstampedLines(plain));

  // `dform export` of the saved result (its meshes name the pieces A and B again), whose
  // report.json records the failed gate: laid out once, stamped.
  const long before = fab::patternsLaidOut();
  MessageSink sink;
  const std::atomic<bool> never{false};
  ExportSettings again;
  again.exportAnyway = true;
  const Result<std::string> exported =
      exportSavedResult(out.string(), again, {(dir_ / "again").string()}, sink, never);
  ASSERT_TRUE(exported.isOk()) << exported.status().message();
  EXPECT_EQ(fab::patternsLaidOut() - before, 1);
  const std::string reexported = fileText(dir_ / "again" / "pattern.svg");
  EXPECT_NE(reexported.find("inkscape:label=\"FailedGate\""), std::string::npos);
  EXPECT_NE(reexported.find("id=\"A-cut\""), std::string::npos);
}

TEST_F(FailedGateRun, AFigureThatFailsStampsTheLayoutTheGateJudged) {
  // The paper model's result: an exact result's L_error is rounding and passes any limit.
  job_.model = ModelChoice::Paper;
  ASSERT_NO_FATAL_FAILURE(solve());
  const fs::path tight = dir_ / "tight.json";
  std::ofstream(tight) << R"({"version": 1, "name": "tight", "limits": {"L_error": 1e-9}})";
  ExportSettings output;
  output.gate = tight.string();
  output.exportAnyway = true;
  long layouts = 0;
  const WrittenResult written = write("figure", output, &layouts);
  ASSERT_TRUE(written.gate.has_value());
  EXPECT_FALSE(written.gate->passed());
  EXPECT_EQ(written.gate->find("pattern_layout")->verdict, CheckResult::Verdict::Pass);
  EXPECT_EQ(layouts, 1);
  const std::string svg = fileText(dir_ / "figure" / "pattern.svg");
  EXPECT_NE(svg.find("inkscape:label=\"FailedGate\""), std::string::npos);
  EXPECT_EQ(unstampedLines(svg), unstampedLines(unmarked("figure-plain", output)));

  // A run that passes: laid out once, no stamp.
  const WrittenResult passed = write("passed", ExportSettings{}, &layouts);
  ASSERT_TRUE(passed.gate.has_value());
  EXPECT_TRUE(passed.gate->passed());
  EXPECT_EQ(layouts, 1);
  EXPECT_EQ(fileText(dir_ / "passed" / "pattern.svg"), unmarked("passed-plain", ExportSettings{}));
}

}  // namespace
}  // namespace dform
