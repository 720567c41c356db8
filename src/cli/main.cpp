// dform: forward and inverse D-Form modelling, export and validation from the command line.
// Thin: parses options into jobs, calls the pipeline, prints. Exit codes: README "Exit codes".
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <set>
#include <string>

#include "dform/cli/commands.h"
#include "dform/cli/terminal.h"
#include "dform/core/allocator.h"
#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"

namespace {

using namespace dform;

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

// "--weight isometry=2" -> the named weight of a forward or inverse job.
Status setWeight(Job& job, const std::string& assignment) {
  const auto eq = assignment.find('=');
  const std::string name = assignment.substr(0, eq);
  double value = 0;
  try {
    if (eq == std::string::npos) throw std::invalid_argument("no =");
    std::size_t used = 0;
    value = std::stod(assignment.substr(eq + 1), &used);
    if (used != assignment.size() - eq - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    return Status(ErrorCode::Usage, "--weight must look like name=value, got '" + assignment + "'");
  }
  if (!setNamedWeight(job, name, value))
    return Status(ErrorCode::Usage, "--weight: unknown weight '" + name + "'");
  return Status::ok();
}

// "X,Y" -> a start point nearest to (X, Y) mm.
bool parsePoint(const std::string& text, StartPoint& start) {
  double x = 0, y = 0;
  char rest = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &x, &y, &rest) != 2) return false;
  start.nearestToPoint = true;
  start.point = {x, y};
  return true;
}

// The options of the cutting patterns and previews (forward, inverse, run and export).
void addExportOptions(CLI::App* command, OutputOptions& out) {
  command->add_option("--profile", out.profile,
                      "export profile name or .json file (default laser)");
  command->add_option("--sheet", out.sheet, "material sheet of a laser profile, e.g. 600x400mm");
  command->add_option("--scale", out.scale,
                      "pattern scale: 1 (true size, the default), 0.8 or 80%, or fit (the largest "
                      "scale up to 1 at which every piece fits its page or sheet)");
  command->add_option(
      "--page", out.page,
      "paper of a print profile: A4, Letter, A3, Tabloid or WxHmm (default: the profile's)");
  command->add_option("--tab-width", out.tabWidthMm,
                      "glue tab width in mm, 0 for none (default 6)");
  command->add_option(
      "--tabs", out.tabs,
      "which piece gets the glue tabs: a, b, alternate or none (default: the profile's)");
  command->add_option("--tick-spacing", out.tickSpacingMm,
                      "seam length between numbered ticks in mm (default 20)");
  command->add_option("--joint", out.joint,
                      "how the pieces are joined: glue (tabs), holes (matched hole pairs for ties "
                      "or stitches), lace, or slots (tongues on A through slots in B, hole pairs "
                      "where the seam bends) (default: the material's, else the profile's)");
  command->add_option("--material", out.material,
                      "sheet material, setting the joint and hole sizes: paper (0.1 mm), card "
                      "(0.3 mm), polypropylene (0.5 mm) or plywood (3 mm)");
  command
      ->add_option("--kerf", out.kerfMm,
                   "the cutter's kerf in mm, 0 to 5: cut paths move half of it away from the "
                   "material (default: the profile's)")
      ->type_name("MM");
  command
      ->add_option("--hole-spacing", out.holeSpacingMm,
                   "joint holes: largest distance between neighbouring holes in mm (default 15)")
      ->type_name("MM");
  command
      ->add_option("--hole-diameter", out.holeDiameterMm, "joint holes: diameter in mm (default 2)")
      ->type_name("MM");
  command
      ->add_option("--hole-edge", out.holeEdgeMm,
                   "joint holes: distance from the seam to the hole centres in mm (default 3)")
      ->type_name("MM");
  command
      ->add_option("--slot-length", out.slotLengthMm,
                   "slots: a tongue's width along the seam in mm (default half the hole spacing)")
      ->type_name("MM");
  command
      ->add_option("--score-folds", out.scoreFoldsDeg,
                   "score every fold of the solved body of at least DEG degrees on its piece "
                   "(SCORE layer, pattern.json); 0 to 180")
      ->type_name("DEG");
  command->add_option("--numbers", out.numbers,
                      "where tick numbers go: face, tabs (hidden once glued) or both (default: "
                      "the profile's)");
  command->add_flag_callback(
      "--hinge", [&out] { out.hinge = true; },
      "kerf-bending cuts across each piece where the solved shape bends, parallel to its folds "
      "(default for plywood; exact model results)");
  command->add_flag_callback(
      "--no-hinge", [&out] { out.hinge = false; }, "no kerf-bending cuts, even in plywood");
  // A callback, not CLI11's "!--no-title" form, whose help shows "--no-title{false}".
  command->add_flag_callback(
      "--no-title", [&out] { out.title = false; },
      "leave the title block and notes off the pattern sheets");
  command->add_flag("--gltf", out.gltfText,
                    "write the 3D preview as text dform.gltf instead of dform.glb");
}

