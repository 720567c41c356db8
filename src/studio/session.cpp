// SPDX-License-Identifier: GPL-3.0-or-later
#include "session.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>

#include "dform/core/interrupt.h"

namespace dform::studio {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

// A solve that its hooks' flag (newer input, a client gone) stops inside its long steps too
// (meshing, the exact body, the figures), not only between iterations.
Result<Solved> solveStoppable(const SolveAt& solve, int resolution, Interior interior,
                              const RunHooks& hooks) {
  const ScopedStop stop(hooks.interrupted);
  return solve(resolution, interior, hooks);
}

}  // namespace

void EventStream::push(const json& event) {
  std::function<void()> listener;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    events_.push_back("id: " + std::to_string(next_) + "\ndata: " + event.dump() + "\n\n");
    ++next_;
    while (events_.size() > kKept) events_.pop_front();
    listener = onPush_;
  }
  changed_.notify_all();
  if (listener) listener();
}

void EventStream::onPush(std::function<void()> listener) {
  std::lock_guard<std::mutex> lock(mutex_);
  onPush_ = std::move(listener);
}

std::string EventStream::waitAfter(long& position, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return closed_ || next_ > position; });
  if (closed_) return "";
  const long oldest = next_ - long(events_.size());
  std::string out;
  for (long k = std::max(position, oldest); k < next_; ++k) out += events_[std::size_t(k - oldest)];
  position = next_;
  return out;
}

void EventStream::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

long EventStream::end() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_;
}

long EventStream::resumeAfter(const std::string& lastId) const {
  const long newest = end();
  if (lastId.empty() || lastId.size() > 18 ||
      lastId.find_first_not_of("0123456789") != std::string::npos)
    return newest;
  const long seen = std::stol(lastId);
  return seen < newest ? seen + 1 : newest;
}

bool EventStream::closed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return closed_;
}

Latest::Ticket Latest::next(std::shared_ptr<std::atomic<bool>> cancel) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& flag : flags_) flag->store(true);
  flags_.assign(1, cancel ? std::move(cancel) : std::make_shared<std::atomic<bool>>(false));
  return {++generation_, flags_.front()};
}

Latest::Ticket Latest::follow(const Ticket& ticket) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto flag = std::make_shared<std::atomic<bool>>(ticket.generation != generation_);
  if (ticket.generation == generation_) flags_.push_back(flag);
  return {ticket.generation, std::move(flag)};
}

bool Latest::current(const Ticket& ticket) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ticket.generation == generation_ && !ticket.cancel->load();
}

void Latest::cancel() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& flag : flags_) flag->store(true);
}

Session::Session(PieceInput a, PieceInput b) : pieces_{std::move(a), std::move(b)} {
  worker_ = std::thread([this] { work(); });
}

Session::~Session() {
  {
    std::lock_guard<std::mutex> lock(workMutex_);
    stopping_ = true;
  }
  live_.cancel();
  strip_.cancel();
  events_->close();
  workReady_.notify_all();
  worker_.join();
}

void Session::setPiece(int which, PieceInput input) {
  std::lock_guard<std::mutex> lock(inputMutex_);
  pieces_[which] = std::move(input);
}

PieceInput Session::piece(int which) const {
  std::lock_guard<std::mutex> lock(inputMutex_);
  return pieces_[which];
}

void Session::setCurve(CurveInput input) {
  std::lock_guard<std::mutex> lock(inputMutex_);
  curve_ = std::move(input);
}

std::optional<CurveInput> Session::curve() const {
  std::lock_guard<std::mutex> lock(inputMutex_);
  return curve_;
}

