// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/studio/studio.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <map>
#include <mutex>
#include <thread>

#include "dform/core/input_file.h"
#include "dform/core/interrupt.h"
#include "dform/io/curve_reader.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/job_file.h"
#include "dform/pipeline/run.h"
#include "dform/pipeline/settings.h"
#include "downloads.h"
#include "guard.h"
#include "outlines.h"
#include "server.h"
#include "session.h"
#include "wire.h"
#include "zip.h"

// Last: glibc's resolv.h, which it includes, defines _res, a name Eigen's headers use.
#include <httplib.h>

namespace dform {

namespace fs = std::filesystem;
using nlohmann::json;
using studio::CurveInput;
using studio::pieceIndex;
using studio::PieceInput;
using studio::RequestError;
using studio::requiredText;
using studio::sequence;
using studio::Session;

namespace {

const std::vector<std::string> kOutlineExtensions = {".svg", ".json"};
const std::vector<std::string> kCurveExtensions = {".obj", ".json"};
const char* const kAssets[] = {"index.html", "studio.js",  "studio.css",   "view3d.js",
                               "pieces.js",  "strip.js",   "downloads.js", "overlay.js",
                               "picking.js", "preview.js", "states.js"};

// JSON answers, sent uncompressed as every answer is (the server drops the request's
// Accept-Encoding: on loopback compression only costs time, brotli on a 150 KB shape about a
// second on a loaded 2-core machine).
void reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json; charset=utf-8");
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

// A piece's outline, read from its text as the command line reads its file.
PieceInput readPiece(const std::string& name, std::string text) {
  Result<Shape2> shape = parseOutline(text, name);
  if (!shape.isOk()) throw RequestError(shape.status().message());
  return {name, std::move(text), std::move(shape).value()};
}

CurveInput readCurveInput(const std::string& name, std::string text, bool forceClosed) {
  CurveReadOptions options;
  options.forceClosed = forceClosed;
  Result<Curve3> curve = parseCurve(text, name, options);
  if (!curve.isOk()) throw RequestError(curve.status().message());
  return {name, std::move(text), std::move(curve).value(), forceClosed};
}

// The gate's verdict on a solved shape, or an error once the studio is being stopped (Ctrl-C):
// the figures poll the stop flag and throw, and the worker that asked must not end the process.
json verdictUnlessStopped(const std::function<json()>& judge) {
  try {
    return judge();
  } catch (const Interrupted& stop) {
    return {{"error", interruptedDuring(stop.stage()).message()}};
  }
}

json pieceSummary(const PieceInput& piece) {
  json out = studio::shapeJson(piece.shape);
  out["name"] = piece.name;
  return out;
}

// What decides whether a forward solve optimises: the pieces and every setting, the starts (the
// studio's fractions) included, for the glued metric's convexity depends on where the seam starts.
std::string forwardDesign(const PieceInput& a, const PieceInput& b, const Job& job) {
  const std::hash<std::string> hash;
  const ForwardSettings& s = std::get<ForwardJob>(job.run);
  return std::to_string(hash(a.text)) + "/" + std::to_string(hash(b.text)) + "/" +
         studio::designSettings(job) + "/" + json{s.startA.fraction, s.startB.fraction}.dump();
}

// The shape first; its figures and the gate's verdict when the session asks for them (after the
// shape is on its way: measuring it costs as much again as the exact solve). Asked for a sparse
// interior, an exact result is meshed as coarsely as a job may be: the same body in fewer
// triangles. Any other model is meshed as the job says.
studio::SolveAt forwardSolve(const PieceInput& a, const PieceInput& b,
                             const ForwardSettings& settings, const GateLimits& gate) {
  return
      [a = a.shape, b = b.shape, settings, gate](int resolution, studio::Interior interior,
                                                 const RunHooks& hooks) -> Result<studio::Solved> {
        ForwardSettings s = settings;
        s.resolution = resolution;
        // The coarsest interior the settings table allows.
        const double coarsest = findSetting(settingKey(Setting::InteriorEdge), true)->max;
        const bool sparse = interior == studio::Interior::Sparse && s.interiorEdgeFactor < coarsest;
        if (sparse) s.interiorEdgeFactor = coarsest;
        MessageSink sink;
        const auto start = std::chrono::steady_clock::now();
        Result<SolvedDForm> made = shapeDForm(a, b, s, sink, hooks);
        if (sparse && made.isOk() && made.value().modelUsed.name != "exact") {
          s.interiorEdgeFactor = settings.interiorEdgeFactor;
          sink = MessageSink();
          made = shapeDForm(a, b, s, sink, hooks);
        }
        if (!made.isOk()) return made.status();
        auto run = std::make_shared<const SolvedDForm>(std::move(made).value());
        const double madeMs = millisecondsSince(start);
        json out = studio::forwardResultJson(*run);
        out["warnings"] = studio::warnings(sink.messages());
        out["timings"]["made"] = madeMs / 1000;
        out["timings"]["answer"] = (millisecondsSince(start) - madeMs) / 1000;
        const bool sparseExact = sparse && run->modelUsed.name == "exact";
        return studio::Solved{out,
                              [run, s, gate]() -> json {
                                Result<Metrics> metrics = measureDForm(*run, s, "the pieces");
                                if (!metrics.isOk()) return {{"error", metrics.status().message()}};
                                return verdictUnlessStopped([&] {
                                  return studio::verdictJson(
                                      run->model, metrics.value(),
                                      runGate(run->model, gate, metrics.value(), nullptr, nullptr));
                                });
                              },
                              sparseExact};
      };
}

studio::SolveAt inverseSolve(const CurveInput& curve, const InverseSettings& settings,
                             const GateLimits& gate) {
  return [curve = curve.curve, settings, gate](int resolution, studio::Interior,
                                               const RunHooks& hooks) -> Result<studio::Solved> {
    InverseSettings s = settings;
    s.resolution = resolution;
    MessageSink sink;
    Result<InverseRun> made = makePieces(curve, s, sink, hooks);
    if (!made.isOk()) return made.status();
    auto run = std::make_shared<const InverseRun>(std::move(made).value());
    json out = studio::inverseResultJson(*run);
    out["warnings"] = studio::warnings(sink.messages());
    return studio::Solved{out, [run, gate] {
                            return verdictUnlessStopped([&] {
                              return studio::verdictJson(run->model, run->metrics,
                                                         runGate(run->model, gate, run->metrics,
                                                                 &run->target, &run->curveMatch));
                            });
                          }};
  };
}

void sendZip(httplib::Response& res, const std::string& zip, const std::string& fileName) {
  res.set_header("Content-Disposition", "attachment; filename=\"" + fileName + "\"");
  res.set_content(zip, "application/zip");
}

}  // namespace

struct Studio::Impl {
  StudioOptions options;
  std::string token;
  int port = 0;
  GateLimits gate;
  std::map<std::string, std::string> assets;
  PieceInput startA, startB;
  /// The starting design's settings, of each mode: the job file's, else the table's defaults
  /// (but fit_perimeter, which the studio's starting design turns on, so that an outline of
  /// another perimeter is scaled to A's rather than refused).
  Job startForward, startInverse{InverseJob()};
  bool startsInverse = false;
  std::optional<CurveInput> startCurve;

