// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table walked row by row (pipeline/settings.h): every setting has its command-line
// flag (listed by --help and taken by the command), its job-file key and its Python keyword
// (tests/python/test_settings.py takes each); each accepts its default, refuses a value out of its
// range or choices with a message naming the setting (by its flag on the command line, its key in
// a job file and in the library's message), and round-trips through a job file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "dform/pipeline/job_file.h"
#include "dform/pipeline/settings.h"
#include "pipeline/setting_values.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct CommandRun {
  int exitCode = 0;
  std::string out;  ///< stdout and stderr
};

CommandRun dform(const std::string& arguments) {
  CommandRun r;
  const std::string command = std::string(DFORM_EXE) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) r.out.append(buffer, n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

// A job of the row's mode.
Job jobOf(const SettingRow& row) {
  return row.scope == SettingScope::Inverse ? Job(InverseJob()) : Job(ForwardJob());
}

// The command line's text of a JSON value.
std::string commandLineText(const SettingRow& row, const std::string& value) {
  const json v = json::parse(value);
  if (v.is_string()) return v.get<std::string>();
  if (row.type == SettingType::Weight) return row.weightName() + "=" + v.dump();
  return v.dump();
}

class SettingsTable : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dform-settings-table-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The command's arguments to run `row`'s mode on the samples, into a folder that cannot be
  // made: a setting the command takes ends in exit 6 (the output), one it refuses in exit 2.
  std::string command(const SettingRow& row) const {
    const std::string samples = DFORM_SAMPLES_DIR;
    const std::string unwritable = " -q -o /proc/dform-settings-table/out";
    if (row.scope == SettingScope::Inverse)
      return "inverse " + samples + "/inverse/tennis-ball.obj" + unwritable;
    return "forward " + samples + "/forward/ellipses-a.svg " + samples + "/forward/ellipses-b.svg" +
           unwritable;
  }

  fs::path dir_;
};

TEST_F(SettingsTable, EveryRowHasItsNamesInEveryShell) {
  std::set<std::string> keys[2];
  const std::regex keyword("^[a-z][a-z0-9_]*$"), flag("^--[a-z][a-z0-9-]*$");
  const std::string forwardHelp = dform("forward --help").out;
  const std::string inverseHelp = dform("inverse --help").out;
  for (const SettingRow& row : settingRows()) {
    SCOPED_TRACE(row.key);
    EXPECT_EQ(row.key.rfind(settingKey(row.id), 0), 0u) << "the key is its setting's";
    EXPECT_TRUE(std::regex_match(row.keyword, keyword)) << row.keyword;
    EXPECT_TRUE(std::regex_match(row.flag, flag)) << row.flag;
    EXPECT_FALSE(row.help.empty());
    for (int mode = 0; mode < 2; ++mode) {
      const bool forward = mode == 0;
      if (forward ? row.scope == SettingScope::Inverse : row.scope == SettingScope::Forward)
        continue;
      EXPECT_TRUE(keys[mode].insert(row.key).second) << "one row per key and mode";
      EXPECT_EQ(findSetting(row.key, forward), &row);
      const std::string& help = forward ? forwardHelp : inverseHelp;
      EXPECT_NE(help.find("  " + row.flag), std::string::npos)
          << row.flag << " missing from " << (forward ? "forward" : "inverse") << " --help";
      if (!row.nearFlag.empty()) {
        EXPECT_NE(help.find("  " + row.nearFlag), std::string::npos);
      }
      if (!row.offFlag.empty()) {
        EXPECT_NE(help.find("  " + row.offFlag), std::string::npos);
      }
      // A number's --help line gives the mode's own default (the inverse solve's stops differ).
      if ((row.type == SettingType::Integer || row.type == SettingType::Number) &&
          row.unset.empty()) {
        const std::size_t line = help.find("  " + row.flag + " ");
        const std::size_t end = help.find("\n  -", line + 1);
        char shown[32];
        std::snprintf(shown, sizeof shown, "%.10g",
                      json::parse(settingDefault(row, forward)).get<double>());
        EXPECT_NE(help.substr(line, end - line).find("(default " + std::string(shown) + ")"),
                  std::string::npos)
            << help.substr(line, end - line);
      }
    }
  }
}