// The answer to the page: the result, or superseded, or the error, with its figures and the
// gate's verdict where `verdict` says so.
json Session::finish(const Result<Solved>& result, const Latest::Ticket& ticket, long seq,
                     bool preview, Verdict verdict) {
  if (!result.isOk()) {
    if (ticket.cancel->load()) return {{"seq", seq}, {"superseded", true}};
    return {{"seq", seq}, {"error", result.status().message()}};
  }
  json out = result.value().result;
  out["seq"] = seq;
  out["preview"] = preview;
  out["refining"] = false;
  if (verdict == Verdict::InAnswer) out.update(result.value().verdict());
  if (verdict == Verdict::AsEvent)
    queue(
        [this, verdict = result.value().verdict, ticket = live_.follow(ticket), seq, preview] {
          if (!live_.current(ticket)) return;
          json event = verdict();
          if (!live_.current(ticket)) return;
          event.update({{"type", "gate"}, {"seq", seq}, {"preview", preview}});
          events_->push(event);
        },
        Task::Gate);
  return out;
}

// The refinement does not take the session's solve lock: newer input cancels it (its hooks poll
// the ticket), and on the worker's lower priority it yields the cores to the live solve anyway,
// which would otherwise wait for a whole refinement and its measuring.
void Session::queueRefinement(const SolveAt& solve, int resolution, const Latest::Ticket& live,
                              long seq) {
  queue(
      [this, solve, resolution, ticket = live_.follow(live), seq] {
        if (!live_.current(ticket)) return;
        auto due = Clock::now() + kProgressDelay;
        RunHooks progress;
        progress.interrupted = ticket.cancel.get();
        progress.onIteration = [&](const char* stage, const IterationSummary& it) {
          if (Clock::now() < due) return;
          due = Clock::now() + kProgressInterval;
          events_->push({{"type", "progress"},
                         {"seq", seq},
                         {"stage", stage},
                         {"iteration", it.iteration},
                         {"cost", it.cost}});
        };
        json result = finish(solveStoppable(solve, resolution, Interior::Job, progress), ticket,
                             seq, false, Verdict::InAnswer);
        if (result.contains("superseded") || !live_.current(ticket)) return;
        result["type"] = "result";
        events_->push(result);
      },
      Task::Refinement);
}

json Session::solveLive(const SolveAt& solve, int resolution, bool optimises, long seq,
                        const std::string& design, std::shared_ptr<std::atomic<bool>> cancel) {
  {
    const std::lock_guard<std::mutex> lock(liveTimesMutex_);
    newestLive_ = std::max(newestLive_, seq);
    if (seq > settled_) lastLive_ = Clock::now();
  }
  const Latest::Ticket ticket = live_.next(std::move(cancel));
  ++liveWaiting_;
  std::unique_lock<std::mutex> lock(solveMutex_);
  --liveWaiting_;
  if (!live_.current(ticket)) return {{"seq", seq}, {"superseded", true}};
  const int preview = std::min(resolution, kPreviewResolution);
  bool refine = (optimises || design == optimisedDesign_) && preview < resolution;
  if (!refine) {
    // Solve in full unless the run starts to optimise (the paper model: its first iteration),
    // which is then stopped and previewed instead. Newer input stops it as well.
    std::atomic<bool> stop{false};
    bool optimising = false;
    RunHooks probe;
    probe.interrupted = &stop;
    probe.onIteration = [&](const char*, const IterationSummary&) {
      if (preview < resolution) optimising = true;
      if (optimising || ticket.cancel->load()) stop = true;
    };
    Result<Solved> full = solveStoppable(solve, resolution, Interior::Sparse, probe);
    if (!optimising) {
      if (!full.isOk() || !full.value().sparse)
        return finish(full, ticket, seq, false, Verdict::AsEvent);
      // The job's shape, meshed sparsely: its mesh as the job says follows, measured and judged.
      json out = finish(full, ticket, seq, false, Verdict::WithRefinement);
      out["refining"] = true;
      queueRefinement(solve, resolution, ticket, seq);
      return out;
    }
    optimisedDesign_ = design;
    refine = true;
  }
  RunHooks hooks;
  hooks.interrupted = ticket.cancel.get();
  json out = finish(solveStoppable(solve, preview, Interior::Job, hooks), ticket, seq, true,
                    Verdict::AsEvent);
  if (!out.contains("error") && !out.contains("superseded")) {
    out["refining"] = true;
    queueRefinement(solve, resolution, ticket, seq);
  }
  return out;
}