  const Job& base(const json& body) const {
    return body.value("mode", "forward") == "inverse" ? startInverse : startForward;
  }

  std::mutex sessionsMutex;
  std::map<std::string, std::pair<std::shared_ptr<Session>, std::chrono::steady_clock::time_point>>
      sessions;
  std::atomic<bool> stopping{false};
  std::unique_ptr<studio::Server> server;
  bool stopped = false;

  std::shared_ptr<Session> session(const std::string& id) {
    std::lock_guard<std::mutex> lock(sessionsMutex);
    auto found = sessions.find(id);
    if (found == sessions.end()) return nullptr;
    found->second.second = std::chrono::steady_clock::now();
    return found->second.first;
  }

  std::string newSession() {
    auto created = std::make_shared<Session>(startA, startB);
    created->events().onPush([this] { server->wake(); });  // its streams are sent at once
    if (startCurve) created->setCurve(*startCurve);
    const std::string id = studio::randomToken().substr(0, 16);
    std::shared_ptr<Session> dropped;  // destroyed outside the lock: it joins its worker
    std::lock_guard<std::mutex> lock(sessionsMutex);
    if (int(sessions.size()) >= options.maxSessions) {
      auto oldest = sessions.begin();
      for (auto it = sessions.begin(); it != sessions.end(); ++it)
        if (it->second.second < oldest->second.second) oldest = it;
      dropped = oldest->second.first;
      sessions.erase(oldest);
    }
    sessions[id] = {created, std::chrono::steady_clock::now()};
    return id;
  }