// A repeatable option takes one value per use ("--weight a=1 --weight b=2"), so that the
// positional arguments after it stay positional.
void addRepeatable(CLI::App* command, const std::string& name, std::vector<std::string>& values,
                   const std::string& help) {
  command->add_option(name, values, help)->allow_extra_args(false)->type_name("NAME=VALUE");
}

// `json`: where --json goes, on the commands that print one result's summary (null: no --json).
void addOutputOptions(CLI::App* command, OutputOptions& out, bool* json = nullptr) {
  command->add_option("-o,--output", out.outDir, "folder for the results (created if missing)")
      ->required();
  command->add_flag_callback(
      "--no-export", [&out] { out.exportFiles = false; },
      "skip the cutting patterns and 3D previews");
  addExportOptions(command, out);
  command->add_option(
      "--gate", out.gate,
      "quality gate: default (the default), strict, lenient, a .json file, or none");
  command->add_flag("--export-anyway", out.exportAnyway,
                    "export even if the gate fails (marked FAILED GATE)");
  command->add_flag("-q,--quiet", out.quiet, "print nothing but errors");
  if (json)
    command->add_flag("--json", *json,
                      "print the summary (model, figures, gate, files, exit code) as one JSON "
                      "object on stdout, and nothing else there");
}

int failUsage(const Status& status) {
  cli::Terminal::error(status.message());
  return exitCode(status.code());
}

// "-" (standard input) may stand for one input of a command, not two.
Status oneStandardInput(const std::vector<std::string>& inputs) {
  if (std::count(inputs.begin(), inputs.end(), kStandardInput) > 1)
    return Status(ErrorCode::Usage, "only one input can be read from stdin ('-')");
  return Status::ok();
}

