// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/text_files.h"
#include "dform/core/file_hash.h"
#include "dform/io/model_files.h"
#include "shipped_samples.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using test::readText;

using test::Outcome;

// A scratch folder per test, removed at the end.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::freshTestFolder("dform_cli"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  static std::string svg(const std::string& body) {
    return "<svg xmlns='http://www.w3.org/2000/svg' width='300mm' height='300mm' viewBox='0 0 300 "
           "300'>" +
           body + "</svg>";
  }

  // Runs dform with `args`, capturing stdout and stderr; `environment` (e.g. "env NAME=value") is
  // put before the command.
  Outcome run(const std::string& args, const std::string& environment = "") const {
    return test::runCaptured(environment + " " + std::string(DFORM_EXE) + " " + args, dir_);
  }

  // The run failed with `code` and said so in one error line, the last, naming `mentions`
  // (progress messages may come before it).
  static void expectError(const Outcome& o, int code, const std::string& mentions) {
    EXPECT_EQ(o.exitCode, code) << o.err;
    std::size_t errors = 0, at = 0;
    while ((at = o.err.find("dform: error: ", at)) != std::string::npos) ++errors, ++at;
    EXPECT_EQ(errors, 1u) << o.err;
    const std::size_t lastLine = o.err.rfind('\n', o.err.size() - 2);
    const std::string last = o.err.substr(lastLine == std::string::npos ? 0 : lastLine + 1);
    EXPECT_EQ(last.rfind("dform: error: ", 0), 0u) << o.err;
    EXPECT_NE(last.find(mentions), std::string::npos) << o.err;
  }

  // Validates a JSON file against templates/schema/report.schema.json (python3-jsonschema).
  int schemaCheck(const std::string& report) const {
    const std::string command =
        "python3 -c 'import json, sys, jsonschema; "
        "jsonschema.validate(json.load(open(sys.argv[1])), json.load(open(sys.argv[2])))' " +
        report + " " + std::string(DFORM_TEMPLATES_DIR) + "/schema/report.schema.json 2>" +
        path("schema.txt");
    return std::system(command.c_str());
  }

  std::string sample(const std::string& name) const {
    return std::string(DFORM_SAMPLES_DIR) + "/" + name;
  }

  fs::path dir_;
};

// The model report.html's 3D view draws (its JSON script).
nlohmann::json viewerModel(const std::string& html) {
  const std::string start = "<script type=\"application/json\" id=\"viewer-model\">";
  const std::size_t from = html.find(start);
  EXPECT_NE(from, std::string::npos);
  if (from == std::string::npos) return nlohmann::json::object();
  const std::size_t begin = from + start.size();
  return nlohmann::json::parse(html.substr(begin, html.find("</script>", begin) - begin));
}

// report.html opens offline: nothing is fetched (scripts are inline: no src/href, no CSS url)
// and every still picture is inline SVG. Returns the page.
std::string expectSelfContainedReport(const std::string& dir, const nlohmann::json& report) {
  std::ifstream in(fs::path(dir) / "report.html");
  EXPECT_TRUE(in.good()) << dir << "/report.html";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string html = text.str();
  // The only addresses allowed are XML namespace names (SVG, Inkscape), which are never fetched.
  const std::string rest =
      std::regex_replace(html, std::regex(R"(xmlns(:\w+)?=["'][^"']*["'])"), "");
  for (const char* remote : {"src=", "href=", "url(", "@import", "http://", "https://"})
    EXPECT_EQ(rest.find(remote), std::string::npos) << remote;
  std::size_t svgs = 0;
  for (std::size_t at = 0; (at = html.find("<svg", at)) != std::string::npos; ++at) ++svgs;
  EXPECT_GE(svgs, 7u) << "4 views, 2 curvature maps and the convergence plot";
  for (const auto& check : report["gate"]["checks"])
    EXPECT_NE(html.find(">" + check["name"].get<std::string>() + "<"), std::string::npos)
        << check["name"];
  return html;
}

TEST_F(CliTest, MissingFileIsUnreadable) {
  const std::string missing = path("nowhere.svg");
  expectError(run("forward " + missing + " " + sample("forward/circle.svg") + " -o " + path("out")),
              3, missing);
  EXPECT_FALSE(fs::exists(path("out")));
}

// Inputs that cannot be read whoever runs the tests (root reads any file, so permissions prove
// nothing): a folder, a path through a regular file, a symbolic-link loop. Each exits 3 naming
// the path and saying what it is.
TEST_F(CliTest, UnreadableInputsEvenForRoot) {
  const std::string circle = sample("forward/circle.svg");
  fs::create_directory(path("folder.svg"));
  expectError(run("forward " + path("folder.svg") + " " + circle + " -o " + path("out")), 3,
              path("folder.svg") + ": is a folder");
  const std::string file = write("a-file", "x");
  expectError(run("forward " + file + "/inner.svg " + circle + " -o " + path("out")), 3,
              file + "/inner.svg");
  fs::create_symlink(path("loop-b.svg"), path("loop-a.svg"));
  fs::create_symlink(path("loop-a.svg"), path("loop-b.svg"));
  expectError(run("forward " + path("loop-a.svg") + " " + circle + " -o " + path("out")), 3,
              path("loop-a.svg") + ": cannot be read (Too many levels of symbolic links)");
  fs::create_directory(path("folder.obj"));
  expectError(run("inverse " + path("folder.obj") + " -o " + path("out")), 3,
              path("folder.obj") + ": is a folder");
  fs::create_directory(path("job.json"));
  expectError(run("run " + path("job.json") + " -o " + path("out")), 3,
              path("job.json") + ": is a folder");
  fs::create_directory(path("gate.json"));
  expectError(run("forward " + circle + " " + circle + " -o " + path("out") + " --gate " +
                  path("gate.json")),
              3, path("gate.json") + ": is a folder");
  EXPECT_FALSE(fs::exists(path("out"))) << "nothing is written for input that cannot be read";
}

// Outputs that cannot be put in place whoever runs the tests: a result file's name taken by a
// folder that is not empty (no rename replaces it, not even root's). Exit 6, naming the file.
TEST_F(CliTest, OutputsThatCannotBePutInPlaceEvenForRoot) {
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  const std::string out = path("out");
  fs::create_directories(fs::path(out) / "report.json" / "keep");
  expectError(run("forward " + pair + " --resolution 30 --no-export -q -o " + out), 6,
              out + "/report.json");
  // A saved result exported where pattern.svg's name is taken.
  const std::string saved = path("saved");
  ASSERT_EQ(run("forward " + pair + " --resolution 30 --no-export -q -o " + saved).exitCode, 0);
  fs::create_directories(fs::path(saved) / "pattern.svg" / "keep");
  expectError(run("export " + saved + " -q"), 6, saved + "/pattern.svg");
}

TEST_F(CliTest, NotSvgIsUnreadable) {
  const std::string junk = write("junk.svg", "this is not an svg file");
  expectError(run("forward " + junk + " " + sample("forward/circle.svg") + " -o " + path("out")), 3,
              junk);
}

TEST_F(CliTest, NoClosedPathIsInvalid) {
  const std::string open = write("open.svg", svg("<path d='M 10 10 L 100 10 L 100 100'/>"));
  expectError(run("forward " + open + " " + sample("forward/circle.svg") + " -o " + path("out")), 4,
              open);
}

TEST_F(CliTest, SelfIntersectingOutlineIsInvalid) {
  const std::string bowtie =
      write("bowtie.svg", svg("<polygon points='10,10 100,100 100,10 10,100'/>"));
  expectError(run("forward " + bowtie + " " + sample("forward/circle.svg") + " -o " + path("out")),
              4, bowtie);
}

TEST_F(CliTest, PieceWithAHoleIsInvalid) {
  const std::string ring =
      write("ring.svg", svg("<path d='M 10 10 H 200 V 200 H 10 Z M 50 50 V 150 H 150 V 50 Z'/>"));
  const Outcome o =
      run("forward " + ring + " " + sample("forward/circle.svg") + " -o " + path("out"));
  expectError(o, 4, ring);
  EXPECT_NE(o.err.find("hole"), std::string::npos) << o.err;
}

