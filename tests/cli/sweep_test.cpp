// SPDX-License-Identifier: GPL-3.0-or-later
// `dform sweep` as a user runs it (build/dform in a real process): every start a complete result
// that validates, sweep.json and gallery.html agreeing row for row, and each result the same as
// the single `dform forward --start-b` run it stands for.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/text_files.h"
#include "headless_chromium.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

using test::occurrences;
using test::readText;

// Runs `command`, its stdout and stderr into `log`; the exit code (-1 when it did not exit).
int shell(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " >" + log.string() + " 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The cards of gallery.html in page order, each as its HTML text.
std::vector<std::string> cards(const std::string& html) {
  std::vector<std::string> out;
  const std::string open = "<div class=\"card";
  for (std::size_t at = html.find(open); at != std::string::npos;) {
    const std::size_t next = html.find(open, at + 1);
    out.push_back(html.substr(at, next == std::string::npos ? std::string::npos : next - at));
    at = next;
  }
  return out;
}

std::string attribute(const std::string& element, const std::string& name) {
  const std::string key = name + "=\"";
  const std::size_t at = element.find(key);
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size();
  return element.substr(begin, element.find('"', begin) - begin);
}

// One sweep of the shipped ellipses with 8 starts, shared by the tests (it takes a few seconds).
class SweepTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = test::freshTestFolder("dform_sweep_test");
    exit_ = shell(exe() + " sweep " + sample("ellipses-a.svg") + " " + sample("ellipses-b.svg") +
                      " --starts 8 -q -o " + (dir_ / "sweep").string(),
                  dir_ / "sweep.log");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::string exe() { return DFORM_EXE; }
  static std::string sample(const std::string& name) {
    return std::string(DFORM_SAMPLES_DIR) + "/forward/" + name;
  }
  static json sweepJson() { return json::parse(readText(dir_ / "sweep" / "sweep.json")); }

  static fs::path dir_;
  static int exit_;
};

fs::path SweepTest::dir_;
int SweepTest::exit_ = -1;

TEST_F(SweepTest, EveryStartIsACompleteResultThatValidates) {
  ASSERT_EQ(exit_, 0) << readText(dir_ / "sweep.log");
  const json sweep = sweepJson();
  ASSERT_EQ(sweep["rows"].size(), 8u);
  std::set<std::string> subfolders;
  for (std::size_t k = 0; k < 8; ++k) {
    const json& row = sweep["rows"][k];
    EXPECT_DOUBLE_EQ(row["start_b"].get<double>(), k / 8.0);
    EXPECT_FALSE(row["flip"].get<bool>());
    EXPECT_TRUE(row["solved"].get<bool>()) << row["reason"];
    const std::string sub = row["subfolder"];
    subfolders.insert(sub);
    const fs::path result = dir_ / "sweep" / sub;
    ASSERT_TRUE(fs::exists(result / "report.html")) << sub;
    // validate recomputes every figure from the meshes and checks report.json against them; its
    // verdict is the row's.
    const int code = shell(exe() + " validate " + result.string(), dir_ / "validate.log");
    EXPECT_EQ(code, row["gate_passed"].get<bool>() ? 0 : 7)
        << sub << ": " << readText(dir_ / "validate.log");
    // The row's start is the start the result records.
    const json report = json::parse(readText(result / "report.json"));
    EXPECT_NEAR(report["start_fraction_b"].get<double>(), k / 8.0, 1e-12) << sub;
    EXPECT_EQ(report["model"]["name"], row["model"]);
    EXPECT_GT(std::abs(row["volume_mm3"].get<double>()), 0.0) << sub;
    EXPECT_GT(row["height_mm"].get<double>(), 0.0) << sub;
  }
  EXPECT_EQ(subfolders.size(), 8u);
  // Nothing but the results, sweep.json and gallery.html: no staging folder or lock left over.
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "sweep")) {
    ++entries;
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(subfolders.count(name) || name == "sweep.json" || name == "gallery.html") << name;
  }
  EXPECT_EQ(entries, 10);
}

TEST_F(SweepTest, GalleryCardsMatchSweepJsonRows) {
  ASSERT_EQ(exit_, 0) << readText(dir_ / "sweep.log");
  const json sweep = sweepJson();
  const std::vector<std::string> page = cards(readText(dir_ / "sweep" / "gallery.html"));
  ASSERT_EQ(page.size(), sweep["rows"].size());
  for (std::size_t k = 0; k < page.size(); ++k) {
    const json& row = sweep["rows"][k];
    const std::string sub = row["subfolder"];
    EXPECT_EQ(attribute(page[k], "data-subfolder"), sub);
    EXPECT_NE(page[k].find("href=\"" + sub + "/report.html\""), std::string::npos) << sub;
    EXPECT_EQ(occurrences(page[k], "<svg"), 1) << sub;
    EXPECT_DOUBLE_EQ(std::stod(attribute(page[k], "data-height")), row["height_mm"].get<double>());
    EXPECT_DOUBLE_EQ(std::stod(attribute(page[k], "data-volume")), row["volume_mm3"].get<double>());
    EXPECT_DOUBLE_EQ(std::stod(attribute(page[k], "data-curvature")),
                     row["max_curvature"].get<double>());
    const bool greyed = attribute(page[k], "class") == "card failed";
    EXPECT_EQ(greyed, !row["gate_passed"].get<bool>()) << sub;
  }
}

