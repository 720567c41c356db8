// SPDX-License-Identifier: GPL-3.0-or-later
// dform: forward and inverse D-Form modelling, export and validation from the command line.
// Thin: parses options into jobs, calls the pipeline, prints. Exit codes: README "Exit codes".
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <set>
#include <string>

#include "commands.h"
#include "dform/core/allocator.h"
#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "json_summary.h"
#include "setting_options.h"
#include "terminal.h"

namespace {

using namespace dform;
using cli::SettingOptions;

// The process's stop flag (core/interrupt.h), which the readers and long loops poll too.
std::atomic<bool>& interrupted = interruptFlag();
volatile std::sig_atomic_t stopSignal = 0;

// Ctrl-C (SIGINT) or a batch system's SIGTERM: the run stops at the next solver iteration and
// writes nothing (README "Exit codes"). A second one ends the program at once: the handler is
// installed with SA_RESETHAND, which gives the signal back its default action.
extern "C" void onStopSignal(int signal) {
  stopSignal = signal;
  interrupted = true;
}

// `rows` of one mode without the settings of `except` (a sweep's own --flip and start_b).
std::vector<const SettingRow*> rowsOf(bool forward, std::initializer_list<SettingScope> scopes,
                                      std::initializer_list<Setting> except = {}) {
  std::vector<const SettingRow*> out;
  for (const SettingRow* row : settingRows(forward))
    if (std::find(scopes.begin(), scopes.end(), row->scope) != scopes.end() &&
        std::find(except.begin(), except.end(), row->id) == except.end())
      out.push_back(row);
  return out;
}

// --json, which every command takes (docs/cli.md, "Machine-readable output").
void addJsonFlag(CLI::App* command, bool& json) {
  command->add_flag("--json", json,
                    "print the outcome (what the command made, the exit code, the error if any) "
                    "as one JSON object on stdout, and nothing else there");
}

// What a run writes where: -o, -q and --json.
struct Output {
  OutputOptions options;
  cli::Printing printing;

  void add(CLI::App* command) {
    command
        ->add_option("-o,--output", options.outDir, "folder for the results (created if missing)")
        ->required();
    command->add_flag("-q,--quiet", printing.quiet, "print nothing but errors");
    addJsonFlag(command, printing.json);
  }
};

int failUsage(const Status& status) {
  cli::Terminal::error(status);
  return exitCode(status.code());
}

// "-" (standard input) may stand for one input of a command, not two.
Status oneStandardInput(const std::vector<std::string>& inputs) {
  if (std::count(inputs.begin(), inputs.end(), kStandardInput) > 1)
    return Status(ErrorCode::Usage, "only one input can be read from stdin ('-')");
  return Status::ok();
}

// Each subcommand: its options as parsed (`add` declares them) and what it runs. The settings'
// options come from the settings table (setting_options.h).
struct ForwardCommand {
  ForwardJob inputs;
  SettingOptions settings;
  Output output;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("forward", "two flat outlines -> the D-Form they make");
    command->add_option("piece_a", inputs.pieceA, "outline of piece A (.svg or .json)")->required();
    command->add_option("piece_b", inputs.pieceB, "outline of piece B (.svg or .json)")->required();
    settings.add(command, settingRows(true));
    output.add(command);
  }
  int run() {
    Job job(inputs);
    if (Status s = oneStandardInput(job.inputs()); !s.isOk()) return failUsage(s);
    if (Status s = settings.apply(job); !s.isOk()) return failUsage(s);
    return cli::runJob(job, output.options, output.printing, interrupted);
  }
};

struct InverseCommand {
  InverseJob inputs;
  SettingOptions settings;
  Output output;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("inverse", "a 3D seam curve -> the two flat pieces that make it");
    command->add_option("curve", inputs.curve, "seam curve (.obj polyline or .json)")->required();
    settings.add(command, settingRows(false), false);
    output.add(command);
  }
  int run() {
    Job job(inputs);
    if (Status s = settings.apply(job); !s.isOk()) return failUsage(s);
    return cli::runJob(job, output.options, output.printing, interrupted);
  }
};

