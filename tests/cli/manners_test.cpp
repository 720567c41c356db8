// SPDX-License-Identifier: GPL-3.0-or-later
// The command line's manners: "-" for standard input, repeatable options that leave the file
// arguments alone, --quiet that prints nothing but errors, --json that prints one object and
// nothing else, one name and unit per figure in the summary, the gate table, --json and
// report.json, clean --help.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "cli/text_files.h"
#include "dform/core/file_hash.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::readText;

using test::Outcome;

class CliMannersTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::freshTestFolder("dform_manners"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string sample(const std::string& name) {
    return std::string(DFORM_SAMPLES_DIR) + "/" + name;
  }
  static std::string pair() {
    return sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  }

  Outcome run(const std::string& args) const {
    return test::runCaptured(std::string(DFORM_EXE) + " " + args, dir_);
  }
  json report(const std::string& folder) const {
    return json::parse(std::ifstream(fs::path(path(folder)) / "report.json"));
  }

  fs::path dir_;
};

// The named figures of a summary or table line: "name value" pairs.
std::map<std::string, double> namedFigures(const std::string& line) {
  std::map<std::string, double> figures;
  const std::regex pair(R"(([A-Za-z_][A-Za-z_0-9]*)\s+(-?[0-9][0-9.eE+-]*|nan))");
  for (auto it = std::sregex_iterator(line.begin(), line.end(), pair); it != std::sregex_iterator();
       ++it)
    figures[(*it)[1]] = std::stod((*it)[2]);
  return figures;
}

// report.json's value of a figure the summary names: its metric of that name, else the gate's
// check of that name (gauss_max_rad is the gate's: report.json's metrics.angle_defect_max_rad takes
// every interior vertex, the gate only those away from the seam).
double reportFigure(const json& report, const std::string& name) {
  if (name == "flipped")
    return report["metrics"]["flipped_2d"].get<double>() +
           report["metrics"]["flipped_3d"].get<double>();
  if (name == "degenerate")
    return report["metrics"]["degenerate_2d"].get<double>() +
           report["metrics"]["degenerate_3d"].get<double>();
  if (report["metrics"].contains(name)) return report["metrics"][name].get<double>();
  for (const json& check : report["gate"]["checks"])
    if (check["name"] == name) return check["value"].get<double>();
  ADD_FAILURE() << name << " is neither a metric nor a check of report.json";
  return NAN;
}

// Printed with four significant digits: equal to that precision.
void expectPrinted(double printed, double exact, const std::string& name) {
  EXPECT_NEAR(printed, exact, 5e-4 * std::abs(exact) + 1e-300) << name;
}

TEST_F(CliMannersTest, ARepeatableOptionTakesOneValuePerUse) {
  const Outcome forward =
      run("forward --weight smooth_3d=0.02 " + pair() +
          " --weight seam=0.03 --resolution 30 --model paper --no-export -q -o " + path("f"));
  ASSERT_EQ(forward.exitCode, 0) << forward.err;
  EXPECT_EQ(report("f")["job"]["weights"]["smooth_3d"].get<double>(), 0.02);
  EXPECT_EQ(report("f")["job"]["weights"]["seam"].get<double>(), 0.03);
  const Outcome inverse = run("inverse --weight smooth_3d=0.005 " + sample("inverse/saddle.obj") +
                              " --resolution 30 --no-export -q -o " + path("i"));
  ASSERT_EQ(inverse.exitCode, 0) << inverse.err;
  EXPECT_EQ(report("i")["job"]["weights"]["smooth_3d"].get<double>(), 0.005);
}