TEST_F(CliTest, UnequalPerimetersGiveBothInMillimetres) {
  const Outcome o = run("forward " + sample("forward/circle.svg") + " " +
                        sample("forward/ellipses-a.svg") + " -o " + path("out"));
  expectError(o, 4, "perimeters differ");
  EXPECT_NE(o.err.find("800.000 mm"), std::string::npos)
      << o.err;  // the circle's 800 mm, flattened at 1e-4 mm
  EXPECT_NE(o.err.find("607.28"), std::string::npos) << o.err;  // the ellipse's 607.282 mm
  EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(CliTest, HugeAndNonFiniteCoordinatesAreInvalid) {
  const std::string huge = write("huge.json", R"({"points": [[0,0],[1e300,0],[0,10]]})");
  expectError(run("forward " + huge + " " + sample("forward/circle.svg") + " -o " + path("out")), 4,
              huge);
  const std::string inf = write("inf.svg", svg("<rect width='1e999' height='10'/>"));
  expectError(run("forward " + inf + " " + sample("forward/circle.svg") + " -o " + path("out")), 4,
              inf);
  // NaN is bad content (4), as the README says; a number that is not one is an unreadable file (3).
  const std::string nan = write("nan.svg", svg("<polygon points='10,10 NaN,100 100,10'/>"));
  expectError(run("forward " + nan + " " + sample("forward/circle.svg") + " -o " + path("out")), 4,
              "non-finite number 'NaN'");
  const std::string word = write("word.svg", svg("<polygon points='10,10 ten,100 100,10'/>"));
  expectError(run("forward " + word + " " + sample("forward/circle.svg") + " -o " + path("out")), 3,
              "malformed 'points'");
  const std::string objNan =
      write("nan.obj", "v nan 0 0\nv 10 0 1\nv 10 10 0\nv 0 10 1\nv -5 5 2\nl 1 2 3 4 5 1\n");
  expectError(run("inverse " + objNan + " -o " + path("out")), 4, objNan);
  EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(CliTest, TooFewPointsIsInvalid) {
  const std::string two = write("two.json", R"({"points": [[0,0],[10,0]]})");
  expectError(run("forward " + two + " " + sample("forward/circle.svg") + " -o " + path("out")), 4,
              two);
}

TEST_F(CliTest, BadOptionsAreUsageErrors) {
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  expectError(run("forward " + pair + " -o " + path("out") + " --resolution 2"), 2, "resolution");
  expectError(run("forward " + pair + " -o " + path("out") + " --start-b 1.5"), 2, "fraction");
  expectError(run("forward " + pair + " -o " + path("out") + " --weight bogus=1"), 2, "bogus");
  expectError(run("forward " + pair + " -o " + path("out") + " --resolution many"), 2,
              "resolution");
  expectError(run("forward " + pair), 2, "output");
  expectError(run("frobnicate"), 2, "frobnicate");
  // An unknown gate preset is a usage mistake like an unknown export profile, found before any
  // work; a gate file that cannot be read is unreadable input.
  const Outcome gate = run("forward " + pair + " -o " + path("out") + " --gate bogus");
  expectError(gate, 2, "unknown gate \"bogus\" (known: default, lenient, strict");
  EXPECT_FALSE(fs::exists(path("out")));
  expectError(run("forward " + pair + " -o " + path("out") + " --gate " + path("missing.json")), 3,
              path("missing.json"));
  expectError(run("forward " + pair + " -o " + path("out") + " --resolution 20 -q --profile bogus"),
              2, "unknown profile \"bogus\"");
  expectError(run("validate " + path("out") + " --gate bogus"), 2, "unknown gate");
}

TEST_F(CliTest, ATemplatesFolderThatIsNotOneIsUnreadableInput) {
  // $DFORM_TEMPLATES set to a folder without gates/ (a user's typo, a half-copied install): one
  // line naming it, exit 3, before any work and for every command that reads templates.
  fs::create_directories(path("templates/profiles"));
  const std::string env = "env DFORM_TEMPLATES=" + path("templates");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  for (const std::string& args :
       {"forward " + pair + " -q -o " + path("out"), std::string("export --list-profiles"),
        "forward " + pair + " -q -o " + path("out") + " --gate strict"}) {
    SCOPED_TRACE(args);
    expectError(run(args, env), 3, "DFORM_TEMPLATES=" + path("templates") + " is not a dform");
  }
  EXPECT_FALSE(fs::exists(path("out")));
  // The same folder completed is one.
  fs::create_directories(path("templates/gates"));
  fs::create_directories(path("templates/report"));
  const Outcome listed = run("export --list-profiles", env);
  EXPECT_EQ(listed.exitCode, 0) << listed.err;
  EXPECT_EQ(listed.out, "");
}

TEST_F(CliTest, UnwritableOutputIsAnOutputError) {
  const std::string file = write("a-file", "x");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  expectError(run("forward " + pair + " --resolution 30 -q -o " + file + "/out"), 6, file);
}

TEST_F(CliTest, ForwardWritesEveryFileAndValidates) {
  const std::string out = path("out");
  const Outcome o = run("forward " + sample("forward/ellipses-a.svg") + " " +
                        sample("forward/ellipses-b.svg") + " --resolution 40 -q -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  for (const char* name :
       {"piece-a-flat.obj", "piece-a-3d.obj", "piece-b-flat.obj", "piece-b-3d.obj", "report.json",
        "pattern.svg", "pattern.dxf", "pattern.pdf", "dform.stl", "dform.glb"})
    EXPECT_TRUE(fs::exists(fs::path(out) / name)) << name;
  // No temporary file is left behind.
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  for (const char* key : {"L_error", "L_max", "B_error", "seam_gap_mm", "angle_defect_max_rad",
                          "angle_defect_mean_rad"})
    EXPECT_TRUE(report["metrics"][key].is_number()) << key;
  // Every stage of the command is timed, and the stages are disjoint parts of its total.
  const nlohmann::json& t = report["timings"];
  double stages = 0;
  for (const char* key : {"run", "gate", "write", "export", "report"}) {
    EXPECT_TRUE(t[key].is_number()) << key;
    EXPECT_GE(t[key].get<double>(), 0.0) << key;
    stages += t[key].get<double>();
  }
  EXPECT_GE(t["run"].get<double>(),
            t["read"].get<double>() + t["mesh"].get<double>() + t["solve"].get<double>());
  EXPECT_GE(t["total"].get<double>(), stages) << t.dump();
  EXPECT_LE(report["metrics"]["L_error"].get<double>(), 0.005);
  EXPECT_EQ(schemaCheck((fs::path(out) / "report.json").string()), 0);
  // The glTF preview carries the curvature map by default; the pattern is fit to cut.
  EXPECT_NE(readText(fs::path(out) / "dform.glb").find("\"COLOR_0\""), std::string::npos);
  const nlohmann::json pattern =
      nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  EXPECT_FALSE(pattern["failed_gate"].get<bool>());
  EXPECT_EQ(pattern["job"], "ellipses-a");
  const std::string html = expectSelfContainedReport(out, report);
  EXPECT_NE(html.find("PASSED"), std::string::npos);
  EXPECT_NE(html.find("id=\"A-cut\""), std::string::npos) << "the flat pattern, inline";
  // The 3D view labels the pattern's ticks, numbered as printed ("6." for a 6 upside down).
  const nlohmann::json viewer = viewerModel(html);
  ASSERT_EQ(viewer["ticks"].size(), pattern["ticks"].size());
  for (size_t k = 0; k < pattern["ticks"].size(); ++k)
    EXPECT_EQ(viewer["ticks"][k]["label"].get<std::string>().rfind(std::to_string(k), 0), 0u) << k;
  const Outcome v = run("validate " + out);
  EXPECT_EQ(v.exitCode, 0) << v.out;
  EXPECT_NE(v.out.find("gate: PASSED"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("match the meshes"), std::string::npos) << v.out;
  // A report whose figures were edited no longer matches its meshes: validate says which, fails.
  nlohmann::json edited = report;
  edited["metrics"]["L_max"] = 0.0001;
  std::ofstream(fs::path(out) / "report.json") << edited.dump();
  const Outcome tampered = run("validate " + out);
  EXPECT_EQ(tampered.exitCode, 7);
  EXPECT_NE(tampered.out.find("L_max"), std::string::npos) << tampered.out;
}

TEST_F(CliTest, ProgressOnlyOnATerminalAndNotWhenQuiet) {
  const std::string args = "forward " + sample("forward/ellipses-a.svg") + " " +
                           sample("forward/ellipses-b.svg") + " --no-export --model paper";
  // The paper model iterates (the exact one answers in one go). util-linux `script` runs the
  // command on a pseudo-terminal and copies what it shows.
  auto onTerminal = [&](const std::string& more, const std::string& out) {
    const std::string command = "script -qec '" + std::string(DFORM_EXE) + " " + args + more +
                                " -o " + path(out) + "' /dev/null > " + path(out + ".txt") +
                                " 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    std::ostringstream text;
    text << std::ifstream(path(out + ".txt")).rdbuf();
    return text.str();
  };
  const std::string shown = onTerminal(" --resolution 30", "tty");
  EXPECT_NE(shown.find("level 1/1: solving 1/100 iterations, cost "), std::string::npos) << shown;
  // Two levels (a seam of 80 has a coarse level of 26): each named, with the time its cap would
  // take at its own rate from its stage's second iteration on.
  const std::string levels = onTerminal(" --resolution 80", "tty-levels");
  EXPECT_NE(levels.find("level 1/2: relaxing 1/"), std::string::npos) << levels;
  EXPECT_TRUE(std::regex_search(
      levels, std::regex(R"(level 2/2: relaxing 2/\d+ steps, cost \S+, ETA \d+ s)")))
      << levels;
  EXPECT_NE(shown.find("\r\033[K"), std::string::npos) << "redrawn in place";
  // The inverse's paper model (a curve off its hull) names its level too.
  const std::string curve = "script -qec '" + std::string(DFORM_EXE) + " inverse " +
                            sample("inverse/pushed-in.obj") +
                            " --resolution 40 --no-export --gate none -o " + path("tty-inverse") +
                            "' /dev/null > " + path("tty-inverse.txt") + " 2>&1";
  EXPECT_EQ(std::system(curve.c_str()), 0) << curve;
  std::ostringstream inverseShown;
  inverseShown << std::ifstream(path("tty-inverse.txt")).rdbuf();
  EXPECT_NE(inverseShown.str().find("level 1/1: relaxing "), std::string::npos)
      << inverseShown.str();
  const std::string quiet = onTerminal(" --resolution 30 -q", "tty-quiet");
  EXPECT_EQ(quiet.find("level 1/1"), std::string::npos) << quiet;
  EXPECT_EQ(quiet.find("gate: PASSED"), std::string::npos) << "quiet prints nothing but errors";
  // Not a terminal (a batch job's log): no progress at all.
  const Outcome piped = run(args + " --resolution 30 -o " + path("piped"));
  EXPECT_EQ(piped.exitCode, 0) << piped.err;
  EXPECT_EQ(piped.err.find("level 1/1"), std::string::npos) << piped.err;
  EXPECT_NE(piped.err.find("solve: converged"), std::string::npos) << "the stages are still logged";
  EXPECT_EQ(piped.err.find('\r'), std::string::npos);
}

TEST_F(CliTest, AFailedGateKeepsTheReportAndReleasesNothing) {
  const std::string out = path("out");
  const std::string pieces =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  ASSERT_EQ(run("forward " + pieces + " --resolution 30 -q -o " + out).exitCode, 0);
  ASSERT_TRUE(fs::exists(fs::path(out) / "pattern.svg"));
  // Run again into the same folder with the paper model against a gate it cannot pass
  // (L_error <= 1e-9; an exact result's L_error is rounding).
  const std::string tight =
      write("tight.json", R"({"version": 1, "name": "tight", "limits": {"L_error": 1e-9}})");
  const Outcome failed =
      run("forward " + pieces + " --resolution 30 --model paper --gate " + tight + " -o " + out);
  expectError(failed, 7, "no cutting files");
  EXPECT_NE(failed.out.find("gate: FAILED (tight: "), std::string::npos) << failed.out;
  for (const char* name :
       {"pattern.svg", "pattern.dxf", "pattern.pdf", "pattern.json", "dform.stl", "dform.glb"})
    EXPECT_FALSE(fs::exists(fs::path(out) / name))
        << name << ": the previous run's file must not stay";
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_FALSE(report["gate"]["passed"].get<bool>());
  EXPECT_EQ(schemaCheck((fs::path(out) / "report.json").string()), 0);
  const std::string html = expectSelfContainedReport(out, report);
  EXPECT_NE(html.find("FAILED GATE"), std::string::npos);
  EXPECT_TRUE(viewerModel(html)["ticks"].empty()) << "no pattern, no tick numbers";
  EXPECT_NE(html.find("<tr class=\"fail\"><td>L_error</td>"), std::string::npos);

  // The saved result is not exported by accident; on purpose it is, marked, and the page shows it.
  EXPECT_EQ(run("export " + out + " -q").exitCode, 7);
  EXPECT_FALSE(fs::exists(fs::path(out) / "pattern.svg"));
  ASSERT_EQ(run("export " + out + " --export-anyway -q").exitCode, 0);
  std::ostringstream svg;
  svg << std::ifstream(fs::path(out) / "pattern.svg").rdbuf();
  EXPECT_NE(svg.str().find("FAILED GATE"), std::string::npos);
  const nlohmann::json reexported =
      nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  EXPECT_TRUE(reexported["failed_gate"].get<bool>());
  EXPECT_EQ(reexported["job"], "ellipses-a") << "the job's name, not the folder's";
  std::ostringstream page;
  page << std::ifstream(fs::path(out) / "report.html").rdbuf();
  EXPECT_NE(page.str().find("id=\"A-cut\""), std::string::npos)
      << "the report shows the new pattern";
  EXPECT_NE(page.str().find("Made by the <strong>paper</strong> model"), std::string::npos)
      << "the page says which model made the shape";
  EXPECT_NE(page.str().find("from the exact D-Form the cut pieces make"), std::string::npos);

  // --export-anyway on the run itself: every cutting file written and marked, still exit 7.
  const std::string anyway = path("anyway");
  const Outcome marked = run("forward " + pieces + " --resolution 30 --model paper -q --gate " +
                             tight + " --export-anyway -o " + anyway);
  EXPECT_EQ(marked.exitCode, 7) << marked.err;
  std::ostringstream stl;
  stl << std::ifstream(fs::path(anyway) / "dform.stl", std::ios::binary).rdbuf();
  EXPECT_NE(stl.str().substr(0, 80).find("FAILED GATE"), std::string::npos)
      << "the STL header says so";
  const nlohmann::json markedReport =
      nlohmann::json::parse(std::ifstream(fs::path(anyway) / "report.json"));
  EXPECT_EQ(markedReport["gate"]["checks"].back()["name"], "pattern_layout");
  EXPECT_EQ(markedReport["gate"]["checks"].back()["verdict"], "pass");
  const nlohmann::json markedPattern =
      nlohmann::json::parse(std::ifstream(fs::path(anyway) / "pattern.json"));
  EXPECT_TRUE(markedPattern["failed_gate"].get<bool>());
}

TEST_F(CliTest, ExportOptionsOnTheCommandLine) {
  const std::string pieces =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  const std::string out = path("out");
  const Outcome o = run("forward " + pieces + " --resolution 30 -q --tabs alternate --tab-width 8" +
                        " --tick-spacing 25 --gltf -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  const nlohmann::json pattern =
      nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  EXPECT_EQ(pattern["tabs_on"], "alternate");
  EXPECT_EQ(pattern["tick_spacing_mm"].get<double>(), 25.0);
  int onB = 0;
  for (const auto& tab : pattern["tabs"]) {
    onB += tab["piece"] == "B";
    EXPECT_LE(tab["width"].get<double>(), 8.0);
  }
  EXPECT_GT(onB, 3) << "tabs on B too";
  EXPECT_EQ(pattern["tabs"][0]["width"].get<double>(), 8.0);
  EXPECT_NEAR(pattern["ticks"][1]["s"].get<double>(), 25.0, 1e-9);
  // A text glTF instead of the binary one, with the curvature colours.
  EXPECT_FALSE(fs::exists(fs::path(out) / "dform.glb"));
  const nlohmann::json gltf = nlohmann::json::parse(std::ifstream(fs::path(out) / "dform.gltf"));
  EXPECT_TRUE(gltf["meshes"][0]["primitives"][0]["attributes"].contains("COLOR_0"));
  // Re-exported without tabs, as a .glb again.
  ASSERT_EQ(run("export " + out + " --tabs none -q").exitCode, 0);
  const nlohmann::json bare = nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  EXPECT_TRUE(bare["tabs"].empty());
  EXPECT_TRUE(fs::exists(fs::path(out) / "dform.glb"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "dform.gltf")) << "the previous preview is replaced";

  // Bad values are usage errors, found before anything is solved or written.
  const std::string bad = path("bad");
  expectError(run("forward " + pieces + " --tabs both -o " + bad), 2,
              "--tabs must be a, b, alternate or none");
  expectError(run("forward " + pieces + " --tab-width 60 -o " + bad), 2,
              "--tab-width must be a number between 0 and 50 mm, got 60");
  expectError(run("forward " + pieces + " --tab-width wide -o " + bad), 2, "--tab-width");
  expectError(run("forward " + pieces + " --tick-spacing 0.5 -o " + bad), 2,
              "--tick-spacing must be a number at least 1 mm");
  expectError(run("run " + sample("forward/ellipse-twin.json") + " --tick-spacing -3 -o " + bad), 2,
              "--tick-spacing must be a number at least 1 mm, got -3");
  EXPECT_FALSE(fs::exists(bad));
  expectError(run("export " + out + " --tabs left"), 2, "--tabs");

  // Joints, material and kerf: re-exported with hole pairs and a kerf, then bad values.
  ASSERT_EQ(run("export " + out + " --joint holes --material card --kerf 0.2 -q").exitCode, 0);
  const nlohmann::json holes = nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  EXPECT_EQ(holes["joint"]["kind"], "holes");
  EXPECT_EQ(holes["joint"]["material"], "card");
  EXPECT_EQ(holes["joint"]["thickness_mm"].get<double>(), 0.3);
  EXPECT_EQ(holes["kerf_mm"].get<double>(), 0.2);
  EXPECT_GT(holes["joint_holes"].size(), 10u);
  EXPECT_TRUE(holes["tabs"].empty()) << "no glue tabs with holes unless asked";
  expectError(run("export " + out + " --joint tape"), 2,
              "--joint must be glue, holes, lace or slots");
  ASSERT_EQ(run("export " + out + " --joint slots --slot-length 8 -q").exitCode, 0);
  const nlohmann::json slots = nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  EXPECT_EQ(slots["joint"]["slot_length_mm"].get<double>(), 8.0);
  EXPECT_GT(slots["joint_slots"].size(), 10u);
  expectError(run("export " + out + " --joint slots --slot-length 1"), 2, "--slot-length");
  expectError(run("export " + out + " --joint slots --tabs a"), 2, "--joint slots");
  expectError(run("export " + out + " --material steel"), 2,
              "--material must be paper, card, polypropylene or plywood");
  expectError(run("export " + out + " --kerf 9"), 2, "--kerf");
  expectError(run("export " + out + " --kerf thin"), 2, "--kerf");
  expectError(run("export " + out + " --hole-edge 1"), 2, "--hole-edge");
  expectError(run("export " + out + " --hole-diameter 0"), 2, "--hole-diameter");
  expectError(run("forward " + pieces + " --hole-spacing 3 -o " + bad), 2, "--hole-spacing");
  EXPECT_FALSE(fs::exists(bad));
}

TEST_F(CliTest, ExportNestsSeveralResultsIntoAFolderOfItsOwn) {
  const std::string pieces =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  for (const char* result : {"r1", "r2"})
    ASSERT_EQ(
        run("forward " + pieces + " --resolution 30 -q --no-export -o " + path(result)).exitCode,
        0);
  const std::string both = path("r1") + " " + path("r2");
  const Outcome nested =
      run("export " + both + " --nest --copies 2 --sheet 600x400mm -q -o " + path("nest"));
  ASSERT_EQ(nested.exitCode, 0) << nested.err;
  const nlohmann::json pattern =
      nlohmann::json::parse(std::ifstream(fs::path(path("nest")) / "pattern.json"));
  ASSERT_EQ(pattern["nest"]["parts"].size(), 8u) << "two pieces, two results, two copies";
  EXPECT_EQ(pattern["nest"]["parts"][0]["job"], "ellipses-a");
  const size_t sheets = pattern["sheets"].size();
  for (size_t k = 1; sheets > 1 && k <= sheets; ++k)
    EXPECT_TRUE(
        fs::exists(fs::path(path("nest")) / ("pattern-sheet-" + std::to_string(k) + ".dxf")));
  // Several results without --nest, a nest without its folder or with no copies: usage errors.
  EXPECT_EQ(run("export " + both + " -q -o " + path("plain")).exitCode, 2);
  EXPECT_EQ(run("export " + both + " --nest -q").exitCode, 2);
  EXPECT_EQ(run("export " + both + " --nest --copies 0 -q -o " + path("none")).exitCode, 2);
}

TEST_F(CliTest, PrintAndCutPutsEachPieceOnItsOwnPage) {
  // A 160 x 100 mm ellipse and a circle of its perimeter (413.8 mm): each fits an A4 page's
  // registration area, the two together do not.
  const std::string a = write("a.svg", svg("<ellipse cx='150' cy='150' rx='80' ry='50'/>"));
  const std::string b = write("b.svg", svg("<circle cx='150' cy='150' r='65.86'/>"));
  const std::string out = path("out");
  const Outcome o =
      run("forward " + a + " " + b + " --resolution 30 -q --profile print-and-cut -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  const nlohmann::json pattern =
      nlohmann::json::parse(std::ifstream(fs::path(out) / "pattern.json"));
  ASSERT_EQ(pattern["pages"].size(), 2u);
  EXPECT_EQ(pattern["pages"][1]["origin"][0].get<double>(), 210.0);
  const std::string svgText = readText(fs::path(out) / "pattern.svg");
  EXPECT_NE(svgText.find("id=\"regmark-square-page-2\""), std::string::npos);
}

TEST_F(CliTest, AFolderWhoseFileNamesAreTakenIsRefusedBeforeTheSolve) {
  // report.json's or pattern.pdf's name taken by a folder: the result folder is replaced as a
  // whole, and the folder in the way is not a result's, so the run stops before solving and
  // changes nothing.
  for (const char* taken : {"report.json", "pattern.pdf"}) {
    const std::string out = path(std::string("out-") + taken);
    fs::create_directories(fs::path(out) / taken / "blocked");
    const Outcome o = run("forward " + sample("forward/ellipses-a.svg") + " " +
                          sample("forward/ellipses-b.svg") + " --resolution 30 -q -o " + out);
    expectError(o, 6, out + "/" + taken + ": is not part of a dform result");
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1) << taken;
    EXPECT_TRUE(fs::is_directory(fs::path(out) / taken / "blocked"));
  }
}

// Occurrences of `needle` in `text`.
std::size_t countOf(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
    ++count;
  return count;
}

// The exact result's fold map: circle + square at resolution 100 folds the disc at its four found
// creases (66.7 degrees, where the square's corners meet it) and gently between them; report.html
// draws each fold on the flat pieces, the creases stronger, with a legend line.
TEST_F(CliTest, TheFoldMapIsListedAndDrawnOnTheFlatPieces) {
  const std::string out = path("folds");
  ASSERT_EQ(run("forward " + sample("forward/circle.svg") + " " + sample("forward/square.svg") +
                " --resolution 100 --no-export -q -o " + out)
                .exitCode,
            0);
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  ASSERT_EQ(report["model"]["name"], "exact");
  std::size_t creases = 0, gentle = 0;
  for (const nlohmann::json& fold : report["model"]["folds"]) {
    EXPECT_NEAR(fold["angle_rad"].get<double>() * 180.0 / std::acos(-1.0),
                fold["angle_deg"].get<double>(), 1e-9);
    if (fold["crease"].get<bool>()) {
      ++creases;
      EXPECT_NEAR(fold["angle_deg"].get<double>(), 66.7, 0.5);
    } else {
      ++gentle;
      EXPECT_LT(fold["angle_deg"].get<double>(), 20.0);
    }
  }
  EXPECT_EQ(creases, 4u);
  EXPECT_EQ(creases, report["model"]["found_creases"].size());
  EXPECT_GT(gentle, 0u);
  const std::string html = readText(fs::path(out) / "report.html");
  EXPECT_EQ(countOf(html, "class='fold steep'"), creases);
  EXPECT_EQ(countOf(html, "class='fold gentle'"), gentle);
  EXPECT_NE(html.find("Faint lines: the folds of the exact body (" +
                      std::to_string(creases + gentle) + ")"),
            std::string::npos);
  // The schema takes the fold map and refuses a fold without its angle or its piece.
  EXPECT_EQ(schemaCheck((fs::path(out) / "report.json").string()), 0);
  for (const char* key : {"angle_deg", "angle_rad", "piece"}) {
    nlohmann::json edited = report;
    edited["model"]["folds"][0].erase(key);
    std::ofstream(path("edited.json")) << edited.dump();
    EXPECT_NE(schemaCheck(path("edited.json")), 0) << "a fold without " << key;
  }
  nlohmann::json nullAngle = report;
  nullAngle["model"]["folds"][0]["angle_deg"] = nullptr;
  std::ofstream(path("edited.json")) << nullAngle.dump();
  EXPECT_NE(schemaCheck(path("edited.json")), 0) << "a fold with a null angle";
}

TEST_F(CliTest, TheGeneralModelReportsHowStationaryItsAnswerIs) {
  const std::string out = path("general");
  ASSERT_EQ(
      run("forward " + sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg") +
          " --model general --resolution 30 --no-export -q -o " + out)
          .exitCode,
      0);
  EXPECT_EQ(schemaCheck((fs::path(out) / "report.json").string()), 0);
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_EQ(report["model"]["name"], "general");
  ASSERT_TRUE(report["model"]["stationarity"].is_number());
  EXPECT_LE(report["model"]["stationarity"].get<double>(), 1e-6);
  EXPECT_GT(report["model"]["newton_steps"].get<int>(), 0);
  EXPECT_EQ(run("validate " + out).exitCode, 0);
  const Outcome bad =
      run("forward " + sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg") +
          " --model generic -q -o " + path("generic"));
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("auto, exact, ruled, paper or general"), std::string::npos) << bad.err;
}

TEST_F(CliTest, ReportsFollowTheirSchema) {
  const std::string forward = path("forward"), inverse = path("inverse");
  // Resolution 30 is coarser than the samples strict is measured on: circle + square by the
  // paper model fails it, exit 7, and the report has the checks all the same.
  const int code =
      run("forward " + sample("forward/circle.svg") + " " + sample("forward/square.svg") +
          " --resolution 30 --model paper --gate strict --no-export -q -o " + forward)
          .exitCode;
  ASSERT_EQ(code, 7);
  ASSERT_TRUE(fs::exists(fs::path(forward) / "report.json"));
  EXPECT_EQ(schemaCheck((fs::path(forward) / "report.json").string()), 0);
  // The preset by its path under templates/, as the docs write it: the same gate.
  const nlohmann::json byName =
      nlohmann::json::parse(std::ifstream(fs::path(forward) / "report.json"));
  EXPECT_EQ(run("validate " + forward + " --gate gates/strict.json").exitCode, code);
  EXPECT_EQ(byName["gate"]["name"], "strict");
  ASSERT_EQ(run("inverse " + sample("inverse/saddle.obj") + " --resolution 40 --no-export -q -o " +
                inverse)
                .exitCode,
            0);
  EXPECT_EQ(schemaCheck((fs::path(inverse) / "report.json").string()), 0);
  // The schema is not a formality: a report missing a figure or with a stray key fails it.
  nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(inverse) / "report.json"));
  report["metrics"].erase("L_max");
  std::ofstream(path("broken.json")) << report.dump();
  EXPECT_NE(schemaCheck(path("broken.json")), 0);
  report = nlohmann::json::parse(std::ifstream(fs::path(inverse) / "report.json"));
  report["surprise"] = 1;
  std::ofstream(path("stray.json")) << report.dump();
  EXPECT_NE(schemaCheck(path("stray.json")), 0);

  // Each mode has its own required parts: a report missing one, or carrying the other mode's,
  // or claiming the other mode, fails.
  const nlohmann::json saved[2] = {
      nlohmann::json::parse(std::ifstream(fs::path(forward) / "report.json")),
      nlohmann::json::parse(std::ifstream(fs::path(inverse) / "report.json"))};
  auto failsWhen = [&](int which, const std::string& what, auto change) {
    nlohmann::json edited = saved[which];
    change(edited);
    std::ofstream(path("edited.json")) << edited.dump();
    EXPECT_NE(schemaCheck(path("edited.json")), 0) << what;
  };
  using J = nlohmann::json;
  failsWhen(1, "inverse without D_error", [](J& r) { r["metrics"].erase("D_error"); });
  failsWhen(1, "inverse without curve_distance_max_mm",
            [](J& r) { r["metrics"].erase("curve_distance_max_mm"); });
  failsWhen(1, "inverse without curve_length_mm",
            [](J& r) { r["metrics"].erase("curve_length_mm"); });
  failsWhen(1, "inverse without pre_dform", [](J& r) { r.erase("pre_dform"); });
  failsWhen(1, "inverse with empty inputs", [](J& r) { r["inputs"] = J::object(); });
  failsWhen(1, "inverse claiming forward", [](J& r) { r["mode"] = "forward"; });
  failsWhen(1, "inverse with a forward job", [&](J& r) { r["job"] = saved[0]["job"]; });
  failsWhen(0, "forward without B_error", [](J& r) { r["metrics"].erase("B_error"); });
  failsWhen(0, "forward without piece_b", [](J& r) { r["inputs"].erase("piece_b"); });
  failsWhen(0, "forward with empty inputs", [](J& r) { r["inputs"] = J::object(); });
  failsWhen(0, "forward with a curve input",
            [&](J& r) { r["inputs"]["curve"] = saved[1]["inputs"]["curve"]; });
  failsWhen(0, "forward with D_error", [](J& r) { r["metrics"]["D_error"] = 0.0; });
  failsWhen(0, "forward claiming inverse", [](J& r) { r["mode"] = "inverse"; });
  failsWhen(0, "forward with a pre-D-Form", [&](J& r) { r["pre_dform"] = saved[1]["pre_dform"]; });
  // The paper model knows no body: no fold map.
  EXPECT_EQ(saved[0]["model"]["name"], "paper");
  EXPECT_FALSE(saved[0]["model"].contains("folds"));
}

// Every shipped sample, as shipped (its job file's options, or an inverse curve's defaults):
// shippedSamples() from tests/shipped_samples.h.
using test::shippedSamples;

// A test name for a sample: its path without the extension, other characters than letters and
// digits as '_'.
std::string sampleTestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(0, info.param.rfind('.'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class SampleUnderStrictGate : public CliTest, public ::testing::WithParamInterface<std::string> {};

// The strict preset is set from the samples' figures with a margin (docs/validation.md): every
// sample passes it, and the gate that ran is the strict one.
TEST_P(SampleUnderStrictGate, Passes) {
  const std::string file = sample(GetParam());
  const bool forward = GetParam().rfind("forward/", 0) == 0;
  const std::string out = path("out");
  const Outcome o = run(std::string(forward ? "run " : "inverse ") + file +
                        " --gate strict --no-export -q -o " + out);
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_EQ(report["gate"]["name"], "strict");
  // The pushed-in curve leaves its hull: its pieces' metric is not convex, and zipped again (by
  // the optimisation) they take another shape, 0.56 % of the diagonal off the curve. The gate
  // says so on the round trip, and on nothing else.
  if (GetParam() == "inverse/pushed-in.obj") {
    EXPECT_EQ(o.exitCode, 7) << o.out << o.err;
    std::vector<std::string> failed;
    for (const auto& check : report["gate"]["checks"])
      if (check["verdict"] == "fail") failed.push_back(check["name"]);
    EXPECT_EQ(failed, std::vector<std::string>{"roundtrip_rel"}) << report["gate"].dump(1);
    return;
  }
  EXPECT_EQ(o.exitCode, 0) << o.out << o.err;
  EXPECT_TRUE(report["gate"]["passed"].get<bool>()) << report["gate"].dump(1);
}

INSTANTIATE_TEST_SUITE_P(Shipped, SampleUnderStrictGate, ::testing::ValuesIn(shippedSamples()),
                         sampleTestName);

class SampleOnEveryKernel : public CliTest, public ::testing::WithParamInterface<std::string> {};

// The figures and the gate's verdicts of a sample do not depend on the machine: OpenBLAS picks a
// kernel per CPU (AVX-512, Haswell, Sandybridge, ...), which round differently, and the linear
// algebra may run on more or fewer threads. Each sample runs in a child process per setting; the
// figures must agree to 3 significant digits and every verdict must be the same.
TEST_P(SampleOnEveryKernel, GivesTheSameFiguresAndVerdicts) {
  const std::string file = sample(GetParam());
  const bool forward = GetParam().rfind("forward/", 0) == 0;
  const std::pair<std::string, std::string> settings[] = {
      {"native", "env -u OPENBLAS_CORETYPE"},
      {"haswell", "env OPENBLAS_CORETYPE=Haswell OPENBLAS_NUM_THREADS=2 OMP_NUM_THREADS=2"},
      {"sandybridge",
       "env OPENBLAS_CORETYPE=Sandybridge OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1"}};
  std::vector<nlohmann::json> reports;
  std::vector<int> codes;
  for (const auto& [name, environment] : settings) {
    const std::string out = path(name);
    const Outcome o = run(std::string(forward ? "run " : "inverse ") + file +
                              " --gate strict --no-export -q -o " + out,
                          environment);
    ASSERT_TRUE(fs::exists(fs::path(out) / "report.json")) << name << ": " << o.err;
    codes.push_back(o.exitCode);
    reports.push_back(nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json")));
  }
  // 3 significant digits: a relative difference below half a unit in the third digit.
  const auto agree = [](double a, double b) {
    return std::abs(a - b) <= 5e-4 * std::max(std::abs(a), std::abs(b));
  };
  const nlohmann::json& first = reports[0];
  ASSERT_FALSE(first["metrics"].empty());
  for (std::size_t s = 1; s < reports.size(); ++s) {
    const std::string& name = settings[s].first;
    const nlohmann::json& other = reports[s];
    EXPECT_EQ(codes[s], codes[0]) << name;
    for (const auto& [key, value] : first["metrics"].items()) {
      ASSERT_TRUE(other["metrics"].contains(key)) << name << ": " << key;
      if (value.is_number())
        EXPECT_PRED2(agree, value.get<double>(), other["metrics"][key].get<double>())
            << name << ": " << key;
      else
        EXPECT_EQ(value, other["metrics"][key]) << name << ": " << key;
    }
    EXPECT_EQ(first["gate"]["passed"], other["gate"]["passed"]) << name;
    const nlohmann::json &checks = first["gate"]["checks"], &otherChecks = other["gate"]["checks"];
    ASSERT_EQ(checks.size(), otherChecks.size()) << name;
    for (std::size_t c = 0; c < checks.size(); ++c)
      EXPECT_EQ(checks[c]["verdict"], otherChecks[c]["verdict"])
          << name << ": " << checks[c]["name"];
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, SampleOnEveryKernel, ::testing::ValuesIn(shippedSamples()),
                         sampleTestName);

TEST_F(CliTest, AFailedExportStillSavesTheResult) {
  const std::string out = path("out");
  const Outcome o =
      run("forward " + sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg") +
          " --resolution 30 -q --sheet 100x100mm -o " + out);
  expectError(o, 2, "does not fit");
  EXPECT_NE(o.err.find("dform export " + out), std::string::npos) << o.err;
  EXPECT_TRUE(fs::exists(fs::path(out) / "report.json"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "piece-b-3d.obj"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "pattern.svg"));
  // Redone alone on a larger sheet.
  EXPECT_EQ(run("export " + out + " --sheet 600x400mm -q").exitCode, 0);
  EXPECT_TRUE(fs::exists(fs::path(out) / "pattern.svg"));
}

TEST_F(CliTest, JobFileReproducesTheRun) {
  const std::string out = path("out");
  const std::string job =
      write("job.json", R"({"mode": "forward", "piece_a": ")" + sample("forward/circle.svg") +
                            R"(", "piece_b": ")" + sample("forward/square.svg") +
                            R"(", "start_b": 0.125, "resolution": 60})");
  const Outcome o = run("run " + job + " --no-export -q -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  EXPECT_FALSE(fs::exists(fs::path(out) / "pattern.svg"));
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_TRUE(report["timings"]["export"].is_null()) << "nothing exported, nothing timed";
  EXPECT_EQ(report["job"]["start_b"].get<double>(), 0.125);
  // The inputs are named by content too: a result can be traced to the exact files.
  EXPECT_EQ(report["inputs"]["piece_a"]["sha256"],
            sha256Hex(readText(sample("forward/circle.svg"))));
  EXPECT_EQ(report["inputs"]["piece_b"]["sha256"],
            sha256Hex(readText(sample("forward/square.svg"))));
  EXPECT_EQ(report["job"]["resolution"].get<int>(), 60);
  // The recorded job runs again to the same figures.
  const std::string again = write("again.json", report["job"].dump());
  ASSERT_EQ(run("run " + again + " --no-export -q -o " + path("out2")).exitCode, 0);
  const nlohmann::json second =
      nlohmann::json::parse(std::ifstream(fs::path(path("out2")) / "report.json"));
  EXPECT_EQ(report["metrics"]["L_error"], second["metrics"]["L_error"]);
  EXPECT_EQ(report["metrics"]["B_error"], second["metrics"]["B_error"]);
}

TEST_F(CliTest, BadJobFilesNameTheKey) {
  const std::string unknown =
      write("unknown.json",
            R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "colour": 3})");
  expectError(run("run " + unknown + " -o " + path("out")), 4, "colour");
  const std::string missing = write("missing.json", R"({"mode": "forward", "piece_a": "a.svg"})");
  expectError(run("run " + missing + " -o " + path("out")), 4, "piece_b");
  const std::string typed =
      write("typed.json",
            R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "resolution": "high"})");
  expectError(run("run " + typed + " -o " + path("out")), 4, "resolution");
  const std::string notJson = write("not.json", "{ mode: forward");
  expectError(run("run " + notJson + " -o " + path("out")), 3, notJson);
}

TEST_F(CliTest, OversizedInputsStopEarlyWithOneLine) {
  // A seam curve of 1.2 million points, past the million the reader takes: refused at the vertex
  // past the limit, never solved.
  std::string vertices;
  for (int i = 0; i < 1'200'000; ++i) vertices += "v 1 2 3\n";
  const std::string curve = write("dense.obj", vertices + "l 1 2 3 1\n");
  expectError(run("inverse " + curve + " -o " + path("out")), 4,
              "line 1000001: more than 1000000 vertices (the limit)");
  EXPECT_FALSE(fs::exists(path("out")));
  // Job and gate files over a megabyte are refused unread.
  for (const char* name : {"job.json", "gate.json"}) {
    write(name, "");
    fs::resize_file(path(name), (std::uintmax_t(1) << 20) + 1);  // sparse: nothing is written
  }
  expectError(run("run " + path("job.json") + " -o " + path("out")), 3, "too large");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  expectError(run("forward " + pair + " --gate " + path("gate.json") + " -o " + path("out")), 3,
              "too large");
  EXPECT_FALSE(fs::exists(path("out")));
}

// The files of a folder and their bytes.
std::map<std::string, std::string> folderContents(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ostringstream bytes;
    bytes << std::ifstream(entry.path(), std::ios::binary).rdbuf();
    files[entry.path().filename().string()] = bytes.str();
  }
  return files;
}

TEST_F(CliTest, InterruptedRunExitsWithoutTouchingTheOutputFolder) {
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  const std::string out = path("out");
  // The folder holds an earlier complete result, which an interrupted run must leave as it is.
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + out).exitCode, 0);
  const std::map<std::string, std::string> before = folderContents(out);
  ASSERT_GE(before.size(), 9u);

  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal == SIGINT ? "SIGINT" : "SIGTERM");
    // A run long enough to be caught solving (seconds: the paper model; the exact one would be
    // done at once), its stderr in a file we watch.
    const std::string err = path("interrupted.txt");
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const std::string command = "exec " + std::string(DFORM_EXE) + " forward " + pair +
                                  " --resolution 250 --model paper -o " + out + " >/dev/null 2>" +
                                  err;
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    // The finest level is meshed, then solved: the signal comes while it solves.
    std::string log;
    for (int waited = 0; log.find("meshed piece A with") == std::string::npos; ++waited) {
      ASSERT_LT(waited, 12000) << "no solve started within 10 minutes: " << log;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      std::ostringstream text;
      text << std::ifstream(err).rdbuf();
      log = text.str();
    }
    ASSERT_EQ(kill(pid, signal), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "ended by the signal instead of stopping cleanly";
    EXPECT_EQ(WEXITSTATUS(status), signal == SIGINT ? 130 : 143);
    std::ostringstream text;
    text << std::ifstream(err).rdbuf();
    EXPECT_NE(text.str().find("dform: error: " + out + ": interrupted"), std::string::npos)
        << text.str();
    // Nothing written, nothing half-written, no temporary file: the earlier result, unchanged.
    EXPECT_TRUE(folderContents(out) == before);
  }
}