// Each subcommand: its options as parsed (`add` declares them) and what it runs.
struct ForwardCommand {
  Job job;
  OutputOptions out;
  bool json = false;
  std::string startANear, startBNear, join, model;
  std::vector<std::string> weights;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("forward", "two flat outlines -> the D-Form they make");
    command->add_option("piece_a", job.forward.pieceA, "outline of piece A (.svg or .json)")
        ->required();
    command->add_option("piece_b", job.forward.pieceB, "outline of piece B (.svg or .json)")
        ->required();
    command->add_option("--resolution", job.forward.resolution,
                        "seam vertices per piece (default 100)");
    command->add_option(
        "--interior-edge", job.forward.interiorEdgeFactor,
        "interior edge length over the seam's edge length, 0.25-8 (default 1): above 1 a "
        "coarser, faster mesh at the same seam resolution");
    command->add_option("--start-a", job.forward.startA.fraction,
                        "start of A's seam: arc-length fraction in [0, 1)");
    command->add_option("--start-b", job.forward.startB.fraction,
                        "start of B's seam: arc-length fraction in [0, 1)");
    command->add_option("--start-a-near", startANear,
                        "start of A's seam: the outline point nearest X,Y (mm)");
    command->add_option("--start-b-near", startBNear,
                        "start of B's seam: the outline point nearest X,Y (mm)");
    command->add_option("--join", join,
                        "boundaries zipped, A's then B's: outer,outer (default), inner,inner "
                        "(anti D-Form) or outer,inner (demi D-Form)");
    command->add_flag("--flip", job.forward.flip, "zip piece B turned over");
    command->add_option(
        "--model", model,
        "auto (default: exact where the pieces make a convex body, else paper), exact, paper or "
        "general (a stiff sheet at a stationary point of its energy)");
    command->add_flag("--fit-perimeter", job.forward.fitPerimeter,
                      "scale piece B to A's perimeter");
    command->add_option("--perimeter-tolerance", job.forward.perimeterTolerance,
                        "largest relative perimeter difference (default 0.005)");
    addRepeatable(command, "--weight", weights,
                  "term weight, e.g. smooth_3d=0.02 (one per use, repeatable)");
    command->add_option("--max-iterations", job.forward.solver.maxIterations,
                        "Levenberg-Marquardt iteration cap");
    addOutputOptions(command, out, &json);
  }
  int run() {
    if (!startANear.empty() && !parsePoint(startANear, job.forward.startA))
      return failUsage(Status(ErrorCode::Usage, "--start-a-near must look like X,Y"));
    if (!startBNear.empty() && !parsePoint(startBNear, job.forward.startB))
      return failUsage(Status(ErrorCode::Usage, "--start-b-near must look like X,Y"));
    if (!join.empty() && !parseJoin(join, job.forward.joinA, job.forward.joinB))
      return failUsage(Status(
          ErrorCode::Usage, "--join must be outer,outer, inner,inner, outer,inner or inner,outer"));
    if (!model.empty() && !parseModelChoice(model, job.forward.model))
      return failUsage(
          Status(ErrorCode::Usage, "--model must be auto, exact, ruled, paper or general"));
    if (Status s = oneStandardInput({job.forward.pieceA, job.forward.pieceB}); !s.isOk())
      return failUsage(s);
    job.forward.weights = defaultWeights(job.forward.joinA, job.forward.joinB);
    for (const std::string& w : weights)
      if (Status s = setWeight(job, w); !s.isOk()) return failUsage(s);
    if (Status s = validateForwardJob(job.forward); !s.isOk()) return failUsage(s);
    return cli::runJob(job, out, json, interrupted);
  }
};

struct InverseCommand {
  Job job;
  OutputOptions out;
  bool json = false;
  std::vector<std::string> weights;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    job.mode = Job::Mode::Inverse;
    command = app.add_subcommand("inverse", "a 3D seam curve -> the two flat pieces that make it");
    command->add_option("curve", job.inverse.curve, "seam curve (.obj polyline or .json)")
        ->required();
    command->add_option("--resolution", job.inverse.resolution, "seam vertices (default 100)");
    command->add_flag("--closed", job.inverse.forceClosed, "close an open OBJ polyline");
    addRepeatable(command, "--weight", weights,
                  "term weight, e.g. smooth_3d=0.005 (one per use, repeatable)");
    command->add_option("--max-iterations", job.inverse.solver.maxIterations,
                        "Levenberg-Marquardt iteration cap");
    addOutputOptions(command, out, &json);
  }
  int run() {
    for (const std::string& w : weights)
      if (Status s = setWeight(job, w); !s.isOk()) return failUsage(s);
    if (Status s = validateInverseJob(job.inverse); !s.isOk()) return failUsage(s);
    return cli::runJob(job, out, json, interrupted);
  }
};

