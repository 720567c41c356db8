// SPDX-License-Identifier: GPL-3.0-or-later
// Every shipped sample's outputs against a stored digest, so that a change meant to move code
// without changing what it computes is seen to change nothing: each sample runs as a user runs it
// (`dform run JOB` or `dform inverse CURVE`, default gate, default export), and its report
// figures and the SHA-256 of every file it writes besides report.json and report.html (which hold
// timings) are compared with tests/pipeline/data/sample_digests/<sample>.json.
//
// Figures are compared to kSignificantDigits significant digits, the agreement the three OpenBLAS
// kernels are held to (SampleOnEveryKernel in tests/cli/cli_test.cpp): a figure agrees when
// |a - b| <= 5e-4 max(|a|, |b|). The files' hashes are compared exactly; pattern.pdf is hashed
// without its /CreationDate, the only text in it that changes from run to run.
//
// A change that means to change the outputs refreshes the digests on purpose, and the diff of
// tests/pipeline/data/sample_digests/ shows what moved:
//   DFORM_REFRESH_DIGESTS=1 ctest --test-dir build -R SampleDigest -j2
// (each test then writes its sample's digest instead of comparing, and passes).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "cli/text_files.h"
#include "dform/core/file_hash.h"
#include "shipped_samples.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kSignificantDigits = 3;
// Figures are stored with more digits than compared, so that the file shows how close they are.
constexpr int kStoredDigits = 6;

// The file name of a sample's digest: its path without the extension, '/' as '-'.
std::string digestName(const std::string& sample) {
  std::string name = sample.substr(0, sample.rfind('.'));
  std::replace(name.begin(), name.end(), '/', '-');
  return name + ".json";
}

double roundToDigits(double value, int digits) {
  if (value == 0.0 || !std::isfinite(value)) return value;
  const double scale = std::pow(10.0, digits - 1 - int(std::floor(std::log10(std::abs(value)))));
  return std::round(value * scale) / scale;
}

// The kernel test's rule: 5e-4 of the larger for 3 digits.
bool agree(double a, double b) {
  const double half = 0.5 * std::pow(10.0, -kSignificantDigits);
  return std::abs(a - b) <= half * std::max(std::abs(a), std::abs(b));
}

// The bytes a file's hash is taken of: pattern.pdf without its creation date.
std::string hashedBytes(const fs::path& file) {
  const std::string bytes = test::readText(file);
  if (file.filename() != "pattern.pdf") return bytes;
  static const std::regex creationDate(R"(/CreationDate \([^)]*\))");
  return std::regex_replace(bytes, creationDate, "/CreationDate ()");
}

// What a run wrote that the digest holds: its report's figures (numbers rounded to
// kStoredDigits, null for a figure that is not finite) and its gate's verdict, and the hash of
// every other file in the folder.
json digestOf(const fs::path& out) {
  const json report = json::parse(std::ifstream(out / "report.json"));
  json digest;
  for (const auto& [key, value] : report["metrics"].items())
    digest["figures"][key] =
        value.is_number_float() ? json(roundToDigits(value.get<double>(), kStoredDigits)) : value;
  digest["gate_passed"] = report["gate"]["passed"];
  for (const auto& entry : fs::directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    if (name == "report.json" || name == "report.html" || !entry.is_regular_file()) continue;
    digest["files"][name] = sha256Hex(hashedBytes(entry.path()));
  }
  return digest;
}

class SampleDigest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { dir_ = test::freshTestFolder("dform_digest"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_P(SampleDigest, MatchesTheStoredDigest) {
  const std::string sample = GetParam();
  const bool forward = sample.rfind("forward/", 0) == 0;
  const fs::path out = dir_ / "out";
  const std::string command = std::string(DFORM_EXE) + (forward ? " run " : " inverse ") +
                              DFORM_SAMPLES_DIR + "/" + sample + " -q -o " + out.string() + " >" +
                              (dir_ / "stdout.txt").string() + " 2>" +
                              (dir_ / "stderr.txt").string();
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << command;
  ASSERT_TRUE(fs::exists(out / "report.json")) << test::readText(dir_ / "stderr.txt");
  json digest = digestOf(out);
  digest["exit_code"] = WEXITSTATUS(status);

  const fs::path stored = fs::path(DFORM_TEST_DATA_DIR) / "sample_digests" / digestName(sample);
  if (const char* refresh = std::getenv("DFORM_REFRESH_DIGESTS");
      refresh && std::string(refresh) == "1") {
    fs::create_directories(stored.parent_path());
    std::ofstream(stored) << digest.dump(2) << "\n";
    std::cout << "refreshed " << stored << "\n";
    return;
  }
  ASSERT_TRUE(fs::exists(stored)) << stored
                                  << " is missing: refresh the digests (this file's header)";
  const json expected = json::parse(std::ifstream(stored));
  EXPECT_EQ(digest["exit_code"], expected["exit_code"]);
  EXPECT_EQ(digest["gate_passed"], expected["gate_passed"]);
  for (const auto& [key, value] : expected["figures"].items()) {
    ASSERT_TRUE(digest["figures"].contains(key)) << key;
    const json& now = digest["figures"][key];
    if (value.is_number() && now.is_number())
      EXPECT_PRED2(agree, value.get<double>(), now.get<double>()) << key;
    else
      EXPECT_EQ(value, now) << key;
  }
  EXPECT_EQ(digest["figures"].size(), expected["figures"].size()) << "figures added or removed";
  EXPECT_EQ(digest["files"], expected["files"]) << "the files written differ";
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(0, info.param.rfind('.'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Shipped, SampleDigest, ::testing::ValuesIn(test::shippedSamples()),
                         testName);

}  // namespace
}  // namespace dform