TEST_F(SweepTest, ARowIsTheSingleForwardRunOfItsStart) {
  ASSERT_EQ(exit_, 0) << readText(dir_ / "sweep.log");
  const json row = sweepJson()["rows"][3];
  const fs::path single = dir_ / "single";
  ASSERT_EQ(shell(exe() + " forward " + sample("ellipses-a.svg") + " " + sample("ellipses-b.svg") +
                      " --start-b 0.375 -q -o " + single.string(),
                  dir_ / "single.log"),
            row["gate_passed"].get<bool>() ? 0 : 7)
      << readText(dir_ / "single.log");
  const fs::path swept = dir_ / "sweep" / row["subfolder"].get<std::string>();
  // The same solve: the same meshes to the byte, the same figures and verdict.
  for (const char* mesh :
       {"piece-a-3d.obj", "piece-b-3d.obj", "piece-a-flat.obj", "piece-b-flat.obj"})
    EXPECT_EQ(readText(single / mesh), readText(swept / mesh)) << mesh;
  const json a = json::parse(readText(single / "report.json"));
  const json b = json::parse(readText(swept / "report.json"));
  EXPECT_EQ(a["metrics"], b["metrics"]);
  EXPECT_EQ(a["gate"]["passed"], b["gate"]["passed"]);
  EXPECT_EQ(a["model"]["name"], b["model"]["name"]);
  EXPECT_EQ(a["job"], b["job"]);
}

// A sweep run again into the folder of an earlier one replaces it whole, start folders and all;
// a folder holding anything else is refused and left as it was.
TEST_F(SweepTest, ASecondSweepReplacesTheFirstWhole) {
  ASSERT_EQ(exit_, 0) << readText(dir_ / "sweep.log");
  const fs::path again = dir_ / "again";
  fs::copy(dir_ / "sweep", again, fs::copy_options::recursive);
  const std::string command = exe() + " sweep " + sample("ellipses-a.svg") + " " +
                              sample("ellipses-b.svg") +
                              " --starts 2 --flip flipped -q --no-export -o " + again.string();
  ASSERT_EQ(shell(command, dir_ / "again.log"), 0) << readText(dir_ / "again.log");
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(again))
    names.insert(entry.path().filename().string());
  EXPECT_EQ(names,
            (std::set<std::string>{"gallery.html", "start-0-flip", "start-1-flip", "sweep.json"}));
  const json rows = json::parse(readText(again / "sweep.json"))["rows"];
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_TRUE(rows[1]["flip"].get<bool>());
  EXPECT_DOUBLE_EQ(rows[1]["start_b"].get<double>(), 0.5);

  std::ofstream(again / "notes.txt") << "mine";
  EXPECT_EQ(shell(command, dir_ / "again.log"), 6);
  EXPECT_NE(readText(dir_ / "again.log").find("notes.txt"), std::string::npos);
  EXPECT_EQ(readText(again / "notes.txt"), "mine");
  EXPECT_TRUE(fs::exists(again / "start-1-flip" / "report.json"));
}

// A folder a user kept beside the starts under a name that begins like one ("start-1-keep": an
// earlier start's result set aside) is not a start of the sweep: refused, never swapped away.
TEST_F(SweepTest, AKeptCopyOfAStartIsNotTakenForOne) {
  ASSERT_EQ(exit_, 0) << readText(dir_ / "sweep.log");
  const fs::path kept = dir_ / "kept";
  fs::copy(dir_ / "sweep", kept, fs::copy_options::recursive);
  for (const char* name : {"start-1-keep", "start-12x", "start-0-flipped"}) {
    fs::copy(kept / "start-1", kept / name);  // only a result's files
    const std::string command = exe() + " sweep " + sample("ellipses-a.svg") + " " +
                                sample("ellipses-b.svg") + " --starts 2 -q --no-export -o " +
                                kept.string();
    EXPECT_EQ(shell(command, dir_ / "kept.log"), 6) << name << ": " << readText(dir_ / "kept.log");
    EXPECT_NE(readText(dir_ / "kept.log").find(std::string("kept/") + name), std::string::npos)
        << readText(dir_ / "kept.log");
    EXPECT_TRUE(fs::exists(kept / name / "report.json")) << name;
    fs::remove_all(kept / name);
  }
  EXPECT_TRUE(fs::exists(kept / "start-7" / "report.json"));  // the earlier sweep is left whole
}

// The gallery in headless Chromium: the page loads and runs its script without a console error,
// and the rendered page has one picture per card.
TEST_F(SweepTest, GalleryRendersInHeadlessChromium) {
  ASSERT_EQ(exit_, 0) << readText(dir_ / "sweep.log");
  if (!test::chromiumInstalled())
    GTEST_SKIP() << "chromium is not installed (scripts/install-deps --browser installs it); "
                    "the gallery was not rendered";
  const fs::path dom = dir_ / "dom.html", log = dir_ / "chromium.log";
  ASSERT_EQ(test::runChromium("--dump-dom", "file://" + (dir_ / "sweep" / "gallery.html").string(),
                              (dir_ / "profile").string(), dom.string(), log.string()),
            0)
      << readText(log);
  const std::string messages = readText(log);
  EXPECT_EQ(messages.find("CONSOLE"), std::string::npos) << messages;
  const std::vector<std::string> rendered = cards(readText(dom));
  ASSERT_EQ(rendered.size(), sweepJson()["rows"].size()) << readText(dom).substr(0, 2000);
  for (const std::string& card : rendered) EXPECT_EQ(occurrences(card, "<svg"), 1);
}

}  // namespace
}  // namespace dform
