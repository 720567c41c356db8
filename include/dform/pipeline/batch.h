// SPDX-License-Identifier: GPL-3.0-or-later
// Batches: many job files, each run into OUT/<job name>/, with a manifest (batch.json)
// rewritten atomically as jobs finish, so that a batch can be resumed, sharded over a cluster's
// scheduler (GNU parallel, a Slurm array) and its shards' manifests merged (docs/batch.md).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "dform/core/status.h"
#include "dform/pipeline/sweep.h"

namespace dform {

/// One job of a batch: its file and the result folder's name (the file's stem).
struct BatchJob {
  int index = 0;       ///< its place in the batch's list, from 0
  std::string path;    ///< the job file, as listed (relative paths of a list file: from its folder)
  std::string name;    ///< `OUT/<name>/`
  std::string sha256;  ///< the JobFacts sha256 of the job when the batch listed it
  double size = 1;     ///< its share of the batch's work (JobFacts size)
};

/// What a batch knows of a job file, from one read of it (so that both describe the same
/// version of a file edited meanwhile):
/// - sha256: what its result is made from, as one SHA-256 of the job file's bytes and those of
///   the inputs it names (the pieces, or the curve). A job file or an input edited since gives
///   another; an input that cannot be read counts as missing; empty when the job file is
///   unreadable.
/// - size: its share of the batch's work, for the time left: the square of its resolution
///   (forward or inverse; vertices grow with it), 1 when the job file cannot be read or parsed.
struct JobFacts {
  std::string sha256;  ///< of the job file and its inputs (see above); empty when unreadable
  double size = 1;     ///< its share of the batch's work (see above)
};
JobFacts readJobFacts(const std::string& jobPath);

/// Seconds left at the pace so far: `elapsed` seconds finished jobs of total size `doneSize`,
/// so jobs of total size `remainingSize` take elapsed * remainingSize / doneSize. NaN (unknown)
/// until a job of some size has finished.
double estimateSecondsLeft(double elapsed, double doneSize, double remainingSize);

/// The identity of a batch's job list: how many jobs, and one SHA-256 of every job's name and
/// job file sha256 (JobFacts) in list order. Shards run from the same list and the same files agree
/// on it.
struct JobList {
  int count = -1;      ///< -1: not recorded
  std::string sha256;  ///< of every job's name and JobFacts sha256, in list order
};
JobList jobListOf(const std::vector<BatchJob>& jobs);

/// Whether `name` can be a job's result folder in OUT: not empty, at most 255 bytes, not hidden
/// (".x": the folders' locks), no '/', and none of the batch's own files (batch.json,
/// gallery.html, batch-shard-I-of-N.json, gallery-shard-I-of-N.html).
bool isJobName(const std::string& name);

/// The jobs of `input`: a text file with one job file per line (blank lines and lines starting
/// with # skipped; relative paths from the list's folder), or every *.json in a folder, sorted by
/// name, each with its JobFacts. InputUnreadable naming the file; InputInvalid when the list is
/// empty, two jobs have the same name, or a name is not isJobName (all refused before anything
/// runs).
Result<std::vector<BatchJob>> listBatchJobs(const std::string& input);

/// Shard `shard` of `shards` (1-based): job k belongs to shard k % shards + 1.
std::vector<BatchJob> shardOf(const std::vector<BatchJob>& jobs, int shard, int shards);

/// "i/N" (decimal digits only) -> {i, N}; false unless 1 <= i <= N <= 1000000.
bool parseShard(const std::string& text, int& shard, int& shards);

/// A finished job: what happened and what its saved result measures.
struct BatchRow {
  BatchJob job;         ///< the job as the batch listed it
  std::string status;   ///< "done", "gate-failed" (result written), "failed" (no result)
  int exitCode = 0;     ///< as `dform run` of the job would exit (pipeline/exit_code.h)
  std::string message;  ///< the error, for a job that failed
  SweepRow figures;     ///< measured on `OUT/<name>/` when a result was written
  double seconds = 0;   ///< the job's wall time, seconds
};

/// What one job's run gives: the exit code `dform run` would give and the error, if any.
struct JobOutcome {
  int exitCode = 0;     ///< the exit code `dform run` of the job would give
  std::string message;  ///< the error, for a job that failed; else empty
};

/// Runs one job into `dir`; called from several threads at once.
using BatchRunner = std::function<JobOutcome(const std::string& jobPath, const std::string& dir)>;

/// Progress after each finished job: done (of total, this run's), failed, and the seconds left by
/// estimateSecondsLeft over the jobs' sizes (NaN: unknown).
using BatchProgress = std::function<void(int done, int failed, int total, double secondsLeft)>;

/// Which slice of a batch runs, whether finished jobs are skipped, and how many run at once.
struct BatchOptions {
  int shard = 1;        ///< run only this slice: shard `shard` (from 1) ...
  int shards = 1;       ///< ... of this many
  bool resume = false;  ///< skip jobs the manifest has as finished with their result in
                        ///< place and the same JobFacts sha256 as now
  int threads = 0;      ///< jobs at once; 0: the machine's cores
};

/// The manifest's file name in OUT: batch.json, or batch-shard-I-of-N.json for a shard (so that
/// shards running at once never write the same file).
std::string manifestName(const BatchOptions& options);

/// The gallery's file name in OUT: gallery.html, or gallery-shard-I-of-N.html for a shard.
std::string galleryName(const BatchOptions& options);

/// Runs the options' shard of `jobs` into `outDir` (created when missing), rewriting the
/// manifest atomically after each job. A lock in `outDir` keeps a second batch off it (shards
/// of one batch may run side by side, each on its own manifest): OutputFailed at once naming the
/// process that holds it. An exception in a job is that job's failure. Draws the slice's gallery
/// (galleryName) when all have run. Returns every row of the manifest (resumed ones too), in job
/// order. Interrupted when `interrupted` is set (the finished jobs are in the manifest);
/// OutputFailed naming the file.
Result<std::vector<BatchRow>> runBatch(const std::vector<BatchJob>& jobs,
                                       const BatchOptions& options, const std::string& outDir,
                                       const BatchRunner& run, const BatchProgress& progress,
                                       const std::atomic<bool>& interrupted);

/// A merge: the rows gathered, how many jobs the list has (-1: not recorded), and the jobs with
/// no row in any manifest: how many, and the first kMissingNamed of them in list order (by name
/// where a manifest lists it, else "#K", K its place in the list from 0).
constexpr int kMissingNamed = 5;
/// The shards' manifests of one batch merged (mergeBatch; see kMissingNamed).
struct MergedBatch {
  std::vector<BatchRow> rows;             ///< every finished job's row, in list order
  int jobCount = 0;                       ///< the jobs the list has (-1: not recorded)
  int missingCount = 0;                   ///< jobs with no row in any manifest
  std::vector<std::string> firstMissing;  ///< the first kMissingNamed of them
};

/// The missing jobs for a message: "a, b, #7, d, e and 3 more".
std::string missingText(const MergedBatch& merged);

/// Gathers every manifest in `outDir` (batch.json and the shards') into batch.json, one row per
/// job (the latest where several have it), in job order, and gallery.html. A job is finished when
/// a manifest has its row (done, gate-failed or failed); a job interrupted or never run has none.
/// SolveFailed (exit 5) listing the missing jobs unless every job of the list has finished or
/// `allowPartial`; InputUnreadable when there is no manifest, InputInvalid naming a manifest that
/// is not one, or the manifests that were run from different job lists (another order, other
/// jobs, a job or an input edited in between): nothing is written then. OutputFailed while a
/// batch runs in `outDir`.
Result<MergedBatch> mergeBatch(const std::string& outDir, bool allowPartial);

}  // namespace dform
