// SPDX-License-Identifier: GPL-3.0-or-later
#include "downloads.h"

#include <malloc.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dform/core/interrupt.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/run.h"
#include "wire.h"
#include "zip.h"

namespace dform::studio {

namespace fs = std::filesystem;
using nlohmann::json;
using Files = std::vector<std::pair<std::string, std::string>>;

namespace {

// jobToJson records an input that exists as a file by its absolute path; the saved job names
// its inputs beside it instead, whatever the server's working folder holds.
std::string withInputs(const Job& job,
                       const std::vector<std::pair<const char*, std::string>>& inputs) {
  json text = json::parse(jobToJson(job));
  for (const auto& [key, name] : inputs) text[key] = name;
  return text.dump(2) + "\n";
}

// A fresh private folder under the system's temporary folder.
Result<fs::path> temporaryFolder() {
  std::string pattern = (fs::temp_directory_path() / "dform-studio-XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    return Status(ErrorCode::OutputFailed, pattern + ": cannot create a temporary folder");
  return fs::path(pattern);
}

Status writeFile(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out << content;
  out.close();
  return out ? Status::ok() : Status(ErrorCode::OutputFailed, path.string() + ": cannot write");
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every regular file under `dir`, by its '/'-separated path relative to it, sorted.
Files filesUnder(const fs::path& dir) {
  Files files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files.emplace_back(fs::relative(entry.path(), dir).generic_string(), readFile(entry.path()));
  std::sort(files.begin(), files.end());
  return files;
}

// `text` with the temporary folder's path taken out: a file beside it named by its name alone,
// the folder itself as ".".
std::string withoutFolder(std::string text, const fs::path& dir) {
  for (const std::string& path : {dir.string() + "/", dir.string()}) {
    const std::string by = path.back() == '/' ? "" : ".";
    for (std::size_t at = text.find(path); at != std::string::npos;
         at = text.find(path, at + by.size()))
      text.replace(at, path.size(), by);
  }
  return text;
}

// The files of the result that may name the folder (the report records its inputs' paths); the
// pattern, meshes and pictures name none, and a PDF's or GLB's bytes are not text to edit.
bool namesPaths(const std::string& name) {
  const auto endsWith = [&](const char* tail) {
    const std::string t = tail;
    return name.size() >= t.size() && name.compare(name.size() - t.size(), t.size(), t) == 0;
  };
  return endsWith(".json") || endsWith(".html");
}

// Why the zip holds no cutting files, and what to do, or "" when it holds them.
std::string missingFiles(const WrittenResult& written, const RunSettings& settings) {
  const std::string holds = "The zip holds the model, its previews and the report, but ";
  if (!written.exported.isOk())
    return "The cutting files could not be made: " + studioWords(written.exported) + ". " + holds +
           "no cutting files: change the export's settings and export again.";
  if (!written.gate || written.gate->passed() || settings.exportAnyway || !settings.cuttingFiles)
    return "";
  std::string failed;
  for (const CheckResult& c : written.gate->checks)
    if (c.verdict == CheckResult::Verdict::Fail) failed += (failed.empty() ? "" : ", ") + c.name;
  return "The design failed the quality gate '" + written.gate->name + "' (" + failed + "). " +
         holds + "no cutting files: tick \"export even if the gate fails\" for cutting " +
         "files marked FAILED GATE, or change the design until the gate passes.";
}

}  // namespace

Files forwardJobFiles(const PieceInput& a, const PieceInput& b, const Job& job) {
  return {{"job.json", withInputs(job, {{"piece_a", a.name}, {"piece_b", b.name}})},
          {a.name, a.text},
          {b.name, b.text}};
}

Files inverseJobFiles(const CurveInput& curve, const Job& job) {
  return {{"job.json", withInputs(job, {{"curve", curve.name}})}, {curve.name, curve.text}};
}

Result<ExportedFiles> exportedFiles(const Files& jobFiles, const std::atomic<bool>* cancel) {
  Result<fs::path> folder = temporaryFolder();
  if (!folder.isOk()) return folder.status();
  const fs::path dir = folder.value();
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
      // The run's hundreds of MB, freed, go back to the system: a server lives on after it.
      ::malloc_trim(0);
    }
  } cleanup{dir};
  // An error names no path of the server's: the folder is the server's, not the designer's.
  const auto failed = [&](const Status& s) {
    return Status(s.code(), withoutFolder(studioWords(s), dir));
  };
  for (const auto& [name, content] : jobFiles)
    if (Status s = writeFile(dir / name, content); !s.isOk()) return failed(s);
  Result<Job> job = readJobFile((dir / "job.json").string());
  if (!job.isOk()) return failed(job.status());
  OutputOptions output;
  output.outDir = (dir / "result").string();
  Result<RunSettings> settings = checkOutput(job.value().exporting);
  if (!settings.isOk()) return failed(settings.status());
  MessageSink sink;
  RunHooks hooks;
  hooks.interrupted = cancel;
  Result<WrittenResult> written = [&] {
    // Stopped inside its long steps (meshing, figures, layout) too, not only between them.
    const ScopedStop stop(cancel);
    return runAndWrite(job.value(), output, settings.value(), sink, hooks);
  }();
  if (!written.isOk()) return failed(written.status());
  if (!fs::is_directory(output.outDir))
    return Status(ErrorCode::OutputFailed, "the export wrote nothing");
  Files files = filesUnder(output.outDir);
  for (auto& [name, content] : files)
    if (namesPaths(name)) content = withoutFolder(content, dir);
  return ExportedFiles{std::move(files), missingFiles(written.value(), settings.value())};
}

Result<ExportedZip> exportedResult(const Files& jobFiles, const std::atomic<bool>* cancel) {
  Result<ExportedFiles> exported = exportedFiles(jobFiles, cancel);
  if (!exported.isOk()) return exported.status();
  return ExportedZip{storedZip(exported.value().files), exported.value().missing};
}

json printPreview(const Result<ExportedFiles>& run) {
  if (!run.isOk()) return {{"error", run.status().message()}};
  const ExportedFiles& exported = run.value();
  const auto file = [&](const std::string& name) -> const std::string* {
    for (const auto& [n, content] : exported.files)
      if (n == name) return &content;
    return nullptr;
  };
  json out = {{"missing", exported.missing}};
  const std::string* sidecar = file("pattern.json");
  if (!sidecar) return out;
  const json pattern = json::parse(*sidecar);
  out["pages"] = pattern.at("pages");
  out["sheets"] = pattern.at("sheets");
  json svgs = json::array();
  for (const json& sheet : pattern.at("sheets")) {
    const std::string* svg = file(sheet.at("file").get<std::string>());
    svgs.push_back(svg ? *svg : std::string());
  }
  out["svg"] = svgs;
  for (const char* key : {"scale", "profile", "failed_gate"})
    if (pattern.contains(key)) out[key] = pattern.at(key);
  return out;
}

json previewOf(const std::function<Files()>& jobFiles, const std::atomic<bool>* cancel) {
  try {
    return printPreview(exportedFiles(jobFiles(), cancel));
  } catch (const RequestError& e) {
    return {{"error", e.what()}};
  }
}

}  // namespace dform::studio
