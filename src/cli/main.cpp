// dform: forward and inverse D-Form modelling, export and validation from the command line.
// Thin: parses options into jobs, calls the pipeline, prints. Exit codes: README "Exit codes".
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <set>
#include <string>

#include "cli/commands.h"
#include "cli/terminal.h"
#include "core/allocator.h"
#include "core/interrupt.h"

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
  command->add_option("--profile", out.profile, "export profile name or .json file (default laser)");
  command->add_option("--sheet", out.sheet, "material sheet of a laser profile, e.g. 600x400mm");
  command->add_option("--scale", out.scale, "pattern scale: 1 (true size, the default), 0.8 or 80%, or fit (the largest scale up to 1 at which every piece fits its page or sheet)");
  command->add_option("--page", out.page, "paper of a print profile: A4, Letter, A3, Tabloid or WxHmm (default: the profile's)");
  command->add_option("--tab-width", out.tabWidthMm, "glue tab width in mm, 0 for none (default 6)");
  command->add_option("--tabs", out.tabs, "which piece gets the glue tabs: a, b, alternate or none (default: the profile's)");
  command->add_option("--tick-spacing", out.tickSpacingMm, "seam length between numbered ticks in mm (default 20)");
  command->add_flag("!--no-title", out.title, "leave the title block and notes off the pattern sheets");
  command->add_flag("--gltf", out.gltfText, "write the 3D preview as text dform.gltf instead of dform.glb");
}

void addOutputOptions(CLI::App* command, OutputOptions& out) {
  command->add_option("-o,--output", out.outDir, "folder for the results (created if missing)")
      ->required();
  command->add_flag("!--no-export", out.exportFiles, "skip the cutting patterns and 3D previews");
  addExportOptions(command, out);
  command->add_option("--gate", out.gate, "quality gate: default (the default), strict, lenient, a .json file, or none");
  command->add_flag("--export-anyway", out.exportAnyway, "export even if the gate fails (marked FAILED GATE)");
  command->add_flag("-q,--quiet", out.quiet, "print only the figures, warnings and errors");
}

int usageError(const std::string& message) {
  cli::Terminal::error(message);
  return exitCode(ErrorCode::Usage);
}

