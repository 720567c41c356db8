// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's downloads against the command line: a saved job that `dform run` reproduces (the
// same figures), and an export whose files are the ones `dform run` writes for that job.
#include "studio/downloads.h"

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <tuple>

#include "dform/core/interrupt.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/settings.h"
#include "pipeline/setting_values.h"
#include "studio_client.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Unzips `zip` into `dir` with Python's zipfile (an independent reader of the archive).
void unzip(const std::string& zip, const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream(dir / "download.zip", std::ios::binary) << zip;
  const std::string command =
      std::string(DFORM_PYTHON3) +
      " -c \"import zipfile,sys; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])\" " +
      (dir / "download.zip").string() + " " + dir.string();
  ASSERT_EQ(std::system(command.c_str()), 0);
  fs::remove(dir / "download.zip");
}

struct StudioDownloads : ::testing::Test {
  fs::path dir =
      fs::temp_directory_path() / ("dform-studio-downloads-" + std::to_string(::getpid()));
  void SetUp() override { fs::remove_all(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(StudioDownloads, SavedJobRunsToTheSameFiguresAndExportToTheSameFiles) {
  test::StudioClient c;
  const std::string session = c.session();
  // Piece B a rounded rectangle: the zip carries its generated text, which the run reads.
  ASSERT_EQ(c.post("/api/parametric", {{"session", session},
                                       {"piece", "b"},
                                       {"kind", "superellipse"},
                                       {"values", {{"a", 105}, {"b", 80}, {"exponent", 2.5}}}})
                .first,
            200);
  const json settings = {{"session", session},
                         {"start_a", 0.05},
                         {"start_b", 0.3125},
                         {"flip", true},
                         {"resolution", 80}};
  test::EventReader events(c, session);
  auto solved = c.post("/api/solve", settings);
  ASSERT_EQ(solved.first, 200);
  ASSERT_FALSE(solved.second.contains("error")) << solved.second;
  const json verdict =
      events.waitFor("result", std::chrono::seconds(120));  // the job's mesh, measured
  ASSERT_FALSE(verdict.is_null());

  auto job = c.raw().Post("/api/job", c.headers(), settings.dump(), "application/json");
  ASSERT_EQ(job->status, 200);
  EXPECT_EQ(job->get_header_value("Content-Type"), "application/zip");
  unzip(job->body, dir / "job");
  ASSERT_TRUE(fs::exists(dir / "job" / "job.json"));
  const std::string run = std::string(DFORM_BINARY) + " run " +
                          (dir / "job" / "job.json").string() + " -o " + (dir / "cli").string() +
                          " --quiet > " + (dir / "run.log").string() + " 2>&1";
  ASSERT_EQ(std::system(run.c_str()), 0) << readAll(dir / "run.log");
  const json report = json::parse(readAll(dir / "cli" / "report.json"));
  for (const char* figure :
       {"L_error", "L_max", "B_error", "seam_gap_mm", "angle_defect_max_rad", "seam_length_3d_mm"})
    EXPECT_DOUBLE_EQ(report["metrics"][figure].get<double>(),
                     verdict["figures"][figure].get<double>())
        << figure;

  json exportRequest = settings;
  exportRequest["export"] = {{"profile", "laser"}};
  auto exported =
      c.raw().Post("/api/export", c.headers(), exportRequest.dump(), "application/json");
  ASSERT_EQ(exported->status, 200) << exported->body;
  unzip(exported->body, dir / "export");
  for (const char* file : {"pattern.svg", "pattern.dxf", "assembly.svg", "pattern.json"}) {
    ASSERT_TRUE(fs::exists(dir / "export" / file)) << file;
    EXPECT_EQ(readAll(dir / "export" / file), readAll(dir / "cli" / file))
        << file << " differs from the CLI's";
  }
  EXPECT_TRUE(fs::exists(dir / "export" / "report.html"));
  EXPECT_TRUE(fs::exists(dir / "export" / "pattern.pdf"));
}

// `dform studio JOB`, then Save job as the page does it (the session's settings of the job's mode
// sent back as they came): the saved job.json equals the job opened, setting by setting.
void expectSavedAsOpened(const fs::path& jobFile, const fs::path& dir) {
  SCOPED_TRACE(jobFile.string());
  const Result<Job> opened = readJobFile(jobFile.string());
  ASSERT_TRUE(opened.isOk()) << opened.status().message();
  StudioOptions options;
  options.jobFile = jobFile.string();
  test::StudioClient c(options);
  const auto [status, started] = c.post("/api/session", json::object());
  ASSERT_EQ(status, 200) << started;
  EXPECT_EQ(started["mode"], opened.value().modeName());
  json request = started["settings"][opened.value().modeName()];
  request["mode"] = opened.value().modeName();
  request["session"] = started["session"];
  auto saved = c.raw().Post("/api/job", c.headers(), request.dump(), "application/json");
  ASSERT_EQ(saved->status, 200) << saved->body;
  unzip(saved->body, dir);
  const Result<Job> read = readJobFile((dir / "job.json").string());
  ASSERT_TRUE(read.isOk()) << read.status().message();
  ASSERT_EQ(read.value().modeName(), opened.value().modeName());
  for (const SettingRow* row : settingRows(opened.value().isForward()))
    EXPECT_EQ(settingValue(read.value(), *row), settingValue(opened.value(), *row)) << row->key;
  fs::remove_all(dir);
}

TEST_F(StudioDownloads, EveryShippedJobIsSavedAsItWasOpened) {
  int jobs = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(DFORM_SAMPLES_DIR) / "forward"))
    if (entry.path().extension() == ".json") {
      expectSavedAsOpened(entry.path(), dir / entry.path().stem());
      ++jobs;
    }
  EXPECT_GE(jobs, 7);
}

// Every setting of the mode away from its default, export options included: a job the studio
// opens and saves again unchanged.
TEST_F(StudioDownloads, AJobWithEverySettingChangedIsSavedAsItWasOpened) {
  const fs::path samples = DFORM_SAMPLES_DIR;
  for (const bool forward : {true, false}) {
    Job job = forward ? Job(ForwardJob{ForwardSettings(), (samples / "forward/circle.svg").string(),
                                       (samples / "forward/square.svg").string()})
                      : Job(InverseJob{InverseSettings(),
                                       (samples / "inverse/tennis-ball.obj").string(), false});
    for (const SettingRow* row : settingRows(forward)) {
      const std::string value = test::otherValue(*row, forward);
      ASSERT_TRUE(setSetting(job, *row, value).isOk()) << row->key << " = " << value;
    }
    fs::create_directories(dir);
    const fs::path file = dir / (forward ? "forward.json" : "inverse.json");
    std::ofstream(file) << jobToJson(job);
    expectSavedAsOpened(file, dir / (forward ? "forward" : "inverse"));
  }
}

TEST_F(StudioDownloads, ExportRefusesUnknownProfilesWithAJsonError) {
  test::StudioClient c;
  auto r = c.post("/api/export",
                  {{"session", c.session()}, {"export", {{"profile", "../../etc/passwd"}}}});
  EXPECT_EQ(r.first, 400);
  EXPECT_TRUE(r.second.contains("error"));
  auto page = c.post("/api/export", {{"session", c.session()},
                                     {"export", {{"profile", "print"}, {"page", "Z9"}}}});
  EXPECT_EQ(page.first, 400);
  EXPECT_NE(page.second["error"].get<std::string>().find("page"), std::string::npos) << page.second;
}

// The export dialog's lists (material, tick numbers, hinge) are the settings table's rows, and
// what the page sends from them reaches the export and the saved job.
TEST_F(StudioDownloads, TheExportDialogsListsAreTheTablesAndReachTheExport) {
  test::StudioClient c;
  const auto [status, started] = c.post("/api/session", json::object());
  ASSERT_EQ(status, 200) << started;
  for (const char* key : {"material", "numbers", "hinge"}) {
    SCOPED_TRACE(key);
    const SettingRow* row = findSetting(std::string("export.") + key, true);
    ASSERT_NE(row, nullptr);
    json choices = json::array();
    if (row->type == SettingType::Flag) choices = {true, false};
    for (const SettingChoice& choice : row->choices) choices.push_back(choice.name);
    EXPECT_EQ(started["choices"][key]["choices"], choices);
    EXPECT_EQ(started["choices"][key]["unset"], row->unset);
    EXPECT_FALSE(row->unset.empty());
  }
  EXPECT_EQ(started["choices"]["numbers"]["choices"].size(), 3u);
  const json base = {{"session", started["session"]}, {"resolution", 60}, {"model", "exact"}};
  // The pattern's numbers on tabs and on the face, and its hinges, as exported with `settings`.
  auto exportWith = [&](const std::string& name, const json& settings) {
    json request = base;
    request["export"] = settings;
    auto r = c.raw().Post("/api/export", c.headers(), request.dump(), "application/json");
    EXPECT_EQ(r->status, 200) << r->body;
    unzip(r->body, dir / name);
    const std::string svg = readAll(dir / name / "pattern.svg");
    const std::regex tab("id=\"[AB]-tick-\\d+-tab-label\""), face("id=\"[AB]-tick-\\d+-label\"");
    const auto count = [&](const std::regex& re) {
      return std::distance(std::sregex_iterator(svg.begin(), svg.end(), re),
                           std::sregex_iterator());
    };
    int hinges = 0;
    const json pattern = json::parse(readAll(dir / name / "pattern.json"));
    for (const json& piece : pattern["pieces"])
      hinges += int(piece.value("hinges", json::array()).size());
    return std::tuple{count(tab), count(face), hinges};
  };
  const auto [faceTabs, faceFace, faceHinges] =
      exportWith("face", {{"profile", "print"}, {"numbers", "face"}});
  const auto [bothTabs, bothFace, bothHinges] =
      exportWith("both", {{"profile", "print"}, {"numbers", "both"}});
  EXPECT_EQ(faceTabs, 0);
  EXPECT_GT(faceFace, 20);
  EXPECT_GT(bothTabs, 10);
  EXPECT_EQ(bothFace, faceFace);
  EXPECT_EQ(faceHinges + bothHinges, 0);
  EXPECT_GT(std::get<2>(exportWith("on", {{"material", "plywood"}, {"hinge", true}})), 0);
  EXPECT_EQ(std::get<2>(exportWith("off", {{"material", "plywood"}, {"hinge", false}})), 0);
  // Save job keeps them.
  json request = base;
  request["export"] = {{"material", "plywood"}, {"hinge", false}, {"numbers", "both"}};
  auto saved = c.raw().Post("/api/job", c.headers(), request.dump(), "application/json");
  ASSERT_EQ(saved->status, 200) << saved->body;
  unzip(saved->body, dir / "job");
  const json job = json::parse(readAll(dir / "job" / "job.json"));
  EXPECT_EQ(job["export"]["hinge"], false) << job;
  EXPECT_EQ(job["export"]["numbers"], "both") << job;
  EXPECT_EQ(job["export"]["material"], "plywood") << job;
}

// An export whose client has gone stops, inside its long steps too (its run is interrupted),
// and the flag is that export's alone.
TEST_F(StudioDownloads, AnExportWhoseClientWentIsStopped) {
  const studio::PieceInput a{
      "a.json", studio::parametricOutline("ellipse", {{"a", 120}, {"b", 70}}), {}};
  const studio::PieceInput b{
      "b.json", studio::parametricOutline("ellipse", {{"a", 110}, {"b", 82.305579}}), {}};
  ForwardJob job;
  job.resolution = 60;
  job.fitPerimeter = true;
  const auto files = studio::forwardJobFiles(a, b, Job(job));
  std::atomic<bool> gone{true};
  const Result<studio::ExportedZip> stopped = studio::exportedResult(files, &gone);
  EXPECT_EQ(stopped.status().code(), ErrorCode::Interrupted) << stopped.status().message();
  // The flag is this export's alone: the thread's next run is not stopped by it.
  EXPECT_FALSE(interruptRequested());
  std::atomic<bool> here{false};
  const Result<studio::ExportedZip> zip = studio::exportedResult(files, &here);
  ASSERT_TRUE(zip.isOk()) << zip.status().message();
  EXPECT_EQ(zip.value().zip.substr(0, 2), "PK");
}

// The ellipses' export with `settings` (a job file's keys) over a paper model solved at
// resolution 40 with two iterations (exact_distance_rel fails the strict gate).
Result<studio::ExportedZip> ellipsesExport(const std::string& settings) {
  const studio::PieceInput a{
      "a.json", studio::parametricOutline("ellipse", {{"a", 120}, {"b", 70}}), {}};
  const studio::PieceInput b{
      "b.json", studio::parametricOutline("ellipse", {{"a", 110}, {"b", 82.305579}}), {}};
  Job job{ForwardJob()};
  EXPECT_TRUE(readSettings(job, R"({"resolution": 40, "fit_perimeter": true, "model": "paper",
                                    "solver": {"max_iterations": 2}})")
                  .isOk());
  const Status set = readSettings(job, settings);
  EXPECT_TRUE(set.isOk()) << set.message();
  return studio::exportedResult(studio::forwardJobFiles(a, b, job));
}