TEST_F(CliTest, TheSameJobGivesBitIdenticalResultsInSeparateProcesses) {
  // Twice each, in separate processes: every figure of report.json and every coordinate of the
  // meshes must be the same to the last bit (no uninitialised value, no reduction whose order
  // changes from run to run, e.g. with the threads of the linear algebra).
  for (const std::string& job : {"run " + sample("forward/ellipses-quarter-turn.json"),
                                 "inverse " + sample("inverse/saddle.obj") + " --resolution 60"}) {
    SCOPED_TRACE(job);
    std::map<std::string, std::string> meshes[2];
    nlohmann::json metrics[2];
    for (int k = 0; k < 2; ++k) {
      const std::string out = path("out" + std::to_string(k));
      ASSERT_EQ(run(job + " --no-export -q -o " + out).exitCode, 0);
      metrics[k] = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"))["metrics"];
      for (const auto& [name, bytes] : folderContents(out))
        if (fs::path(name).extension() == ".obj") meshes[k][name] = bytes;
      fs::remove_all(out);
    }
    EXPECT_GE(metrics[0].size(), 10u);
    EXPECT_EQ(metrics[0], metrics[1]) << metrics[0].dump() << "\n" << metrics[1].dump();
    EXPECT_GE(meshes[0].size(), 4u);
    EXPECT_TRUE(meshes[0] == meshes[1]) << "the meshes differ";
  }
}

