// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/sweep.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <new>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "dform/core/atomic_file.h"
#include "dform/core/input_file.h"
#include "dform/core/message_text.h"
#include "dform/core/result_folder.h"
#include "dform/io/model_files.h"
#include "dform/report/views.h"
#include "dform/validate/metrics.h"
#include "json_values.h"
#include "run_steps.h"

namespace dform {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// Signed volume enclosed by the triangles of a piece's 3D shape, as cones from `apex`.
double coneVolume(const Piece& piece, const Eigen::Vector3d& apex) {
  double volume = 0;
  for (int f = 0; f < piece.F.rows(); ++f) {
    const Eigen::Vector3d a = piece.shape.row(piece.F(f, 0)).transpose() - apex;
    const Eigen::Vector3d b = piece.shape.row(piece.F(f, 1)).transpose() - apex;
    const Eigen::Vector3d c = piece.shape.row(piece.F(f, 2)).transpose() - apex;
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

double maxAbs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

}  // namespace

Status runGuarded(const std::function<Status()>& run) {
  try {
    return run();
  } catch (const std::bad_alloc&) {
    return Status(ErrorCode::Usage,
                  "out of memory (the machine or its limits give this run less "
                  "than it needs); try a lower resolution");
  } catch (const std::exception& e) {
    return Status(ErrorCode::Internal, std::string("internal error: ") + printable(e.what(), 200));
  } catch (...) {
    return Status(ErrorCode::Internal, "internal error");
  }
}

std::vector<SweepStart> sweepStarts(const Job& base, const SweepOptions& options) {
  std::vector<SweepStart> starts;
  const int width = int(std::to_string(std::max(options.starts - 1, 0)).size());
  for (const bool flip : {false, true}) {
    if (flip && !options.bothFlips) break;
    for (int k = 0; k < options.starts; ++k) {
      SweepStart s;
      s.job = base;
      s.startB = double(k) / options.starts;
      ForwardJob& forward = std::get<ForwardJob>(s.job.run);
      s.flip = options.bothFlips ? flip : forward.flip;
      forward.startB = StartPoint{};
      forward.startB.fraction = s.startB;
      forward.flip = s.flip;
      char name[32];
      std::snprintf(name, sizeof name, "start-%0*d%s", width, k, s.flip ? "-flip" : "");
      s.subfolder = name;
      starts.push_back(std::move(s));
    }
  }
  return starts;
}

SweepRow measureResult(const std::string& dir) {
  SweepRow row;
  std::ifstream in(fs::path(dir) / "report.json");
  const json report = json::parse(in, nullptr, false);
  Result<DForm> model = readModel(dir);
  if (!report.is_object() || !model.isOk()) {
    row.reason =
        model.isOk() ? dir + "/report.json: missing or not JSON" : model.status().message();
    return row;
  }
  row.solved = true;
  const DForm& m = model.value();
  row.model = report.value("/model/name"_json_pointer, std::string());
  const Eigen::Vector3d apex =
      (m.a.shape.colwise().mean() + m.b.shape.colwise().mean()).transpose() / 2;
  row.volumeMm3 = coneVolume(m.a, apex) + coneVolume(m.b, apex);
  const double zMax = std::max(m.a.shape.col(2).maxCoeff(), m.b.shape.col(2).maxCoeff());
  const double zMin = std::min(m.a.shape.col(2).minCoeff(), m.b.shape.col(2).minCoeff());
  row.heightMm = zMax - zMin;
  row.maxCurvature = std::max(maxAbs(curvatureMap(m.a)), maxAbs(curvatureMap(m.b)));
  row.seconds = report.value("/timings/total"_json_pointer, 0.0);
  const json gate = report.value("gate", json(nullptr));
  if (gate.is_object()) {
    row.passed = gate.value("passed", false);
    for (const json& check : gate.value("checks", json::array()))
      if (check.value("verdict", std::string()) == "fail") {
        row.failing.push_back(check.value("name", std::string()));
        row.reason += (row.reason.empty() ? "" : "; ") + check.value("name", std::string()) + ": " +
                      check.value("detail", std::string());
      }
    if (!row.passed && row.reason.empty()) row.reason = "the gate did not pass";
  } else {
    row.reason = "no gate was run";
  }
  View camera;  // one camera for every card, so that the shapes compare
  camera.widthPx = 240;
  row.svg = shapeSvg(m, camera);
  return row;
}

void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& work,
                 const std::atomic<bool>& stop) {
  std::atomic<std::size_t> next{0};
  // An exception that escaped a worker thread would end the process (std::terminate, exit 134)
  // with the folders' locks and staging left behind: the first is kept, the pool stops handing
  // out work, and it is thrown again here once every thread has joined.
  std::exception_ptr failure;
  std::mutex failureMutex;
  std::atomic<bool> failed{false};
  const auto worker = [&] {
    try {
      for (std::size_t k; !stop && !failed && (k = next++) < count;) work(k);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
      failed = true;
    }
  };
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t n = std::min<std::size_t>(threads > 0 ? std::size_t(threads) : cores, count);
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

Result<std::vector<SweepRow>> runSweep(const Job& base, const SweepOptions& options,
                                       const std::string& outDir, const SweepRunner& run,
                                       const SweepProgress& progress,
                                       const std::atomic<bool>& interrupted, MessageSink* notes) {
  const std::vector<SweepStart> starts = sweepStarts(base, options);
  ResultFolder folder;
  // An earlier sweep in the folder is replaced whole, its start folders with it.
  const auto isStartFolder = [](const std::string& name) {
    int k = 0, used = 0;
    return std::sscanf(name.c_str(), "start-%d%n", &k, &used) == 1 &&
           (name.size() == std::size_t(used) || name.substr(used) == "-flip");
  };
  if (Status s = folder.begin(outDir, {"sweep.json", "gallery.html"}, isStartFolder); !s.isOk())
    return s;
  // Each earlier start folder, and each this sweep makes, is locked as a run locks its folder,
  // and refused as a run refuses it when it holds anything but a result's files: it goes with
  // the swap, and a run or an export into it meanwhile would be swapped away with it.
  std::vector<std::unique_ptr<ResultFolder>> heldStarts;
  std::error_code ec;
  std::set<std::string> startNames;
  for (const fs::directory_entry& entry : fs::directory_iterator(outDir, ec))
    if (isStartFolder(entry.path().filename().string()))
      startNames.insert(entry.path().filename().string());
  if (fs::is_directory(outDir, ec))
    for (const SweepStart& start : starts) startNames.insert(start.subfolder);
  for (const std::string& name : startNames) {
    heldStarts.push_back(std::make_unique<ResultFolder>());
    if (Status s = heldStarts.back()->hold((fs::path(outDir) / name).string(), resultFileNames());
        !s.isOk())
      return s;
  }
  const auto begun = Clock::now();
  std::vector<SweepRow> rows(starts.size());
  std::vector<Status> outcomes(starts.size());
  std::mutex mutex;
  int done = 0, failed = 0;
  const auto work = [&](std::size_t k) {
    const SweepStart& start = starts[k];
    const std::string dir = (fs::path(folder.staging()) / start.subfolder).string();
    const auto jobBegun = Clock::now();
    MessageSink sink;  // each job its own: its messages go into its report.json
    const Status status = runGuarded([&] { return run(start.job, dir, sink); });
    // A result whose export failed is saved all the same: measured, and failed with why.
    SweepRow row = fs::exists(fs::path(dir) / "report.json") ? measureResult(dir) : SweepRow{};
    if (!status.isOk()) {
      row.error = status.code();
      row.passed = false;
      row.reason = folder.named(status).message() + (row.reason.empty() ? "" : "; " + row.reason);
    }
    row.startB = start.startB;
    row.flip = start.flip;
    row.subfolder = start.subfolder;
    char label[48];
    std::snprintf(label, sizeof label, "start B %.4f%s", start.startB,
                  start.flip ? " flipped" : "");
    row.label = label;
    if (!row.solved) row.seconds = std::chrono::duration<double>(Clock::now() - jobBegun).count();
    const std::lock_guard<std::mutex> lock(mutex);
    ++done;
    if (!row.solved || !row.passed) ++failed;
    rows[k] = std::move(row);
    outcomes[k] = status;
    if (progress)
      progress(done, failed, int(starts.size()),
               std::chrono::duration<double>(Clock::now() - begun).count());
  };
  parallelFor(starts.size(), options.threads, work, interrupted);
  if (interrupted)
    return Status(ErrorCode::Interrupted, outDir + ": interrupted; the folder was left as it was");
  // A sweep that solved no start made nothing to keep: it fails as its first start failed (an
  // input every start shares, unequal perimeters say, with the code a single run gives it), and
  // the folder keeps what it held, no folder made for it.
  if (std::none_of(rows.begin(), rows.end(), [](const SweepRow& r) { return r.solved; })) {
    const Status& first = outcomes.at(0);
    return Status(first.isOk() ? ErrorCode::SolveFailed : first.code(),
                  outDir + ": no start was solved (first: " + rows.at(0).reason + ")");
  }
  for (const auto& [name, text] :
       {std::pair<const char*, std::string>{"sweep.json", sweepJson(base, options, rows)},
        {"gallery.html",
         galleryHtml("D-Form sweep: " + fs::path(inputName(base.inputs()[0])).filename().string() +
                         " + " + fs::path(inputName(base.inputs()[1])).filename().string(),
                     rows)}})
    if (Status s = writeFileAtomically((fs::path(folder.staging()) / name).string(), text);
        !s.isOk())
      return folder.named(s);
  if (Status s = folder.commit(notes); !s.isOk()) return s;
  return rows;
}

Status unwrittenStarts(const std::string& outDir, const std::vector<SweepRow>& rows) {
  constexpr int kNamed = 8;
  std::string names, first;
  int count = 0;
  for (const SweepRow& r : rows) {
    if (r.error != ErrorCode::OutputFailed) continue;
    if (++count <= kNamed) names += (names.empty() ? "" : ", ") + r.subfolder;
    if (first.empty()) first = printable(r.reason, 200);
  }
  if (count == 0) return Status::ok();
  if (count > kNamed) names += " and " + std::to_string(count - kNamed) + " more";
  return {ErrorCode::OutputFailed, outDir + ": " + std::to_string(count) + " of " +
                                       std::to_string(rows.size()) + " starts were not written (" +
                                       names + "; first: " + first + ")"};
}

std::string sweepJson(const Job& base, const SweepOptions& options,
                      const std::vector<SweepRow>& rows) {
  json out = {{"schema", "dform-sweep"},
              {"schema_version", 1},
              {"job", json::parse(jobToJson(base))},
              {"starts", options.starts},
              {"flip", options.bothFlips                     ? "both"
                       : std::get<ForwardJob>(base.run).flip ? "flipped"
                                                             : "as drawn"}};
  json list = json::array();
  for (const SweepRow& r : rows)
    list.push_back({{"start_b", r.startB},
                    {"flip", r.flip},
                    {"subfolder", r.subfolder},
                    {"solved", r.solved},
                    {"model", r.model},
                    {"height_mm", numberOrNull(r.heightMm)},
                    {"volume_mm3", numberOrNull(r.volumeMm3)},
                    {"max_curvature", numberOrNull(r.maxCurvature)},
                    {"gate_passed", r.passed},
                    {"failing_checks", r.failing},
                    {"reason", r.reason},
                    {"seconds", numberOrNull(r.seconds)}});
  out["rows"] = list;
  return out.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace dform