// What a zip holds, unzipped by an independent reader: file name -> content.
std::map<std::string, std::string> unzipped(const std::string& zip, const fs::path& dir) {
  unzip(zip, dir);
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).generic_string()] = readAll(entry.path());
  return files;
}

// An export that lacks its cutting files says so and what to do, in the page's words (its
// fields' labels, no command-line flag); the files it holds name no folder of the server's.
TEST_F(StudioDownloads, AnExportWithoutItsCuttingFilesSaysWhyAndWhatToDo) {
  const Result<studio::ExportedZip> failed = ellipsesExport(R"({"gate": "strict"})");
  ASSERT_TRUE(failed.isOk()) << failed.status().message();
  const std::string& why = failed.value().missing;
  EXPECT_NE(why.find("failed the quality gate 'strict' (exact_distance_rel"), std::string::npos)
      << why;
  EXPECT_NE(why.find("tick \"export even if the gate fails\""), std::string::npos) << why;
  std::map<std::string, std::string> files = unzipped(failed.value().zip, dir / "failed");
  EXPECT_TRUE(files.count("report.json"));
  EXPECT_FALSE(files.count("pattern.svg"));
  for (const auto& [name, content] : files)
    EXPECT_EQ(content.find("dform-studio-"), std::string::npos)
        << name << " names the server's folder";
  EXPECT_NE(files["report.json"].find("\"path\": \"a.json\""), std::string::npos)
      << "report.json names its inputs as the saved job does";

  const Result<studio::ExportedZip> anyway =
      ellipsesExport(R"({"gate": "strict", "export": {"export_anyway": true}})");
  ASSERT_TRUE(anyway.isOk()) << anyway.status().message();
  EXPECT_EQ(anyway.value().missing, "");
  EXPECT_TRUE(unzipped(anyway.value().zip, dir / "anyway").count("pattern.svg"));

  const Result<studio::ExportedZip> small =
      ellipsesExport(R"({"export": {"profile": "laser", "sheet": "100x100mm"}})");
  ASSERT_TRUE(small.isOk()) << small.status().message();
  const std::string& tooSmall = small.value().missing;
  EXPECT_NE(tooSmall.find("does not fit the sheet"), std::string::npos) << tooSmall;
  EXPECT_NE(tooSmall.find("\"scale\" fit"), std::string::npos) << tooSmall;
  EXPECT_NE(tooSmall.find("a larger \"sheet\""), std::string::npos) << tooSmall;
  for (const char* shell : {"--", "dform export", "/tmp", "export.sheet"})
    EXPECT_EQ(tooSmall.find(shell), std::string::npos) << shell << " in: " << tooSmall;
  EXPECT_FALSE(unzipped(small.value().zip, dir / "small").count("pattern.svg"));
}