TEST_F(CliTest, FitPerimeterScalesPieceB) {
  // An ellipse about 0.9 % longer than the 800 mm circle (a circle zipped to a scaled copy of
  // itself would close flat: two congruent discs make no D-Form).
  const std::string big = write("big.svg", svg("<ellipse cx='150' cy='150' rx='130' ry='127'/>"));
  double perimeter = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const double t0 = 2 * M_PI * k / 100000, t1 = 2 * M_PI * (k + 1) / 100000;
    perimeter +=
        std::hypot(130 * (std::cos(t1) - std::cos(t0)), 127 * (std::sin(t1) - std::sin(t0)));
  }
  const std::string out = path("out");
  const Outcome o = run("forward " + sample("forward/circle.svg") + " " + big +
                        " --fit-perimeter --resolution 30 --no-export -q -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_NEAR(report["fit_perimeter_scale"].get<double>(), 800.0 / perimeter, 1e-4);
  // Both flat seams then measure 800 mm, to 1e-4 of it (a tenth of the default gate's limit).
  EXPECT_NEAR(report["metrics"]["seam_length_a_mm"].get<double>(),
              report["metrics"]["seam_length_b_mm"].get<double>(), 0.08);
}

TEST_F(CliTest, AntiDFormFromTheCommandLineCutsItsHolesAndValidatesAgain) {
  const std::string out = path("anti");
  const Outcome o =
      run("forward " + sample("forward/anti-a.svg") + " " + sample("forward/anti-b.svg") +
          " --join inner,inner --resolution 30 -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  EXPECT_NE((o.out + o.err).find("joining its hole, its outline stays free"), std::string::npos)
      << o.err;
  std::ifstream svgFile(fs::path(out) / "pattern.svg");
  const std::string pattern((std::istreambuf_iterator<char>(svgFile)),
                            std::istreambuf_iterator<char>());
  EXPECT_NE(pattern.find("id=\"A-cut-hole-1\""), std::string::npos);
  EXPECT_NE(pattern.find("id=\"B-cut-hole-1\""), std::string::npos);
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_EQ(report["job"]["join"], "inner,inner");
  EXPECT_EQ(report["job"]["weights"]["smooth_3d"].get<double>(), 0.001);  // the variants' default
  // The saved model reads back with its free outlines, and its figures agree with the report.
  const Outcome check = run("validate " + out);
  EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("its figures match the meshes"), std::string::npos) << check.out;

  expectError(run("forward " + sample("forward/anti-a.svg") + " " + sample("forward/anti-b.svg") +
                  " --join holes -o " + path("bad")),
              2, "--join must be");
}

