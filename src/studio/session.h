// SPDX-License-Identifier: GPL-3.0-or-later
// One browser tab's design: its outlines (or seam curve), its solves and its event stream. Newest
// input wins: a solve cancels the one before it. An exact solve answers with the shape meshed
// sparsely, a paper-model solve with a coarse preview, and a worker streams the result as the
// job makes it (progress, then the shape with its figures and verdict) as events.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/pipeline/forward_pipeline.h"

namespace dform::studio {

/// An input as the page gave it: the name it is saved under, the text as uploaded or generated,
/// and what the reader made of it.
struct PieceInput {
  std::string name, text;
  Shape2 shape;
};
struct CurveInput {
  std::string name, text;
  Curve3 curve;
  bool forceClosed = false;  ///< an open polyline was closed (`--closed`)
};

/// Server-sent events of one session: a bounded queue that each open stream reads from its own
/// position.
class EventStream {
 public:
  /// Queues one event (a JSON object; its "type" names it).
  void push(const nlohmann::json& event);
  /// Waits up to `timeout` for events from `position` on (0: from the oldest kept); returns them
  /// as SSE text ("id: <position>\ndata: ...\n\n" each) and moves `position` on. Empty on
  /// timeout or once closed. The ids let a client that reconnects (an EventSource sends the last
  /// id it saw as Last-Event-ID) resume where it stopped instead of losing what came between.
  std::string waitAfter(long& position, std::chrono::milliseconds timeout);
  void close();
  bool closed() const;
  /// Called after each push (outside the stream's lock): the server sends the news at once.
  void onPush(std::function<void()> listener);
  long end() const;  ///< the position after the newest event
  /// Where a stream starts: after `lastId`, the Last-Event-ID a reconnecting client sends (a
  /// number below end(); anything else is ignored), else at end(), the news from now on.
  long resumeAfter(const std::string& lastId) const;

 private:
  static constexpr std::size_t kKept = 256;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::string> events_;
  long next_ = 0;  ///< the number the next event gets
  bool closed_ = false;
  std::function<void()> onPush_;
};

/// Tickets of which only the newest is current: taking one cancels the one before.
class Latest {
 public:
  struct Ticket {
    long generation = 0;
    std::shared_ptr<std::atomic<bool>> cancel;
  };
  /// A new current ticket, cancelling the one before; `cancel`, when given, is its flag (set also
  /// by its owner: a request whose client went away).
  Ticket next(std::shared_ptr<std::atomic<bool>> cancel = nullptr);
  /// A ticket of the same generation as `ticket` with a flag of its own, cancelled by newer
  /// tickets and cancel() only: work queued for the page (a refinement, a verdict) that must
  /// outlive the request that asked for it, whose client goes once it has its answer.
  Ticket follow(const Ticket& ticket);
  bool current(const Ticket& ticket) const;
  void cancel();

 private:
  mutable std::mutex mutex_;
  long generation_ = 0;
  std::vector<std::shared_ptr<std::atomic<bool>>> flags_;  ///< the current generation's
};

/// A solve's answer for the page (wire.h): its shape, and its figures with the gate's verdict on
/// them ({"figures", "gate"}), which the live loop sends as an event after the shape (measuring
/// the shape and the gate's checks cost as much again as an exact solve).
struct Solved {
  nlohmann::json result;
  std::function<nlohmann::json()> verdict;
  /// The shape was meshed sparsely (Interior::Sparse) and is the job's shape all the same: the
  /// exact model's body, which every mesh of it draws alike (its triangles follow the body's
  /// folds).
  bool sparse = false;
};

/// How finely a solve meshes the pieces' interiors: as the job says, or as coarsely as the mesher
/// allows where that shows the same shape (the exact model; any other model is meshed as the job
/// says). A sparse answer is drawn at once and its mesh as the job says follows with the figures.
enum class Interior { Job, Sparse };

/// A solve at a seam resolution, or why it failed.
using SolveAt =
    std::function<Result<Solved>(int resolution, Interior interior, const RunHooks& hooks)>;

class Session {
 public:
  Session(PieceInput a, PieceInput b);
  ~Session();  ///< cancels its solves and joins its worker

  void setPiece(int which, PieceInput input);  ///< 0: A, 1: B
  PieceInput piece(int which) const;
  void setCurve(CurveInput input);
  std::optional<CurveInput> curve() const;

  /// Solves at `resolution` for the request numbered `seq`; newer requests cancel it (answer
  /// {"superseded": true}). The figures and the gate's verdict follow as a "gate" event, sent
  /// only while no newer solve was asked for. An exact result is answered meshed sparsely, with
  /// "refining": true, and the worker streams it meshed as the job says with its figures and
  /// verdict (a "result" event). Where the solve turns out to need the paper model's optimisation
  /// (or `optimises` says so, or the last solve of the same `design` did), the answer is a
  /// preview at kPreviewResolution with "preview" and "refining" true, and the worker streams the
  /// full solve ("progress" and "result" events). `design` names what decides the model: the
  /// pieces and every setting, the starts included (the glued metric's convexity depends on where
  /// the seam starts, so every new position asks the exact engine first). `cancel`, when given,
  /// stops the solve when set (its client went away), as newer input does.
  nlohmann::json solveLive(const SolveAt& solve, int resolution, bool optimises, long seq,
                           const std::string& design,
                           std::shared_ptr<std::atomic<bool>> cancel = nullptr);

