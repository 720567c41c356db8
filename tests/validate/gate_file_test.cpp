// SPDX-License-Identifier: GPL-3.0-or-later
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "dform/validate/gate.h"

namespace dform {
namespace {

namespace fs = std::filesystem;

std::string preset(const std::string& name) {
  return std::string(DFORM_TEMPLATES_DIR) + "/gates/" + name + ".json";
}

// Every limit of a gate, in one list so that the comparisons below cover each field.
std::vector<double> fields(const GateLimits& g) {
  return {g.lengthError,     g.lengthErrorMax,    g.seamError,     g.curveError,
          g.seamGapMm,       g.gaussMaxRad,       g.seamLengthRel, g.hullDistanceRel,
          double(g.flipped), double(g.degenerate)};
}

TEST(GateFile, PresetsReadAndAreOrdered) {
  const Result<GateLimits> def = readGateFile(preset("default"));
  const Result<GateLimits> strict = readGateFile(preset("strict"));
  const Result<GateLimits> lenient = readGateFile(preset("lenient"));
  ASSERT_TRUE(def.isOk()) << def.status().message();
  ASSERT_TRUE(strict.isOk()) << strict.status().message();
  ASSERT_TRUE(lenient.isOk()) << lenient.status().message();
  EXPECT_EQ(def.value().name, "default");
  EXPECT_EQ(strict.value().name, "strict");
  EXPECT_EQ(lenient.value().name, "lenient");
  // The built-in defaults are the default preset.
  EXPECT_EQ(fields(def.value()), fields(GateLimits{}));
  const std::vector<double> s = fields(strict.value()), d = fields(def.value()),
                            l = fields(lenient.value());
  for (size_t i = 0; i < d.size(); ++i) {
    EXPECT_LE(s[i], d[i]) << "field " << i;
    EXPECT_LE(d[i], l[i]) << "field " << i;
  }
  EXPECT_LT(s[0], d[0]);
  EXPECT_LT(d[0], l[0]);
}

TEST(GateFile, EveryPresetFileInTheTemplatesFolderReads) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(std::string(DFORM_TEMPLATES_DIR) + "/gates")) {
    if (entry.path().extension() != ".json") continue;
    const Result<GateLimits> gate = readGateFile(entry.path().string());
    EXPECT_TRUE(gate.isOk()) << gate.status().message();
    EXPECT_EQ(gate.value().name, entry.path().stem().string());
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(GateFile, LeftOutLimitsKeepTheirDefaults) {
  const Result<GateLimits> gate =
      parseGateJson(R"({"version": 1, "limits": {"L_error": 0.02, "flipped": 3}})", "g.json");
  ASSERT_TRUE(gate.isOk()) << gate.status().message();
  EXPECT_EQ(gate.value().lengthError, 0.02);
  EXPECT_EQ(gate.value().flipped, 3);
  EXPECT_EQ(gate.value().lengthErrorMax, GateLimits{}.lengthErrorMax);
  EXPECT_EQ(gate.value().name, GateLimits{}.name);
}

struct BadGate {
  const char* text;
  ErrorCode code;
  const char* mentions;  // the field (or problem) the one-line message must name
};

TEST(GateFile, EveryBadFieldIsNamed) {
  const BadGate cases[] = {
      {R"({"version": 1, "colour": "red"})", ErrorCode::InputInvalid, "'colour'"},
      {R"({"version": 1, "limits": {"L_eror": 0.1}})", ErrorCode::InputInvalid, "'limits.L_eror'"},
      {R"({"version": 1, "limits": {"L_error": "0.1"}})", ErrorCode::InputInvalid,
       "limits.L_error"},
      {R"({"version": 1, "limits": {"L_max": -0.1}})", ErrorCode::InputInvalid, "limits.L_max"},
      {R"({"version": 1, "limits": {"seam_gap_mm": null}})", ErrorCode::InputInvalid,
       "limits.seam_gap_mm"},
      {R"({"version": 1, "limits": {"gauss_max_rad": true}})", ErrorCode::InputInvalid,
       "limits.gauss_max_rad"},
      {R"({"version": 1, "limits": {"B_error": -1e-9}})", ErrorCode::InputInvalid,
       "limits.B_error"},
      {R"({"version": 1, "limits": {"D_error": [1]}})", ErrorCode::InputInvalid, "limits.D_error"},
      {R"({"version": 1, "limits": {"seam_length_rel": -1}})", ErrorCode::InputInvalid,
       "limits.seam_length_rel"},
      {R"({"version": 1, "limits": {"hull_distance_rel": {}}})", ErrorCode::InputInvalid,
       "limits.hull_distance_rel"},
      {R"({"version": 1, "limits": {"flipped": 1.5}})", ErrorCode::InputInvalid, "limits.flipped"},
      {R"({"version": 1, "limits": {"degenerate": -1}})", ErrorCode::InputInvalid,
       "limits.degenerate"},
      {R"({"version": 1, "limits": [0.1]})", ErrorCode::InputInvalid, "limits"},
      {R"({"version": 2})", ErrorCode::InputInvalid, "version"},
      {R"({"version": "1"})", ErrorCode::InputInvalid, "version"},
      {R"({"limits": {}})", ErrorCode::InputInvalid, "'version'"},
      {R"({"version": 1, "name": 7})", ErrorCode::InputInvalid, "name"},
      {R"({"version": 1, "description": false})", ErrorCode::InputInvalid, "description"},
      {R"([1, 2])", ErrorCode::InputInvalid, "object"},
      {R"({"version": 1,)", ErrorCode::InputUnreadable, "not JSON"},
  };
  for (const BadGate& bad : cases) {
    const Result<GateLimits> gate = parseGateJson(bad.text, "bad.json");
    ASSERT_FALSE(gate.isOk()) << bad.text;
    EXPECT_EQ(gate.status().code(), bad.code) << bad.text;
    const std::string& message = gate.status().message();
    EXPECT_EQ(message.rfind("bad.json: ", 0), 0u) << message;
    EXPECT_NE(message.find(bad.mentions), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(GateFile, FileErrorsNameThePath) {
  const fs::path dir =
      fs::temp_directory_path() /
      ("dform_gate_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  const std::string missing = (dir / "missing.json").string();
  const Result<GateLimits> none = readGateFile(missing);
  EXPECT_EQ(none.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(none.status().message().rfind(missing + ": ", 0), 0u) << none.status().message();

  const std::string negative = (dir / "negative.json").string();
  std::ofstream(negative) << R"({"version": 1, "limits": {"L_error": -0.5}})";
  const Result<GateLimits> bad = readGateFile(negative);
  EXPECT_EQ(bad.status().code(), ErrorCode::InputInvalid);
  EXPECT_EQ(bad.status().message().rfind(negative + ": limits.L_error", 0), 0u)
      << bad.status().message();

  const std::string huge = (dir / "huge.json").string();
  std::ofstream(huge) << "";
  fs::resize_file(huge, (std::uintmax_t(1) << 20) + 1);  // sparse: nothing is written
  const Result<GateLimits> big = readGateFile(huge);
  EXPECT_EQ(big.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(big.status().message().rfind(huge + ": file is too large", 0), 0u)
      << big.status().message();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dform

namespace dform {
namespace {

// Every limit written by gateLimitsJson reads back, each one changed alone changes the text: a
// report records the limits its gate judged by, and a later export compares them.
TEST(GateFile, LimitsWrittenAsJsonReadBackAndEachOneCounts) {
  GateLimits limits;
  limits.lengthError = 0.011;
  limits.lengthErrorMax = 0.022;
  limits.seamError = 3.3e-7;
  limits.curveError = 4.4e-7;
  limits.seamGapMm = 0.055;
  limits.gaussMaxRad = 0.066;
  limits.seamLengthRel = 7.7e-3;
  limits.hullDistanceRel = 0.088;
  limits.exactDistanceRel = 9.9e-3;
  limits.roundtripRel = 1.01e-3;
  limits.flipped = 3;
  limits.degenerate = 4;
  const std::string written = gateLimitsJson(limits);
  const Result<GateLimits> read =
      parseGateJson(R"({"version": 1, "limits": )" + written + "}", "written");
  ASSERT_TRUE(read.isOk()) << read.status().message();
  EXPECT_EQ(gateLimitsJson(read.value()), written);
  const GateLimits& r = read.value();
  EXPECT_EQ(r.lengthError, limits.lengthError);
  EXPECT_EQ(r.lengthErrorMax, limits.lengthErrorMax);
  EXPECT_EQ(r.seamError, limits.seamError);
  EXPECT_EQ(r.curveError, limits.curveError);
  EXPECT_EQ(r.seamGapMm, limits.seamGapMm);
  EXPECT_EQ(r.gaussMaxRad, limits.gaussMaxRad);
  EXPECT_EQ(r.seamLengthRel, limits.seamLengthRel);
  EXPECT_EQ(r.hullDistanceRel, limits.hullDistanceRel);
  EXPECT_EQ(r.exactDistanceRel, limits.exactDistanceRel);
  EXPECT_EQ(r.roundtripRel, limits.roundtripRel);
  EXPECT_EQ(r.flipped, limits.flipped);
  EXPECT_EQ(r.degenerate, limits.degenerate);
  // Each limit of the defaults changed alone gives another text.
  const std::string defaults = gateLimitsJson(GateLimits{});
  std::vector<std::function<void(GateLimits&)>> changes = {
      [](GateLimits& l) { l.lengthError *= 2; },      [](GateLimits& l) { l.lengthErrorMax *= 2; },
      [](GateLimits& l) { l.seamError *= 2; },        [](GateLimits& l) { l.curveError *= 2; },
      [](GateLimits& l) { l.seamGapMm *= 2; },        [](GateLimits& l) { l.gaussMaxRad *= 2; },
      [](GateLimits& l) { l.seamLengthRel *= 2; },    [](GateLimits& l) { l.hullDistanceRel *= 2; },
      [](GateLimits& l) { l.exactDistanceRel *= 2; }, [](GateLimits& l) { l.roundtripRel *= 2; },
      [](GateLimits& l) { l.flipped += 1; },          [](GateLimits& l) { l.degenerate += 1; }};
  for (size_t k = 0; k < changes.size(); ++k) {
    GateLimits changed;
    changes[k](changed);
    EXPECT_NE(gateLimitsJson(changed), defaults) << "limit " << k;
  }
}

}  // namespace
}  // namespace dform