TEST_F(CliTest, ARunTooLargeForTheMachineStopsAtOnceSayingWhatFits) {
  // About 69 million vertices: hundreds of GB, far beyond any machine this runs on. The run
  // must refuse before meshing (so at once), as a usage error naming the resolution that fits.
  const Outcome forward =
      run("forward " + sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg") +
          " --resolution 20000 -o " + path("huge"));
  expectError(forward, 2, "GB of memory");
  EXPECT_NE(forward.err.find("a resolution of "), std::string::npos) << forward.err;
  EXPECT_FALSE(fs::exists(fs::path(path("huge")) / "report.json"));
  expectError(
      run("inverse " + sample("inverse/saddle.obj") + " --resolution 20000 -o " + path("huge2")), 2,
      "GB of memory");
  expectError(
      run("inverse " + sample("inverse/saddle.obj") + " --resolution 20001 -o " + path("huge3")), 2,
      "between 8 and 20000");
}

// ---- The result folder as one transaction ---------------------------------------------------

// The hidden entries a run keeps beside its result folder while it works (the lock, the staging
// folder, the old result): none may stay once it has ended, unless it was killed outright.
std::vector<std::string> leftoversBeside(const std::string& folder) {
  const fs::path path(folder);
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(path.parent_path())) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("." + path.filename().string() + ".dform-", 0) == 0) found.push_back(name);
  }
  return found;
}

