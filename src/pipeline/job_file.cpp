// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/job_file.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "dform/pipeline/settings.h"
#include "settings_json.h"

namespace dform {

namespace {

using nlohmann::json;

// A problem with one key of the job file, reported as "<file>: <key>: <problem>".
struct KeyError {
  std::string key, problem;
};

std::string path(const json& object, const std::string& key, const std::string& baseDir) {
  if (!object.contains(key)) throw KeyError{key, "is missing"};
  const json& v = object.at(key);
  if (!v.is_string() || v.get<std::string>().empty()) throw KeyError{key, "must be a file name"};
  const std::filesystem::path p(v.get<std::string>());
  return (p.is_absolute() ? p : std::filesystem::path(baseDir) / p).lexically_normal().string();
}

// The keys a job file of the mode may hold: its inputs', "mode", and each setting's key, an
// object's members ("weights.isometry") allowed inside that object.
void onlyKnownKeys(const json& root, const std::vector<std::string>& inputs, bool forward) {
  std::set<std::string> allowed = {"mode"};
  allowed.insert(inputs.begin(), inputs.end());
  std::set<std::string> objects;
  for (const SettingRow* row : settingRows(forward)) {
    allowed.insert(row->key);
    const std::size_t dot = row->key.find('.');
    if (dot != std::string::npos) objects.insert(row->key.substr(0, dot));
  }
  for (const auto& [key, value] : root.items()) {
    if (objects.count(key)) {
      if (!value.is_object()) throw KeyError{printable(key), "must be a JSON object"};
      for (const auto& [member, inner] : value.items())
        if (!allowed.count(key + "." + member))
          throw KeyError{printable(key) + "." + printable(member), "unknown key"};
    } else if (!allowed.count(key)) {
      throw KeyError{printable(key), "unknown key"};
    }
  }
}

Job parse(const json& root, const std::string& baseDir) {
  if (!root.is_object()) throw KeyError{"(top level)", "must be a JSON object"};
  if (!root.contains("mode") || !root["mode"].is_string())
    throw KeyError{"mode", "must be \"forward\" or \"inverse\""};
  const std::string mode = root["mode"].get<std::string>();
  Job job;
  if (mode == "forward") {
    onlyKnownKeys(root, {"piece_a", "piece_b"}, true);
    ForwardJob forward;
    forward.pieceA = path(root, "piece_a", baseDir);
    forward.pieceB = path(root, "piece_b", baseDir);
    job = Job(forward);
  } else if (mode == "inverse") {
    onlyKnownKeys(root, {"curve"}, false);
    InverseJob inverse;
    inverse.curve = path(root, "curve", baseDir);
    job = Job(inverse);
  } else {
    throw KeyError{"mode", "must be \"forward\" or \"inverse\", not \"" + printable(mode) + "\""};
  }
  // In the table's order: a join sets the weights' defaults before the weights are read.
  const auto [row, why] = readSettingsObject(job, root);
  if (row) throw KeyError{row->key, why};
  return job;
}

}  // namespace

Result<Job> parseJobJson(const std::string& text, const std::string& source,
                         const std::string& baseDir) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    return Status(ErrorCode::InputUnreadable,
                  source + ": not valid JSON (" + parserReason(e.what()) + ")");
  }
  try {
    return parse(root, baseDir);
  } catch (const KeyError& e) {
    return Status(ErrorCode::InputInvalid, source + ": " + e.key + ": " + e.problem);
  } catch (const json::exception& e) {
    return Status(ErrorCode::InputInvalid, source + ": " + parserReason(e.what()));
  }
}

Result<Job> readJobFile(const std::string& path) {
  const Result<std::string> text = readInputFile(path, kMaxSettingsBytes);
  if (!text.isOk()) return text.status();
  return parseJobFileText(text.value(), path);
}

Result<Job> parseJobFileText(const std::string& text, const std::string& path) {
  const std::string base = std::filesystem::path(path).parent_path().string();
  return parseJobJson(text, inputName(path), base.empty() ? "." : base);
}

namespace {

// An input as a job file records it: a file by its absolute path (the job runs again from any
// folder); a name that is no file (a shape made in memory, named by its role) as it is. Bytes
// that are not UTF-8 (a Latin-1 file name) are recorded as the text \xNN: JSON holds text only.
std::string recordedInput(const std::string& input) {
  std::error_code ec;
  return utf8Text(std::filesystem::exists(input, ec) ? std::filesystem::absolute(input).string()
                                                     : input);
}

}  // namespace

std::string jobToJson(const Job& job) {
  json out = {{"mode", job.modeName()}};
  const std::vector<std::string> inputs = job.inputs();
  const std::vector<std::string> keys = job.isForward()
                                            ? std::vector<std::string>{"piece_a", "piece_b"}
                                            : std::vector<std::string>{"curve"};
  for (std::size_t k = 0; k < keys.size(); ++k) out[keys[k]] = recordedInput(inputs[k]);
  out.update(settingsObject(job));
  return out.dump(2, ' ', false, json::error_handler_t::replace);
}

}  // namespace dform