// An export that writes nothing answers the run's error, naming no folder of the server's.
TEST_F(StudioDownloads, AnExportThatFailsNamesNoServerFolder) {
  const studio::PieceInput a{"a.svg", "<svg xmlns='http://www.w3.org/2000/svg'/>", {}};
  const studio::PieceInput b{
      "b.json", studio::parametricOutline("ellipse", {{"a", 110}, {"b", 82}}), {}};
  const Result<studio::ExportedZip> zip =
      studio::exportedResult(studio::forwardJobFiles(a, b, Job(ForwardJob())));
  ASSERT_FALSE(zip.isOk());
  EXPECT_NE(zip.status().message().find("a.svg"), std::string::npos) << zip.status().message();
  EXPECT_EQ(zip.status().message().find("dform-studio-"), std::string::npos)
      << zip.status().message();
}

// The print preview is the export's layout: the pages, tiles and sheets of the pattern.json the
// same request's export holds, and each sheet's SVG; what the export would refuse, said instead.
TEST_F(StudioDownloads, ThePrintPreviewIsTheExportsLayout) {
  test::StudioClient c;
  const json request = {{"session", c.session()},
                        {"export", {{"profile", "print"}, {"page", "A4"}, {"scale", 1}}}};
  auto preview = c.post("/api/preview", request);
  ASSERT_EQ(preview.first, 200) << preview.second;
  auto exported = c.raw().Post("/api/export", c.headers(), request.dump(), "application/json");
  ASSERT_EQ(exported->status, 200) << exported->body;
  unzip(exported->body, dir / "export");
  const json pattern = json::parse(readAll(dir / "export" / "pattern.json"));
  EXPECT_GT(preview.second["pages"].size(), 1u) << "the ellipses at true size tile A4";
  EXPECT_EQ(preview.second["pages"], pattern["pages"]);
  EXPECT_EQ(preview.second["sheets"], pattern["sheets"]);
  ASSERT_EQ(preview.second["svg"].size(), pattern["sheets"].size());
  for (std::size_t k = 0; k < pattern["sheets"].size(); ++k)
    EXPECT_EQ(preview.second["svg"][k].get<std::string>(),
              readAll(dir / "export" / pattern["sheets"][k]["file"].get<std::string>()));
  EXPECT_EQ(preview.second["missing"], "");

  auto small = c.post("/api/preview", {{"session", c.session()},
                                       {"export", {{"profile", "laser"}, {"sheet", "100x100mm"}}}});
  ASSERT_EQ(small.first, 200) << small.second;
  EXPECT_FALSE(small.second.contains("pages"));
  EXPECT_NE(small.second["missing"].get<std::string>().find("the largest scale that fits is"),
            std::string::npos)
      << small.second;
  // A setting Export refuses (400 there) is the preview's answer (the page asks as one types).
  const json foreign = {{"session", c.session()}, {"export", {{"profile", "../../etc/passwd"}}}};
  auto refused = c.post("/api/export", foreign), bad = c.post("/api/preview", foreign);
  EXPECT_EQ(refused.first, 400);
  EXPECT_EQ(bad.first, 200);
  EXPECT_EQ(bad.second["error"], refused.second["error"]) << bad.second;
}

TEST(ScopedStop, StopsTheRunsOfItsThreadOnly) {
  std::atomic<bool> flag{false};
  EXPECT_FALSE(interruptRequested());
  {
    const ScopedStop stop(&flag);
    EXPECT_FALSE(interruptRequested());
    flag = true;
    EXPECT_TRUE(interruptRequested());
    EXPECT_THROW(throwIfInterrupted("the test"), Interrupted);
    bool elsewhere = true;
    std::thread([&] { elsewhere = interruptRequested(); }).join();
    EXPECT_FALSE(elsewhere);
    {
      const ScopedStop none(nullptr);  // no flag of its own: the enclosing one still holds
      EXPECT_TRUE(interruptRequested());
    }
    std::atomic<bool> inner{false};
    {
      const ScopedStop nested(&inner);
      EXPECT_FALSE(interruptRequested());
    }
    EXPECT_TRUE(interruptRequested());
  }
  EXPECT_FALSE(interruptRequested());
}

}  // namespace
}  // namespace dform