int run(int argc, char** argv) {
  CLI::App app{"dform: design and fabricate D-Forms (forward, inverse, export, validate)"};
  app.set_version_flag("--version", std::string("dform ") + DFORM_VERSION);
  app.require_subcommand(1);

  Job forwardJob;
  OutputOptions forwardOut;
  std::string startANear, startBNear, join, model;
  std::vector<std::string> forwardWeights;
  CLI::App* forward = app.add_subcommand("forward", "two flat outlines -> the D-Form they make");
  forward->add_option("piece_a", forwardJob.forward.pieceA, "outline of piece A (.svg or .json)")->required();
  forward->add_option("piece_b", forwardJob.forward.pieceB, "outline of piece B (.svg or .json)")->required();
  forward->add_option("--resolution", forwardJob.forward.resolution, "seam vertices per piece (default 100)");
  forward->add_option("--interior-edge", forwardJob.forward.interiorEdgeFactor,
                      "interior edge length over the seam's edge length, 0.25-8 (default 1): above 1 a "
                      "coarser, faster mesh at the same seam resolution");
  forward->add_option("--start-a", forwardJob.forward.startA.fraction, "start of A's seam: arc-length fraction in [0, 1)");
  forward->add_option("--start-b", forwardJob.forward.startB.fraction, "start of B's seam: arc-length fraction in [0, 1)");
  forward->add_option("--start-a-near", startANear, "start of A's seam: the outline point nearest X,Y (mm)");
  forward->add_option("--start-b-near", startBNear, "start of B's seam: the outline point nearest X,Y (mm)");
  forward->add_option("--join", join, "boundaries zipped, A's then B's: outer,outer (default), inner,inner "
                                      "(anti D-Form) or outer,inner (demi D-Form)");
  forward->add_flag("--flip", forwardJob.forward.flip, "zip piece B turned over");
  forward->add_option("--model", model, "auto (default: exact where the pieces make a convex body), exact or paper");
  forward->add_flag("--fit-perimeter", forwardJob.forward.fitPerimeter,
                    "scale piece B to A's perimeter");
  forward->add_option("--perimeter-tolerance", forwardJob.forward.perimeterTolerance,
                      "largest relative perimeter difference (default 0.005)");
  forward->add_option("--weight", forwardWeights, "term weight, e.g. smooth_3d=0.02 (repeatable)");
  forward->add_option("--max-iterations", forwardJob.forward.solve.solver.maxIterations,
                      "Levenberg-Marquardt iteration cap");
  addOutputOptions(forward, forwardOut);

  Job inverseJob;
  inverseJob.mode = Job::Mode::Inverse;
  OutputOptions inverseOut;
  std::vector<std::string> inverseWeights;
  CLI::App* inverse =
      app.add_subcommand("inverse", "a 3D seam curve -> the two flat pieces that make it");
  inverse->add_option("curve", inverseJob.inverse.curve, "seam curve (.obj polyline or .json)")
      ->required();
  inverse->add_option("--resolution", inverseJob.inverse.resolution, "seam vertices (default 100)");
  inverse->add_flag("--closed", inverseJob.inverse.forceClosed, "close an open OBJ polyline");
  inverse->add_option("--weight", inverseWeights, "term weight, e.g. smooth_3d=0.005 (repeatable)");
  inverse->add_option("--max-iterations", inverseJob.inverse.solve.solver.maxIterations,
                      "Levenberg-Marquardt iteration cap");
  addOutputOptions(inverse, inverseOut);

  Job sweepJob;
  SweepOptions sweepOptions;
  OutputOptions sweepOut;
  std::string sweepFlip = "none", sweepModel;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "two outlines from many starting pairs -> a gallery of the D-Forms to choose from");
  sweep->add_option("piece_a", sweepJob.forward.pieceA, "outline of piece A (.svg or .json)")->required();
  sweep->add_option("piece_b", sweepJob.forward.pieceB, "outline of piece B (.svg or .json)")->required();
  sweep->add_option("--starts", sweepOptions.starts, "starting pairs: start_b = k/N, k = 0 .. N-1 (default 8)");
  sweep->add_option("--flip", sweepFlip, "none (B as drawn, the default), flipped (B turned over) or both");
  sweep->add_option("--start-a", sweepJob.forward.startA.fraction, "start of A's seam: arc-length fraction in [0, 1)");
  sweep->add_option("--model", sweepModel, "auto (default), exact or paper");
  sweep->add_option("--resolution", sweepJob.forward.resolution, "seam vertices per piece (default 100)");
  sweep->add_option("--interior-edge", sweepJob.forward.interiorEdgeFactor, "as for forward (default 1)");
  sweep->add_flag("--fit-perimeter", sweepJob.forward.fitPerimeter, "scale piece B to A's perimeter");
  sweep->add_option("--threads", sweepOptions.threads, "starts solved at once (default: the machine's cores)");
  addOutputOptions(sweep, sweepOut);

  std::string batchInput, batchShard = "1/1", mergeDir;
  BatchOptions batchOptions;
  OutputOptions batchOut;
  CLI::App* batch = app.add_subcommand(
      "batch", "many job files, each into OUT/<job name>/, with a resumable manifest batch.json");
  batch->add_option("jobs", batchInput, "a text file listing job files (one a line), or a folder of *.json jobs");
  batch->add_flag("--resume", batchOptions.resume, "skip the jobs the manifest has as finished");
  batch->add_option("--shard", batchShard, "run only slice I of N (job k goes to slice k % N + 1), e.g. 2/8");
  batch->add_option("--merge", mergeDir, "gather the shards' manifests in this folder into batch.json and gallery.html");
  batch->add_option("--threads", batchOptions.threads, "jobs run at once (default: the machine's cores)");
  addOutputOptions(batch, batchOut);
  batch->get_option("--output")->required(false);

  std::string jobPath;
  OutputOptions runOut;
  CLI::App* runCommand = app.add_subcommand("run", "run a job file (forward or inverse)");
  runCommand->add_option("job", jobPath, "job file (.json, see docs/cli.md)")->required();
  addOutputOptions(runCommand, runOut);

  std::string exportDir;
  OutputOptions exportOut;
  bool listOnly = false;
  CLI::App* exportCommand =
      app.add_subcommand("export", "write cutting patterns and previews of a saved result");
  exportCommand->add_option("dir", exportDir, "a result folder written by forward, inverse or run");
  addExportOptions(exportCommand, exportOut);
  exportCommand->add_option("-o,--output", exportOut.outDir,
                            "write the patterns into this folder (created if missing) instead of "
                            "the result folder, which is left untouched");
  exportCommand->add_flag("--export-anyway", exportOut.exportAnyway,
                          "export a result that failed its gate, or a pattern that does not lay "
                          "out cleanly (marked FAILED GATE)");
  exportCommand->add_flag("--list-profiles", listOnly, "list the profiles and exit");
  exportCommand->add_flag("-q,--quiet", exportOut.quiet, "print only warnings and errors");

  std::string validateDir, validateGate = "default";
  CLI::App* validate =
      app.add_subcommand("validate", "re-check a saved result against a quality gate");
  validate->add_option("dir", validateDir, "a result folder")->required();
  validate->add_option("--gate", validateGate, "default, strict, lenient or a .json file");

  const std::set<std::string> commands = {"forward", "inverse", "run", "sweep", "batch", "export", "validate"};
  if (argc > 1 && argv[1][0] != '-' && !commands.count(argv[1]))
    return usageError("unknown command '" + std::string(argv[1]) +
                      "' (commands: forward, inverse, run, sweep, batch, export, validate; see dform --help)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usageError(e.what());
  }

  // Without SA_RESTART, so that a blocked read the signal reaches returns EINTR at once (the
  // reader polls the flag too, core/input_file.cpp).
  struct sigaction stop {};
  stop.sa_handler = onStopSignal;
  sigemptyset(&stop.sa_mask);
  stop.sa_flags = SA_RESETHAND;  // a second signal ends the program at once
  sigaction(SIGINT, &stop, nullptr);
  sigaction(SIGTERM, &stop, nullptr);
  auto usage = [](const Status& s) {
    cli::Terminal::error(s.message());
    return exitCode(s.code());
  };
  if (*forward) {
    if (!startANear.empty() && !parsePoint(startANear, forwardJob.forward.startA))
      return usage(Status(ErrorCode::Usage, "--start-a-near must look like X,Y"));
    if (!startBNear.empty() && !parsePoint(startBNear, forwardJob.forward.startB))
      return usage(Status(ErrorCode::Usage, "--start-b-near must look like X,Y"));
    if (!join.empty() && !parseJoin(join, forwardJob.forward.joinA, forwardJob.forward.joinB))
      return usage(Status(ErrorCode::Usage, "--join must be outer,outer, inner,inner, outer,inner or inner,outer"));
    if (!model.empty() && !parseModelChoice(model, forwardJob.forward.model))
      return usage(Status(ErrorCode::Usage, "--model must be auto, exact or paper"));
    forwardJob.forward.solve.weights = defaultWeights(forwardJob.forward.joinA, forwardJob.forward.joinB);
    for (const std::string& w : forwardWeights)
      if (Status s = setWeight(forwardJob, w); !s.isOk()) return usage(s);
    if (Status s = validateForwardJob(forwardJob.forward); !s.isOk()) return usage(s);
    return cli::runJob(forwardJob, forwardOut, interrupted);
  }
  if (*inverse) {
    for (const std::string& w : inverseWeights)
      if (Status s = setWeight(inverseJob, w); !s.isOk()) return usage(s);
    if (Status s = validateInverseJob(inverseJob.inverse); !s.isOk()) return usage(s);
    return cli::runJob(inverseJob, inverseOut, interrupted);
  }
  if (*sweep) {
    if (!sweepModel.empty() && !parseModelChoice(sweepModel, sweepJob.forward.model))
      return usage(Status(ErrorCode::Usage, "--model must be auto, exact or paper"));
    if (sweepFlip != "none" && sweepFlip != "flipped" && sweepFlip != "both")
      return usage(Status(ErrorCode::Usage, "--flip must be none, flipped or both"));
    if (sweepOptions.starts < 1 || sweepOptions.starts > 4096)
      return usage(Status(ErrorCode::Usage, "--starts must be between 1 and 4096"));
    if (sweepOptions.threads < 0)
      return usage(Status(ErrorCode::Usage, "--threads must be 0 (the machine's cores) or more"));
    sweepJob.forward.solve.weights = defaultWeights(sweepJob.forward.joinA, sweepJob.forward.joinB);
    sweepJob.forward.flip = sweepFlip == "flipped";
    sweepOptions.bothFlips = sweepFlip == "both";
    if (Status s = validateForwardJob(sweepJob.forward); !s.isOk()) return usage(s);
    return cli::runSweepCommand(sweepJob, sweepOptions, sweepOut, interrupted);
  }
  if (*batch) {
    if (!mergeDir.empty()) {
      if (!batchInput.empty() || !batchOut.outDir.empty())
        return usage(Status(ErrorCode::Usage, "batch --merge DIR takes no job list and no -o"));
      return cli::mergeBatchCommand(mergeDir);
    }
    if (batchInput.empty() || batchOut.outDir.empty())
      return usage(Status(ErrorCode::Usage, "batch needs a job list or folder and -o OUT (or --merge OUT)"));
    if (!parseShard(batchShard, batchOptions.shard, batchOptions.shards))
      return usage(Status(ErrorCode::Usage, "--shard must look like I/N with 1 <= I <= N, got '" + batchShard + "'"));
    if (batchOptions.threads < 0)
      return usage(Status(ErrorCode::Usage, "--threads must be 0 (the machine's cores) or more"));
    Result<std::vector<BatchJob>> jobs = listBatchJobs(batchInput);
    if (!jobs.isOk()) return usage(jobs.status());
    return cli::runBatchCommand(jobs.value(), batchOptions, batchOut, interrupted);
  }
  if (*runCommand) {
    Result<Job> job = readJobFile(jobPath);
    if (!job.isOk()) return usage(job.status());
    return cli::runJob(job.value(), runOut, interrupted);
  }
  if (*exportCommand) {
    if (listOnly) return cli::listProfiles();
    if (exportDir.empty()) return usage(Status(ErrorCode::Usage, "export needs a result folder"));
    return cli::exportSaved(exportDir, exportOut, interrupted);
  }
  return cli::validateSaved(validateDir, validateGate);
}

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemory();
  try {
    const int code = run(argc, argv);
    // Interrupted: 130 for Ctrl-C, 143 for SIGTERM, as a shell reports a process they ended.
    const int interruptedCode = dform::exitCode(dform::ErrorCode::Interrupted);
    return code == interruptedCode && stopSignal ? 128 + stopSignal : code;
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