  Status readStart();
  std::string tooLargeText() const {
    return "the request is larger than " + std::to_string(options.maxUploadBytes) + " bytes";
  }
  void guard(httplib::Server& server);
  void routes(httplib::Server& server);
  void pageRoutes(httplib::Server& server);
  void solveRoutes(httplib::Server& server);
  void api(httplib::Server& server, const char* path,
           std::function<void(const json&, Session&, httplib::Response&)> handle);
};

// The first design of every session: the files given, a job file's, or two built-in ellipses
// (the shipped sample pair's semi-axes: 120 x 70 and 110 x 82.3 mm, equal perimeters).
Status Studio::Impl::readStart() {
  auto piece = [](const std::string& path, const char* fallback) -> Result<PieceInput> {
    Result<std::string> text = readInputFile(path);
    if (!text.isOk()) return text.status();
    Result<Shape2> shape = parseOutline(text.value(), path);
    if (!shape.isOk()) return shape.status();
    return PieceInput{studio::safeFileName(path, kOutlineExtensions, fallback), text.value(),
                      shape.value()};
  };
  std::string a = options.pieceA, b = options.pieceB;
  std::get<ForwardJob>(startForward.run).fitPerimeter = true;
  if (!options.jobFile.empty()) {
    Result<Job> job = readJobFile(options.jobFile);
    if (!job.isOk()) return job.status();
    if (const ForwardJob* f = std::get_if<ForwardJob>(&job.value().run)) {
      a = f->pieceA;
      b = f->pieceB;
      startForward = job.value();
    } else {
      const InverseJob& i = std::get<InverseJob>(job.value().run);
      Result<std::string> text = readInputFile(i.curve);
      if (!text.isOk()) return text.status();
      try {
        startCurve = readCurveInput(studio::safeFileName(i.curve, kCurveExtensions, "curve.json"),
                                    text.value(), i.forceClosed);
      } catch (const RequestError& e) {
        return Status(ErrorCode::InputInvalid, e.what());
      }
      startInverse = job.value();
      startsInverse = true;
    }
  }
  if (a.empty()) {
    startA =
        readPiece("ellipse-a.json", studio::parametricOutline("ellipse", {{"a", 120}, {"b", 70}}));
    startB = readPiece("ellipse-b.json",
                       studio::parametricOutline("ellipse", {{"a", 110}, {"b", 82.305579}}));
    return Status::ok();
  }
  Result<PieceInput> readA = piece(a, "piece-a.svg"), readB = piece(b, "piece-b.svg");
  if (!readA.isOk()) return readA.status();
  if (!readB.isOk()) return readB.status();
  startA = readA.value();
  startB = readB.value();
  if (startB.name == startA.name) startB.name = "b-" + startB.name;
  return Status::ok();
}

// Every request: Host, Origin and token checked before anything is routed, and before its body
// is read: a refused request's connection is closed after its answer.
void Studio::Impl::guard(httplib::Server& server) {
  server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    studio::RequestFacts facts{
        req.get_header_value("Host"),           req.get_header_value("Origin"),
        req.get_header_value("Sec-Fetch-Site"), req.get_param_value("token"),
        req.get_header_value("X-Dform-Token"),  req.get_header_value("Cookie")};
    const std::string why = studio::refusal(facts, port, token);
    const bool tooLarge = std::strtoull(req.get_header_value("Content-Length").c_str(), nullptr,
                                        10) > options.maxUploadBytes;
    if (why.empty() && !tooLarge) {
      studio::Server::admitBody();
      return httplib::Server::HandlerResponse::Unhandled;
    }
    studio::Server::closeAfterAnswer();
    res.set_header("Connection", "close");
    reply(res, why.empty() ? 413 : 403, {{"error", why.empty() ? tooLargeText() : why}});
    return httplib::Server::HandlerResponse::Handled;
  });
  server.set_error_handler([this](const httplib::Request&, httplib::Response& res) {
    if (studio::Server::bodyTooLarge()) {  // cut off at the limit, chunked or not
      res.status = 413;
      res.body.clear();
      res.set_header("Connection", "close");
    }
    if (!res.body.empty()) return;
    const std::string why = res.status == 413   ? tooLargeText()
                            : res.status == 404 ? "no such page or API"
                                                : "HTTP " + std::to_string(res.status);
    reply(res, res.status, {{"error", why}});
  });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
        reply(res, 500, {{"error", "internal error"}});
      });
  server.set_payload_max_length(options.maxUploadBytes);
  server.set_keep_alive_timeout(5);  // as the server's idle deadline
}