// Runs `command` through sh in a child process after `prepare` (limits, signal dispositions) ran
// in it; returns its pid.
pid_t spawn(const std::string& command, const std::function<void()>& prepare = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (prepare) prepare();
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// Waits for a child; its exit code, or -signal when a signal ended it.
int waitFor(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1000;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// Waits until `file` holds `text` (a stage's message on stderr), at most 10 minutes.
bool waitForText(const std::string& file, const std::string& text) {
  for (int waited = 0; waited < 12000; ++waited) {
    if (readText(file).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

TEST_F(CliTest, AResultFolderIsReplacedWholeAndNothingElseIsTouched) {
  const std::string out = path("out");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  ASSERT_EQ(
      run("inverse " + sample("inverse/saddle.obj") + " --resolution 30 -q -o " + out).exitCode, 0);
  ASSERT_TRUE(fs::exists(fs::path(out) / "target-curve.obj"));
  ASSERT_TRUE(fs::exists(fs::path(out) / "pattern.svg"));
  // A forward run into it: none of the inverse result's files stays (its target curve would make
  // validate measure the forward seam against it), and the result validates.
  const Outcome forward = run("forward " + pair + " --resolution 30 --no-export -q -o " + out);
  ASSERT_EQ(forward.exitCode, 0) << forward.err;
  for (const char* gone :
       {"target-curve.obj", "pattern.svg", "pattern.dxf", "pattern.pdf", "dform.glb"})
    EXPECT_FALSE(fs::exists(fs::path(out) / gone)) << gone;
  const Outcome v = run("validate " + out);
  EXPECT_EQ(v.exitCode, 0) << v.out << v.err;
  EXPECT_TRUE(leftoversBeside(out).empty());
  // A folder holding a file of the user's is never swapped away: refused before the solve.
  write("out/notes.txt", "mine");
  const std::map<std::string, std::string> before = folderContents(out);
  expectError(run("forward " + pair + " --resolution 30 -q -o " + out), 6, out + "/notes.txt");
  EXPECT_TRUE(folderContents(out) == before);
  // The same through a symbolic link: the folder it names is checked and replaced, the link kept.
  fs::remove(fs::path(out) / "notes.txt");
  fs::create_directory_symlink(out, path("link"));
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + path("link")).exitCode, 0);
  EXPECT_TRUE(fs::is_symlink(path("link")));
  EXPECT_TRUE(fs::exists(fs::path(out) / "pattern.svg"));
  EXPECT_TRUE(leftoversBeside(out).empty());
}

// A file that cannot be written (a full disk; here the file-size limit, which fails a write the
// same way) fails the run with exit 6 naming the file in the result folder, and leaves exactly the
// old result, whichever file it was.
TEST_F(CliTest, AFailedWriteLeavesExactlyTheOldResult) {
  const std::string out = path("out");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + out).exitCode, 0);
  const std::map<std::string, std::string> before = folderContents(out);
  std::size_t largest = 0;
  for (const auto& [name, bytes] : before) largest = std::max(largest, bytes.size());
  std::set<std::string> failedFiles;
  // From the first file written (a mesh) to the last ones (the pattern, the report page).
  for (const double fraction : {0.01, 0.1, 0.3, 0.6, 0.9}) {
    const rlim_t limit = rlim_t(fraction * double(largest));
    SCOPED_TRACE("file size limit " + std::to_string(limit));
    const std::string err = path("err.txt");
    const pid_t pid = spawn(std::string(DFORM_EXE) + " forward " + pair +
                                " --resolution 36 -q -o " + out + " >/dev/null 2>" + err,
                            [limit] {
                              const struct rlimit fsize = {limit, limit};
                              setrlimit(RLIMIT_FSIZE, &fsize);
                              std::signal(SIGXFSZ, SIG_IGN);  // a write past it then fails
                            });
    Outcome o;
    o.exitCode = waitFor(pid);
    o.err = readText(err);
    expectError(o, 6, out + "/");
    EXPECT_EQ(o.err.find(".dform-new"), std::string::npos)
        << "named as the user knows it: " << o.err;
    failedFiles.insert(o.err.substr(o.err.find(out + "/")));
    EXPECT_TRUE(folderContents(out) == before);
    EXPECT_TRUE(leftoversBeside(out).empty());
  }
  EXPECT_GE(failedFiles.size(), 2u) << "the limits stop different files";
  EXPECT_EQ(run("validate " + out).exitCode, 0);
}

// Two runs on one folder: the second fails at once (exit 6, saying another run is writing it)
// and touches nothing; the first then stops on SIGTERM, leaving the old result.
TEST_F(CliTest, ASecondRunOnTheSameFolderFailsWhileTheFirstHoldsIt) {
  const std::string out = path("out");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + out).exitCode, 0);
  const std::map<std::string, std::string> before = folderContents(out);
  const std::string err = path("first.txt");
  // The paper model at this resolution runs for seconds (the exact one would be done at once).
  const pid_t first = spawn(std::string(DFORM_EXE) + " forward " + pair +
                            " --resolution 250 --model paper -o " + out + " >/dev/null 2>" + err);
  ASSERT_TRUE(waitForText(err, "meshed piece A with")) << readText(err);
  expectError(run("inverse " + sample("inverse/saddle.obj") + " --resolution 30 -q -o " + out), 6,
              out + ": another dform run (process " + std::to_string(first) + ") is writing");
  expectError(run("export " + out + " -q"), 6, "another dform run");
  ASSERT_EQ(kill(first, SIGTERM), 0);
  EXPECT_EQ(waitFor(first), 143);
  EXPECT_TRUE(folderContents(out) == before);
  EXPECT_TRUE(leftoversBeside(out).empty());
  // Free again.
  EXPECT_EQ(
      run("inverse " + sample("inverse/saddle.obj") + " --resolution 30 -q -o " + out).exitCode, 0);
}