  /// The page's input has settled at its request `seq` (a drag was released there): the
  /// refinement of that request starts without waiting kRefinementQuiet, whether its live request
  /// was answered already or is still on its way. A live request numbered above `seq` holds
  /// refinements again; a settle older than the newest live request changes nothing.
  void settle(long seq);
  /// When the worker may start the refinement waiting for it (steady clock): kRefinementQuiet
  /// after the last live request, or at once once the input has settled.
  std::chrono::steady_clock::time_point refinementDue() const;

  /// Solves each of `starts` (queued to the worker, one "strip" event each, then "strip_done"),
  /// cancelling the strip asked for before.
  void startStrip(std::vector<std::pair<nlohmann::json, SolveAt>> starts, long seq);

  EventStream& events() { return *events_; }
  /// The events, for a stream that must not keep the session (its solves and worker) alive.
  std::shared_ptr<EventStream> eventStream() const { return events_; }

  /// Seam vertices of a live preview (where the paper model or the ruled engine makes the shape),
  /// as at the paper model's coarsest level: few enough that a drag gets a shape within 150 ms of
  /// every move. At 36 the non-convex sample's preview is several times slower where its shape is
  /// about to change, the paper model's relaxation drifting along a soft mode (docs/benchmarks.md,
  /// "Studio").
  static constexpr int kPreviewResolution = 24;
  /// Seam vertices of the alternative-starts strip's cards (solved in the background).
  static constexpr int kStripResolution = 36;
  /// The nice value of the session's worker thread (measuring, the gate, refinements, the strip):
  /// on a busy machine it yields to the live solves and the page.
  static constexpr int kWorkerNice = 5;
  /// The least time between a refinement's progress events: each one repaints the page, which
  /// costs a software-rendered browser a frame's worth of a core that the refinement needs.
  static constexpr std::chrono::milliseconds kProgressInterval{250};
  /// A refinement's first progress event comes once it has run this long: one that ends sooner
  /// shows the preview's "refining…" until its result, and takes no core from the refinement to
  /// repaint the page meanwhile (docs/benchmarks.md, "Studio").
  static constexpr std::chrono::milliseconds kProgressDelay{1000};
  /// How long after the last live request a refinement may start: during a drag every new
  /// position cancels the refinement of the one before, and one begun in between costs the page
  /// (on two cores) the CPU it draws the live shapes with.
  static constexpr std::chrono::milliseconds kRefinementQuiet{80};

 private:
  void work();
  enum class Task { Gate, Refinement, Strip };
  void queue(std::function<void()> task, Task kind);
  /// Where an answer's figures and verdict go: into it, as a "gate" event after it, or nowhere
  /// (a refinement that carries its own follows it).
  enum class Verdict { InAnswer, AsEvent, WithRefinement };
  nlohmann::json finish(const Result<Solved>& result, const Latest::Ticket& ticket, long seq,
                        bool preview, Verdict verdict);
  /// Queues the worker's solve of `resolution` meshed as the job says, streamed as a "result"
  /// event with its figures and verdict unless newer input came first (a ticket following
  /// `live`: the live request's client going once it has its answer does not stop it).
  void queueRefinement(const SolveAt& solve, int resolution, const Latest::Ticket& live, long seq);

  mutable std::mutex inputMutex_;
  PieceInput pieces_[2];
  std::optional<CurveInput> curve_;

  std::mutex solveMutex_;  ///< one live or strip solve at a time per session
  /// Live solves waiting for solveMutex_: the worker's tasks let them go first (a mutex is not
  /// fair, and a strip's back-to-back solves would otherwise hold a drag for seconds).
  std::atomic<int> liveWaiting_{0};
  /// When the last live request came (steady clock; none: the epoch), the newest live request's
  /// seq and the newest settled one (refinementDue).
  mutable std::mutex liveTimesMutex_;
  std::chrono::steady_clock::time_point lastLive_{};
  long newestLive_ = std::numeric_limits<long>::min();
  long settled_ = std::numeric_limits<long>::min();
  std::unique_lock<std::mutex> lockAfterLive();
  /// The last design (position included) whose solve optimised (under solveMutex_).
  std::string optimisedDesign_;
  Latest live_, strip_;
  std::shared_ptr<EventStream> events_ = std::make_shared<EventStream>();

  std::mutex workMutex_;
  std::condition_variable workReady_;
  std::optional<std::function<void()>> gate_, refinement_;
  std::deque<std::function<void()>> stripTasks_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace dform::studio