struct SweepCommand {
  Job job;
  SweepOptions options;
  OutputOptions out;
  std::string flip = "none", model;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand(
        "sweep",
        "two outlines from many starting pairs -> a gallery of the D-Forms to choose from");
    command->add_option("piece_a", job.forward.pieceA, "outline of piece A (.svg or .json)")
        ->required();
    command->add_option("piece_b", job.forward.pieceB, "outline of piece B (.svg or .json)")
        ->required();
    command->add_option("--starts", options.starts,
                        "starting pairs: start_b = k/N, k = 0 .. N-1 (default 8)");
    command->add_option("--flip", flip,
                        "none (B as drawn, the default), flipped (B turned over) or both");
    command->add_option("--start-a", job.forward.startA.fraction,
                        "start of A's seam: arc-length fraction in [0, 1)");
    command->add_option("--model", model, "auto (default), exact, ruled, paper or general");
    command->add_option("--resolution", job.forward.resolution,
                        "seam vertices per piece (default 100)");
    command->add_option("--interior-edge", job.forward.interiorEdgeFactor,
                        "as for forward (default 1)");
    command->add_flag("--fit-perimeter", job.forward.fitPerimeter,
                      "scale piece B to A's perimeter");
    command->add_option("--threads", options.threads,
                        "starts solved at once (default: the machine's cores)");
    addOutputOptions(command, out);
  }
  int run() {
    if (!model.empty() && !parseModelChoice(model, job.forward.model))
      return failUsage(
          Status(ErrorCode::Usage, "--model must be auto, exact, ruled, paper or general"));
    if (flip != "none" && flip != "flipped" && flip != "both")
      return failUsage(Status(ErrorCode::Usage, "--flip must be none, flipped or both"));
    if (options.starts < 1 || options.starts > 4096)
      return failUsage(Status(ErrorCode::Usage, "--starts must be between 1 and 4096"));
    if (options.threads < 0)
      return failUsage(
          Status(ErrorCode::Usage, "--threads must be 0 (the machine's cores) or more"));
    job.forward.weights = defaultWeights(job.forward.joinA, job.forward.joinB);
    if (Status s = oneStandardInput({job.forward.pieceA, job.forward.pieceB}); !s.isOk())
      return failUsage(s);
    job.forward.flip = flip == "flipped";
    options.bothFlips = flip == "both";
    if (Status s = validateForwardJob(job.forward); !s.isOk()) return failUsage(s);
    return cli::runSweepCommand(job, options, out, interrupted);
  }
};

struct BatchCommand {
  std::string input, shard = "1/1", mergeDir;
  bool allowPartial = false;
  BatchOptions options;
  OutputOptions out;
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
    addOutputOptions(command, out);
    command->get_option("--output")->required(false);
  }
  int run() {
    if (!mergeDir.empty()) {
      if (!input.empty() || !out.outDir.empty())
        return failUsage(Status(ErrorCode::Usage, "batch --merge DIR takes no job list and no -o"));
      return cli::mergeBatchCommand(mergeDir, allowPartial, out.quiet);
    }
    if (allowPartial)
      return failUsage(Status(ErrorCode::Usage, "--allow-partial goes with --merge DIR"));
    if (input.empty() || out.outDir.empty())
      return failUsage(
          Status(ErrorCode::Usage, "batch needs a job list or folder and -o OUT (or --merge OUT)"));
    if (!parseShard(shard, options.shard, options.shards))
      return failUsage(Status(ErrorCode::Usage,
                              "--shard must look like I/N with 1 <= I <= N, got '" + shard + "'"));
    if (options.threads < 0)
      return failUsage(
          Status(ErrorCode::Usage, "--threads must be 0 (the machine's cores) or more"));
    Result<std::vector<BatchJob>> jobs = listBatchJobs(input);
    if (!jobs.isOk()) return failUsage(jobs.status());
    return cli::runBatchCommand(jobs.value(), options, out, interrupted);
  }
};

struct RunCommand {
  std::string jobPath;
  OutputOptions out;
  bool json = false;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("run", "run a job file (forward or inverse)");
    command->add_option("job", jobPath, "job file (.json, see docs/cli.md)")->required();
    addOutputOptions(command, out, &json);
  }
  int run() {
    Result<Job> job = readJobFile(jobPath);
    if (!job.isOk()) return failUsage(job.status());
    const Job& read = job.value();
    if (Status s = oneStandardInput(
            {jobPath, read.forward.pieceA, read.forward.pieceB, read.inverse.curve});
        !s.isOk())
      return failUsage(s);
    return cli::runJob(job.value(), out, json, interrupted);
  }
};