// A JSON API route: the body parsed, its session found, any error a JSON answer.
void Studio::Impl::api(httplib::Server& server, const char* path,
                       std::function<void(const json&, Session&, httplib::Response&)> handle) {
  server.Post(path, [this, handle](const httplib::Request& req, httplib::Response& res) {
    try {
      // Server-Timing (read by the page's drag breakdown): parsing the request, handling it
      // (waiting for the session's solver, solving, building the answer) and writing its JSON.
      const auto start = std::chrono::steady_clock::now();
      const json body = json::parse(req.body);
      const double parsed = millisecondsSince(start);
      if (!body.is_object()) throw RequestError("the request must be a JSON object");
      std::shared_ptr<Session> found = session(requiredText(body, "session"));
      if (!found) throw RequestError("unknown session (reload the page)");
      handle(body, *found, res);
      const double handled = millisecondsSince(start);
      res.set_header("Server-Timing",
                     "parse;dur=" + std::to_string(parsed) +
                         ", handle;dur=" + std::to_string(handled - parsed) +
                         ", total;dur=" + std::to_string(millisecondsSince(start)));
    } catch (const json::parse_error&) {
      reply(res, 400, {{"error", "the request is not JSON"}});
    } catch (const RequestError& e) {
      reply(res, 400, {{"error", e.what()}});
    } catch (const json::exception& e) {
      reply(res, 400, {{"error", std::string("malformed request: ") + e.what()}});
    } catch (const std::bad_alloc&) {
      reply(res, 503, {{"error", "out of memory"}});
    }
  });
}

void Studio::Impl::routes(httplib::Server& server) {
  pageRoutes(server);
  solveRoutes(server);
}

/// The page, its assets, a new session and the session's event stream.
void Studio::Impl::pageRoutes(httplib::Server& server) {
  server.Get("/", [this](const httplib::Request&, httplib::Response& res) {
    std::string page = assets["index.html"];
    const std::string mark = "{{token}}";
    page.replace(page.find(mark), mark.size(), token);
    res.set_header("Set-Cookie", studio::tokenCookieName(port) + "=" + token +
                                     "; Path=/; HttpOnly; SameSite=Strict");
    res.set_header("Content-Security-Policy",
                   "default-src 'self'; img-src 'self' data: blob:; frame-ancestors 'none'");
    res.set_header("Cache-Control", "no-store");
    res.set_content(page, "text/html; charset=utf-8");
  });
  for (const char* name : kAssets) {
    if (std::string(name) == "index.html") continue;
    server.Get(std::string("/") + name,
               [this, name = std::string(name)](const httplib::Request&, httplib::Response& res) {
                 const bool js = name.size() > 3 && name.compare(name.size() - 3, 3, ".js") == 0;
                 res.set_content(assets[name],
                                 js ? "text/javascript; charset=utf-8" : "text/css; charset=utf-8");
               });
  }
  server.Post("/api/session", [this](const httplib::Request&, httplib::Response& res) {
    json out = {{"session", newSession()},
                {"kinds", studio::outlineKindsJson()},
                {"settings",
                 {{"forward", json::parse(settingsJson(startForward))},
                  {"inverse", json::parse(settingsJson(startInverse))}}},
                {"mode", startsInverse ? "inverse" : "forward"},
                {"placeholders", studio::exportPlaceholders()},
                {"choices", studio::exportChoices()},
                {"pieces", {pieceSummary(startA), pieceSummary(startB)}},
                {"profiles", exportProfileNames()},
                {"preview_resolution", Session::kPreviewResolution}};
    for (int i = 0; i < 2; ++i)
      out["pieces"][i]["text"] = (i == 0 ? startA : startB).text;  // for undo
    if (startCurve) out["curve"] = studio::curveJson(startCurve->curve);
    reply(res, 200, out);
  });
  server.Get("/api/events", [this](const httplib::Request& req, httplib::Response& res) {
    std::shared_ptr<Session> found = session(req.get_param_value("session"));
    if (!found) return reply(res, 400, {{"error", "unknown session (reload the page)"}});
    // The stream holds the session's events, not the session: a dropped session ends it. A
    // client that reconnects resumes after the last event it saw; a new one starts with the news.
    studio::Server::streamEvents([this, events = found->eventStream(),
                                  position = found->events().resumeAfter(req.get_header_value(
                                      "Last-Event-ID"))](std::string& out) mutable {
      if (stopping || events->closed()) return false;
      out += events->waitAfter(position, std::chrono::milliseconds(0));
      return true;
    });
  });
}