void Session::settle(long seq) {
  {
    const std::lock_guard<std::mutex> lock(liveTimesMutex_);
    if (seq < newestLive_) return;
    settled_ = std::max(settled_, seq);
    lastLive_ = Clock::time_point{};
  }
  // Through the worker's mutex: a worker that read the old due time is waiting by now.
  { const std::lock_guard<std::mutex> lock(workMutex_); }
  workReady_.notify_one();
}

Clock::time_point Session::refinementDue() const {
  const std::lock_guard<std::mutex> lock(liveTimesMutex_);
  return lastLive_ + kRefinementQuiet;
}

void Session::startStrip(std::vector<std::pair<json, SolveAt>> starts, long seq) {
  const Latest::Ticket ticket = strip_.next();
  {
    std::lock_guard<std::mutex> lock(workMutex_);
    stripTasks_.clear();
  }
  const int count = int(starts.size());
  for (int k = 0; k < count; ++k) {
    auto [card, solve] = std::move(starts[std::size_t(k)]);
    queue(
        [this, card = std::move(card), solve = std::move(solve), ticket, seq, k, count] {
          std::unique_lock<std::mutex> solving = lockAfterLive();
          if (!strip_.current(ticket)) return;
          RunHooks hooks;
          hooks.interrupted = ticket.cancel.get();
          Result<Solved> result = solveStoppable(solve, kStripResolution, Interior::Job, hooks);
          if (!strip_.current(ticket)) return;
          json event = card;
          event["type"] = "strip";
          event["seq"] = seq;
          event["index"] = k;
          if (result.isOk()) {
            event["result"] = result.value().result;
            event["result"].update(result.value().verdict());
            event["result"].erase("overlay");  // a card shows no overlay
          } else {
            event["error"] = result.status().message();
          }
          events_->push(event);
          if (k + 1 == count) events_->push({{"type", "strip_done"}, {"seq", seq}});
        },
        Task::Strip);
  }
}

std::unique_lock<std::mutex> Session::lockAfterLive() {
  for (;;) {
    while (liveWaiting_.load() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::unique_lock<std::mutex> lock(solveMutex_);
    if (liveWaiting_.load() == 0) return lock;
  }
}

void Session::queue(std::function<void()> task, Task kind) {
  {
    std::lock_guard<std::mutex> lock(workMutex_);
    if (kind == Task::Gate) gate_ = std::move(task);
    if (kind == Task::Refinement) refinement_ = std::move(task);
    if (kind == Task::Strip) stripTasks_.push_back(std::move(task));
  }
  workReady_.notify_one();
}

// The worker: the newest shape's gate first, then the newest refinement once the live requests
// have paused (kRefinementQuiet), then the strip's starts one at a time, so that neither waits
// for a whole strip. Its thread runs at a lower priority (Linux: a thread's own nice value) than
// the live solves, answered on the server's threads, and the browser drawing them: on a busy
// machine a shape's measuring must not delay the next shape.
void Session::work() {
  setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), kWorkerNice);  // best effort: not fatal
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock<std::mutex> lock(workMutex_);
      workReady_.wait(lock,
                      [&] { return stopping_ || gate_ || refinement_ || !stripTasks_.empty(); });
      if (stopping_) return;
      if (gate_) {
        task = std::move(*gate_);
        gate_.reset();
      } else if (refinement_) {
        const auto due = refinementDue();
        if (Clock::now() < due) {
          workReady_.wait_until(lock, due);
          continue;
        }
        task = std::move(*refinement_);
        refinement_.reset();
      } else {
        task = std::move(stripTasks_.front());
        stripTasks_.pop_front();
      }
    }
    task();
  }
}

}  // namespace dform::studio