TEST_F(CliMannersTest, QuietPrintsNothingButErrors) {
  const std::string common = " --resolution 30 --model paper -q";
  Outcome o = run("forward " + pair() + common + " -o " + path("out"));
  ASSERT_EQ(o.exitCode, 0) << o.err;
  EXPECT_EQ(o.out + o.err, "");
  for (const std::string& args :
       {"validate -q " + path("out"), "validate -q --gate none " + path("out"),
        "export -q " + path("out") + " --profile print -o " + path("printed"),
        "inverse " + sample("inverse/saddle.obj") + " --resolution 30 -q -o " + path("inv"),
        "sweep " + pair() + " --starts 2 --resolution 30 --no-export -q -o " + path("sweep")}) {
    o = run(args);
    EXPECT_EQ(o.exitCode, 0) << args << "\n" << o.err;
    EXPECT_EQ(o.out + o.err, "") << args;
  }
  // A failure still says so, in its one error line and nothing else.
  std::ofstream(path("tight.json"))
      << R"({"version": 1, "name": "tight", "limits": {"L_error": 1e-9}})";
  o = run("forward " + pair() + common + " --gate " + path("tight.json") + " -o " + path("out"));
  EXPECT_EQ(o.exitCode, 7);
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(test::occurrences(o.err, "\n"), 1) << o.err;
  EXPECT_EQ(o.err.rfind("dform: error: ", 0), 0u) << o.err;
  o = run("validate -q " + path("out"));
  EXPECT_EQ(o.exitCode, 0) << "the failed run left the passing result in place: " << o.err;
  EXPECT_EQ(o.out + o.err, "");
}

TEST_F(CliMannersTest, ValidateWithoutAGateMeasuresAndGivesNoVerdict) {
  ASSERT_EQ(
      run("forward " + pair() + " --resolution 30 --model paper -q -o " + path("out")).exitCode, 0);
  std::ofstream(path("tight.json"))
      << R"({"version": 1, "name": "tight", "limits": {"L_error": 1e-9}})";
  EXPECT_EQ(run("validate --gate " + path("tight.json") + " " + path("out")).exitCode, 7);
  const Outcome none = run("validate --gate none " + path("out"));
  EXPECT_EQ(none.exitCode, 0) << none.err;
  EXPECT_NE(none.out.find("gate: none"), std::string::npos) << none.out;
  for (const char* verdict : {" pass", " fail", "PASSED", "FAILED"})
    EXPECT_EQ(none.out.find(verdict), std::string::npos) << verdict << "\n" << none.out;
  // Every check is measured, with the value report.json holds.
  const json saved = report("out");
  for (const json& check : saved["gate"]["checks"]) {
    const std::string name = check["name"];
    const std::smatch row = [&] {
      std::smatch m;
      std::regex_search(none.out, m, std::regex("\n" + name + R"(\s+(\S+)\n)"));
      return m;
    }();
    ASSERT_FALSE(row.empty()) << name << "\n" << none.out;
    // validate re-checks the meshes, not the pattern's layout (`dform export` does).
    if (name == "pattern_layout") continue;
    if (check["value"].is_number()) expectPrinted(std::stod(row[1]), check["value"], name);
  }
  const Outcome asJson = run("validate --json --gate none " + path("out"));
  ASSERT_EQ(asJson.exitCode, 0) << asJson.err;
  const json parsed = json::parse(asJson.out);
  EXPECT_TRUE(parsed["gate"]["passed"].is_null());
  EXPECT_EQ(parsed["gate"]["name"], "none");
  // The same summary as the run's: its model, its figures (measured again from the meshes) and
  // the folder's files.
  EXPECT_EQ(parsed["model"], saved["model"]["name"]);
  for (const char* name : {"L_error", "L_max", "B_error", "seam_gap_mm", "gauss_max_rad"}) {
    ASSERT_TRUE(parsed["figures"][name].is_number()) << name << "\n" << asJson.out;
    const double savedValue = reportFigure(saved, name);
    EXPECT_NEAR(parsed["figures"][name].get<double>(), savedValue, 1e-9 * std::abs(savedValue))
        << name;
  }
  const json files = parsed["files"];
  for (const char* name : {"report.json", "piece-a-3d.obj", "piece-b-flat.obj"})
    EXPECT_NE(std::find(files.begin(), files.end(), name), files.end()) << name;
  // An unreadable folder or a report that disagrees with its meshes is still an error.
  EXPECT_EQ(run("validate --gate none " + path("missing")).exitCode, 3);
  json edited = saved;
  edited["metrics"]["L_max"] = 1e-4;
  std::ofstream(fs::path(path("out")) / "report.json") << edited.dump();
  EXPECT_EQ(run("validate --gate none -q " + path("out")).exitCode, 7);
}