/// The requests that change a session's inputs, solve, and make files from them.
void Studio::Impl::solveRoutes(httplib::Server& server) {
  api(server, "/api/outline", [](const json& body, Session& s, httplib::Response& res) {
    const int which = pieceIndex(body);
    std::string name = studio::safeFileName(requiredText(body, "name"), kOutlineExtensions,
                                            which == 0 ? "piece-a.svg" : "piece-b.svg");
    if (name == s.piece(1 - which).name) name = (which == 0 ? "a-" : "b-") + name;
    PieceInput piece = readPiece(name, requiredText(body, "text"));
    json out = pieceSummary(piece);
    s.setPiece(which, std::move(piece));
    reply(res, 200, out);
  });
  api(server, "/api/parametric", [](const json& body, Session& s, httplib::Response& res) {
    const int which = pieceIndex(body);
    const std::string kind = requiredText(body, "kind");
    std::map<std::string, double> values;
    if (body.contains("values")) values = body.at("values").get<std::map<std::string, double>>();
    const std::string text = studio::parametricOutline(kind, values);
    if (text.empty()) throw RequestError("kind: unknown outline kind");
    PieceInput piece = readPiece(std::string(which == 0 ? "a-" : "b-") + kind + ".json", text);
    json out = pieceSummary(piece);
    s.setPiece(which, std::move(piece));
    reply(res, 200, out);
  });
  api(server, "/api/solve", [this](const json& body, Session& s, httplib::Response& res) {
    const Job job = studio::jobFrom(body, startForward);
    const ForwardSettings& settings = std::get<ForwardJob>(job.run);
    const PieceInput a = s.piece(0), b = s.piece(1);
    reply(res, 200,
          s.solveLive(forwardSolve(a, b, settings, gate), settings.resolution,
                      settings.model == ModelChoice::Paper, sequence(body),
                      forwardDesign(a, b, job), studio::Server::clientGone()));
  });
  api(server, "/api/settle", [](const json& body, Session& s, httplib::Response& res) {
    s.settle(sequence(body, true));
    reply(res, 200, {{"seq", sequence(body)}});
  });
  api(server, "/api/strip", [this](const json& body, Session& s, httplib::Response& res) {
    const Job job = studio::jobFrom(body, startForward);
    const ForwardSettings& settings = std::get<ForwardJob>(job.run);
    const int starts = body.value("starts", 16);
    if (starts < 1 || starts > 64) throw RequestError("starts: must be in [1, 64]");
    const bool bothFlips = body.value("both_flips", true);
    std::vector<std::pair<json, studio::SolveAt>> cards;
    const PieceInput a = s.piece(0), b = s.piece(1);
    for (bool flip : {false, true}) {
      if (flip && !bothFlips) break;
      for (int k = 0; k < starts; ++k) {
        ForwardSettings card = settings;
        card.startB.fraction = double(k) / starts;
        card.flip = bothFlips ? flip : settings.flip;
        cards.emplace_back(json{{"start_b", card.startB.fraction}, {"flip", card.flip}},
                           forwardSolve(a, b, card, gate));
      }
    }
    s.startStrip(std::move(cards), sequence(body));
    reply(res, 200, {{"queued", starts * (bothFlips ? 2 : 1)}, {"seq", sequence(body)}});
  });
  api(server, "/api/curve", [](const json& body, Session& s, httplib::Response& res) {
    CurveInput curve = readCurveInput(
        studio::safeFileName(requiredText(body, "name"), kCurveExtensions, "curve.obj"),
        requiredText(body, "text"),
        body.value(settingKey(Setting::Closed), InverseJob().forceClosed));
    json out = studio::curveJson(curve.curve);
    out["name"] = curve.name;
    s.setCurve(std::move(curve));
    reply(res, 200, out);
  });
  api(server, "/api/inverse", [this](const json& body, Session& s, httplib::Response& res) {
    const Job job = studio::jobFrom(body, startInverse);
    const InverseSettings& settings = std::get<InverseJob>(job.run);
    std::optional<CurveInput> curve = s.curve();
    if (!curve) throw RequestError("no seam curve loaded");
    reply(res, 200,
          s.solveLive(inverseSolve(*curve, settings, gate), settings.resolution, false,
                      sequence(body),
                      std::to_string(std::hash<std::string>()(curve->text)) + "/" +
                          std::to_string(settings.resolution),
                      studio::Server::clientGone()));
  });
  // Save job and Export: the job with every setting of the request (the page sends all it had
  // from the session, export options included), its files as the zip holds them.
  const auto jobFiles = [this](const json& body, Session& s) {
    const Job job = studio::jobFrom(body, base(body));
    if (job.isForward()) return studio::forwardJobFiles(s.piece(0), s.piece(1), job);
    std::optional<CurveInput> curve = s.curve();
    if (!curve) throw RequestError("no seam curve loaded");
    Job closed = job;  // the curve as the session read it: closed or not when it was loaded
    std::get<InverseJob>(closed.run).forceClosed = curve->forceClosed;
    return studio::inverseJobFiles(*curve, closed);
  };
  api(server, "/api/job", [jobFiles](const json& body, Session& s, httplib::Response& res) {
    sendZip(res, studio::storedZip(jobFiles(body, s)), "dform-job.zip");
  });
  api(server, "/api/export", [jobFiles](const json& body, Session& s, httplib::Response& res) {
    // Left to run, an export abandoned by its client would hold its memory for its whole run.
    Result<studio::ExportedZip> zip =
        studio::exportedResult(jobFiles(body, s), studio::Server::clientGone().get());
    if (!zip.isOk()) throw RequestError(zip.status().message());
    // What the zip lacks, said by the page before the zip is saved (a header: percent-encoded).
    if (!zip.value().missing.empty())
      res.set_header("X-Dform-Missing", studio::percentEncoded(zip.value().missing));
    sendZip(res, zip.value().zip, "dform-export.zip");
  });
  // The export's layout: the same run, its pages instead of a zip (previewOf).
  api(server, "/api/preview", [jobFiles](const json& body, Session& s, httplib::Response& res) {
    reply(res, 200,
          studio::previewOf([&] { return jobFiles(body, s); }, studio::Server::clientGone().get()));
  });
}

