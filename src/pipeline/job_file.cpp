#include "dform/pipeline/job_file.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "dform/model/term_table.h"

namespace dform {

namespace {

using nlohmann::json;

// A problem with one key of the job file, reported as "<file>: <key>: <problem>".
struct KeyError {
  std::string key, problem;
};

void onlyKeys(const json& object, const std::set<std::string>& allowed, const std::string& where) {
  for (const auto& [key, value] : object.items())
    if (!allowed.count(key)) throw KeyError{where + printable(key), "unknown key"};
}

double number(const json& object, const std::string& key, const std::string& where) {
  const json& v = object.at(key);
  if (!v.is_number()) throw KeyError{where + key, "must be a number"};
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw KeyError{where + key, "must be finite"};
  return d;
}

bool flag(const json& object, const std::string& key) {
  const json& v = object.at(key);
  if (!v.is_boolean()) throw KeyError{key, "must be true or false"};
  return v.get<bool>();
}

std::string path(const json& object, const std::string& key, const std::string& baseDir) {
  if (!object.contains(key)) throw KeyError{key, "is missing"};
  const json& v = object.at(key);
  if (!v.is_string() || v.get<std::string>().empty()) throw KeyError{key, "must be a file name"};
  const std::filesystem::path p(v.get<std::string>());
  return (p.is_absolute() ? p : std::filesystem::path(baseDir) / p).lexically_normal().string();
}

int integer(const json& object, const std::string& key) {
  const json& v = object.at(key);
  if (!v.is_number_integer()) throw KeyError{key, "must be a whole number"};
  // get<int>() would wrap a larger number silently (4294967396 became a resolution of 100).
  const bool fits = v.is_number_unsigned()
                        ? v.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max())
                        : v.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                              v.get<std::int64_t>() <= std::numeric_limits<int>::max();
  if (!fits) throw KeyError{key, "is out of range (" + describeJsonValue(v) + ")"};
  return v.get<int>();
}

// "start_a": 0.25 | {"fraction": 0.25} | {"near": [x, y]}
StartPoint startPoint(const json& v, const std::string& key) {
  StartPoint s;
  if (v.is_number()) {
    s.fraction = v.get<double>();
  } else if (v.is_object() && v.size() == 1 && v.contains("fraction") &&
             v["fraction"].is_number()) {
    s.fraction = v["fraction"].get<double>();
  } else if (v.is_object() && v.size() == 1 && v.contains("near") && v["near"].is_array() &&
             v["near"].size() == 2 && v["near"][0].is_number() && v["near"][1].is_number()) {
    s.nearestToPoint = true;
    s.point = {v["near"][0].get<double>(), v["near"][1].get<double>()};
  } else {
    throw KeyError{key, "must be a fraction, {\"fraction\": f} or {\"near\": [x, y]}"};
  }
  return s;
}

void readSolver(const json& object, SolverOptions& options) {
  onlyKeys(object, {"max_iterations", "function_tolerance", "gradient_tolerance"}, "solver.");
  if (object.contains("max_iterations")) options.maxIterations = integer(object, "max_iterations");
  if (object.contains("function_tolerance"))
    options.functionTolerance = number(object, "function_tolerance", "solver.");
  if (object.contains("gradient_tolerance"))
    options.gradientTolerance = number(object, "gradient_tolerance", "solver.");
}

template <typename Weights>
void readWeights(const json& object, const TermTable<Weights>& table, Weights& weights) {
  std::set<std::string> allowed;
  for (const TermRow<Weights>& row : table) allowed.insert(row.name);
  onlyKeys(object, allowed, "weights.");
  for (const TermRow<Weights>& row : table)
    if (object.contains(row.name)) weights.*row.weight = number(object, row.name, "weights.");
}

Job parse(const json& root, const std::string& baseDir) {
  if (!root.is_object()) throw KeyError{"(top level)", "must be a JSON object"};
  if (!root.contains("mode") || !root["mode"].is_string())
    throw KeyError{"mode", "must be \"forward\" or \"inverse\""};
  const std::string mode = root["mode"].get<std::string>();
  Job job;
  if (mode == "forward") {
    onlyKeys(root,
             {"mode", "model", "piece_a", "piece_b", "join", "start_a", "start_b", "resolution",
              "interior_edge", "flip", "fit_perimeter", "perimeter_tolerance", "weights", "solver"},
             "");
    ForwardJob& f = job.forward;
    f.pieceA = path(root, "piece_a", baseDir);
    f.pieceB = path(root, "piece_b", baseDir);
    if (root.contains("join") &&
        !(root["join"].is_string() && parseJoin(root["join"].get<std::string>(), f.joinA, f.joinB)))
      throw KeyError{
          "join", "must be \"outer,outer\", \"inner,inner\", \"outer,inner\" or \"inner,outer\""};
    f.weights = defaultWeights(f.joinA, f.joinB);
    if (root.contains("model") &&
        !(root["model"].is_string() && parseModelChoice(root["model"].get<std::string>(), f.model)))
      throw KeyError{"model", "must be \"auto\", \"exact\", \"ruled\", \"paper\" or \"general\""};
    if (root.contains("start_a")) f.startA = startPoint(root["start_a"], "start_a");
    if (root.contains("start_b")) f.startB = startPoint(root["start_b"], "start_b");
    if (root.contains("resolution")) f.resolution = integer(root, "resolution");
    if (root.contains("interior_edge")) f.interiorEdgeFactor = number(root, "interior_edge", "");
    if (root.contains("flip")) f.flip = flag(root, "flip");
    if (root.contains("fit_perimeter")) f.fitPerimeter = flag(root, "fit_perimeter");
    if (root.contains("perimeter_tolerance"))
      f.perimeterTolerance = number(root, "perimeter_tolerance", "");
    if (root.contains("weights")) readWeights(root["weights"], forwardTerms(), f.weights);
    if (root.contains("solver")) readSolver(root["solver"], f.solver);
  } else if (mode == "inverse") {
    job.mode = Job::Mode::Inverse;
    onlyKeys(root, {"mode", "curve", "closed", "resolution", "weights", "solver"}, "");
    InverseJob& i = job.inverse;
    i.curve = path(root, "curve", baseDir);
    if (root.contains("closed")) i.forceClosed = flag(root, "closed");
    if (root.contains("resolution")) i.resolution = integer(root, "resolution");
    if (root.contains("weights")) readWeights(root["weights"], inverseTerms(), i.weights);
    if (root.contains("solver")) readSolver(root["solver"], i.solver);
  } else {
    throw KeyError{"mode", "must be \"forward\" or \"inverse\", not \"" + printable(mode) + "\""};
  }
  return job;
}

json startJson(const StartPoint& s) {
  if (s.nearestToPoint) return json{{"near", {s.point.x(), s.point.y()}}};
  return s.fraction;
}

json solverJson(const SolverOptions& o) {
  return {{"max_iterations", o.maxIterations},
          {"function_tolerance", o.functionTolerance},
          {"gradient_tolerance", o.gradientTolerance}};
}

template <typename Weights>
json weightsJson(const TermTable<Weights>& table, const Weights& weights) {
  json out = json::object();
  for (const TermRow<Weights>& row : table) out[row.name] = weights.*row.weight;
  return out;
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
    Job job = parse(root, baseDir);
    const Status valid = job.mode == Job::Mode::Forward ? validateForwardJob(job.forward)
                                                        : validateInverseJob(job.inverse);
    if (!valid.isOk()) return Status(ErrorCode::InputInvalid, source + ": " + valid.message());
    return job;
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

bool setNamedWeight(Job& job, const std::string& name, double value) {
  const auto set = [&name, value](const auto& table, auto& weights) {
    const auto* row = findTerm(table, name);
    if (row) weights.*row->weight = value;
    return row != nullptr;
  };
  return job.mode == Job::Mode::Forward ? set(forwardTerms(), job.forward.weights)
                                        : set(inverseTerms(), job.inverse.weights);
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
  json out;
  if (job.mode == Job::Mode::Forward) {
    const ForwardJob& f = job.forward;
    out = {{"mode", "forward"},
           {"model", modelChoiceName(f.model)},
           {"piece_a", recordedInput(f.pieceA)},
           {"piece_b", recordedInput(f.pieceB)},
           {"join", std::string(joinedBoundaryName(f.joinA)) + "," + joinedBoundaryName(f.joinB)},
           {"start_a", startJson(f.startA)},
           {"start_b", startJson(f.startB)},
           {"resolution", f.resolution},
           {"interior_edge", f.interiorEdgeFactor},
           {"flip", f.flip},
           {"fit_perimeter", f.fitPerimeter},
           {"perimeter_tolerance", f.perimeterTolerance},
           {"weights", weightsJson(forwardTerms(), f.weights)},
           {"solver", solverJson(f.solver)}};
  } else {
    const InverseJob& i = job.inverse;
    out = {{"mode", "inverse"},
           {"curve", recordedInput(i.curve)},
           {"closed", i.forceClosed},
           {"resolution", i.resolution},
           {"weights", weightsJson(inverseTerms(), i.weights)},
           {"solver", solverJson(i.solver)}};
  }
  return out.dump(2, ' ', false, json::error_handler_t::replace);
}

}  // namespace dform
