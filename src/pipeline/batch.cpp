#include "pipeline/batch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "io/json_util.h"

namespace dform {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using io_detail::numberOrNull;
using Clock = std::chrono::steady_clock;

double number(const json& row, const char* key) {
  const auto at = row.find(key);
  return at != row.end() && at->is_number() ? at->get<double>() : NAN;
}

json rowJson(const BatchRow& r) {
  const SweepRow& f = r.figures;
  return {{"index", r.job.index},
          {"job", r.job.path},
          {"name", r.job.name},
          {"status", r.status},
          {"exit_code", r.exitCode},
          {"message", r.message},
          {"model", f.model},
          {"height_mm", f.solved ? numberOrNull(f.heightMm) : json(nullptr)},
          {"volume_mm3", f.solved ? numberOrNull(f.volumeMm3) : json(nullptr)},
          {"max_curvature", f.solved ? numberOrNull(f.maxCurvature) : json(nullptr)},
          {"gate_passed", f.passed},
          {"failing_checks", f.failing},
          {"seconds", numberOrNull(r.seconds)}};
}

// A manifest's row back; false when it is not one.
bool rowFromJson(const json& j, BatchRow& r) {
  if (!j.is_object() || !j.contains("index") || !j["index"].is_number_integer() ||
      !j.contains("job") || !j["job"].is_string() || !j.contains("name") ||
      !j["name"].is_string() || !j.contains("status") || !j["status"].is_string())
    return false;
  r.job.index = j["index"].get<int>();
  r.job.path = j["job"].get<std::string>();
  r.job.name = j["name"].get<std::string>();
  r.status = j["status"].get<std::string>();
  r.exitCode = j.value("exit_code", 1);
  r.message = j.value("message", std::string());
  SweepRow& f = r.figures;
  f.subfolder = f.label = r.job.name;
  f.model = j.value("model", std::string());
  f.heightMm = number(j, "height_mm");
  f.volumeMm3 = number(j, "volume_mm3");
  f.maxCurvature = number(j, "max_curvature");
  f.solved = std::isfinite(f.heightMm);
  f.passed = j.value("gate_passed", false);
  if (j.contains("failing_checks") && j["failing_checks"].is_array())
    for (const json& name : j["failing_checks"])
      if (name.is_string()) f.failing.push_back(name.get<std::string>());
  f.reason = r.message;
  r.seconds = number(j, "seconds");
  f.seconds = r.seconds;
  return true;
}

std::string manifestText(const std::vector<BatchRow>& rows, const BatchOptions& options,
                         bool merged) {
  json list = json::array();
  for (const BatchRow& r : rows) list.push_back(rowJson(r));
  json out = {{"schema", "dform-batch"}, {"schema_version", 1}};
  if (merged)
    out["merged"] = true;
  else
    out["shard"] = {options.shard, options.shards};
  out["rows"] = list;
  return out.dump(2) + "\n";
}

// The rows of one manifest file; InputInvalid naming it when it is not one.
Result<std::vector<BatchRow>> readManifest(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return Status(ErrorCode::InputUnreadable, path.string() + ": cannot be read");
  const json manifest = json::parse(in, nullptr, false);
  if (!manifest.is_object() || manifest.value("schema", std::string()) != "dform-batch" ||
      !manifest.contains("rows") || !manifest["rows"].is_array())
    return Status(ErrorCode::InputInvalid, path.string() + ": is not a dform batch manifest");
  std::vector<BatchRow> rows;
  for (const json& j : manifest["rows"]) {
    BatchRow r;
    if (!rowFromJson(j, r))
      return Status(ErrorCode::InputInvalid, path.string() + ": a row is not a batch job's");
    rows.push_back(std::move(r));
  }
  return rows;
}

bool isManifestName(const std::string& name) {
  int i = 0, n = 0;
  char rest = 0;
  return name == "batch.json" ||
         std::sscanf(name.c_str(), "batch-shard-%d-of-%d.json%c", &i, &n, &rest) == 2;
}

std::vector<SweepRow> galleryRows(const std::vector<BatchRow>& rows) {
  std::vector<SweepRow> cards;
  for (const BatchRow& r : rows) cards.push_back(r.figures);
  return cards;
}

// The gallery of `rows` as OUT/<fileName>, each card drawn from its saved result (the manifests
// keep the figures, not the drawings).
Status writeGallery(const std::string& outDir, const std::vector<BatchRow>& rows,
                    const std::string& fileName) {
  std::vector<SweepRow> cards = galleryRows(rows);
  for (SweepRow& card : cards)
    if (card.solved) {
      const SweepRow measured = measureResult((fs::path(outDir) / card.subfolder).string());
      card.svg = measured.svg;
      if (!card.passed && card.reason.empty()) card.reason = measured.reason;
    }
  return writeFileAtomically((fs::path(outDir) / fileName).string(),
                             galleryHtml("dform batch: " + outDir, cards));
}

}  // namespace