Studio::Studio(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Studio::~Studio() { stop(); }

Result<std::unique_ptr<Studio>> Studio::start(const StudioOptions& options) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->token = options.token.empty() ? studio::randomToken() : options.token;
  if (options.port < 0 || options.port > 65535)
    return Status(ErrorCode::Usage,
                  "the port must be in [0, 65535], got " + std::to_string(options.port));
  if (Status s = impl->readStart(); !s.isOk()) return s;
  Result<GateLimits> gate = loadGate("default");
  if (!gate.isOk()) return gate.status();
  impl->gate = gate.value();
  const Result<std::string> templates = templatesDir();
  if (!templates.isOk()) return templates.status();
  const fs::path assets = fs::path(templates.value()) / "studio";
  for (const char* name : kAssets) {
    Result<std::string> text = readInputFile((assets / name).string());
    if (!text.isOk()) return text.status();
    impl->assets[name] = text.value();
  }
  // Every tab may hold a few event streams (reloads, a second window on one session).
  studio::ServerLimits limits;
  limits.maxBodyBytes = options.maxUploadBytes;
  limits.maxStreams = std::size_t(4 * std::max(options.maxSessions, 1));
  impl->server = std::make_unique<studio::Server>(limits);
  impl->guard(impl->server->routes());
  impl->routes(impl->server->routes());
  impl->port = impl->server->bindLoopback(options.port);
  if (impl->port <= 0)
    return Status(ErrorCode::OutputFailed, "127.0.0.1:" + std::to_string(options.port) +
                                               ": cannot listen (the port is taken?)");
  impl->server->start();
  return std::unique_ptr<Studio>(new Studio(std::move(impl)));
}

int Studio::port() const { return impl_->port; }
const std::string& Studio::token() const { return impl_->token; }
std::string Studio::url() const {
  return "http://127.0.0.1:" + std::to_string(impl_->port) + "/?token=" + impl_->token;
}

void Studio::stop() {
  if (impl_->stopped) return;
  impl_->stopped = true;
  impl_->stopping = true;
  {
    std::lock_guard<std::mutex> lock(impl_->sessionsMutex);
    for (auto& [id, entry] : impl_->sessions) entry.first->events().close();
  }
  if (impl_->server) impl_->server->stop();
  std::lock_guard<std::mutex> lock(impl_->sessionsMutex);
  impl_->sessions.clear();
}

}  // namespace dform
