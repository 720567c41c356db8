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

}  // namespace

Files forwardJobFiles(const PieceInput& a, const PieceInput& b, const Job& job) {
  return {{"job.json", withInputs(job, {{"piece_a", a.name}, {"piece_b", b.name}})},
          {a.name, a.text},
          {b.name, b.text}};
}

Files inverseJobFiles(const CurveInput& curve, const Job& job) {
  return {{"job.json", withInputs(job, {{"curve", curve.name}})}, {curve.name, curve.text}};
}

Result<std::string> exportedResult(const Files& jobFiles, const std::atomic<bool>* cancel) {
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
  for (const auto& [name, content] : jobFiles)
    if (Status s = writeFile(dir / name, content); !s.isOk()) return s;
  Result<Job> job = readJobFile((dir / "job.json").string());
  if (!job.isOk()) return job.status();
  OutputOptions output;
  output.outDir = (dir / "result").string();
  Result<RunSettings> settings = checkOutput(job.value().exporting);
  if (!settings.isOk()) return settings.status();
  MessageSink sink;
  RunHooks hooks;
  hooks.interrupted = cancel;
  Result<WrittenResult> written = [&] {
    // Stopped inside its long steps (meshing, figures, layout) too, not only between them.
    const ScopedStop stop(cancel);
    return runAndWrite(job.value(), output, settings.value(), sink, hooks);
  }();
  if (!fs::is_directory(output.outDir))
    return written.isOk() ? Status(ErrorCode::OutputFailed, "the export wrote nothing")
                          : written.status();
  return storedZip(filesUnder(output.outDir));
}

}  // namespace dform::studio
