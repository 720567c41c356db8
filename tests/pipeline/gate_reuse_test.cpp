// SPDX-License-Identifier: GPL-3.0-or-later
// `dform export` of a saved result reuses the gate report.json records where it still holds (the
// meshes are the bytes the run wrote, the same dform and the same limits), and measures again
// where anything of that changed, or when asked (`regate`). A changed mesh that fails the gate is
// refused although report.json says it passed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dform/io/model_files.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/run.h"
#include "dform/pipeline/saved_result.h"
#include "pipeline/reference_seams.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string text(const fs::path& path) {
  std::ostringstream s;
  s << std::ifstream(path, std::ios::binary).rdbuf();
  return s.str();
}

class GateReuse : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dform-gate-reuse-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ForwardJob job;
    job.pieceA = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-a.svg";
    job.pieceB = std::string(DFORM_SAMPLES_DIR) + "/forward/ellipses-b.svg";
    job.resolution = 30;
    Result<Shape2> a = readOutline(job.pieceA), b = readOutline(job.pieceB);
    ASSERT_TRUE(a.isOk() && b.isOk());
    MessageSink sink;
    Result<ForwardRun> run = makeDForm(a.value(), b.value(), job, sink);
    ASSERT_TRUE(run.isOk()) << run.status().message();
    OutputOptions output;
    output.outDir = result().string();
    const Result<RunSettings> settings = checkOutput(ExportSettings());
    ASSERT_TRUE(settings.isOk());
    ASSERT_TRUE(
        writeResult(Job(job), SolvedRun(run.value()), output, settings.value(), sink).isOk());
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path result() const { return dir_ / "result"; }

  // Exports the saved result into a fresh folder: its status, and whether the gate was measured
  // (rather than report.json's reused).
  struct Export {
    Status status = Status::ok();
    bool measured = false;
    bool saidReused = false;
  };
  Export exportIt(bool regate = false) {
    SavedExport how;
    how.outDir = (dir_ / ("out-" + std::to_string(++exports_))).string();
    how.regate = regate;
    MessageSink sink;
    const std::atomic<bool> never{false};
    const long before = modelsMeasuredForGate();
    Export e;
    e.status = exportSavedResult(result().string(), ExportSettings(), how, sink, never).status();
    e.measured = modelsMeasuredForGate() > before;
    for (const Message& m : sink.messages())
      e.saidReused = e.saidReused || m.text.find("report.json's") != std::string::npos;
    return e;
  }

  void editReport(const std::function<void(json&)>& edit) {
    json report = json::parse(text(result() / "report.json"));
    edit(report);
    std::ofstream(result() / "report.json") << report.dump(2);
  }

  fs::path dir_;
  int exports_ = 0;
};

TEST_F(GateReuse, AnUnchangedResultIsExportedOnItsRecordedVerdict) {
  const json report = json::parse(text(result() / "report.json"));
  ASSERT_TRUE(report.contains("result_files"));
  for (const char* name :
       {ModelFileNames::aFlat, ModelFileNames::a3d, ModelFileNames::bFlat, ModelFileNames::b3d}) {
    ASSERT_TRUE(report["result_files"].contains(name)) << name;
    EXPECT_EQ(report["result_files"][name].get<std::string>().size(), 64u);
  }
  EXPECT_EQ(report["gate"]["limits"], json::parse(gateLimitsJson(loadGate("default").value())));
  const Export reused = exportIt();
  ASSERT_TRUE(reused.status.isOk()) << reused.status.message();
  EXPECT_FALSE(reused.measured);
  EXPECT_TRUE(reused.saidReused);
  // Asked to, it measures again; so it does when the meshes were read from other bytes.
  const Export regated = exportIt(true);
  ASSERT_TRUE(regated.status.isOk()) << regated.status.message();
  EXPECT_TRUE(regated.measured);
  EXPECT_FALSE(regated.saidReused);
}

TEST_F(GateReuse, AChangedMeshIsMeasuredAgainAndAFailingOneRefused) {
  // A comment added: the same model, other bytes.
  std::ofstream(result() / ModelFileNames::b3d, std::ios::app) << "# touched\n";
  const Export touched = exportIt();
  ASSERT_TRUE(touched.status.isOk()) << touched.status.message();
  EXPECT_TRUE(touched.measured);
  // A 3D vertex moved 5 mm off: L_max fails; report.json still says passed.
  std::istringstream in(text(result() / ModelFileNames::a3d));
  std::ostringstream out;
  bool moved = false;
  for (std::string line; std::getline(in, line);) {
    if (!moved && line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x, y, z;
      v >> x >> y >> z;
      line = "v " + std::to_string(x + 5) + " " + std::to_string(y) + " " + std::to_string(z);
      moved = true;
    }
    out << line << "\n";
  }
  std::ofstream(result() / ModelFileNames::a3d) << out.str();
  const Export failing = exportIt();
  EXPECT_TRUE(failing.measured);
  EXPECT_EQ(failing.status.code(), ErrorCode::GateFailed) << failing.status.message();
}

TEST_F(GateReuse, ARecordThatNoLongerHoldsIsMeasuredAgain) {
  const json original = json::parse(text(result() / "report.json"));
  const std::vector<std::pair<std::string, std::function<void(json&)>>> edits = {
      {"another dform", [](json& r) { r["tool"]["version"] = "0.0.0-other"; }},
      {"other limits", [](json& r) { r["gate"]["limits"]["L_max"] = 0.5; }},
      {"another gate", [](json& r) { r["gate"]["name"] = "strict"; }},
      {"no hashes", [](json& r) { r.erase("result_files"); }},
      {"a hash of other bytes",
       [](json& r) { r["result_files"][ModelFileNames::aFlat] = std::string(64, '0'); }},
      {"a file more", [](json& r) { r["result_files"]["extra.obj"] = std::string(64, '0'); }},
  };
  for (const auto& [what, edit] : edits) {
    SCOPED_TRACE(what);
    std::ofstream(result() / "report.json") << original.dump(2);
    editReport(edit);
    const Export e = exportIt();
    ASSERT_TRUE(e.status.isOk()) << e.status.message();
    EXPECT_TRUE(e.measured);
  }
  // The recorded verdict holds, a failed one too: refused without measuring.
  std::ofstream(result() / "report.json") << original.dump(2);
  editReport([](json& r) {
    r["gate"]["passed"] = false;
    r["gate"]["checks"][0]["verdict"] = "fail";
  });
  const Export refused = exportIt();
  EXPECT_FALSE(refused.measured);
  EXPECT_EQ(refused.status.code(), ErrorCode::GateFailed) << refused.status.message();
}

}  // namespace
}  // namespace dform