struct SweepCommand {
  ForwardJob inputs;
  SweepOptions options;
  SettingOptions settings;
  Output output;
  std::string flip = "none";
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand(
        "sweep",
        "two outlines from many starting pairs -> a gallery of the D-Forms to choose from");
    command->add_option("piece_a", inputs.pieceA, "outline of piece A (.svg or .json)")->required();
    command->add_option("piece_b", inputs.pieceB, "outline of piece B (.svg or .json)")->required();
    command->add_option("--starts", options.starts,
                        "starting pairs: start_b = k/N, k = 0 .. N-1 (default 8)");
    command->add_option("--flip", flip,
                        "none (B as drawn, the default), flipped (B turned over) or both");
    command->add_option("--threads", options.threads,
                        "starts solved at once (default: the machine's cores)");
    settings.add(command, rowsOf(true,
                                 {SettingScope::Forward, SettingScope::Solve, SettingScope::Export,
                                  SettingScope::Output},
                                 {Setting::Flip, Setting::StartB}));
    output.add(command);
  }
  int run() {
    if (flip != "none" && flip != "flipped" && flip != "both")
      return failUsage(Status(ErrorCode::Usage, "--flip must be none, flipped or both"));
    if (options.starts < 1 || options.starts > 4096)
      return failUsage(Status(ErrorCode::Usage, "--starts must be between 1 and 4096"));
    if (options.threads < 0)
      return failUsage(
          Status(ErrorCode::Usage, "--threads must be 0 (the machine's cores) or more"));
    Job job(inputs);
    if (Status s = oneStandardInput(job.inputs()); !s.isOk()) return failUsage(s);
    if (Status s = settings.apply(job); !s.isOk()) return failUsage(s);
    std::get<ForwardJob>(job.run).flip = flip == "flipped";
    options.bothFlips = flip == "both";
    return cli::runSweepCommand(job, options, output.options, output.printing, interrupted);
  }
};

struct BatchCommand {
  std::string input, shard = "1/1", mergeDir, outDir;
  bool allowPartial = false;
  BatchOptions options;
  SettingOptions settings;
  cli::Printing printing;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand(
        "batch", "many job files, each into OUT/<job name>/, with a resumable manifest batch.json");
    command->add_option("jobs", input,
                        "a text file listing job files (one a line), or a folder of *.json jobs");
    command->add_flag("--resume", options.resume, "skip the jobs the manifest has as finished");
    command->add_option("--shard", shard,
                        "run only slice I of N (job k goes to slice k % N + 1), e.g. 2/8");
    command->add_option(
        "--merge", mergeDir,
        "gather the shards' manifests in this folder into batch.json and gallery.html "
        "(refused while a job has not finished)");
    command->add_flag("--allow-partial", allowPartial,
                      "with --merge: merge the finished jobs although others have not finished");
    command->add_option("--threads", options.threads,
                        "jobs run at once (default: the machine's cores)");
    // The pattern and gate settings given here apply to every job, over its file's.
    settings.add(command, rowsOf(true, {SettingScope::Export, SettingScope::Output}));
    command->add_option("-o,--output", outDir, "folder for the results (created if missing)");
    command->add_flag("-q,--quiet", printing.quiet, "print nothing but errors");
    addJsonFlag(command, printing.json);
  }
  int run() {
    if (!mergeDir.empty()) {
      if (!input.empty() || !outDir.empty())
        return failUsage(Status(ErrorCode::Usage, "batch --merge DIR takes no job list and no -o"));
      return cli::mergeBatchCommand(mergeDir, allowPartial, printing.quiet);
    }
    if (allowPartial)
      return failUsage(Status(ErrorCode::Usage, "--allow-partial goes with --merge DIR"));
    if (input.empty() || outDir.empty())
      return failUsage(
          Status(ErrorCode::Usage, "batch needs a job list or folder and -o OUT (or --merge OUT)"));
    if (!parseShard(shard, options.shard, options.shards))
      return failUsage(Status(ErrorCode::Usage,
                              "--shard must look like I/N with 1 <= I <= N, got '" + shard + "'"));
    if (options.threads < 0)
      return failUsage(
          Status(ErrorCode::Usage, "--threads must be 0 (the machine's cores) or more"));
    // The settings given are checked once, before any job runs.
    Job probe;
    if (Status s = settings.apply(probe); !s.isOk()) return failUsage(s);
    if (Result<RunSettings> checked = checkOutput(probe.exporting); !checked.isOk())
      return failUsage(checked.status());
    Result<std::vector<BatchJob>> jobs = listBatchJobs(input);
    if (!jobs.isOk()) return failUsage(jobs.status());
    OutputOptions output;
    output.outDir = outDir;
    return cli::runBatchCommand(
        jobs.value(), options, output, printing, [this](Job& job) { return settings.apply(job); },
        interrupted);
  }
};

