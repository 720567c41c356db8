// SPDX-License-Identifier: GPL-3.0-or-later
#include "json_summary.h"

#include <cctype>
#include <cstdio>

#include "dform/core/setting.h"
#include "dform/pipeline/exit_code.h"
#include "dform/pipeline/settings.h"

namespace dform::cli::json_summary {

namespace {

struct State {
  bool enabled = false;
  bool printed = false;
  nlohmann::json command;
  nlohmann::json fields = nlohmann::json::object();
  nlohmann::json error;  // null until the first error
  std::optional<ErrorCode> code;
};

State& state() {
  static State s;
  return s;
}

const char* codeName(ErrorCode code) {
  switch (code) {
    case ErrorCode::Ok: return "ok";
    case ErrorCode::Usage: return "usage";
    case ErrorCode::InputUnreadable: return "input_unreadable";
    case ErrorCode::InputInvalid: return "input_invalid";
    case ErrorCode::SolveFailed: return "solve_failed";
    case ErrorCode::OutputFailed: return "output_failed";
    case ErrorCode::GateFailed: return "gate_failed";
    case ErrorCode::Interrupted: return "interrupted";
    case ErrorCode::Internal: return "internal";
  }
  return "internal";
}

// The error kind an exit code stands for (130 and 143: interrupted, as a shell reports them).
ErrorCode codeOfExit(int exitCode) {
  if (exitCode == 128 + 2 || exitCode == 128 + 15) return ErrorCode::Interrupted;
  for (ErrorCode c : {ErrorCode::Usage, ErrorCode::InputUnreadable, ErrorCode::InputInvalid,
                      ErrorCode::SolveFailed, ErrorCode::OutputFailed, ErrorCode::GateFailed,
                      ErrorCode::Interrupted})
    if (exitCode == dform::exitCode(c)) return c;
  return ErrorCode::Internal;
}

}  // namespace

void enable(const std::optional<std::string>& command) {
  state().enabled = true;
  state().command = command ? nlohmann::json(*command) : nlohmann::json();
}

bool enabled() { return state().enabled; }

void add(const nlohmann::json& fields) {
  for (const auto& [key, value] : fields.items()) state().fields[key] = value;
}

namespace {

// The job-file key of the setting whose command-line flag `message` names first ("--resolution
// must be ..." is about `resolution`), or null.
nlohmann::json settingOfFlags(const std::string& message) {
  for (std::size_t at = message.find("--"); at != std::string::npos;
       at = message.find("--", at + 2)) {
    std::size_t end = at + 2;
    while (end < message.size() &&
           (std::isalnum(static_cast<unsigned char>(message[end])) || message[end] == '-'))
      ++end;
    const std::string flag = message.substr(at, end - at);
    for (const SettingRow& row : settingRows())
      if (flag == row.flag || flag == row.nearFlag || flag == row.offFlag)
        return row.type == SettingType::Weight ? nlohmann::json(settingKey(Setting::Weight))
                                               : nlohmann::json(row.key);
  }
  return nullptr;
}

}  // namespace

void error(const std::string& shownMessage, const Status* status) {
  State& s = state();
  if (!s.error.is_null()) return;
  s.error = {{"message", shownMessage}, {"setting", settingOfFlags(shownMessage)}};
  if (status) {
    s.code = status->code();
    if (const std::optional<Setting> setting = status->setting())
      s.error["setting"] = settingKey(*setting);
  }
}

void printNow(int exitCode) {
  State& s = state();
  if (!s.enabled || s.printed) return;
  nlohmann::json out = s.fields;
  out["command"] = s.command;
  out["exit_code"] = exitCode;
  out["ok"] = exitCode == 0;
  if (!s.error.is_null() && exitCode != 0) {
    nlohmann::json e = s.error;
    e["code"] = codeName(s.code.value_or(codeOfExit(exitCode)));
    out["error"] = e;
  } else if (exitCode != 0) {
    out["error"] = {{"code", codeName(codeOfExit(exitCode))},
                    {"message", "exit code " + std::to_string(exitCode)},
                    {"setting", nullptr}};
  } else {
    out["error"] = nullptr;
  }
  std::fprintf(stdout, "%s\n", out.dump(2).c_str());
  std::fflush(stdout);
  s.printed = true;
}

void cancel() { state().printed = true; }

int finish(int exitCode) {
  printNow(exitCode);
  return exitCode;
}

}  // namespace dform::cli::json_summary