Result<std::vector<BatchJob>> listBatchJobs(const std::string& input) {
  std::vector<BatchJob> jobs;
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    std::vector<std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(input, ec))
      if (entry.path().extension() == ".json" && entry.is_regular_file(ec))
        files.push_back(entry.path().string());
    if (ec) return Status(ErrorCode::InputUnreadable, input + ": cannot be read (" + ec.message() + ")");
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) jobs.push_back({0, f, ""});
  } else {
    std::ifstream in(input);
    if (!in) return Status(ErrorCode::InputUnreadable, input + ": no such job list or folder");
    const fs::path base = fs::path(input).parent_path();
    std::string line;
    while (std::getline(in, line)) {
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      const auto last = line.find_last_not_of(" \t\r");
      const fs::path path = line.substr(first, last - first + 1);
      jobs.push_back({0, (path.is_absolute() ? path : base / path).string(), ""});
    }
  }
  if (jobs.empty()) return Status(ErrorCode::InputInvalid, input + ": lists no job files");
  std::map<std::string, std::string> byName;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    jobs[k].index = int(k);
    jobs[k].name = fs::path(jobs[k].path).stem().string();
    const auto [at, inserted] = byName.emplace(jobs[k].name, jobs[k].path);
    if (!inserted)
      return Status(ErrorCode::InputInvalid, input + ": " + at->second + " and " + jobs[k].path +
                                                 " would both write " + jobs[k].name + "/");
  }
  return jobs;
}

std::vector<BatchJob> shardOf(const std::vector<BatchJob>& jobs, int shard, int shards) {
  std::vector<BatchJob> slice;
  for (const BatchJob& job : jobs)
    if (job.index % shards + 1 == shard) slice.push_back(job);
  return slice;
}

bool parseShard(const std::string& text, int& shard, int& shards) {
  char rest = 0;
  return std::sscanf(text.c_str(), "%d/%d%c", &shard, &shards, &rest) == 2 && shards >= 1 &&
         shard >= 1 && shard <= shards;
}

std::string manifestName(const BatchOptions& options) {
  return options.shards == 1 ? "batch.json"
                             : "batch-shard-" + std::to_string(options.shard) + "-of-" +
                                   std::to_string(options.shards) + ".json";
}

std::string galleryName(const BatchOptions& options) {
  return options.shards == 1 ? "gallery.html"
                             : "gallery-shard-" + std::to_string(options.shard) + "-of-" +
                                   std::to_string(options.shards) + ".html";
}