// Signals while the result is being written: SIGTERM leaves the old or the new result (exit 143;
// 0 when the run had finished), SIGKILL the old or the new one too, and the next run clears what a
// killed one left beside the folder. Never a mixture.
TEST_F(CliTest, SignalsDuringTheWriteLeaveTheOldOrTheNewResult) {
  const std::string out = path("out");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  // The two results the trials alternate between, and their meshes.
  std::map<std::string, std::string> meshes[2];
  const int resolutions[2] = {30, 34};
  for (int k : {1, 0}) {
    ASSERT_EQ(
        run("forward " + pair + " --resolution " + std::to_string(resolutions[k]) + " -q -o " + out)
            .exitCode,
        0);
    for (const auto& [name, bytes] : folderContents(out))
      if (name.find(".obj") != std::string::npos) meshes[k][name] = bytes;
  }
  const auto meshesOf = [](const std::map<std::string, std::string>& files) {
    std::map<std::string, std::string> objs;
    for (const auto& [name, bytes] : files)
      if (name.find(".obj") != std::string::npos) objs[name] = bytes;
    return objs;
  };
  const std::set<std::string> complete = [&] {
    std::set<std::string> names;
    for (const auto& entry : folderContents(out)) names.insert(entry.first);
    return names;
  }();
  for (int trial = 0; trial < 8; ++trial) {
    const int signal = trial % 2 ? SIGKILL : SIGTERM;
    const int k = 1 - (trial / 2) % 2;  // the result asked for: the other one, every two trials
    SCOPED_TRACE("trial " + std::to_string(trial));
    const std::map<std::string, std::string> previous = folderContents(out);
    // A file of its own: the previous trial's "export (" must not be taken for this one's.
    const std::string err = path("err-" + std::to_string(trial) + ".txt");
    const pid_t pid = spawn(std::string(DFORM_EXE) + " forward " + pair + " --resolution " +
                            std::to_string(resolutions[k]) + " -o " + out + " >/dev/null 2>" + err);
    // "export (laser): 6 files" is said just before the result is written.
    ASSERT_TRUE(waitForText(err, "export (")) << readText(err);
    ASSERT_EQ(kill(pid, signal), 0);
    const int code = waitFor(pid);
    const std::map<std::string, std::string> now = folderContents(out);
    const bool old = now == previous;
    std::set<std::string> names;
    for (const auto& entry : now) names.insert(entry.first);
    const bool asked = names == complete && meshesOf(now) == meshes[k];
    EXPECT_TRUE(old || asked) << "a mixture after exit " << code;
    if (signal == SIGTERM) {
      EXPECT_TRUE(code == 143 || (code == 0 && asked)) << code << readText(err);
      if (code == 143) {
        EXPECT_NE(readText(err).find("dform: error: " + out + ": interrupted"), std::string::npos);
      }
    } else {
      EXPECT_TRUE(code == -SIGKILL || (code == 0 && asked)) << code;
    }
    if (asked) {
      EXPECT_EQ(run("validate " + out).exitCode, 0);
    }
  }
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + out).exitCode, 0);
  EXPECT_TRUE(leftoversBeside(out).empty()) << "what killed runs left is cleared";
}

// dform export writes into a staging copy of the result and swaps it in: a preview of the other
// kind (dform.gltf after dform.glb) replaces the old one, and an interrupted export changes
// nothing. It runs the gate again on the meshes rather than trusting report.json's verdict.
TEST_F(CliTest, ExportIsOneTransactionAndChecksTheGateItself) {
  const std::string out = path("out");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + out).exitCode, 0);
  ASSERT_TRUE(fs::exists(fs::path(out) / "dform.glb"));
  ASSERT_EQ(run("export " + out + " --gltf -q").exitCode, 0);
  EXPECT_TRUE(fs::exists(fs::path(out) / "dform.gltf"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "dform.glb")) << "the old preview goes with the swap";
  EXPECT_EQ(run("validate " + out).exitCode, 0);
  EXPECT_TRUE(leftoversBeside(out).empty());
  // A SIGTERM once the export is being written: exit 143 and the folder as it was, or the whole
  // new export when the signal came during the swap (143, saying so) or after it (0).
  const std::map<std::string, std::string> beforeSignal = folderContents(out);
  const std::string err = path("export-err.txt");
  const pid_t pid = spawn(std::string(DFORM_EXE) + " export " + out + " >/dev/null 2>" + err);
  ASSERT_TRUE(waitForText(err, "export (")) << readText(err);
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const int code = waitFor(pid);
  const std::string said = readText(err);
  if (said.find(out + ": interrupted; the folder was left as it was") != std::string::npos) {
    EXPECT_EQ(code, 143);
    EXPECT_TRUE(folderContents(out) == beforeSignal);
  } else {
    EXPECT_TRUE(code == 0 ||
                said.find(out + ": interrupted; the new export was written completely") !=
                    std::string::npos)
        << code << said;
    EXPECT_TRUE(fs::exists(fs::path(out) / "dform.glb") &&
                !fs::exists(fs::path(out) / "dform.gltf"));
    EXPECT_EQ(run("validate " + out).exitCode, 0);
  }
  EXPECT_TRUE(leftoversBeside(out).empty());
  // Piece A's 3D mesh stretched by 5 %: report.json still says the gate passed, but the meshes
  // fail it, and nothing is exported.
  std::istringstream lines(readText(fs::path(out) / "piece-a-3d.obj"));
  std::string line, stretched;
  while (std::getline(lines, line)) {
    double x, y, z;
    if (std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3) {
      char text[128];
      std::snprintf(text, sizeof text, "v %.17g %.17g %.17g", 1.05 * x, 1.05 * y, 1.05 * z);
      line = text;
    }
    stretched += line + "\n";
  }
  std::ofstream(fs::path(out) / "piece-a-3d.obj") << stretched;
  const std::map<std::string, std::string> before = folderContents(out);
  const Outcome o = run("export " + out + " -q");
  expectError(
      o, 7,
      out +
          ": the result failed its quality gate 'default' (checked again on the meshes: L_error, ");
  EXPECT_TRUE(folderContents(out) == before);
}

// Everything that can be checked before the solve is: a bad profile, gate or sheet, a folder
// that cannot be written. Each fails at once, naming the option or file, and the earlier
// result stays as it was.
TEST_F(CliTest, OptionsAndTheOutputFolderAreCheckedBeforeTheSolve) {
  const std::string out = path("out");
  const std::string pair =
      sample("forward/ellipses-a.svg") + " " + sample("forward/ellipses-b.svg");
  ASSERT_EQ(run("forward " + pair + " --resolution 30 -q -o " + out).exitCode, 0);
  const std::map<std::string, std::string> before = folderContents(out);
  // At resolution 20000 a solve would take hours or be refused for memory: these fail first.
  const std::string big = "forward " + pair + " --resolution 250 -q -o " + out;
  expectError(run(big + " --profile nope"), 2, "unknown profile \"nope\"");
  expectError(run(big + " --profile " + path("missing-profile.json")), 3,
              path("missing-profile.json"));
  expectError(run(big + " --gate " + path("missing-gate.json")), 3, path("missing-gate.json"));
  expectError(run(big + " --sheet 600x400furlong"), 2, "--sheet");
  expectError(run(big + " --sheet 600x400"), 2, "--sheet needs a unit");
  expectError(run(big + " --profile print --kerf 0.2"), 2, "kerf: profile print");
  expectError(run(big + " --material plywood --joint slots"), 2, "joint slots: plywood");
  expectError(run(big + " --hinge"), 2, "hinge:");
  expectError(run(big + " --numbers inside"), 2, "--numbers");
  EXPECT_TRUE(folderContents(out) == before);
  // Page names in any case.
  const std::string letter = path("letter");
  ASSERT_EQ(run("export " + out + " -o " + letter + " --profile print --page letter -q").exitCode,
            0);
  const nlohmann::json pattern = nlohmann::json::parse(readText(fs::path(letter) / "pattern.json"));
  EXPECT_NEAR(pattern["sheet"]["height"].get<double>(), 279.4, 1e-9) << pattern["sheet"];  // 11 in
  const std::string file = write("a-file", "x");
  expectError(run(big.substr(0, big.find(" -o ")) + " -o " + file + "/out"), 6, file + "/out");
}