struct RunCommand {
  std::string jobPath;
  SettingOptions settings;
  Output output;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("run", "run a job file (forward or inverse)");
    command->add_option("job", jobPath, "job file (.json, see docs/cli.md)")->required();
    // The pattern and gate settings given here apply over the job file's.
    settings.add(command, rowsOf(true, {SettingScope::Export, SettingScope::Output}));
    output.add(command);
  }
  int run() {
    Result<Job> job = readJobFile(jobPath);
    if (!job.isOk()) return failUsage(job.status());
    std::vector<std::string> inputs = job.value().inputs();
    inputs.push_back(jobPath);
    if (Status s = oneStandardInput(inputs); !s.isOk()) return failUsage(s);
    if (Status s = settings.apply(job.value()); !s.isOk()) return failUsage(s);
    return cli::runJob(job.value(), output.options, output.printing, interrupted);
  }
};

struct ExportCommand {
  std::vector<std::string> dirs;
  SettingOptions settings;
  SavedExport how;
  bool listOnly = false, quiet = false, nest = false, json = false;
  int copies = 1;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("export", "write cutting patterns and previews of a saved result");
    command->add_option("dir", dirs,
                        "a result folder written by forward, inverse or run (several with --nest)");
    settings.add(command, rowsOf(true, {SettingScope::Export}));
    settings.add(command, {findSetting(settingKey(Setting::ExportAnyway), true)});
    command->add_option("-o,--output", how.outDir,
                        "write the patterns into this folder (created if missing) instead of "
                        "the result folder, which is left untouched");
    command->add_flag("--regate", how.regate,
                      "measure and judge the result again even where report.json's gate verdict "
                      "still holds (its meshes unchanged since the run)");
    command->add_flag("--nest", nest,
                      "put the pieces of every result given (and --copies) on as few sheets as "
                      "hold them, into the -o folder");
    command
        ->add_option("--copies", copies, "with --nest: cut each D-Form this many times (1 to 1000)")
        ->type_name("N");
    command->add_flag("--list-profiles", listOnly, "list the profiles and exit");
    command->add_flag("-q,--quiet", quiet, "print only warnings and errors");
    addJsonFlag(command, json);
  }
  int run() {
    if (listOnly) return cli::listProfiles();
    if (dirs.empty()) return failUsage(Status(ErrorCode::Usage, "export needs a result folder"));
    Job job;
    if (Status s = settings.apply(job); !s.isOk()) return failUsage(s);
    if (nest) return cli::exportNested(dirs, copies, job.exporting, how, quiet, interrupted);
    if (dirs.size() > 1 || copies != 1)
      return failUsage(Status(ErrorCode::Usage,
                              "several result folders, or --copies, are exported together with "
                              "--nest -o FOLDER"));
    return cli::exportSaved(dirs.front(), job.exporting, how, quiet, interrupted);
  }
};

struct ValidateCommand {
  std::string dir, gate = ExportSettings().gate;  // the settings table's default gate
  cli::Printing printing;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("validate", "re-check a saved result against a quality gate");
    command->add_option("dir", dir, "a result folder")->required();
    command->add_option("--gate", gate,
                        "default, strict, lenient, a .json file, or none (the figures measured "
                        "and printed, no verdict)");
    command->add_flag("-q,--quiet", printing.quiet, "print nothing but errors");
    addJsonFlag(command, printing.json);
  }
  int run() { return cli::validateSaved(dir, gate, printing); }
};

// `dform studio`: serves the design page until Ctrl-C or SIGTERM (docs/studio.md).
struct StudioCommand {
  std::vector<std::string> inputs;
  StudioOptions options;
  bool noBrowser = false, json = false;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("studio", "design a D-Form live in the browser");
    command->add_option("inputs", inputs,
                        "two outlines (A B) or a job file to start from (default: two ellipses)");
    command->add_option("--port", options.port, "port on 127.0.0.1 (default: any free one)");
    command->add_flag("--no-browser", noBrowser, "print the address but do not open a browser");
    addJsonFlag(command, json);
  }
  int run() {
    if (inputs.size() == 2) {
      options.pieceA = inputs[0];
      options.pieceB = inputs[1];
    } else if (inputs.size() == 1) {
      options.jobFile = inputs[0];
    } else if (!inputs.empty()) {
      return failUsage(
          Status(ErrorCode::Usage, "studio takes two outlines (A B), a job file, or nothing"));
    }
    return cli::runStudio(options, !noBrowser, interrupted);
  }
};