Result<std::vector<BatchRow>> runBatch(const std::vector<BatchJob>& jobs,
                                       const BatchOptions& options, const std::string& outDir,
                                       const BatchRunner& run, const SweepProgress& progress,
                                       const std::atomic<bool>& interrupted) {
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (!fs::is_directory(outDir))
    return Status(ErrorCode::OutputFailed, outDir + ": cannot create the folder (" + ec.message() + ")");
  const fs::path manifest = fs::path(outDir) / manifestName(options);
  const std::vector<BatchJob> slice = shardOf(jobs, options.shard, options.shards);
  // Resumed: a job the manifest has as finished, with its result still in place, is kept.
  std::map<int, BatchRow> kept;
  if (options.resume && fs::exists(manifest)) {
    Result<std::vector<BatchRow>> earlier = readManifest(manifest);
    if (!earlier.isOk()) return earlier.status();
    for (const BatchRow& r : earlier.value())
      if (r.status != "failed" && fs::exists(fs::path(outDir) / r.job.name / "report.json"))
        kept[r.job.index] = r;
  }
  std::vector<BatchRow> rows;
  std::vector<BatchJob> pending;
  for (const BatchJob& job : slice) {
    const auto at = kept.find(job.index);
    if (at != kept.end() && at->second.job.path == job.path)
      rows.push_back(at->second);
    else
      pending.push_back(job);
  }
  std::mutex mutex;
  Status written = writeFileAtomically(manifest.string(), manifestText(rows, options, false));
  if (!written.isOk()) return written;
  const auto begun = Clock::now();
  int done = 0, failed = 0;
  parallelFor(
      pending.size(), options.threads,
      [&](std::size_t k) {
        const BatchJob& job = pending[k];
        const std::string dir = (fs::path(outDir) / job.name).string();
        const auto jobBegun = Clock::now();
        const JobOutcome outcome = run(job.path, dir);
        // An interrupted job is not finished: no row, so that a resumed batch runs it.
        if (interrupted) return;
        BatchRow row;
        row.job = job;
        row.exitCode = outcome.exitCode;
        row.message = outcome.message;
        const bool saved = (outcome.exitCode == 0 || outcome.exitCode == 7) &&
                           fs::exists(fs::path(dir) / "report.json");
        if (saved) row.figures = measureResult(dir);
        row.figures.svg.clear();  // the manifest keeps figures; the gallery draws from results
        row.figures.subfolder = row.figures.label = job.name;
        if (!outcome.message.empty()) row.figures.reason = outcome.message;
        if (row.message.empty()) row.message = row.figures.reason;  // a failed gate's checks
        row.status = !saved ? "failed" : outcome.exitCode == 0 ? "done" : "gate failed";
        row.seconds = std::chrono::duration<double>(Clock::now() - jobBegun).count();
        row.figures.seconds = row.seconds;
        const std::lock_guard<std::mutex> lock(mutex);
        rows.push_back(std::move(row));
        std::sort(rows.begin(), rows.end(),
                  [](const BatchRow& a, const BatchRow& b) { return a.job.index < b.job.index; });
        ++done;
        failed += outcome.exitCode != 0;
        if (written.isOk())
          written = writeFileAtomically(manifest.string(), manifestText(rows, options, false));
        if (progress)
          progress(done, failed, int(pending.size()),
                   std::chrono::duration<double>(Clock::now() - begun).count());
      },
      interrupted);
  if (!written.isOk()) return written;
  if (interrupted)
    return Status(ErrorCode::Interrupted,
                  outDir + ": interrupted; " + manifest.filename().string() +
                      " lists the finished jobs (--resume runs the rest)");
  if (Status s = writeGallery(outDir, rows, galleryName(options)); !s.isOk()) return s;
  return rows;
}

Result<std::vector<BatchRow>> mergeBatch(const std::string& outDir) {
  std::vector<fs::path> manifests;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(outDir, ec))
    if (isManifestName(entry.path().filename().string())) manifests.push_back(entry.path());
  if (manifests.empty())
    return Status(ErrorCode::InputUnreadable, outDir + ": holds no batch manifest (batch.json or "
                                                       "batch-shard-I-of-N.json)");
  // Oldest first, so that a job in several manifests keeps its latest row.
  std::sort(manifests.begin(), manifests.end(), [](const fs::path& a, const fs::path& b) {
    return fs::last_write_time(a) < fs::last_write_time(b);
  });
  std::map<int, BatchRow> byIndex;
  for (const fs::path& path : manifests) {
    Result<std::vector<BatchRow>> rows = readManifest(path);
    if (!rows.isOk()) return rows.status();
    for (BatchRow& r : rows.value()) byIndex[r.job.index] = std::move(r);
  }
  std::vector<BatchRow> rows;
  for (auto& [index, row] : byIndex) rows.push_back(std::move(row));
  const fs::path base = fs::path(outDir);
  if (Status s = writeFileAtomically((base / "batch.json").string(), manifestText(rows, {}, true));
      !s.isOk())
    return s;
  if (Status s = writeGallery(outDir, rows, "gallery.html"); !s.isOk()) return s;
  return rows;
}

}  // namespace dform
