// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/job_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dform/model/term_table.h"
#include "dform/pipeline/settings.h"

namespace dform {
namespace {

TEST(JobFile, ForwardJobRoundTrips) {
  const std::string text = R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "/abs/b.svg",
    "start_a": {"fraction": 0.1}, "start_b": {"near": [3.5, -2]}, "resolution": 80, "interior_edge": 1.5, "flip": true,
    "fit_perimeter": true, "perimeter_tolerance": 0.01, "weights": {"smooth_3d": 0.02},
    "solver": {"max_iterations": 30}})";
  const Result<Job> job = parseJobJson(text, "job.json", "/base");
  ASSERT_TRUE(job.isOk()) << job.status().message();
  const ForwardJob& f = std::get<ForwardJob>(job.value().run);
  EXPECT_EQ(f.pieceA, "/base/a.svg");
  EXPECT_EQ(f.pieceB, "/abs/b.svg");
  EXPECT_DOUBLE_EQ(f.startA.fraction, 0.1);
  EXPECT_TRUE(f.startB.nearestToPoint);
  EXPECT_EQ(f.startB.point, Eigen::Vector2d(3.5, -2));
  EXPECT_EQ(f.resolution, 80);
  EXPECT_DOUBLE_EQ(f.interiorEdgeFactor, 1.5);
  EXPECT_TRUE(f.flip && f.fitPerimeter);
  EXPECT_DOUBLE_EQ(f.weights.smooth3d, 0.02);
  EXPECT_DOUBLE_EQ(f.weights.isometry, 1.0);
  EXPECT_EQ(f.solver.maxIterations, 30);

  const Result<Job> again = parseJobJson(jobToJson(job.value()), "again.json", "/elsewhere");
  ASSERT_TRUE(again.isOk()) << again.status().message();
  EXPECT_EQ(jobToJson(again.value()), jobToJson(job.value()));
}

// Sets the weight named `name` of `job`'s mode through its row of the settings table (as
// --weight, Python's weights and job files do): false for a name the mode has no weight of.
bool setNamedWeight(Job& job, const std::string& name, double value) {
  const SettingRow* row = findSetting("weights." + name, job.isForward());
  return row && setSetting(job, *row, std::to_string(value)).isOk();
}

// The settings table's weight rows, the job file's writer and its reader all go through the
// mode's table of terms: a distinct value per row, set by its name, reaches the row's member, is
// written under its name and read back into the same member; a name of the other mode's table is
// unknown.
template <typename Weights>
void expectNamedWeightsRoundTrip(Job job, const TermTable<Weights>& table,
                                 Weights& (*weightsOf)(Job&)) {
  const auto value = [](std::size_t k) { return 0.5 + double(k); };
  for (std::size_t k = 0; k < table.size(); ++k) {
    ASSERT_TRUE(setNamedWeight(job, table[k].name, value(k))) << table[k].name;
    EXPECT_EQ(weightsOf(job).*table[k].weight, value(k)) << table[k].name;
  }
  const std::string text = jobToJson(job);
  const nlohmann::json written = nlohmann::json::parse(text)["weights"];
  EXPECT_EQ(written.size(), table.size());
  const Result<Job> read = parseJobJson(text, "job.json", "/base");
  ASSERT_TRUE(read.isOk()) << read.status().message();
  Job again = read.value();
  for (std::size_t k = 0; k < table.size(); ++k) {
    EXPECT_EQ(written.at(table[k].name).template get<double>(), value(k)) << table[k].name;
    EXPECT_EQ(weightsOf(again).*table[k].weight, value(k)) << table[k].name;
  }
}

TEST(JobFile, NamedWeightsRoundTripThroughTheTables) {
  ForwardJob forwardInputs;
  forwardInputs.pieceA = "a.svg";
  forwardInputs.pieceB = "b.svg";
  Job forward(forwardInputs);
  expectNamedWeightsRoundTrip(
      forward, forwardTerms(),
      +[](Job& job) -> ForwardWeights& { return std::get<ForwardJob>(job.run).weights; });
  EXPECT_FALSE(setNamedWeight(forward, "closeness", 1.0));
  InverseJob inverseInputs;
  inverseInputs.curve = "c.obj";
  Job inverse(inverseInputs);
  expectNamedWeightsRoundTrip(
      inverse, inverseTerms(),
      +[](Job& job) -> InverseWeights& { return std::get<InverseJob>(job.run).weights; });
  EXPECT_FALSE(setNamedWeight(inverse, "seam", 1.0));
}

