// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/pipeline/batch.h"

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

#include "dform/core/atomic_file.h"
#include "dform/core/file_hash.h"
#include "dform/core/input_file.h"
#include "dform/core/lock_file.h"
#include "dform/core/message_text.h"
#include "dform/pipeline/exit_code.h"
#include "dform/pipeline/job_file.h"
#include "json_values.h"

namespace dform {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

double number(const json& row, const char* key) {
  const auto at = row.find(key);
  return at != row.end() && at->is_number() ? at->get<double>() : NAN;
}

// A manifest's field of the expected type, else `otherwise` (a hand-edited manifest).
std::string text(const json& row, const char* key) {
  const auto at = row.find(key);
  return at != row.end() && at->is_string() ? at->get<std::string>() : std::string();
}
bool flag(const json& row, const char* key) {
  const auto at = row.find(key);
  return at != row.end() && at->is_boolean() && at->get<bool>();
}

json rowJson(const BatchRow& r) {
  const SweepRow& f = r.figures;
  return {{"index", r.job.index},
          {"job", utf8Text(r.job.path)},
          {"name", utf8Text(r.job.name)},
          {"sha256", r.job.sha256},
          {"status", r.status},
          {"exit_code", r.exitCode},
          {"message", printableMessage(r.message)},
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
  r.job.sha256 = text(j, "sha256");
  r.status = j["status"].get<std::string>();
  if (r.status == "gate failed") r.status = "gate-failed";  // a manifest of schema version 2
  const auto code = j.find("exit_code");
  r.exitCode = code != j.end() && code->is_number_integer() ? code->get<int>() : 1;
  r.message = text(j, "message");
  SweepRow& f = r.figures;
  f.label = r.job.name;
  f.subfolder = isJobName(r.job.name) ? r.job.name : "";  // a forged row links nowhere
  f.model = text(j, "model");
  f.heightMm = number(j, "height_mm");
  f.volumeMm3 = number(j, "volume_mm3");
  f.maxCurvature = number(j, "max_curvature");
  f.solved = std::isfinite(f.heightMm);
  f.passed = flag(j, "gate_passed");
  if (j.contains("failing_checks") && j["failing_checks"].is_array())
    for (const json& name : j["failing_checks"])
      if (name.is_string()) f.failing.push_back(name.get<std::string>());
  f.reason = r.message;
  r.seconds = number(j, "seconds");
  f.seconds = r.seconds;
  return true;
}

// The jobs a manifest was to run, by their place in the list: their names, so that a merge can
// name the jobs that did not finish.
using ListedJobs = std::map<int, std::string>;

ListedJobs listedJobs(const std::vector<BatchJob>& jobs) {
  ListedJobs listed;
  for (const BatchJob& job : jobs) listed[job.index] = job.name;
  return listed;
}

std::string manifestText(const std::vector<BatchRow>& rows, const BatchOptions& options,
                         const JobList& jobs, const ListedJobs& listed, bool merged) {
  json list = json::array();
  for (const BatchRow& r : rows) list.push_back(rowJson(r));
  json slice = json::array();
  for (const auto& [index, name] : listed) slice.push_back({index, utf8Text(name)});
  json out = {{"schema", "dform-batch"},
              {"schema_version", 3},
              {"jobs", {{"count", jobs.count}, {"sha256", jobs.sha256}}}};
  if (merged)
    out["merged"] = true;
  else
    out["shard"] = {options.shard, options.shards};
  out["slice"] = slice;
  out["rows"] = list;
  return out.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

// One manifest: its rows and the job list it was run from (empty for a manifest that does not
// record it).
struct Manifest {
  std::vector<BatchRow> rows;
  JobList jobs;
  ListedJobs listed;  ///< empty for a manifest that does not record its slice
};

// The rows of one manifest file; InputInvalid naming it when it is not one.
Result<Manifest> readManifest(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return Status(ErrorCode::InputUnreadable, path.string() + ": cannot be read");
  const json manifest = json::parse(in, nullptr, false);
  if (!manifest.is_object() || text(manifest, "schema") != "dform-batch" ||
      !manifest.contains("rows") || !manifest["rows"].is_array())
    return Status(ErrorCode::InputInvalid, path.string() + ": is not a dform batch manifest");
  Manifest read;
  for (const json& j : manifest["rows"]) {
    BatchRow r;
    if (!rowFromJson(j, r))
      return Status(ErrorCode::InputInvalid, path.string() + ": a row is not a batch job's");
    read.rows.push_back(std::move(r));
  }
  const auto jobs = manifest.find("jobs");
  if (jobs != manifest.end() && jobs->is_object() && jobs->contains("count") &&
      (*jobs)["count"].is_number_integer() && jobs->contains("sha256") &&
      (*jobs)["sha256"].is_string()) {
    read.jobs.count = (*jobs)["count"].get<int>();
    read.jobs.sha256 = (*jobs)["sha256"].get<std::string>();
  }
  const auto slice = manifest.find("slice");
  if (slice != manifest.end() && slice->is_array())
    for (const json& entry : *slice)
      if (entry.is_array() && entry.size() == 2 && entry[0].is_number_integer() &&
          entry[1].is_string())
        read.listed[entry[0].get<int>()] = entry[1].get<std::string>();
  return read;
}

// "PREFIX<digits>-of-<digits>SUFFIX": a shard's manifest or gallery.
bool isShardFileName(const std::string& name, const std::string& prefix,
                     const std::string& suffix) {
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string middle =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  const std::size_t of = middle.find("-of-");
  const auto digits = [](const std::string& t) {
    return !t.empty() && t.find_first_not_of("0123456789") == std::string::npos;
  };
  return of != std::string::npos && digits(middle.substr(0, of)) && digits(middle.substr(of + 4));
}

bool isManifestName(const std::string& name) {
  return name == "batch.json" || isShardFileName(name, "batch-shard-", ".json");
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
  for (SweepRow& card : cards) {
    // A card links only to a job's folder in OUT that holds a result.
    std::error_code ec;
    if (!isJobName(card.subfolder) ||
        !fs::is_regular_file(fs::path(outDir) / card.subfolder / "report.json", ec)) {
      card.subfolder.clear();
      card.solved = false;
    }
    if (card.solved) {
      const SweepRow measured = measureResult((fs::path(outDir) / card.subfolder).string());
      card.svg = measured.svg;
      if (!card.passed && card.reason.empty()) card.reason = measured.reason;
    }
  }
  return writeFileAtomically((fs::path(outDir) / fileName).string(),
                             galleryHtml("dform batch: " + outDir, cards));
}

// The lock that keeps a second batch off OUT: exclusive for a whole batch and for a merge,
// shared by the shards of one batch, which take their own manifest's lock exclusively besides.
struct BatchLock {
  LockFile batch, manifest;
  Status acquire(const std::string& outDir, const BatchOptions& options, bool merging) {
    const bool alone = merging || options.shards == 1;
    if (Status s = batch.acquire((fs::path(outDir) / ".dform-batch.lock").string(), alone, outDir,
                                 "batch");
        !s.isOk())
      return s;
    if (alone) return Status::ok();
    return manifest.acquire(
        (fs::path(outDir) / ("." + manifestName(options) + ".dform-lock")).string(), true, outDir,
        "batch shard " + std::to_string(options.shard) + "/" + std::to_string(options.shards));
  }
};

}  // namespace

bool isJobName(const std::string& name) {
  return !name.empty() && name.size() <= 255 && name[0] != '.' &&
         name.find('/') == std::string::npos && name.find('\0') == std::string::npos &&
         !isManifestName(name) && name != "gallery.html" &&
         !isShardFileName(name, "gallery-shard-", ".html");
}

JobFacts readJobFacts(const std::string& jobPath) {
  JobFacts facts;
  const Result<std::string> bytes = readInputFile(jobPath, kMaxSettingsBytes);
  if (!bytes.isOk()) return facts;
  std::string hashes = sha256Hex(bytes.value());
  const Result<Job> job = parseJobFileText(bytes.value(), jobPath);
  if (job.isOk()) {
    for (const std::string& input : job.value().inputs()) {
      const Result<std::string> read = readInputFile(input);
      hashes += " " + (read.isOk() ? sha256Hex(read.value()) : std::string("missing"));
    }
    const double resolution = job.value().resolution();
    facts.size = resolution * resolution;
  }
  facts.sha256 = sha256Hex(hashes);
  return facts;
}

double estimateSecondsLeft(double elapsed, double doneSize, double remainingSize) {
  if (!(doneSize > 0) || !(elapsed >= 0) || !(remainingSize >= 0)) return NAN;
  return elapsed * remainingSize / doneSize;
}

std::string missingText(const MergedBatch& merged) {
  std::string text;
  for (std::size_t k = 0; k < merged.firstMissing.size(); ++k)
    text += (k ? ", " : "") + printable(merged.firstMissing[k], 60);
  const int more = merged.missingCount - int(merged.firstMissing.size());
  if (more > 0) text += " and " + std::to_string(more) + " more";
  return text;
}

JobList jobListOf(const std::vector<BatchJob>& jobs) {
  std::string all;
  for (const BatchJob& job : jobs) all += sha256Hex(job.name) + " " + job.sha256 + "\n";
  return {int(jobs.size()), sha256Hex(all)};
}

Result<std::vector<BatchJob>> listBatchJobs(const std::string& input) {
  std::vector<BatchJob> jobs;
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    std::vector<std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(input, ec))
      if (entry.path().extension() == ".json" && entry.is_regular_file(ec))
        files.push_back(entry.path().string());
    if (ec)
      return Status(ErrorCode::InputUnreadable, input + ": cannot be read (" + ec.message() + ")");
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) jobs.push_back({0, f, "", ""});
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
      jobs.push_back({0, (path.is_absolute() ? path : base / path).string(), "", ""});
    }
  }
  if (jobs.empty()) return Status(ErrorCode::InputInvalid, input + ": lists no job files");
  std::map<std::string, std::string> byName;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    jobs[k].index = int(k);
    jobs[k].name = fs::path(jobs[k].path).stem().string();
    if (!isJobName(jobs[k].name))
      return Status(ErrorCode::InputInvalid,
                    input + ": " + printable(jobs[k].path, 200) +
                        " cannot have its result in OUT/" + printable(jobs[k].name, 200) +
                        "/ (a hidden name, one longer than 255 bytes, or one of the "
                        "batch's own files: batch.json, gallery.html, their shards'); "
                        "nothing was run (rename the job file)");
    const auto [at, inserted] = byName.emplace(jobs[k].name, jobs[k].path);
    if (!inserted)
      return Status(ErrorCode::InputInvalid, input + ": " + printable(at->second, 200) + " and " +
                                                 printable(jobs[k].path, 200) +
                                                 " would both write " +
                                                 printable(jobs[k].name, 200) + "/");
  }
  for (BatchJob& job : jobs) {
    const JobFacts facts = readJobFacts(job.path);
    job.sha256 = facts.sha256;
    job.size = facts.size;
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
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  // Decimal digits only, at most 7 of them: no sign, no space, no overflow to wrap around.
  const auto number = [](const std::string& digits, int& value) {
    if (digits.empty() || digits.size() > 7 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    value = std::stoi(digits);
    return true;
  };
  int i = 0, n = 0;
  if (!number(text.substr(0, slash), i) || !number(text.substr(slash + 1), n) || n < 1 ||
      n > 1000000 || i < 1 || i > n)
    return false;
  shard = i;
  shards = n;
  return true;
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
                                       const BatchRunner& run, const BatchProgress& progress,
                                       const std::atomic<bool>& interrupted) {
  std::error_code ec, made;
  fs::create_directories(outDir, made);  // its error, not the check's: why the folder is missing
  if (!fs::is_directory(outDir, ec))
    return Status(ErrorCode::OutputFailed,
                  outDir + ": cannot create the folder (" + (made ? made : ec).message() + ")");
  BatchLock lock;
  if (Status s = lock.acquire(outDir, options, false); !s.isOk()) return s;
  const JobList list = jobListOf(jobs);
  const fs::path manifest = fs::path(outDir) / manifestName(options);
  const std::vector<BatchJob> slice = shardOf(jobs, options.shard, options.shards);
  const ListedJobs listed = listedJobs(slice);
  // Resumed: a job the manifest has as finished, made from the same job file and inputs as now,
  // with its result still in place, is kept.
  std::map<std::string, BatchRow> kept;
  if (options.resume && fs::exists(manifest, ec)) {
    Result<Manifest> earlier = readManifest(manifest);
    if (!earlier.isOk()) return earlier.status();
    for (const BatchRow& r : earlier.value().rows)
      if (r.status != "failed" && !r.job.sha256.empty() && isJobName(r.job.name) &&
          fs::exists(fs::path(outDir) / r.job.name / "report.json"))
        kept[r.job.name] = r;
  }
  std::vector<BatchRow> rows;
  std::vector<BatchJob> pending;
  for (const BatchJob& job : slice) {
    const auto at = kept.find(job.name);
    if (at != kept.end() && at->second.job.sha256 == job.sha256 && !job.sha256.empty()) {
      rows.push_back(at->second);
      rows.back().job = job;  // its place in this list
    } else {
      pending.push_back(job);
    }
  }
  std::mutex mutex;
  Status written =
      writeFileAtomically(manifest.string(), manifestText(rows, options, list, listed, false));
  if (!written.isOk()) return written;
  const auto begun = Clock::now();
  int done = 0, failed = 0;
  double doneSize = 0, remainingSize = 0;
  for (const BatchJob& job : pending) remainingSize += job.size;
  parallelFor(
      pending.size(), options.threads,
      [&](std::size_t k) {
        const BatchJob& job = pending[k];
        const std::string dir = (fs::path(outDir) / job.name).string();
        const auto jobBegun = Clock::now();
        JobOutcome outcome;
        const Status guarded = runGuarded([&] {
          outcome = run(job.path, dir);
          return Status::ok();
        });
        if (!guarded.isOk()) outcome = {exitCode(guarded.code()), guarded.message()};
        // An interrupted job is not finished: no row, so that a resumed batch runs it.
        if (interrupted) return;
        BatchRow row;
        row.job = job;
        row.exitCode = outcome.exitCode;
        row.message = outcome.message;
        const bool saved =
            (outcome.exitCode == 0 || outcome.exitCode == exitCode(ErrorCode::GateFailed)) &&
            fs::exists(fs::path(dir) / "report.json");
        if (saved) row.figures = measureResult(dir);
        row.figures.svg.clear();  // the manifest keeps figures; the gallery draws from results
        row.figures.subfolder = row.figures.label = job.name;
        if (!outcome.message.empty()) row.figures.reason = outcome.message;
        if (row.message.empty()) row.message = row.figures.reason;  // a failed gate's checks
        row.status = !saved ? "failed" : outcome.exitCode == 0 ? "done" : "gate-failed";
        row.seconds = std::chrono::duration<double>(Clock::now() - jobBegun).count();
        row.figures.seconds = row.seconds;
        const std::lock_guard<std::mutex> held(mutex);
        rows.push_back(std::move(row));
        std::sort(rows.begin(), rows.end(),
                  [](const BatchRow& a, const BatchRow& b) { return a.job.index < b.job.index; });
        ++done;
        failed += outcome.exitCode != 0;
        doneSize += job.size;
        remainingSize -= job.size;
        if (written.isOk())
          written = writeFileAtomically(manifest.string(),
                                        manifestText(rows, options, list, listed, false));
        if (progress)
          progress(done, failed, int(pending.size()),
                   estimateSecondsLeft(std::chrono::duration<double>(Clock::now() - begun).count(),
                                       doneSize, std::max(0.0, remainingSize)));
      },
      interrupted);
  if (!written.isOk()) return written;
  if (interrupted)
    return Status(ErrorCode::Interrupted, outDir + ": interrupted; " +
                                              manifest.filename().string() +
                                              " lists the finished jobs (a resumed batch runs the "
                                              "rest)");
  if (Status s = writeGallery(outDir, rows, galleryName(options)); !s.isOk()) return s;
  return rows;
}

Result<MergedBatch> mergeBatch(const std::string& outDir, bool allowPartial) {
  std::vector<fs::path> manifests;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(outDir, ec))
    if (isManifestName(entry.path().filename().string())) manifests.push_back(entry.path());
  if (manifests.empty())
    return Status(ErrorCode::InputUnreadable, outDir +
                                                  ": holds no batch manifest (batch.json or "
                                                  "batch-shard-I-of-N.json)");
  BatchLock lock;
  if (Status s = lock.acquire(outDir, {}, true); !s.isOk()) return s;
  // Oldest first, so that a job in several manifests keeps its latest row.
  std::sort(manifests.begin(), manifests.end(), [](const fs::path& a, const fs::path& b) {
    std::error_code e;
    return fs::last_write_time(a, e) < fs::last_write_time(b, e);
  });
  // Every manifest must come from one job list: shards of another order, of other jobs, or run
  // after a job file or an input was edited would merge into a table that matches no list.
  std::map<std::string, BatchRow> byName;
  std::map<int, std::string> nameAt;
  ListedJobs listed;
  JobList list;
  fs::path listedBy;
  const auto mismatch = [&](const fs::path& a, const fs::path& b, const std::string& what) {
    return Status(ErrorCode::InputInvalid,
                  a.string() + " and " + b.filename().string() + " were run from different job " +
                      "lists (" + what +
                      "); nothing was merged (run the shards again from one list)");
  };
  for (const fs::path& path : manifests) {
    Result<Manifest> read = readManifest(path);
    if (!read.isOk()) return read.status();
    const JobList& jobs = read.value().jobs;
    listed.insert(read.value().listed.begin(), read.value().listed.end());
    if (jobs.count >= 0) {
      if (list.count >= 0 && (jobs.count != list.count || jobs.sha256 != list.sha256))
        return mismatch(listedBy, path,
                        jobs.count != list.count ? "another number of jobs"
                                                 : "other jobs, another order or "
                                                   "edited files");
      if (list.count < 0) {
        list = jobs;
        listedBy = path;
      }
    }
    for (BatchRow& r : read.value().rows) {
      const auto named = nameAt.emplace(r.job.index, r.job.name);
      if (!named.second && named.first->second != r.job.name)
        return mismatch(manifests.front(), path,
                        "job " + std::to_string(r.job.index) + " is " + named.first->second +
                            " in one, " + r.job.name + " in the other");
      byName[r.job.name] = std::move(r);
    }
  }
  std::vector<BatchRow> rows;
  for (auto& [name, row] : byName) rows.push_back(std::move(row));
  std::sort(rows.begin(), rows.end(),
            [](const BatchRow& a, const BatchRow& b) { return a.job.index < b.job.index; });
  for (std::size_t k = 1; k < rows.size(); ++k)
    if (rows[k].job.index == rows[k - 1].job.index)
      return mismatch(manifests.front(), manifests.back(),
                      rows[k - 1].job.name + " and " + rows[k].job.name + " are both job " +
                          std::to_string(rows[k].job.index));
  // Every job of the list must have finished somewhere: a shard missing, killed part way or
  // never started would otherwise merge into a table that looks whole.
  MergedBatch merged;
  merged.jobCount = list.count;
  if (list.count < 0 && !allowPartial)
    return Status(ErrorCode::SolveFailed,
                  outDir + ": the manifests do not record their job list, so whether every job " +
                      "finished cannot be told; nothing was merged (a partial merge takes them " +
                      "all the same)");
  for (const BatchRow& r : rows) listed[r.job.index] = r.job.name;
  std::set<int> finished;
  for (const BatchRow& r : rows)
    if (r.job.index >= 0 && r.job.index < list.count) finished.insert(r.job.index);
  merged.missingCount = std::max(0, list.count - int(finished.size()));
  for (int k = 0; k < list.count && int(merged.firstMissing.size()) < kMissingNamed; ++k)
    if (!finished.count(k)) {
      const auto name = listed.find(k);
      merged.firstMissing.push_back(name != listed.end() ? name->second : "#" + std::to_string(k));
    }
  if (merged.missingCount > 0 && !allowPartial)
    return Status(
        ErrorCode::SolveFailed,
        outDir + ": " + std::to_string(merged.missingCount) + " of " + std::to_string(list.count) +
            " jobs have not finished in any manifest (" + missingText(merged) +
            "); nothing was merged (run their shards, resume a shard cut short, or merge " +
            "what is there as a partial merge)");
  const fs::path base = fs::path(outDir);
  if (Status s = writeFileAtomically((base / "batch.json").string(),
                                     manifestText(rows, {}, list, listed, true));
      !s.isOk())
    return s;
  if (Status s = writeGallery(outDir, rows, "gallery.html"); !s.isOk()) return s;
  merged.rows = std::move(rows);
  return merged;
}

}  // namespace dform