TEST_F(SettingsTable, EveryRowTakesItsDefaultAndRefusesAValueOutOfRange) {
  for (const SettingRow& row : settingRows()) {
    SCOPED_TRACE(row.key);
    // The library: its default is taken, a bad value refused naming the setting.
    Job job = jobOf(row);
    const std::string fallback = settingDefault(row);
    EXPECT_TRUE(setSetting(job, row, fallback).isOk()) << fallback;
    EXPECT_EQ(settingValue(job, row), fallback);
    const auto [bad, badText] = test::badValue(row);
    ASSERT_FALSE(bad.empty()) << "no bad value for this row's type";
    const Status refused = setSetting(job, row, bad);
    EXPECT_EQ(refused.code(), ErrorCode::Usage) << bad;
    EXPECT_EQ(refused.setting(), row.id) << refused.message();
    EXPECT_EQ(refused.message().rfind(row.key + " ", 0), 0u) << refused.message();
    EXPECT_EQ(settingValue(job, row), fallback) << "a refused value leaves the setting as it was";

    // A job file: the default read, the bad value refused naming the key.
    for (const std::string& value : {fallback, bad}) {
      const std::size_t dot = row.key.find('.');
      json file = {{"mode", row.scope == SettingScope::Inverse ? "inverse" : "forward"},
                   {"piece_a", "a.svg"},
                   {"piece_b", "b.svg"},
                   {"curve", "c.obj"}};
      file.erase(row.scope == SettingScope::Inverse ? "piece_a" : "curve");
      file.erase(row.scope == SettingScope::Inverse ? "piece_b" : "curve");
      if (dot == std::string::npos)
        file[row.key] = json::parse(value);
      else
        file[row.key.substr(0, dot)][row.key.substr(dot + 1)] = json::parse(value);
      if (json::parse(value).is_null()) continue;  // an unset optional setting: no key to write
      const Result<Job> read = parseJobJson(file.dump(), "job.json", "/base");
      if (value == fallback) {
        EXPECT_TRUE(read.isOk()) << read.status().message();
      } else {
        ASSERT_FALSE(read.isOk()) << file.dump();
        EXPECT_EQ(read.status().code(), ErrorCode::InputInvalid);
        EXPECT_EQ(read.status().message().rfind("job.json: " + row.key + ": ", 0), 0u)
            << read.status().message();
      }
    }
  }
}

TEST_F(SettingsTable, TheCommandLineTakesEveryDefaultAndRefusesAValueOutOfRange) {
  for (const SettingRow& row : settingRows()) {
    SCOPED_TRACE(row.key);
    const std::string fallback = settingDefault(row);
    if (row.type == SettingType::Flag) {
      // A flag sets the value it names; it takes no value, so none is out of range. A hinge is
      // for a rigid sheet alone (a usage error without one).
      const std::string needs = row.id == Setting::Hinge ? " --material plywood" : "";
      EXPECT_EQ(dform(command(row) + " " + row.flag + needs).exitCode, 6);
      if (row.id == Setting::Hinge) {
        EXPECT_EQ(dform(command(row) + " " + row.flag).exitCode, 2);
      }
      if (!row.offFlag.empty()) {
        EXPECT_EQ(dform(command(row) + " " + row.offFlag).exitCode, 6);
        EXPECT_EQ(dform(command(row) + " " + row.flag + needs + " " + row.offFlag).exitCode, 2)
            << "the flag and its opposite exclude each other";
      }
      continue;
    }
    if (fallback != "null") {
      const CommandRun taken =
          dform(command(row) + " " + row.flag + " " + quoted(commandLineText(row, fallback)));
      EXPECT_EQ(taken.exitCode, 6) << taken.out;
    }
    const std::string badText = test::badValue(row).second;
    const CommandRun refused =
        dform(command(row) + " " + row.flag + " " +
              quoted(row.type == SettingType::Weight ? row.weightName() + "=" + badText : badText));
    EXPECT_EQ(refused.exitCode, 2) << refused.out;
    EXPECT_EQ(refused.out.rfind("dform: error: " + row.flag, 0), 0u) << refused.out;
  }
}

// report.json's schema (templates/schema/report.schema.json) describes the job it records: every
// row of each mode is a property of the mode's job there, with the row's choices and range.
TEST_F(SettingsTable, TheReportSchemaDescribesEveryRow) {
  std::ifstream in(DFORM_REPORT_SCHEMA);
  const json schema = json::parse(in);
  const json& defs = schema.at("$defs");
  const auto resolved = [&defs](const json& node) -> const json& {
    if (!node.contains("$ref")) return node;
    const std::string ref = node.at("$ref").get<std::string>();
    return defs.at(ref.substr(ref.rfind('/') + 1));
  };
  for (const bool forward : {true, false}) {
    const json& job = defs.at(forward ? "forwardJob" : "inverseJob");
    for (const SettingRow* row : settingRows(forward)) {
      SCOPED_TRACE(row->key);
      const std::size_t dot = row->key.find('.');
      const json& properties = job.at("properties");
      const std::string first = row->key.substr(0, dot);
      ASSERT_TRUE(properties.contains(first));
      const json* property = &resolved(properties.at(first));
      if (dot != std::string::npos) {
        const std::string member = row->key.substr(dot + 1);
        if (row->type == SettingType::Weight) {  // any term name: a number >= 0
          EXPECT_EQ(property->at("additionalProperties").at("minimum"), 0);
          continue;
        }
        ASSERT_TRUE(property->at("properties").contains(member));
        property = &property->at("properties").at(member);
      }
      if (property->contains("oneOf")) {  // a number or its text form (the scale)
        for (const json& alternative : property->at("oneOf"))
          if (alternative.value("type", "") == "number") property = &alternative;
      }
      if (row->type == SettingType::Choice) {
        std::vector<std::string> choices;
        for (const SettingChoice& c : row->choices) choices.push_back(c.name);
        EXPECT_EQ(property->at("enum").get<std::vector<std::string>>(), choices);
      }
      if (row->type == SettingType::Flag) {
        EXPECT_EQ(property->at("type"), "boolean");
      }
      if (row->type != SettingType::Integer && row->type != SettingType::Number &&
          row->id != Setting::Scale)
        continue;
      const bool wholeRange = row->max >= std::numeric_limits<int>::max();
      const char* low = row->minExcluded ? "exclusiveMinimum" : "minimum";
      const char* high = row->maxExcluded ? "exclusiveMaximum" : "maximum";
      if (std::isfinite(row->min)) {
        EXPECT_EQ(property->value(low, json()), row->min) << property->dump();
      }
      if (std::isfinite(row->max) && !wholeRange) {
        EXPECT_EQ(property->value(high, json()), row->max) << property->dump();
      } else {
        EXPECT_FALSE(property->contains(high)) << property->dump();
      }
    }
  }
}

