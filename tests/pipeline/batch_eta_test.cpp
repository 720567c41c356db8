// SPDX-License-Identifier: GPL-3.0-or-later
// The batch's time left: remaining jobs weighed by their size (resolution², as their vertex
// count grows), not counted.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "dform/pipeline/batch.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

TEST(BatchEta, RemainingJobsWeighByTheirSize) {
  // Nine jobs at resolution 40 done in 9 s; three at resolution 400 left, each 100 times the
  // size of one done: 9 s * 3 * 160000 / (9 * 1600) = 300 s, where counting jobs says 3 s.
  const double small = 40.0 * 40.0, large = 400.0 * 400.0;
  EXPECT_DOUBLE_EQ(estimateSecondsLeft(9, 9 * small, 3 * large), 300);
  // Jobs of one size: the count's answer.
  EXPECT_DOUBLE_EQ(estimateSecondsLeft(12, 4 * small, 8 * small), 24);
  EXPECT_DOUBLE_EQ(estimateSecondsLeft(12, 4 * small, 0), 0);
  // Nothing finished yet, or nonsense figures: unknown, not 0 or infinity.
  EXPECT_TRUE(std::isnan(estimateSecondsLeft(5, 0, large)));
  EXPECT_TRUE(std::isnan(estimateSecondsLeft(5, NAN, large)));
  EXPECT_TRUE(std::isnan(estimateSecondsLeft(NAN, small, large)));
  EXPECT_TRUE(std::isnan(estimateSecondsLeft(5, small, -1)));
}

TEST(BatchEta, AJobsSizeIsItsResolutionSquared) {
  const fs::path dir = fs::temp_directory_path() / ("dform_eta_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "forward.json")
      << R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "resolution": 300})";
  std::ofstream(dir / "inverse.json")
      << R"({"mode": "inverse", "curve": "c.obj", "resolution": 50})";
  std::ofstream(dir / "default.json")
      << R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg"})";
  std::ofstream(dir / "broken.json") << "{";
  EXPECT_DOUBLE_EQ(readJobFacts((dir / "forward.json").string()).size, 90000);
  EXPECT_DOUBLE_EQ(readJobFacts((dir / "inverse.json").string()).size, 2500);
  EXPECT_DOUBLE_EQ(readJobFacts((dir / "default.json").string()).size, 10000);  // resolution 100
  EXPECT_DOUBLE_EQ(readJobFacts((dir / "broken.json").string()).size, 1);
  EXPECT_DOUBLE_EQ(readJobFacts((dir / "absent.json").string()).size, 1);
  // listBatchJobs gives each job its size.
  const Result<std::vector<BatchJob>> jobs = listBatchJobs(dir.string());
  ASSERT_TRUE(jobs.isOk()) << jobs.status().message();
  ASSERT_EQ(jobs.value().size(), 4u);
  for (const BatchJob& job : jobs.value())
    EXPECT_DOUBLE_EQ(job.size, readJobFacts(job.path).size) << job.name;
  EXPECT_DOUBLE_EQ(jobs.value()[2].size, 90000) << jobs.value()[2].name;  // forward.json
  fs::remove_all(dir);
}

// runBatch's progress weighs the jobs left by size: on one thread, jobs of sizes 1, 1000 and 1
// leave elapsed * 1001 after the first and elapsed / 1001 after the second (counting jobs: 2 and
// 1/2 times). The elapsed time lies between the first job's own time and the time since the
// call, so the bounds hold on any machine.
TEST(BatchEta, RunBatchWeighsTheJobsLeftBySize) {
  using Clock = std::chrono::steady_clock;
  const fs::path dir = fs::temp_directory_path() / ("dform_eta_run_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::vector<BatchJob> jobs;
  const double sizes[] = {1, 1000, 1};
  for (int k = 0; k < 3; ++k)
    jobs.push_back({k, (dir / ("j" + std::to_string(k) + ".json")).string(),
                    "j" + std::to_string(k), "sha", sizes[k]});
  std::vector<double> jobSeconds;
  const BatchRunner run = [&](const std::string&, const std::string&) {
    const auto begun = Clock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    jobSeconds.push_back(std::chrono::duration<double>(Clock::now() - begun).count());
    return JobOutcome{4, "no result"};
  };
  struct Call {
    int done;
    double secondsLeft, sinceCall;
  };
  std::vector<Call> calls;
  const auto called = Clock::now();
  const BatchProgress progress = [&](int done, int, int total, double secondsLeft) {
    EXPECT_EQ(total, 3);
    calls.push_back(
        {done, secondsLeft, std::chrono::duration<double>(Clock::now() - called).count()});
  };
  BatchOptions options;
  options.threads = 1;
  const std::atomic<bool> interrupted{false};
  ASSERT_TRUE(runBatch(jobs, options, (dir / "out").string(), run, progress, interrupted).isOk());
  ASSERT_EQ(calls.size(), 3u);
  ASSERT_EQ(jobSeconds.size(), 3u);
  EXPECT_GE(calls[0].secondsLeft, 1001 * jobSeconds[0]);
  EXPECT_LE(calls[0].secondsLeft, 1001 * calls[0].sinceCall);
  EXPECT_GE(calls[1].secondsLeft, (jobSeconds[0] + jobSeconds[1]) / 1001);
  EXPECT_LE(calls[1].secondsLeft, calls[1].sinceCall / 1001);
  EXPECT_EQ(calls[2].secondsLeft, 0);
  fs::remove_all(dir);
}

// A merged table has one row per job, keyed by its name (its result folder, OUT/<name>): a
// manifest that names one job at two places of the list does not merge into a table with that
// job twice, and the place it does not hold is a job that has not finished.
TEST(BatchMerge, AJobNamedAtTwoPlacesIsMergedOnceUnderItsLatestPlace) {
  const fs::path dir = fs::temp_directory_path() / ("dform_merge_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "batch.json") << R"({"schema": "dform-batch", "schema_version": 3,
    "jobs": {"count": 2, "sha256": "ab"}, "shard": [1, 1], "slice": [[0, "a"], [1, "a"]],
    "rows": [{"index": 0, "job": "a.json", "name": "a", "status": "done", "exit_code": 0},
             {"index": 1, "job": "a.json", "name": "a", "status": "failed", "exit_code": 5,
              "message": "the later row"}]})";
  const Result<MergedBatch> strict = mergeBatch(dir.string(), false);
  ASSERT_FALSE(strict.isOk());
  EXPECT_EQ(strict.status().code(), ErrorCode::SolveFailed) << strict.status().message();
  EXPECT_NE(strict.status().message().find("1 of 2 jobs have not finished"), std::string::npos)
      << strict.status().message();
  const Result<MergedBatch> partial = mergeBatch(dir.string(), true);
  ASSERT_TRUE(partial.isOk()) << partial.status().message();
  ASSERT_EQ(partial.value().rows.size(), 1u);
  EXPECT_EQ(partial.value().rows[0].job.index, 1);
  EXPECT_EQ(partial.value().rows[0].message, "the later row");
  EXPECT_EQ(partial.value().missingCount, 1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dform