// The names are the job files' interface (docs/cli.md): each sets the weight it says, so two
// rows whose names were swapped fail here even though every table check above still holds.
TEST(JobFile, EachWeightNameSetsItsOwnWeight) {
  const std::vector<std::pair<std::string, double ForwardWeights::*>> forwardNames = {
      {"isometry", &ForwardWeights::isometry},        {"alignment", &ForwardWeights::alignment},
      {"boundary_fix", &ForwardWeights::boundaryFix}, {"smooth_3d", &ForwardWeights::smooth3d},
      {"smooth_2d", &ForwardWeights::smooth2d},       {"seam", &ForwardWeights::seam}};
  for (const auto& [name, member] : forwardNames) {
    Job forward;  // a fresh one each time: a weight set by another name must not pass here
    ASSERT_TRUE(setNamedWeight(forward, name, 123.5)) << name;
    EXPECT_EQ(std::get<ForwardJob>(forward.run).weights.*member, 123.5) << name;
  }
  const std::vector<std::pair<std::string, double InverseWeights::*>> inverseNames = {
      {"isometry", &InverseWeights::isometry},
      {"closeness", &InverseWeights::closeness},
      {"smooth_3d", &InverseWeights::smooth3d},
      {"smooth_2d", &InverseWeights::smooth2d}};
  for (const auto& [name, member] : inverseNames) {
    Job inverse{InverseJob()};
    ASSERT_TRUE(setNamedWeight(inverse, name, 0.25)) << name;
    EXPECT_EQ(std::get<InverseJob>(inverse.run).weights.*member, 0.25) << name;
  }
}

TEST(JobFile, InverseJobRoundTrips) {
  const Result<Job> job = parseJobJson(R"({"mode": "inverse", "curve": "seam.obj", "closed": true,
    "weights": {"closeness": 2}})",
                                       "job.json", "/base");
  ASSERT_TRUE(job.isOk()) << job.status().message();
  ASSERT_FALSE(job.value().isForward());
  const InverseJob& i = std::get<InverseJob>(job.value().run);
  EXPECT_EQ(i.curve, "/base/seam.obj");
  EXPECT_TRUE(i.forceClosed);
  EXPECT_DOUBLE_EQ(i.weights.closeness, 2.0);
  const Result<Job> again = parseJobJson(jobToJson(job.value()), "again.json", "/x");
  ASSERT_TRUE(again.isOk());
  EXPECT_EQ(jobToJson(again.value()), jobToJson(job.value()));
}

TEST(JobFile, EveryMistakeNamesItsKey) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"({"piece_a": "a.svg", "piece_b": "b.svg"})", "mode"},
      {R"({"mode": "sideways", "piece_a": "a.svg", "piece_b": "b.svg"})", "mode"},
      {R"({"mode": "forward", "piece_a": "a.svg"})", "piece_b"},
      {R"({"mode": "forward", "piece_a": 3, "piece_b": "b.svg"})", "piece_a"},
      {R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "colour": 1})", "colour"},
      {R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "resolution": 1.5})",
       "resolution"},
      {R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "start_b": {"near": [1]}})",
       "start_b"},
      {R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "weights": {"glue": 1}})",
       "glue"},
      {R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "flip": "yes"})", "flip"},
      {R"({"mode": "forward", "piece_a": "a.svg", "piece_b": "b.svg", "resolution": 3})",
       "resolution"},
      {R"({"mode": "inverse"})", "curve"},
      // Past int: once read as 100, a valid resolution, by wrapping round.
      {R"({"mode": "inverse", "curve": "c.obj", "resolution": 4294967396})", "resolution"},
      {R"({"mode": "inverse", "curve": "c.obj", "solver": {"max_iterations": -4294967296}})",
       "max_iterations"},
  };
  for (const auto& [text, key] : bad) {
    const Result<Job> job = parseJobJson(text, "job.json", ".");
    ASSERT_FALSE(job.isOk()) << text;
    EXPECT_EQ(job.status().code(), ErrorCode::InputInvalid) << text;
    EXPECT_NE(job.status().message().find("job.json"), std::string::npos);
    EXPECT_NE(job.status().message().find(key), std::string::npos) << job.status().message();
  }
  const Result<Job> notJson = parseJobJson("{ nope", "job.json", ".");
  EXPECT_EQ(notJson.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(readJobFile("/nonexistent/job.json").status().code(), ErrorCode::InputUnreadable);
}

TEST(JobFile, AFileOverOneMebibyteIsRefusedUnread) {
  const std::string path = testing::TempDir() + "huge-job-" + std::to_string(::getpid()) + ".json";
  std::ofstream(path) << "";
  std::filesystem::resize_file(path, (std::uintmax_t(1) << 20) + 1);  // sparse: nothing is written
  const Result<Job> job = readJobFile(path);
  EXPECT_EQ(job.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(job.status().message().rfind(path + ": file is too large", 0), 0u)
      << job.status().message();
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace dform