// validate trusts nothing: report.json missing or not JSON is unreadable (3); a report that is
// not an object, lacks its figures, or records other mesh sizes or another mode fails (7); an
// inverse result without its target curve fails.
TEST_F(CliTest, ValidateFailsAReportThatIsMissingIncompleteOrWrong) {
  const std::string fwd = path("fwd"), inv = path("inv");
  ASSERT_EQ(run("forward " + sample("forward/ellipses-a.svg") + " " +
                sample("forward/ellipses-b.svg") + " --resolution 30 --no-export -q -o " + fwd)
                .exitCode,
            0);
  ASSERT_EQ(
      run("inverse " + sample("inverse/saddle.obj") + " --resolution 30 --no-export -q -o " + inv)
          .exitCode,
      0);
  const fs::path report = fs::path(fwd) / "report.json";
  const std::string good = readText(report);
  const nlohmann::json saved = nlohmann::json::parse(good);
  ASSERT_EQ(run("validate " + fwd).exitCode, 0);
  const auto validateWith = [&](const std::string& text) {
    std::ofstream(report, std::ios::binary | std::ios::trunc) << text;
    return run("validate " + fwd);
  };
  fs::remove(report);
  expectError(run("validate " + fwd), 3, report.string() + ": no such file");
  expectError(validateWith("{\"metrics\": "), 3, report.string() + ": not valid JSON");
  expectError(validateWith("[]"), 7, report.string());
  nlohmann::json edited = saved;
  edited.erase("metrics");
  const Outcome noMetrics = validateWith(edited.dump());
  expectError(noMetrics, 7, "report.json says nothing");
  EXPECT_NE(noMetrics.out.find("metrics.L_error: report.json says nothing"), std::string::npos)
      << noMetrics.out;
  edited = saved;
  edited["mesh"]["vertices_a"] = saved["mesh"]["vertices_a"].get<int>() + 1;
  expectError(validateWith(edited.dump()), 7, "mesh.vertices_a");
  edited = saved;
  edited["mode"] = "inverse";
  expectError(validateWith(edited.dump()), 7, "mode");
  EXPECT_EQ(validateWith(good).exitCode, 0);
  // The inverse result without its target curve is a forward result to the folder, not its report.
  fs::remove(fs::path(inv) / "target-curve.obj");
  expectError(run("validate " + inv), 7, "mode");
}

// Messages are one printable line whatever the names and values hold.
TEST_F(CliTest, MessagesAreOneEscapedLineNamingTheFile) {
  const std::string strange = path("a\nb\x1b[31m.svg");
  const Outcome o =
      run("forward '" + strange + "' " + sample("forward/circle.svg") + " -o " + path("out"));
  expectError(o, 3, path("a\\nb\\x1b[31m.svg") + ": no such file");
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  EXPECT_EQ(o.err.find('\x1b'), std::string::npos);
  // A ten-million-digit number is quoted cut short.
  const std::string huge = write("huge.obj", "v 1" + std::string(10'000'000, '0') + "x 0 0\n");
  const Outcome h = run("inverse " + huge + " -o " + path("out"));
  expectError(h, 3, huge + ": line 1: '1000");
  EXPECT_LT(h.err.size(), 1000u) << "cut, not quoted whole";
}

// Exact exit codes: a root size in an unknown unit is unreadable (3) like an element's; a number
// too large for a double is invalid (4) in an OBJ as in an SVG; an outline too small to cut is
// refused (4), not reshaped.
TEST_F(CliTest, UnitsRangesAndSizesHaveTheirExitCodes) {
  const std::string circle = sample("forward/circle.svg");
  for (const char* size : {"300furlong", "100%"}) {
    const std::string file =
        write("root.svg", "<svg xmlns='http://www.w3.org/2000/svg' width='" + std::string(size) +
                              "' height='300mm' viewBox='0 0 300 300'>"
                              "<rect x='10' y='10' width='100' height='100'/></svg>");
    expectError(run("forward " + file + " " + circle + " -o " + path("out")), 3,
                file + ": has an unknown unit in its 'width' attribute '" + size + "'");
  }
  const std::string obj =
      write("far.obj", "v 0 0 0\nv 1e999 0 0\nv 1 1 0\nv 0 1 1\nv 2 2 2\nl 1 2 3 4 5 1\n");
  expectError(run("inverse " + obj + " -o " + path("out")), 4,
              obj + ": line 2: '1e999' is out of range");
  const std::string tiny =
      write("tiny.svg", svg("<rect x='10' y='10' width='0.01' height='0.01'/>"));
  expectError(run("forward " + tiny + " " + circle + " -o " + path("out")), 4,
              "mm across; outlines and holes must be at least 1 mm across");
  EXPECT_FALSE(fs::exists(path("out")));
}

// A run reading a FIFO no one writes to stops on SIGTERM (exit 143), naming the file.
TEST_F(CliTest, ARunWaitingOnAFifoCanBeInterrupted) {
  const std::string fifo = path("piece.svg");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string err = path("err.txt");
  const pid_t pid = spawn(std::string(DFORM_EXE) + " forward " + fifo + " " +
                          sample("forward/circle.svg") + " -o " + path("out") + " 2>" + err);
  // Blocked opening the FIFO (waiting for a writer): the kernel function its reading thread
  // sleeps in says so.
  const auto waitingForAWriter = [pid] {
    std::error_code ec;
    for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec))
      if (readText((task.path() / "wchan").string()) == "wait_for_partner") return true;
    return false;
  };
  bool waiting = false;
  for (int waited = 0; waited < 12000 && !waiting; ++waited) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    waiting = waitingForAWriter();
  }
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  EXPECT_EQ(waitFor(pid), 143) << (waiting ? "" : "never seen waiting for a writer");
  Outcome o;
  o.exitCode = 143;
  o.err = readText(err);
  expectError(o, 143, fifo + ": interrupted while waiting to read it");
}

// Under an address-space limit (ulimit -v) a run too large for it is refused at once with the
// resolution that fits (exit 2), not ended by a failed allocation, and that resolution runs.
TEST_F(CliTest, AnAddressSpaceLimitIsHonoured) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory needs more address space than any limit admits";
#endif
  const auto limited = [this](int resolution, const std::string& out) {
    const std::string err = path("err.txt");
    const pid_t pid =
        spawn(std::string(DFORM_EXE) + " forward " + sample("forward/ellipses-a.svg") + " " +
                  sample("forward/ellipses-b.svg") + " --resolution " + std::to_string(resolution) +
                  " --no-export -q -o " + out + " >/dev/null 2>" + err,
              [] {
                const rlim_t limit = rlim_t(400000) * 1024;  // ulimit -v 400000
                const struct rlimit as = {limit, limit};
                setrlimit(RLIMIT_AS, &as);
              });
    Outcome o;
    o.exitCode = waitFor(pid);
    o.err = readText(err);
    return o;
  };
  // Resolution 1000 needs about 1.7 GB: more than the limit, less than a test machine has.
  const Outcome refused = limited(1000, path("big"));
  expectError(refused, 2, "a resolution of ");
  EXPECT_FALSE(fs::exists(path("big")));
  const std::size_t at = refused.err.find("a resolution of ") + std::strlen("a resolution of ");
  const int fits = std::atoi(refused.err.c_str() + at);
  ASSERT_GE(fits, 8) << refused.err;
  const Outcome accepted = limited(fits, path("fits"));
  EXPECT_EQ(accepted.exitCode, 0) << refused.err << "\n" << accepted.err;
}

TEST_F(CliTest, InverseRunAndItsBadInputs) {
  const std::string out = path("out");
  const Outcome o = run("inverse " + sample("inverse/tennis-ball.obj") +
                        " --resolution 60 --no-export -q -o " + out);
  ASSERT_EQ(o.exitCode, 0) << o.err;
  EXPECT_TRUE(fs::exists(fs::path(out) / ModelFileNames::targetCurve));
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(fs::path(out) / "report.json"));
  EXPECT_LE(report["metrics"]["D_error"].get<double>(), 1e-6);
  const std::string html = expectSelfContainedReport(out, report);
  EXPECT_NE(html.find("No pattern was exported"), std::string::npos) << "--no-export says so";
  EXPECT_NE(html.find(">D_error<"), std::string::npos);
  EXPECT_EQ(run("validate " + out).exitCode, 0);

  const std::string planar =
      write("planar.obj", "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv -5 5 0\nl 1 2 3 4 5 1\n");
  expectError(run("inverse " + planar + " -o " + path("o2")), 4, planar);
  const std::string faces = write("faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError(run("inverse " + faces + " -o " + path("o3")), 4,
              faces + ": has faces but no polyline");
  const std::string open =
      write("open.obj", "v 0 0 0\nv 10 0 1\nv 10 10 0\nv 0 10 1\nv -5 5 2\nl 1 2 3 4 5\n");
  expectError(run("inverse " + open + " -o " + path("o4")), 4, open);
}

}  // namespace
}  // namespace dform
