// SPDX-License-Identifier: GPL-3.0-or-later
// Design sweeps: one forward job solved from N starting pairs evenly spaced along piece
// B (and with B turned over), each into a subfolder of its own, gathered into sweep.json and
// gallery.html. The sweep folder is written as one transaction (core/result_folder.h).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/pipeline/job_file.h"

namespace dform {

/// Which starting pairs a sweep runs and how many at once.
struct SweepOptions {
  int starts = 8;          ///< starting pairs along B: start_b = k / starts, k = 0 .. starts-1
  bool bothFlips = false;  ///< also every start with B turned over
  int threads = 0;         ///< jobs solved at once; 0: std::thread::hardware_concurrency()
};

/// One start of the sweep: its job and the subfolder its result goes into.
struct SweepStart {
  Job job;                ///< the base job with this start and flip
  double startB = 0;      ///< piece B's start: an arc-length fraction in [0, 1)
  bool flip = false;      ///< piece B turned over
  std::string subfolder;  ///< "start-03" or "start-03-flip" (zero-padded to the count's width)
};

/// The jobs of a sweep: `base` with start_b = k / starts, unflipped first, then (bothFlips) the
/// flipped ones. Starts as given in `base` for A are kept.
std::vector<SweepStart> sweepStarts(const Job& base, const SweepOptions& options);

/// One gallery card, one sweep.json row: a start and what its saved result measures.
struct SweepRow {
  double startB = 0;        ///< piece B's start: an arc-length fraction in [0, 1)
  bool flip = false;        ///< piece B turned over
  std::string subfolder;    ///< the result's subfolder of the sweep's folder
  std::string label;        ///< the card's first line: "start B 0.1250 flipped", a job's name
  bool solved = false;      ///< the run wrote a result (else `reason` says why not)
  std::string model;        ///< "exact" or "paper", as report.json records it
  double heightMm = 0;      ///< z extent of the 3D shape as solved (both pieces)
  double volumeMm3 = 0;     ///< signed volume enclosed by the closed 3D mesh (A and B)
  double maxCurvature = 0;  ///< largest |curvature| (angle defect, rad) of either piece
  bool passed = false;      ///< the gate passed (false without a gate)
  std::vector<std::string> failing;  ///< names of the failed gate checks
  std::string reason;  ///< why the row failed: the run's error, or the failed checks' details
  double seconds = 0;  ///< the run's wall time, start to commit
  std::string svg;     ///< the 3D shape from the gallery's camera (empty when not solved)
  ErrorCode error = ErrorCode::Ok;  ///< how the start's run failed (OutputFailed: not written)
};

/// Runs one start: writes a complete result into `dir` (a fresh folder) or returns why not.
/// Called from several threads at once, each with its own sink.
using SweepRunner =
    std::function<Status(const Job& job, const std::string& dir, MessageSink& sink)>;

/// Progress after each finished start: done (of total), failed (not solved or gate failed), and
/// the seconds since the sweep began.
using SweepProgress = std::function<void(int done, int failed, int total, double seconds)>;

/// Locks and stages `outDir` (which must be missing or empty, or hold only an earlier sweep:
/// sweep.json, gallery.html and start-K[-flip] folders, all replaced), runs every start with `run`
/// on a pool of threads, measures each saved result, writes sweep.json and gallery.html, and swaps
/// the folder in. Interrupted when `interrupted` is set meanwhile (the folder is left as it was);
/// OutputFailed naming the file. `progress` is called under a lock, one call at a time; what the
/// swap kept that appeared in the folder meanwhile is a warning in `notes`.
Result<std::vector<SweepRow>> runSweep(const Job& base, const SweepOptions& options,
                                       const std::string& outDir, const SweepRunner& run,
                                       const SweepProgress& progress,
                                       const std::atomic<bool>& interrupted,
                                       MessageSink* notes = nullptr);

/// `run()`, or an exception it throws as a Status (Internal naming the exception, Usage for an
/// allocation that failed): one job of many fails, not the process.
Status runGuarded(const std::function<Status()>& run);

/// Calls `work(k)` for k = 0 .. count-1 on `threads` threads (0: the machine's cores), each k
/// once, stopping to hand out new ones once `stop` is set. `work` must be safe to call at once
/// from several threads. An exception thrown by `work` stops the handing out and is thrown
/// again once every thread has finished.
void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& work,
                 const std::atomic<bool>& stop);

/// OutputFailed naming the starts of `rows` whose result could not be written (a full disk): the
/// sweep's other results are in place, but it did not do what was asked, as a batch fails for its
/// jobs. Ok when every start was written (solved or not).
Status unwrittenStarts(const std::string& outDir, const std::vector<SweepRow>& rows);

/// The measured row of a saved result folder (report.json and the meshes).
SweepRow measureResult(const std::string& dir);

/// sweep.json's text: the pieces, the options and every row (schema: docs/sweep.md).
std::string sweepJson(const Job& base, const SweepOptions& options,
                      const std::vector<SweepRow>& rows);

/// gallery.html: a self-contained page headed `title`, one card per row with its picture and
/// figures, sortable by the figures (and back to the rows' order), each linking to its
/// subfolder's report.html; failed rows greyed with why.
std::string galleryHtml(const std::string& title, const std::vector<SweepRow>& rows);

}  // namespace dform