// A default is written once, where its member is declared (the settings structs' initialisers):
// no shell binds a setting's name to its default literal ("resolution", 100; arg("join") =
// "outer,outer"; resolution: 100; resolution=100), which would drift from the table.
TEST_F(SettingsTable, EveryDefaultIsWrittenOnce) {
  // The shells and the pipeline, where a setting is read and written (a local `scale` or
  // `closed` in a module below is another thing).
  std::vector<fs::path> files;
  for (const char* folder :
       {"src/pipeline", "src/cli", "src/python", "src/studio", "templates/studio"})
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(DFORM_SOURCE_DIR) / folder))
      if (entry.is_regular_file() &&
          std::set<std::string>{".cpp", ".h", ".py", ".pyi", ".js", ".html"}.count(
              entry.path().extension().string()))
        files.push_back(entry.path());
  std::map<fs::path, std::string> texts;
  for (const fs::path& file : files) {
    std::ifstream in(file);
    texts[file] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  int checked = 0;
  for (const SettingRow& row : settingRows()) {
    const json fallback = json::parse(settingDefault(row));
    std::string literal;
    if (fallback.is_boolean()) {
      literal = fallback.get<bool>() ? "(true|True)" : "(false|False)";
    } else if (fallback.is_number()) {
      const double d = fallback.get<double>();
      literal = std::regex_replace(fallback.dump(), std::regex("\\."), "\\.");
      if (d == std::floor(d)) literal = std::to_string((long long)d) + "(\\.0*)?";
    } else if (fallback.is_string()) {
      literal = "[\"']" + fallback.get<std::string>() + "[\"']";
    } else {
      continue;  // unset, or a start point: no literal of its own
    }
    const std::string name = row.key.substr(row.key.rfind('.') + 1);
    std::set<std::string> names = {name, row.keyword};
    if (row.type == SettingType::Weight) names = {row.weightName()};
    for (const std::string& n : names) {
      // "name", x and arg("name") = x (C++), name: x (JavaScript), name=x (Python); not a
      // variable of that name assigned (closed = false).
      const std::regex bound("(^|[^A-Za-z0-9_-])" + n +
                             "([\"']\\s*(\\)\\s*)?[:=,]\\s*|\\s*:\\s*|=)" + literal +
                             "([^0-9A-Za-z_.]|$)");
      for (const auto& [file, text] : texts) {
        std::smatch found;
        EXPECT_FALSE(std::regex_search(text, found, bound))
            << row.key << "'s default written again in " << file.string() << ": " << found.str();
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

TEST_F(SettingsTable, EveryRowRoundTripsThroughAJobFile) {
  for (const bool forward : {true, false}) {
    // Every setting of the mode at once at a value other than its default.
    Job job = forward ? Job(ForwardJob{ForwardSettings(), "/base/a.svg", "/base/b.svg"})
                      : Job(InverseJob{InverseSettings(), "/base/c.obj", false});
    for (const SettingRow* row : settingRows(forward)) {
      const std::string value = test::otherValue(*row, forward);
      ASSERT_FALSE(value.empty()) << row->key << ": no other value for this row";
      const Status set = setSetting(job, *row, value);
      ASSERT_TRUE(set.isOk()) << row->key << " = " << value << ": " << set.message();
    }
    const std::string written = jobToJson(job);
    const Result<Job> read = parseJobJson(written, "job.json", "/base");
    ASSERT_TRUE(read.isOk()) << read.status().message() << "\n" << written;
    for (const SettingRow* row : settingRows(forward)) {
      EXPECT_EQ(settingValue(read.value(), *row), settingValue(job, *row)) << row->key;
      EXPECT_NE(settingValue(read.value(), *row), settingDefault(*row, forward)) << row->key;
    }
    EXPECT_EQ(jobToJson(read.value()), written);
  }
}

}  // namespace
}  // namespace dform
