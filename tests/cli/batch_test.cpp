// SPDX-License-Identifier: GPL-3.0-or-later
// `dform batch` as a cluster runs it (build/dform in real processes): shards merged equal the
// whole batch, and a resumed batch finishes what was left and redoes nothing already finished.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/text_files.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

using test::occurrences;
using test::readText;

class BatchTest : public ::testing::Test {
 public:
  void SetUp() override { dir_ = test::freshTestFolder("dform_batch"); }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs dform with `args`; the exit code, the output in `log_`.
  int dform(const std::string& args) {
    const int status = std::system(
        (std::string(DFORM_EXE) + " " + args + " >" + (dir_ / "log.txt").string() + " 2>&1")
            .c_str());
    log_ = readText(dir_ / "log.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  static std::string samples() { return std::string(DFORM_SAMPLES_DIR) + "/forward"; }
  static json rows(const fs::path& manifest) { return json::parse(readText(manifest))["rows"]; }

  fs::path dir_;
  std::string log_;
};

// The same job measured twice agrees to rounding (the solver's sums may run in another order).
void expectSameRow(const json& a, const json& b) {
  for (const char* key :
       {"index", "job", "name", "status", "exit_code", "model", "gate_passed", "failing_checks"})
    EXPECT_EQ(a[key], b[key]) << a["name"] << " " << key;
  for (const char* key : {"height_mm", "volume_mm3", "max_curvature"}) {
    ASSERT_EQ(a[key].is_null(), b[key].is_null()) << a["name"] << " " << key;
    if (a[key].is_null()) continue;
    const double x = a[key], y = b[key];
    EXPECT_NEAR(x, y, 1e-6 * std::max(1.0, std::abs(x))) << a["name"] << " " << key;
  }
}

// A folder of seven jobs as a lab writes them: the exact and the paper model, the Squaricle (at
// this coarse resolution it fails the default gate on its distance from the exact shape) and a
// job whose piece is missing. Small resolutions keep it quick enough for the sanitizers.
fs::path writeJobFolder(const fs::path& dir) {
  const std::string svg = std::string(DFORM_SAMPLES_DIR) + "/forward/";
  auto job = [&](const std::string& name, const std::string& a, const std::string& b,
                 const std::string& extra) {
    std::ofstream(dir / (name + ".json"))
        << "{\"mode\": \"forward\", \"piece_a\": \"" << svg + a << "\", \"piece_b\": \"" << svg + b
        << "\", \"resolution\": 40" << extra << "}\n";
  };
  fs::create_directories(dir);
  job("twin", "ellipses-a.svg", "ellipses-a.svg", ", \"start_b\": 0.25");
  job("pair-0", "ellipses-a.svg", "ellipses-b.svg", "");
  job("pair-0.3", "ellipses-a.svg", "ellipses-b.svg", ", \"start_b\": 0.3");
  job("paper", "ellipses-a.svg", "ellipses-b.svg", ", \"start_b\": 0.1, \"model\": \"paper\"");
  job("circle-square", "circle.svg", "square.svg", ", \"start_b\": 0.125");
  job("squaricle", "squaricle-disc.svg", "squaricle-square.svg", "");
  job("missing", "no-such-piece.svg", "square.svg", "");
  return dir;
}

// Runs the jobs at `jobs` whole and in three shards merged: every result validates with its row's
// verdict, the batch exits with the first failure's code, and the merged table and gallery equal
// the whole batch's. The whole batch's rows.
json expectShardsMergeToTheWhole(BatchTest& t, const fs::path& jobs, const fs::path& dir,
                                 int jobCount) {
  const fs::path whole = dir / "whole", sharded = dir / "sharded";
  const int wholeCode =
      t.dform("batch " + jobs.string() + " -o " + whole.string() + " --no-export -q");
  const std::string wholeLog = t.log_;
  const json all = BatchTest::rows(whole / "batch.json");
  EXPECT_EQ(int(all.size()), jobCount) << wholeLog;
  int firstFailure = 0;
  for (const json& row : all) {
    if (row["exit_code"] != 0 && firstFailure == 0) firstFailure = row["exit_code"];
    // Every written result is one `dform validate` accepts with the row's verdict.
    if (row["status"] == "failed") continue;
    const int code = t.dform("validate " + (whole / row["name"].get<std::string>()).string());
    EXPECT_EQ(code, row["gate_passed"].get<bool>() ? 0 : 7) << row["name"] << ": " << t.log_;
  }
  EXPECT_EQ(wholeCode, firstFailure) << wholeLog;
  // The whole batch draws its gallery, a card per job; each shard its slice's.
  EXPECT_EQ(occurrences(readText(whole / "gallery.html"), "<div class=\"card"), jobCount);

  for (int i = 1; i <= 3; ++i) {
    t.dform("batch " + jobs.string() + " -o " + sharded.string() + " --no-export -q --shard " +
            std::to_string(i) + "/3");
    const std::string shard = std::to_string(i) + "-of-3";
    const json slice = BatchTest::rows(sharded / ("batch-shard-" + shard + ".json"));
    for (const json& row : slice) EXPECT_EQ(row["index"].get<int>() % 3 + 1, i) << t.log_;
    EXPECT_EQ(
        occurrences(readText(sharded / ("gallery-shard-" + shard + ".html")), "<div class=\"card"),
        int(slice.size()));
  }
  EXPECT_FALSE(fs::exists(sharded / "gallery.html"));  // drawn by --merge
  EXPECT_EQ(t.dform("batch --merge " + sharded.string()), 0) << t.log_;
  const json merged = BatchTest::rows(sharded / "batch.json");
  EXPECT_EQ(merged.size(), all.size());
  for (std::size_t k = 0; k < std::min(all.size(), merged.size()); ++k)
    expectSameRow(all[k], merged[k]);
  // The merged gallery has a card per job.
  const std::string gallery = readText(sharded / "gallery.html");
  EXPECT_EQ(occurrences(gallery, "<div class=\"card"), jobCount);
  return all;
}

// Every shipped job (the Release suite; minutes under the sanitizers, which run the next test).
TEST_F(BatchTest, ShardsMergedEqualTheWholeBatch) {
  int jobs = 0;
  for (const auto& entry : fs::directory_iterator(samples()))
    jobs += entry.path().extension() == ".json";
  ASSERT_GE(jobs, 7);
  expectShardsMergeToTheWhole(*this, samples(), dir_, jobs);
}

TEST_F(BatchTest, ShardsOfMixedOutcomesMergeToTheWhole) {
  const json all = expectShardsMergeToTheWhole(*this, writeJobFolder(dir_ / "jobs"), dir_, 7);
  std::map<std::string, int> statuses, models;
  for (const json& row : all) {
    ++statuses[row["status"].get<std::string>()];
    if (row["status"] != "failed") ++models[row["model"].get<std::string>()];
  }
  EXPECT_EQ(statuses, (std::map<std::string, int>{{"done", 5}, {"failed", 1}, {"gate-failed", 1}}));
  EXPECT_EQ(models, (std::map<std::string, int>{{"exact", 4}, {"paper", 2}}));
}

TEST_F(BatchTest, ProgressOnlyOnATerminalAndNotWhenQuiet) {
  const fs::path jobs = writeJobFolder(dir_ / "jobs");
  // util-linux `script` runs the batch on a pseudo-terminal and copies what it shows.
  auto onTerminal = [&](const std::string& more, const std::string& out) {
    const fs::path log = dir_ / (out + ".txt");
    const std::string command = "script -qec '" + std::string(DFORM_EXE) + " batch " +
                                jobs.string() + " --no-export --threads 1 -o " +
                                (dir_ / out).string() + more + "' /dev/null > " + log.string() +
                                " 2>&1";
    // The batch's exit code is not the point here: its terminal output is.
    [[maybe_unused]] const int code = std::system(command.c_str());
    return readText(log);
  };
  const std::string shown = onTerminal("", "tty");
  for (int done = 1; done <= 7; ++done)
    EXPECT_NE(shown.find("batch: " + std::to_string(done) + " of 7 done, "), std::string::npos)
        << shown;
  EXPECT_NE(shown.find(" failed, about "), std::string::npos) << shown;
  EXPECT_NE(shown.find("\r\033[K"), std::string::npos) << "redrawn in place";
  EXPECT_EQ(onTerminal(" -q", "tty-quiet").find(" of 7 done"), std::string::npos);
  // On a pipe (a scheduler's log): the table at the end, no progress.
  dform("batch " + jobs.string() + " --no-export -o " + (dir_ / "piped").string());
  EXPECT_EQ(log_.find(" of 7 done"), std::string::npos) << log_;
  EXPECT_EQ(log_.find('\r'), std::string::npos);
  EXPECT_NE(log_.find("7 jobs (shard 1 of 1): 5 done, 2 failed"), std::string::npos) << log_;
}

struct Stamp {
  ino_t inode;
  long long mtimeNs;
  bool operator==(const Stamp& o) const { return inode == o.inode && mtimeNs == o.mtimeNs; }
};
Stamp stamp(const fs::path& path) {
  struct stat s {};
  EXPECT_EQ(::stat(path.c_str(), &s), 0) << path;
  return {s.st_ino, (long long)s.st_mtim.tv_sec * 1000000000LL + s.st_mtim.tv_nsec};
}

TEST_F(BatchTest, ResumeFinishesTheRestAndRedoesNothingFinished) {
  // A job list as a lab writes one: comments, a blank line, paths relative to the list.
  const fs::path list = dir_ / "jobs.txt";
  std::ofstream(list) << "# three quick jobs\n"
                      << samples() << "/ellipse-twin.json\n\n"
                      << fs::relative(samples() + "/ellipses-quarter-turn.json", dir_).string()
                      << "\n"
                      << samples() << "/squaricle.json\n";
  const fs::path out = dir_ / "out";
  ASSERT_EQ(dform("batch " + list.string() + " -o " + out.string() + " -q"), 0) << log_;
  json manifest = json::parse(readText(out / "batch.json"));
  ASSERT_EQ(manifest["rows"].size(), 3u);

  // As if the batch had been stopped before its second job finished: no row, no result.
  manifest["rows"].erase(1);
  std::ofstream(out / "batch.json") << manifest.dump(2);
  fs::remove_all(out / "ellipses-quarter-turn");
  std::map<std::string, Stamp> before;
  for (const char* name : {"ellipse-twin", "squaricle"})
    before[name] = stamp(out / name / "report.json");

  ASSERT_EQ(dform("batch " + list.string() + " -o " + out.string() + " -q --resume"), 0) << log_;
  const json resumed = rows(out / "batch.json");
  ASSERT_EQ(resumed.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(resumed[k]["index"], int(k));
  EXPECT_EQ(resumed[1]["status"], "done");
  EXPECT_TRUE(fs::exists(out / "ellipses-quarter-turn" / "report.json"));
  for (const auto& [name, s] : before) EXPECT_TRUE(stamp(out / name / "report.json") == s) << name;

  // Resumed once more: everything is finished, nothing runs.
  const Stamp third = stamp(out / "ellipses-quarter-turn" / "report.json");
  ASSERT_EQ(dform("batch " + list.string() + " -o " + out.string() + " -q --resume"), 0) << log_;
  EXPECT_TRUE(stamp(out / "ellipses-quarter-turn" / "report.json") == third);
  for (const auto& [name, s] : before) EXPECT_TRUE(stamp(out / name / "report.json") == s) << name;
  EXPECT_EQ(rows(out / "batch.json"), resumed);
}

// The demi job's figures, bit for bit, alone and on three threads beside two other paper-model
// jobs, five times: nothing the process shares between its threads (METIS's rand() state, Eigen's
// cache sizes) may change a job's path. It differed about one run in seven while analyses ran
// at once (cholmodAnalysisMutex).
TEST_F(BatchTest, TheDemiJobGivesTheSameFiguresAloneAndInAThreeThreadBatch) {
  const std::string demi = samples() + "/demi.json";
  ASSERT_EQ(dform("run " + demi + " --no-export -q -o " + (dir_ / "alone").string()), 0) << log_;
  const json alone = json::parse(readText(dir_ / "alone" / "report.json"))["metrics"];
  ASSERT_TRUE(alone.is_object());
  const fs::path list = dir_ / "jobs.txt";
  std::ofstream(list) << samples() << "/squaricle.json\n"
                      << demi << "\n"
                      << samples() << "/nonconvex-shifted.json\n";
  for (int round = 0; round < 5; ++round) {
    const fs::path out = dir_ / ("batch-" + std::to_string(round));
    dform("batch " + list.string() + " --threads 3 --no-export -q -o " + out.string());
    const std::string report = readText(out / "demi" / "report.json");
    ASSERT_FALSE(report.empty()) << log_;
    EXPECT_EQ(json::parse(report)["metrics"].dump(), alone.dump()) << "round " << round;
  }
}

// Quick batches (jobs that fail at once, a twin at resolution 40): the fast label.
class BatchMergeTest : public BatchTest {
 public:
  // `count` jobs j00, j01, ... whose piece is missing (each fails at once with its row), listed
  // in jobs.txt.
  fs::path failingJobs(int count) {
    fs::create_directories(dir_ / "jobs");
    std::ofstream list(dir_ / "jobs.txt");
    for (int k = 0; k < count; ++k) {
      const std::string name = (k < 10 ? "j0" : "j") + std::to_string(k);
      std::ofstream(dir_ / "jobs" / (name + ".json"))
          << R"({"mode": "forward", "piece_a": "nowhere.svg", "piece_b": "x.svg"})";
      list << "jobs/" << name << ".json\n";
    }
    return dir_ / "jobs.txt";
  }
  // Runs shard `shard` of `shards` of `list` into `out`.
  void runShard(const fs::path& list, const fs::path& out, int shard, int shards) {
    EXPECT_EQ(dform("batch " + list.string() + " -q --no-export -o " + out.string() + " --shard " +
                    std::to_string(shard) + "/" + std::to_string(shards)),
              3)
        << log_;
  }
  // A refused merge: exit 5, one error line naming what is missing, nothing written.
  void expectRefused(const fs::path& out, const std::string& missing) {
    EXPECT_EQ(dform("batch --merge " + out.string()), 5) << log_;
    EXPECT_EQ(log_.rfind("dform: error: " + out.string() + ": " + missing, 0), 0u) << log_;
    EXPECT_EQ(occurrences(log_, "\n"), 1) << log_;
    EXPECT_FALSE(fs::exists(out / "batch.json"));
    EXPECT_FALSE(fs::exists(out / "gallery.html"));
  }
};

TEST_F(BatchMergeTest, AShardMissingIsRefusedUnlessAllowPartial) {
  const fs::path list = failingJobs(12), out = dir_ / "out";
  runShard(list, out, 2, 3);
  runShard(list, out, 3, 3);
  // Shard 1 never ran: its jobs are named by their place, no manifest lists their names.
  expectRefused(out, "4 of 12 jobs have not finished in any manifest (#0, #3, #6, #9); nothing");
  EXPECT_NE(log_.find("--allow-partial"), std::string::npos) << log_;
  ASSERT_EQ(dform("batch --merge " + out.string() + " --allow-partial"), 0) << log_;
  EXPECT_NE(log_.find("8 of 12 jobs merged into"), std::string::npos) << log_;
  EXPECT_NE(log_.find("4 have not finished: #0, #3, #6, #9"), std::string::npos) << log_;
  EXPECT_EQ(rows(out / "batch.json").size(), 8u);
  // With shard 1 run, the partial merge and the shards merge whole.
  runShard(list, out, 1, 3);
  ASSERT_EQ(dform("batch --merge " + out.string()), 0) << log_;
  EXPECT_NE(log_.find("12 of 12 jobs merged into"), std::string::npos) << log_;
  EXPECT_EQ(rows(out / "batch.json").size(), 12u);
  // --allow-partial belongs to --merge.
  EXPECT_EQ(dform("batch " + list.string() + " -o " + (dir_ / "o2").string() + " --allow-partial"),
            2);
  EXPECT_NE(log_.find("--allow-partial goes with --merge"), std::string::npos) << log_;
}

TEST_F(BatchMergeTest, AShardKilledPartWayIsRefusedNamingItsUnfinishedJobs) {
  const fs::path list = failingJobs(18), out = dir_ / "out";
  for (int shard = 1; shard <= 3; ++shard) runShard(list, out, shard, 3);
  // Shard 2 killed after 4 of its 6 jobs: its manifest lacks the last two rows; a folder the
  // killed job had begun holds no finished result.
  const fs::path manifest = out / "batch-shard-2-of-3.json";
  json killed = json::parse(readText(manifest));
  ASSERT_EQ(killed["rows"].size(), 6u);
  killed["rows"].erase(5);
  killed["rows"].erase(4);
  std::ofstream(manifest) << killed.dump(2);
  fs::create_directories(out / "j13");
  expectRefused(out, "2 of 18 jobs have not finished in any manifest (j13, j16); nothing");
  ASSERT_EQ(dform("batch --merge " + out.string() + " --allow-partial"), 0) << log_;
  EXPECT_NE(log_.find("16 of 18 jobs merged"), std::string::npos) << log_;
  EXPECT_EQ(rows(out / "batch.json").size(), 16u);
}

TEST_F(BatchMergeTest, OnlyTheLastShardIsRefusedWithTheListShortened) {
  const fs::path list = failingJobs(12), out = dir_ / "out";
  runShard(list, out, 8, 8);
  expectRefused(out,
                "11 of 12 jobs have not finished in any manifest (#0, #1, #2, #3, #4 and 6 "
                "more); nothing");
}

// A row of a schema-version-2 manifest, "gate failed", merges as the one word "gate-failed".
TEST_F(BatchMergeTest, AnOlderManifestsGateFailedStatusMergesAsOneWord) {
  const fs::path list = failingJobs(2), out = dir_ / "out";
  EXPECT_EQ(dform("batch " + list.string() + " -q --no-export -o " + out.string()), 3) << log_;
  json older = json::parse(readText(out / "batch.json"));
  older["schema_version"] = 2;
  older.erase("slice");
  older["rows"][1]["status"] = "gate failed";
  std::ofstream(out / "batch.json") << older.dump(2);
  ASSERT_EQ(dform("batch --merge " + out.string()), 0) << log_;
  EXPECT_EQ(rows(out / "batch.json")[1]["status"], "gate-failed");
  EXPECT_NE(log_.find("j01                      gate-failed"), std::string::npos) << log_;
}

// A failed row has no figures: "-" in the run's table and the merge's, never 0 or nan.
TEST_F(BatchMergeTest, AFailedRowShowsDashesInBothTables) {
  const fs::path jobs = dir_ / "jobs";
  fs::create_directories(jobs);
  std::ofstream(jobs / "lost.json") << R"({"mode": "forward", "piece_a": "nowhere.svg", )"
                                    << R"("piece_b": "x.svg"})";
  std::ofstream(jobs / "twin.json")
      << R"({"mode": "forward", "piece_a": ")" << samples() << R"(/ellipses-a.svg", "piece_b": ")"
      << samples() << R"(/ellipses-a.svg", "resolution": 40, "start_b": 0.25})";
  const auto expectDashes = [&](const std::string& table) {
    std::istringstream lines(table);
    std::string line, lost, twin;
    while (std::getline(lines, line)) {
      if (line.rfind("lost ", 0) == 0) lost = line;
      if (line.rfind("twin ", 0) == 0) twin = line;
    }
    std::istringstream lostFields(lost), twinFields(twin);
    std::vector<std::string> l, t;
    for (std::string f; lostFields >> f;) l.push_back(f);
    for (std::string f; twinFields >> f;) t.push_back(f);
    ASSERT_EQ(l.size(), 7u) << table;
    ASSERT_EQ(t.size(), 7u) << table;
    EXPECT_EQ(l[1], "failed");
    EXPECT_EQ(l[2], "3");
    for (int k = 3; k < 6; ++k) EXPECT_EQ(l[k], "-") << table;  // height, volume, curvature
    EXPECT_TRUE(std::isfinite(std::stod(l[6]))) << table;       // its wall time
    EXPECT_EQ(t[1], "done");
    EXPECT_GT(std::stod(t[3]), 100) << table;  // the twin's height, about 137 mm
    EXPECT_EQ(table.find("nan"), std::string::npos) << table;
  };
  EXPECT_EQ(dform("batch " + jobs.string() + " --no-export -o " + (dir_ / "whole").string()), 3);
  expectDashes(log_);
  for (int shard = 1; shard <= 2; ++shard)
    dform("batch " + jobs.string() + " --no-export -q -o " + (dir_ / "sharded").string() +
          " --shard " + std::to_string(shard) + "/2");
  ASSERT_EQ(dform("batch --merge " + (dir_ / "sharded").string()), 0) << log_;
  expectDashes(log_);
}

TEST_F(BatchTest, BadShardIsAUsageErrorAMissingListUnreadable) {
  EXPECT_EQ(dform("batch " + samples() + " -o " + (dir_ / "o").string() + " --shard 4/3"), 2);
  EXPECT_NE(log_.find("--shard"), std::string::npos) << log_;
  EXPECT_EQ(dform("batch " + (dir_ / "missing.txt").string() + " -o " + (dir_ / "o").string()), 3);
  EXPECT_NE(log_.find("missing.txt"), std::string::npos) << log_;
  EXPECT_EQ(dform("batch --merge " + dir_.string()), 3);
}

}  // namespace
}  // namespace dform