struct ExportCommand {
  std::vector<std::string> dirs;
  OutputOptions out;
  bool listOnly = false, nest = false;
  int copies = 1;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("export", "write cutting patterns and previews of a saved result");
    command->add_option("dir", dirs,
                        "a result folder written by forward, inverse or run (several with --nest)");
    addExportOptions(command, out);
    command->add_option("-o,--output", out.outDir,
                        "write the patterns into this folder (created if missing) instead of "
                        "the result folder, which is left untouched");
    command->add_flag("--export-anyway", out.exportAnyway,
                      "export a result that failed its gate, or a pattern that does not lay "
                      "out cleanly (marked FAILED GATE)");
    command->add_flag("--regate", out.regate,
                      "measure and judge the result again even where report.json's gate verdict "
                      "still holds (its meshes unchanged since the run)");
    command->add_flag("--nest", nest,
                      "put the pieces of every result given (and --copies) on as few sheets as "
                      "hold them, into the -o folder");
    command
        ->add_option("--copies", copies, "with --nest: cut each D-Form this many times (1 to 1000)")
        ->type_name("N");
    command->add_flag("--list-profiles", listOnly, "list the profiles and exit");
    command->add_flag("-q,--quiet", out.quiet, "print only warnings and errors");
  }
  int run() {
    if (listOnly) return cli::listProfiles();
    if (dirs.empty()) return failUsage(Status(ErrorCode::Usage, "export needs a result folder"));
    if (nest) return cli::exportNested(dirs, copies, out, interrupted);
    if (dirs.size() > 1 || copies != 1)
      return failUsage(Status(ErrorCode::Usage,
                              "several result folders, or --copies, are exported together with "
                              "--nest -o FOLDER"));
    return cli::exportSaved(dirs.front(), out, interrupted);
  }
};

struct ValidateCommand {
  std::string dir, gate = "default";
  cli::Printing printing;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("validate", "re-check a saved result against a quality gate");
    command->add_option("dir", dir, "a result folder")->required();
    command->add_option("--gate", gate,
                        "default, strict, lenient, a .json file, or none (the figures measured "
                        "and printed, no verdict)");
    command->add_flag("-q,--quiet", printing.quiet, "print nothing but errors");
    command->add_flag("--json", printing.json,
                      "print the checks and the verdict as one JSON object on stdout");
  }
  int run() { return cli::validateSaved(dir, gate, printing); }
};

// `dform studio`: serves the design page until Ctrl-C or SIGTERM (docs/studio.md).
struct StudioCommand {
  std::vector<std::string> inputs;
  StudioOptions options;
  bool noBrowser = false;
  CLI::App* command = nullptr;

  void add(CLI::App& app) {
    command = app.add_subcommand("studio", "design a D-Form live in the browser");
    command->add_option("inputs", inputs,
                        "two outlines (A B) or a job file to start from (default: two ellipses)");
    command->add_option("--port", options.port, "port on 127.0.0.1 (default: any free one)");
    command->add_flag("--no-browser", noBrowser, "print the address but do not open a browser");
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
  if (argc > 1 && argv[1][0] != '-' && !commands.count(argv[1]))
    return failUsage(
        Status(ErrorCode::Usage, "unknown command '" + std::string(argv[1]) +
                                     "' (commands: forward, inverse, run, sweep, "
                                     "batch, export, validate, studio; see dform --help)"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
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
    return code == interruptedCode && stopSignal ? 128 + stopSignal : code;
  } catch (const dform::Interrupted& stop) {
    // A stop inside a computation no stage turned into a status: everything it held is undone
    // by the unwinding (the folder's lock and staging among it).
    dform::cli::Terminal::error(std::string("interrupted during ") + stop.stage());
    return stopSignal ? 128 + stopSignal : dform::exitCode(dform::ErrorCode::Interrupted);
  } catch (const std::bad_alloc&) {
    // An allocation the memory check did not foresee (a limit it cannot see, another process
    // taking the memory meanwhile): the run needs more memory than it can get, a usage matter.
    dform::cli::Terminal::error(
        "out of memory (the machine or its limits, e.g. ulimit -v, give this run less than it "
        "needs); try a lower --resolution");
    return dform::exitCode(dform::ErrorCode::Usage);
  } catch (const std::exception& e) {
    dform::cli::Terminal::error(std::string("internal error: ") + e.what());
  } catch (...) {
    dform::cli::Terminal::error("internal error");
  }
  return 1;
}