// One solve printed three ways: the summary line, the gate table and --json name every figure
// as report.json and the gate file do, in their units (fractions, mm, rad).
TEST_F(CliMannersTest, EveryFigureHasOneNameAndUnitEverywhere) {
  const std::string args = "forward " + pair() + " --resolution 30 --model paper --no-export";
  const Outcome text = run(args + " -o " + path("text"));
  ASSERT_EQ(text.exitCode, 0) << text.err;
  const json saved = report("text");
  const std::map<std::string, double> summary =
      namedFigures(text.out.substr(0, text.out.find('\n')));
  for (const char* name : {"L_error", "L_max", "B_error", "seam_gap_mm", "gauss_max_rad"})
    EXPECT_TRUE(summary.count(name)) << name << "\n" << text.out;
  for (const auto& [name, value] : summary) expectPrinted(value, reportFigure(saved, name), name);
  // The gate table: the same figures where both name one.
  for (const json& check : saved["gate"]["checks"]) {
    const std::string name = check["name"];
    std::smatch row;
    ASSERT_TRUE(std::regex_search(text.out, row, std::regex("\n" + name + R"(\s+(\S+)\s)")))
        << name;
    if (check["value"].is_number()) expectPrinted(std::stod(row[1]), check["value"], name);
    if (summary.count(name)) expectPrinted(summary.at(name), std::stod(row[1]), name);
  }

  // --json: stdout is one object, and nothing else; its figures are report.json's exactly.
  const Outcome asJson = run(args + " --json -o " + path("json"));
  ASSERT_EQ(asJson.exitCode, 0) << asJson.err;
  const json summaryJson = json::parse(asJson.out);
  const json savedToo = report("json");
  EXPECT_EQ(summaryJson["command"], "forward");
  EXPECT_EQ(summaryJson["model"], savedToo["model"]["name"]);
  EXPECT_EQ(summaryJson["exit_code"], 0);
  EXPECT_EQ(summaryJson["output"], path("json"));
  for (const auto& [name, value] : summary) {
    ASSERT_TRUE(summaryJson["figures"].contains(name)) << name;
    EXPECT_EQ(summaryJson["figures"][name].get<double>(), reportFigure(savedToo, name)) << name;
  }
  ASSERT_EQ(summaryJson["gate"]["checks"].size(), savedToo["gate"]["checks"].size());
  for (std::size_t k = 0; k < savedToo["gate"]["checks"].size(); ++k) {
    const json& a = summaryJson["gate"]["checks"][k];
    const json& b = savedToo["gate"]["checks"][k];
    EXPECT_EQ(a["name"], b["name"]);
    EXPECT_EQ(a["value"], b["value"]) << b["name"];
    EXPECT_EQ(a["verdict"], b["verdict"]) << b["name"];
  }
  EXPECT_EQ(summaryJson["gate"]["passed"], savedToo["gate"]["passed"]);
  for (const json& name : summaryJson["files"])
    EXPECT_TRUE(fs::is_regular_file(fs::path(path("json")) / name.get<std::string>())) << name;
  EXPECT_NE(std::find(summaryJson["files"].begin(), summaryJson["files"].end(), "report.json"),
            summaryJson["files"].end());
}

TEST_F(CliMannersTest, JsonOnInverseRunAndAFailedGate) {
  Outcome o = run("inverse " + sample("inverse/saddle.obj") +
                  " --resolution 30 --no-export --json -o " + path("inv"));
  ASSERT_EQ(o.exitCode, 0) << o.err;
  json parsed = json::parse(o.out);
  EXPECT_EQ(parsed["command"], "inverse");
  EXPECT_EQ(parsed["figures"]["D_error"].get<double>(),
            report("inv")["metrics"]["D_error"].get<double>());
  std::ofstream(path("job.json")) << json({{"mode", "forward"},
                                           {"piece_a", sample("forward/ellipses-a.svg")},
                                           {"piece_b", sample("forward/ellipses-b.svg")},
                                           {"resolution", 30},
                                           {"model", "paper"}})
                                         .dump();
  std::ofstream(path("tight.json"))
      << R"({"version": 1, "name": "tight", "limits": {"L_error": 1e-9}})";
  o = run("run " + path("job.json") + " --json --gate " + path("tight.json") + " -o " +
          path("run"));
  EXPECT_EQ(o.exitCode, 7) << o.err;
  parsed = json::parse(o.out);
  EXPECT_EQ(parsed["exit_code"], 7);
  EXPECT_EQ(parsed["gate"]["passed"], false);
  EXPECT_NE(o.err.find("dform: error: "), std::string::npos) << "the verdict also on stderr";
}