int run(int argc, char** argv) {
  CLI::App app{"dform: design and fabricate D-Forms (forward, inverse, export, validate)"};
  app.set_version_flag("--version", std::string("dform ") + DFORM_VERSION);
  app.require_subcommand(1);
  ForwardCommand forward;
  InverseCommand inverse;
  SweepCommand sweep;
  BatchCommand batch;
  RunCommand runCommand;
  ExportCommand exportCommand;
  ValidateCommand validate;
  StudioCommand studio;
  forward.add(app);
  inverse.add(app);
  sweep.add(app);
  batch.add(app);
  runCommand.add(app);
  exportCommand.add(app);
  validate.add(app);
  studio.add(app);

  const std::set<std::string> commands = {"forward", "inverse", "run",      "sweep",
                                          "batch",   "export",  "validate", "studio"};
  // --json anywhere on the line: one JSON object on stdout, a usage error's too.
  for (int k = 1; k < argc; ++k)
    if (std::string(argv[k]) == "--json")
      cli::json_summary::enable(
          argc > 1 && commands.count(argv[1]) ? std::optional<std::string>(argv[1]) : std::nullopt);
  if (argc > 1 && argv[1][0] != '-' && !commands.count(argv[1]))
    return failUsage(
        Status(ErrorCode::Usage, "unknown command '" + std::string(argv[1]) +
                                     "' (commands: forward, inverse, run, sweep, "
                                     "batch, export, validate, studio; see dform --help)"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    cli::json_summary::cancel();
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    cli::json_summary::cancel();
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return failUsage(Status(ErrorCode::Usage, e.what()));
  }

  // Without SA_RESTART, so that a blocked read the signal reaches returns EINTR at once (the
  // reader polls the flag too, core/input_file.cpp).
  struct sigaction stop {};
  stop.sa_handler = onStopSignal;
  sigemptyset(&stop.sa_mask);
  stop.sa_flags = SA_RESETHAND;  // a second signal ends the program at once
  sigaction(SIGINT, &stop, nullptr);
  sigaction(SIGTERM, &stop, nullptr);
  if (*forward.command) return forward.run();
  if (*inverse.command) return inverse.run();
  if (*sweep.command) return sweep.run();
  if (*batch.command) return batch.run();
  if (*runCommand.command) return runCommand.run();
  if (*exportCommand.command) return exportCommand.run();
  if (*studio.command) return studio.run();
  return validate.run();
}

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemory();
  try {
    const int code = run(argc, argv);
    // Interrupted: 130 for Ctrl-C, 143 for SIGTERM, as a shell reports a process they ended.
    const int interruptedCode = dform::exitCode(dform::ErrorCode::Interrupted);
    return dform::cli::json_summary::finish(code == interruptedCode && stopSignal ? 128 + stopSignal
                                                                                  : code);
  } catch (const dform::Interrupted& stop) {
    // A stop inside a computation no stage turned into a status: everything it held is undone
    // by the unwinding (the folder's lock and staging among it).
    dform::cli::Terminal::error(std::string("interrupted during ") + stop.stage());
    return dform::cli::json_summary::finish(
        stopSignal ? 128 + stopSignal : dform::exitCode(dform::ErrorCode::Interrupted));
  } catch (const std::bad_alloc&) {
    // An allocation the memory check did not foresee (a limit it cannot see, another process
    // taking the memory meanwhile): the run needs more memory than it can get, a usage matter.
    dform::cli::Terminal::error(
        "out of memory (the machine or its limits, e.g. ulimit -v, give this run less than it "
        "needs); try a lower --resolution");
    return dform::cli::json_summary::finish(dform::exitCode(dform::ErrorCode::Usage));
  } catch (const std::exception& e) {
    dform::cli::Terminal::error(std::string("internal error: ") + e.what());
  } catch (...) {
    dform::cli::Terminal::error("internal error");
  }
  return dform::cli::json_summary::finish(1);
}