// "-" reads standard input: its format told by its content, named "stdin" in messages, recorded
// in report.json as "-" with the SHA-256 of what was read, the same bytes for every read.
TEST_F(CliMannersTest, ADashReadsStandardInput) {
  const std::string a = sample("forward/ellipses-a.svg"), b = sample("forward/ellipses-b.svg");
  Outcome o = run("forward - " + b + " --resolution 30 --no-export -q -o " + path("f") + " < " + a);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  json input = report("f")["inputs"]["piece_a"];
  EXPECT_EQ(input["path"], "-");
  EXPECT_EQ(input["sha256"], sha256Hex(readText(a)));
  // A seam curve from stdin: an OBJ told from its opening lines.
  const std::string curve = sample("inverse/saddle.obj");
  o = run("inverse - --resolution 30 --no-export -q -o " + path("i") + " < " + curve);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  EXPECT_EQ(report("i")["inputs"]["curve"]["path"], "-");
  EXPECT_EQ(report("i")["inputs"]["curve"]["sha256"], sha256Hex(readText(curve)));
  // A job file from stdin, whose outlines are files.
  std::ofstream(path("job.json"))
      << json({{"mode", "forward"}, {"piece_a", a}, {"piece_b", b}, {"resolution", 30}}).dump();
  o = run("run - --no-export -q -o " + path("r") + " < " + path("job.json"));
  ASSERT_EQ(o.exitCode, 0) << o.err;
  EXPECT_EQ(report("r")["job"]["resolution"], 30);
  // Bad input on stdin is named "stdin"; two inputs from one stdin are a usage error.
  std::ofstream(path("junk.txt")) << "hello\n";
  o = run("forward - " + b + " -o " + path("x") + " < " + path("junk.txt"));
  EXPECT_EQ(o.exitCode, 3);
  EXPECT_EQ(o.err.rfind("dform: error: stdin: ", 0), 0u) << o.err;
  o = run("inverse - -o " + path("x") + " < " + path("junk.txt"));
  EXPECT_EQ(o.exitCode, 3);
  EXPECT_EQ(o.err.rfind("dform: error: stdin: ", 0), 0u) << o.err;
  o = run("forward - - -o " + path("x") + " < " + a);
  EXPECT_EQ(o.exitCode, 2);
  EXPECT_NE(o.err.find("stdin"), std::string::npos) << o.err;
  EXPECT_EQ(run("sweep - - -o " + path("x") + " < " + a).exitCode, 2);
  EXPECT_FALSE(fs::exists(path("x")));
  // A sweep reads stdin once and gives every start the same bytes: each start solves what the
  // same sweep of the file solves.
  const std::string sweep = " --starts 2 --resolution 30 --model paper --no-export -q -o ";
  o = run("sweep - " + b + sweep + path("s-stdin") + " < " + a);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  ASSERT_EQ(run("sweep " + a + " " + b + sweep + path("s-file")).exitCode, 0);
  int starts = 0;
  for (const auto& entry : fs::directory_iterator(path("s-file"))) {
    if (!entry.is_directory()) continue;
    const std::string start = entry.path().filename().string();
    const json fromFile = report("s-file/" + start);
    const json fromStdin = report("s-stdin/" + start);
    EXPECT_EQ(fromStdin["inputs"]["piece_a"]["path"], "-") << start;
    EXPECT_EQ(fromStdin["inputs"]["piece_a"]["sha256"], sha256Hex(readText(a))) << start;
    EXPECT_EQ(fromStdin["metrics"]["L_max"], fromFile["metrics"]["L_max"]) << start;
    ++starts;
  }
  EXPECT_EQ(starts, 2);
}

TEST_F(CliMannersTest, HelpShowsNoFlagDefaults) {
  for (const char* command :
       {"forward", "inverse", "run", "sweep", "batch", "export", "validate", "studio"}) {
    const Outcome help = run(std::string(command) + " --help");
    EXPECT_EQ(help.exitCode, 0) << command;
    EXPECT_FALSE(std::regex_search(help.out, std::regex(R"(\{(true|false|0|1)\})")))
        << command << "\n"
        << help.out;
  }
  const Outcome forward = run("forward --help");
  EXPECT_NE(forward.out.find("--no-export "), std::string::npos) << forward.out;
  EXPECT_NE(forward.out.find("--no-title "), std::string::npos) << forward.out;
}

}  // namespace
}  // namespace dform
