// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's server over loopback: the token, Host and Origin guard, malformed requests, upload
// limits, independent sessions, results equal to the pipeline's in memory, and newest-input-wins.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "dform/io/outline_reader.h"
#include "dform/pipeline/forward_pipeline.h"
#include "dform/pipeline/report.h"
#include "dform/studio/studio.h"
#include "studio/session.h"
#include "studio/wire.h"
#include "studio_client.h"

// clang-format off
#include <httplib.h>  // last: its resolv.h defines _res, a name Eigen uses
// clang-format on

namespace dform {
namespace {

using nlohmann::json;
using test::StudioClient;

// A stop straight after start (a quick Ctrl-C, a short test) ends both listening threads: httplib
// ignores a stop that comes before its listen has begun, which start() waits out. The loop runs
// on a thread so that a hang fails here instead of stalling the suite.
TEST(StudioServer, StopsRightAfterStart) {
  // Shared: the detached thread may still be inside set_value() when the test returns.
  auto stopped = std::make_shared<std::promise<int>>();
  std::future<int> done = stopped->get_future();
  std::thread([stopped] {
    int count = 0;
    for (; count < 300; ++count) {
      Result<std::unique_ptr<Studio>> studio = Studio::start({});
      if (!studio.isOk()) break;
      studio.value()->stop();
    }
    stopped->set_value(count);
  }).detach();
  if (done.wait_for(std::chrono::seconds(120)) != std::future_status::ready) {
    std::fprintf(stderr, "a studio stopped right after its start did not end within 120 s\n");
    std::_Exit(1);  // the hung thread cannot be joined
  }
  EXPECT_EQ(done.get(), 300);
}

TEST(StudioServer, RefusesRequestsWithoutTheToken) {
  StudioClient c;
  auto page = c.raw().Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 403);
  EXPECT_TRUE(json::parse(page->body).contains("error"));
  auto api = c.raw().Post("/api/session", "{}", "application/json");
  ASSERT_TRUE(api);
  EXPECT_EQ(api->status, 403);
  auto wrong = c.raw().Get(("/?token=" + std::string(c.studio().token().size(), '0')).c_str());
  EXPECT_EQ(wrong->status, 403);
  // With the token: the page, which carries it for its own requests and sets the cookie.
  auto good = c.raw().Get(("/?token=" + c.studio().token()).c_str());
  ASSERT_TRUE(good);
  EXPECT_EQ(good->status, 200);
  EXPECT_NE(good->body.find(c.studio().token()), std::string::npos);
  EXPECT_NE(good->get_header_value("Set-Cookie").find("HttpOnly"), std::string::npos);
  auto script = c.raw().Get("/studio.js", {{"Cookie", c.cookie()}});
  EXPECT_EQ(script->status, 200);
}

// cpp-httplib would compress them with brotli for a client that accepts it: between two
// processes on one machine, time lost.
TEST(StudioServer, SendsThePageAndItsAssetsUncompressed) {
  StudioClient c;
  c.raw().set_decompress(false);  // the body as sent
  const std::pair<std::string, std::string> assets[] = {
      {"/?token=" + c.studio().token(), "<!doctype html>"},
      {"/studio.js", "// dform studio's page"},
      {"/studio.css", "/* dform studio"}};
  for (const auto& [path, opening] : assets)
    for (const char* name : {"Accept-Encoding", "accept-encoding", "ACCEPT-ENCODING"}) {
      // The token's cookie is sent after the dropped line: a script answered 200 kept it.
      auto got = c.raw().Get(path.c_str(), {{name, "gzip, deflate, br"}, {"Cookie", c.cookie()}});
      ASSERT_TRUE(got) << path;
      EXPECT_EQ(got->status, 200) << path;
      EXPECT_EQ(got->get_header_value("Content-Encoding"), "") << path << ", " << name;
      EXPECT_EQ(got->body.rfind(opening, 0), 0u) << path << ": " << got->body.substr(0, 40);
    }
}

TEST(StudioServer, RefusesForeignOriginAndHost) {
  StudioClient c;
  const std::string port = std::to_string(c.studio().port());
  auto post = [&](const httplib::Headers& extra) {
    httplib::Headers h = c.headers();
    h.insert(extra.begin(), extra.end());
    return c.raw().Post("/api/session", h, "{}", "application/json")->status;
  };
  EXPECT_EQ(post({{"Origin", "http://evil.example"}}), 403);
  EXPECT_EQ(post({{"Origin", "http://127.0.0.1:" + port + ".evil.example"}}), 403);
  EXPECT_EQ(post({{"Origin", "null"}}), 403);
  EXPECT_EQ(post({{"Sec-Fetch-Site", "cross-site"}}), 403);
  EXPECT_EQ(post({{"Host", "evil.example:" + port}}), 403);  // DNS rebinding
  EXPECT_EQ(post({{"Host", "127.0.0.1:1"}}), 403);
  EXPECT_EQ(post({{"Origin", "http://127.0.0.1:" + port}}), 200);
  EXPECT_EQ(post({{"Origin", "http://localhost:" + port}, {"Host", "localhost:" + port}}), 200);
}

TEST(StudioServer, MalformedRequestsGetJsonErrorsAndTheServerKeepsServing) {
  StudioClient c;
  const std::string session = c.session();
  for (const char* body :
       {"{not json", "[]", "42", "{}", "{\"session\": 7}", "{\"session\": \"nope\"}"}) {
    auto r = c.raw().Post("/api/solve", c.headers(), body, "application/json");
    ASSERT_TRUE(r) << body;
    EXPECT_EQ(r->status, 400) << body;
    EXPECT_TRUE(json::parse(r->body).contains("error")) << body;
  }
  for (const json& bad :
       {json{{"start_a", 1.5}}, json{{"resolution", "many"}}, json{{"join", "sideways"}},
        json{{"model", "magic"}}, json{{"resolution", 3}}, json{{"flip", 1}}}) {
    json body = bad;
    body["session"] = session;
    auto r = c.post("/api/solve", body);
    EXPECT_EQ(r.first, 400) << bad;
    EXPECT_TRUE(r.second.contains("error")) << bad;
  }
  for (const json& bad : {json{}, json{{"seq", "last"}}, json{{"seq", 1.5}}}) {
    json body = bad;
    body["session"] = session;
    const auto r = c.post("/api/settle", body);
    EXPECT_EQ(r.first, 400) << bad;
    EXPECT_EQ(r.second.value("error", ""), "seq: must be a whole number") << bad;
  }
  EXPECT_EQ(c.post("/api/settle", {{"session", session}, {"seq", 1}}).first, 200);
  auto unknown = c.raw().Get("/no/such/page", c.headers());
  EXPECT_EQ(unknown->status, 404);
  EXPECT_TRUE(json::parse(unknown->body).contains("error"));
  EXPECT_EQ(c.post("/api/solve", {{"session", session}, {"seq", 1}}).first, 200);
}

TEST(StudioServer, UploadsAreSizeLimitedAndReadAsContent) {
  StudioOptions options;
  options.maxUploadBytes = 64 * 1024;
  StudioClient c(options);
  const std::string session = c.session();
  json big = {{"session", session},
              {"piece", "a"},
              {"name", "big.svg"},
              {"text", std::string(70 * 1024, ' ')}};
  auto r = c.raw().Post("/api/outline", c.headers(), big.dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_TRUE(json::parse(r->body).contains("error"));
  // A name that looks like a path is only a name: the text is what is read.
  auto bad =
      c.post("/api/outline", {{"session", session},
                              {"piece", "a"},
                              {"name", "../../etc/passwd.svg"},
                              {"text", "<svg xmlns='http://www.w3.org/2000/svg'><rect/></svg>"}});
  EXPECT_EQ(bad.first, 400);
  EXPECT_NE(bad.second["error"].get<std::string>().find("passwd.svg"), std::string::npos)
      << bad.second;
  EXPECT_EQ(bad.second["error"].get<std::string>().find("../"), std::string::npos) << bad.second;
  auto good =
      c.post("/api/outline",
             {{"session", session},
              {"piece", "a"},
              {"name", "/etc/hosts.json"},
              {"text", "{\"points\": [[0,0],[100,0],[100,80],[0,80]], \"units\": \"mm\"}"}});
  EXPECT_EQ(good.first, 200) << good.second;
  EXPECT_EQ(good.second["name"], "hosts.json");
  EXPECT_NEAR(good.second["perimeter"].get<double>(), 360.0, 1e-9);
}

TEST(StudioServer, TwoSessionsAreIndependent) {
  StudioClient c;
  const std::string one = c.session(), two = c.session();
  ASSERT_NE(one, two);
  auto square = c.post("/api/parametric", {{"session", one},
                                           {"piece", "b"},
                                           {"kind", "polygon"},
                                           {"values", {{"sides", 4}, {"radius", 96}}}});
  ASSERT_EQ(square.first, 200) << square.second;
  auto a = c.post("/api/solve", {{"session", one}, {"seq", 1}});
  auto b = c.post("/api/solve", {{"session", two}, {"seq", 1}});
  ASSERT_EQ(a.first, 200);
  ASSERT_EQ(b.first, 200);
  // Session one zips an ellipse to a square (corners: seam vertices at the corners, the paper
  // model or folds); session two still has the two ellipses of the start.
  EXPECT_NE(a.second["pieces"][1]["flat"], b.second["pieces"][1]["flat"]);
  auto again = c.post("/api/solve", {{"session", two}, {"seq", 2}});
  EXPECT_EQ(again.second["pieces"][1]["flat"], b.second["pieces"][1]["flat"]);
}

// The 3D point of a piece's answer at a flat point: linear over the flat triangle holding it
// (nullopt outside every triangle). Exact for a mesh whose triangles lie in the body's faces.
std::optional<Eigen::Vector3d> pointAt(const json& piece, const Eigen::Vector2d& q) {
  const std::vector<double> flat = test::decodeDoubles(piece["flat"]),
                            shape = test::decodeDoubles(piece["shape"]);
  const std::vector<std::uint32_t> faces = test::decodeIndices(piece["faces"]);
  for (std::size_t f = 0; f + 2 < faces.size(); f += 3) {
    const auto corner = [&](int k) {
      return Eigen::Vector2d(flat[2 * faces[f + k]], flat[2 * faces[f + k] + 1]);
    };
    const Eigen::Vector2d a = corner(0), b = corner(1), c = corner(2);
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    const double wb = ((q - a).x() * (c - a).y() - (q - a).y() * (c - a).x()) / area;
    const double wc = ((b - a).x() * (q - a).y() - (b - a).y() * (q - a).x()) / area;
    const double wa = 1 - wb - wc;
    if (std::min({wa, wb, wc}) < -1e-9) continue;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    const double w[3] = {wa, wb, wc};
    for (int k = 0; k < 3; ++k)
      p += w[k] * Eigen::Vector3d(shape[3 * faces[f + k]], shape[3 * faces[f + k] + 1],
                                  shape[3 * faces[f + k] + 2]);
    return p;
  }
  return std::nullopt;
}

TEST(StudioServer, ShapeEqualsTheInMemoryRunForTheSameStart) {
  StudioClient c;
  const std::string session = c.session();
  test::EventReader events(c, session);
  auto r =
      c.post("/api/solve", {{"session", session}, {"seq", 3}, {"start_a", 0.1}, {"start_b", 0.37}});
  ASSERT_EQ(r.first, 200) << r.second;
  ASSERT_FALSE(r.second.contains("error")) << r.second;
  EXPECT_EQ(r.second["seq"], 3);
  EXPECT_EQ(r.second["model"]["name"], "exact");
  ForwardSettings s;
  s.startA.fraction = 0.1;
  s.startB.fraction = 0.37;
  s.fitPerimeter = true;
  MessageSink sink;
  Result<ForwardRun> direct =
      makeDForm(test::startEllipse(120, 70, "ellipse-a.json"),
                test::startEllipse(110, 82.305579, "ellipse-b.json"), s, sink);
  ASSERT_TRUE(direct.isOk()) << direct.status().message();
  // The answer is the exact body meshed sparsely, the job's mesh and its figures to follow: no
  // figures yet, and fewer vertices drawing the same shape. Every vertex of the job's mesh,
  // looked up in the answer's flat triangles, lands on its own 3D point.
  EXPECT_FALSE(r.second["preview"].get<bool>());
  EXPECT_TRUE(r.second["refining"].get<bool>());
  EXPECT_FALSE(r.second.contains("figures"));
  EXPECT_FALSE(r.second.contains("gate"));
  const double diagonal = (direct.value().model.a.shape.colwise().maxCoeff() -
                           direct.value().model.a.shape.colwise().minCoeff())
                              .norm();
  for (int piece = 0; piece < 2; ++piece) {
    const Piece& job = piece == 0 ? direct.value().model.a : direct.value().model.b;
    const json& sparse = r.second["pieces"][piece];
    EXPECT_LT(test::decodeDoubles(sparse["shape"]).size(), std::size_t(job.shape.size()) / 4);
    double worst = 0;
    for (Eigen::Index v = 0; v < job.flat.rows(); ++v) {
      const std::optional<Eigen::Vector3d> p = pointAt(sparse, job.flat.row(v).transpose());
      ASSERT_TRUE(p) << "piece " << piece << " vertex " << v
                     << " lies in no triangle of the answer";
      worst = std::max(worst, (*p - job.shape.row(v).transpose()).norm());
    }
    EXPECT_LE(worst, 1e-9 * diagonal) << "piece " << piece;
  }
  // Then the job's mesh: every vertex as makeDForm's, with its figures (every one as makeDForm's,
  // as report.json writes them) and the gate's verdict.
  const json result = events.waitFor("result", std::chrono::seconds(60));
  ASSERT_FALSE(result.is_null());
  EXPECT_EQ(result["seq"], 3);
  EXPECT_FALSE(result["refining"].get<bool>());
  for (int piece = 0; piece < 2; ++piece) {
    const Points3& expected =
        piece == 0 ? direct.value().model.a.shape : direct.value().model.b.shape;
    const std::vector<double> got = test::decodeDoubles(result["pieces"][piece]["shape"]);
    ASSERT_EQ(got.size(), std::size_t(expected.size()));
    for (Eigen::Index v = 0; v < expected.rows(); ++v)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(got[std::size_t(3 * v + k)], expected(v, k));
  }
  EXPECT_EQ(result["figures"], json::parse(metricsJsonText(direct.value().metrics, nullptr)))
      << result["figures"];
  EXPECT_DOUBLE_EQ(result["figures"]["L_error"].get<double>(), direct.value().metrics.lengthError);
  EXPECT_TRUE(result["gate"]["passed"].get<bool>()) << result["gate"];
  EXPECT_GE(result["gate"]["checks"].size(), 10u);
  for (const json& e : events.seen())
    EXPECT_NE(e["type"], "gate") << "the sparse answer is not judged: " << e;
  // Sent uncompressed even to a client that accepts compression (on loopback it only costs).
  httplib::Headers accepting = c.headers();
  accepting.emplace("Accept-Encoding", "gzip, deflate, br");
  auto plain = c.raw().Post("/api/solve", accepting, json{{"session", session}, {"seq", 4}}.dump(),
                            "application/json");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->get_header_value("Content-Encoding"), "");
}

TEST(StudioServer, AJobMeshedAsSparselyAsAJobMayBeIsAnsweredInFull) {
  StudioClient c;
  const std::string session = c.session();
  test::EventReader events(c, session);
  // The job's mesh is the sparse one: the answer is final, and its verdict follows it.
  auto sparsest = c.post(
      "/api/solve", {{"session", session}, {"seq", 1}, {"interior_edge", kMaxInteriorEdgeFactor}});
  ASSERT_EQ(sparsest.first, 200) << sparsest.second;
  EXPECT_EQ(sparsest.second["model"]["name"], "exact");
  EXPECT_FALSE(sparsest.second["refining"].get<bool>()) << sparsest.second;
  const json gate = events.waitFor("gate", std::chrono::seconds(60));
  ASSERT_FALSE(gate.is_null());
  EXPECT_EQ(gate["seq"], 1);
  EXPECT_TRUE(gate["gate"]["passed"].get<bool>()) << gate;
  auto finer = c.post("/api/solve", {{"session", session}, {"seq", 2}, {"interior_edge", 0.1}});
  EXPECT_EQ(finer.first, 400) << "an interior edge factor out of range is refused";
  EXPECT_EQ(finer.second["error"], "interior_edge must be a number between 0.25 and 8, got 0.1")
      << "named by its field, the setting's key";
}

TEST(StudioServer, NewestInputWinsAndStaleRefinementsNeverArrive) {
  StudioClient c;
  const std::string session = c.session();
  test::EventReader events(c, session);
  json paper = {{"session", session}, {"model", "paper"}, {"resolution", 60}};
  paper["seq"] = 1;
  paper["start_b"] = 0.1;
  auto first = c.post("/api/solve", paper);
  ASSERT_EQ(first.first, 200) << first.second;
  EXPECT_TRUE(first.second["preview"].get<bool>()) << first.second;
  EXPECT_TRUE(first.second["refining"].get<bool>());
  EXPECT_EQ(first.second["pieces"][0]["seam"].size(), 24u) << "a preview at 24 seam points";
  paper["seq"] = 2;
  paper["start_b"] = 0.2;
  auto second = c.post("/api/solve", paper);
  ASSERT_EQ(second.first, 200) << second.second;
  const json result = events.waitFor("result", std::chrono::seconds(120));
  ASSERT_FALSE(result.is_null()) << "no refined result streamed";
  EXPECT_EQ(result["seq"], 2);
  EXPECT_FALSE(result["preview"].get<bool>());
  EXPECT_EQ(result["pieces"][0]["seam"].size(), 60u);
  EXPECT_TRUE(result["gate"].contains("passed"));      // a refined result carries its verdict
  EXPECT_TRUE(result["figures"].contains("L_error"));  // and its figures
  for (const json& e : events.seen())
    EXPECT_NE(e.value("seq", 0) == 1 && e["type"] == "result", true) << e;
}

// Whether the glued metric is convex depends on where the seam starts: a square against a square
// whose bottom side is notched (190 degrees at the notch) is convex only where a corner of B meets
// the notch. A position that needs the optimiser leaves the next one, which the exact engine
// glues, answered by the exact engine at full resolution, not as a preview.
TEST(StudioServer, EveryPositionAsksTheExactEngineFirst) {
  StudioClient c;
  const std::string session = c.session();
  const double notch = 50.0 * std::tan(5.0 * 3.14159265358979323846 / 180.0);
  const double side = (2.0 * std::hypot(50.0, notch) + 300.0) / 4.0;
  char a[160], b[160];
  std::snprintf(a, sizeof a, "{\"points\": [[50,%.12f],[100,0],[100,100],[0,100],[0,0]]}", notch);
  std::snprintf(b, sizeof b, "{\"points\": [[0,0],[%.12f,0],[%.12f,%.12f],[0,%.12f]]}", side, side,
                side, side);
  for (const auto& [piece, text] : {std::pair{"a", a}, std::pair{"b", b}}) {
    auto r = c.post("/api/outline", {{"session", session},
                                     {"piece", piece},
                                     {"name", std::string(piece) + ".json"},
                                     {"text", text}});
    ASSERT_EQ(r.first, 200) << r.second;
  }
  json job = {{"session", session}, {"resolution", 60}, {"start_a", 0.0}};
  // B's side against the notch: 370 degrees there, the optimiser's preview.
  job["seq"] = 1;
  job["start_b"] = 0.125;
  auto notched = c.post("/api/solve", job);
  ASSERT_EQ(notched.first, 200) << notched.second;
  EXPECT_TRUE(notched.second["preview"].get<bool>()) << notched.second;
  // B's corner in the notch: convex, the exact body at the page's resolution.
  job["seq"] = 2;
  job["start_b"] = 0.0;
  auto corner = c.post("/api/solve", job);
  ASSERT_EQ(corner.first, 200) << corner.second;
  EXPECT_EQ(corner.second["model"]["name"], "exact") << corner.second;
  EXPECT_FALSE(corner.second["preview"].get<bool>());
  EXPECT_EQ(corner.second["pieces"][0]["seam"].size(), 60u);
  // Back at the notched position: the optimiser again.
  job["seq"] = 3;
  job["start_b"] = 0.125;
  auto again = c.post("/api/solve", job);
  ASSERT_EQ(again.first, 200) << again.second;
  EXPECT_TRUE(again.second["preview"].get<bool>()) << again.second;
}

// The strip's cards are thumbnails solved in the background at 36 seam points, finer than a
// drag's previews; the paper model's too.
TEST(StudioServer, StripCardsAreSolvedAt36SeamPoints) {
  StudioClient c;
  const std::string session = c.session();
  test::EventReader events(c, session);
  auto strip = c.post(
      "/api/strip",
      {{"session", session}, {"seq", 1}, {"model", "paper"}, {"starts", 1}, {"both_flips", false}});
  ASSERT_EQ(strip.first, 200) << strip.second;
  const json card = events.waitFor("strip", std::chrono::seconds(120));
  ASSERT_FALSE(card.is_null()) << "no card streamed";
  ASSERT_TRUE(card.contains("result")) << card;
  EXPECT_EQ(card["result"]["pieces"][0]["seam"].size(), 36u) << card["result"]["model"];
  EXPECT_EQ(card["result"]["model"]["name"], "paper");
}

TEST(StudioServer, LatestTicketCancelsTheOneBefore) {
  studio::Latest latest;
  const studio::Latest::Ticket one = latest.next();
  EXPECT_TRUE(latest.current(one));
  const studio::Latest::Ticket two = latest.next();
  EXPECT_TRUE(one.cancel->load());
  EXPECT_FALSE(latest.current(one));
  EXPECT_TRUE(latest.current(two));
  latest.cancel();
  EXPECT_FALSE(latest.current(two));
}

// A followed ticket is current with its generation and has a flag of its own: the followed
// ticket's flag (its client gone) leaves it current, a newer ticket and cancel() do not.
TEST(StudioServer, AFollowedTicketOutlivesItsRequestButNotNewerInput) {
  studio::Latest latest;
  auto gone = std::make_shared<std::atomic<bool>>(false);
  const studio::Latest::Ticket live = latest.next(gone);
  const studio::Latest::Ticket queued = latest.follow(live);
  gone->store(true);
  EXPECT_FALSE(latest.current(live));
  EXPECT_TRUE(latest.current(queued));
  const studio::Latest::Ticket newer = latest.next();
  EXPECT_TRUE(queued.cancel->load());
  EXPECT_FALSE(latest.current(latest.follow(live))) << "a ticket followed too late";
  const studio::Latest::Ticket newerQueued = latest.follow(newer);
  latest.cancel();
  EXPECT_FALSE(latest.current(newerQueued));
}

// A client that reconnects with the last id it saw gets every event after it, each once, with
// its id; a new client, or one whose Last-Event-ID is not an id of this stream, starts at the news.
TEST(StudioServer, AReconnectingEventStreamResumesAfterTheLastEventItSaw) {
  studio::EventStream stream;
  for (int k = 0; k < 3; ++k) stream.push({{"type", "step"}, {"k", k}});
  long position = stream.resumeAfter("0");
  EXPECT_EQ(position, 1);
  EXPECT_EQ(stream.waitAfter(position, std::chrono::milliseconds(0)),
            "id: 1\ndata: {\"k\":1,\"type\":\"step\"}\n\n"
            "id: 2\ndata: {\"k\":2,\"type\":\"step\"}\n\n");
  EXPECT_EQ(position, 3);
  EXPECT_EQ(stream.waitAfter(position, std::chrono::milliseconds(0)), "");
  for (const char* notAnId : {"", "2", "3", "99", "-1", "1x", " 1", "99999999999999999999"})
    EXPECT_EQ(stream.resumeAfter(notAnId), 3) << "'" << notAnId << "'";
  EXPECT_EQ(stream.resumeAfter("1"), 2);
}

}  // namespace
}  // namespace dform

namespace dform {
namespace {

std::string sampleText(const std::string& name) {
  std::ifstream in(std::string(DFORM_SAMPLES_DIR) + "/inverse/" + name);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A seam curve on its convex hull gets the exact pieces; one pushed inside its hull says which
// points are inside; both with the round trip's figures.
TEST(StudioServer, InverseShowsTheOnHullTestAndTheRoundTrip) {
  test::StudioClient c;
  const std::string session = c.session();
  auto missing = c.post("/api/inverse", {{"session", session}, {"seq", 1}});
  EXPECT_EQ(missing.first, 400);
  auto curve = c.post(
      "/api/curve",
      {{"session", session}, {"name", "tennis-ball.obj"}, {"text", sampleText("tennis-ball.obj")}});
  ASSERT_EQ(curve.first, 200) << curve.second;
  EXPECT_GT(curve.second["length"].get<double>(), 100.0);
  auto ball = c.post("/api/inverse", {{"session", session}, {"seq", 2}, {"resolution", 60}});
  ASSERT_EQ(ball.first, 200) << ball.second;
  ASSERT_FALSE(ball.second.contains("error")) << ball.second;
  EXPECT_TRUE(ball.second["on_hull"]["on_hull"].get<bool>());
  EXPECT_EQ(ball.second["model"]["name"], "exact");
  EXPECT_LT(ball.second["curve_match"]["roundtrip_max_rel"].get<double>(), 0.01);
  EXPECT_EQ(test::decodeDoubles(ball.second["target"]).size(), 60u * 3);

  ASSERT_EQ(c.post("/api/curve", {{"session", session},
                                  {"name", "pushed-in.obj"},
                                  {"text", sampleText("pushed-in.obj")}})
                .first,
            200);
  auto pushed = c.post("/api/inverse", {{"session", session}, {"seq", 3}, {"resolution", 60}});
  ASSERT_EQ(pushed.first, 200) << pushed.second;
  EXPECT_FALSE(pushed.second["on_hull"]["on_hull"].get<bool>()) << pushed.second["on_hull"];
  EXPECT_FALSE(pushed.second["on_hull"]["inside_points"].empty());
  EXPECT_FALSE(pushed.second["on_hull"]["summary"].get<std::string>().empty());

  auto bad = c.post("/api/curve",
                    {{"session", session},
                     {"name", "flat.obj"},
                     {"text", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 2 0\nl 1 2 3 4 5 1\n"}});
  EXPECT_EQ(bad.first, 400);
  EXPECT_NE(bad.second["error"].get<std::string>().find("flat.obj"), std::string::npos)
      << bad.second;
}

}  // namespace
}  // namespace dform

namespace dform {
namespace {

// The nice value of each thread of this process (/proc/self/task/TID/stat, field 19).
std::vector<int> threadNiceValues() {
  std::vector<int> out;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream in(task.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::istringstream fields(stat.substr(stat.rfind(')') + 2));  // after "pid (name) "
    std::string field;
    for (int k = 3; k <= 19 && fields >> field; ++k)
      if (k == 19) out.push_back(std::stoi(field));
  }
  return out;
}

// What a stand-in solver answers: the resolution asked for, a passing verdict, and whether it
// was asked to mesh sparsely (then the session refines it).
studio::Solved stubSolved(int resolution, studio::Interior interior) {
  studio::Solved solved;
  solved.result = {{"resolution", resolution}};
  solved.verdict = [] { return json{{"gate", {{"passed", true}}}}; };
  solved.sparse = interior == studio::Interior::Sparse;
  return solved;
}

// The session's events up to the first holding `text` (by default its first result), waiting at
// most `tries` tenths of a second.
std::string eventsUntilResult(studio::Session& session, int tries,
                              const std::string& text = "\"type\":\"result\"") {
  long position = 0;
  std::string events;
  for (int k = 0; k < tries && events.find(text) == std::string::npos; ++k)
    events += session.events().waitAfter(position, std::chrono::milliseconds(100));
  return events;
}

// The page asks for a shape and its client closes the connection once it has the answer; the
// refinement the answer promises ("refining": true) still arrives as an event. The solve at the
// job's mesh waits for the client to have gone, so the order is the same on every machine.
TEST(StudioSession, ARefinementOutlivesTheRequestThatAskedForIt) {
  studio::PieceInput a{"a.json", "", test::startEllipse(120, 70, "a.json")};
  studio::PieceInput b{"b.json", "", test::startEllipse(110, 82.305579, "b.json")};
  studio::Session session(a, b);
  auto gone = std::make_shared<std::atomic<bool>>(false);
  const studio::SolveAt solve = [gone](int resolution, studio::Interior interior,
                                       const RunHooks&) -> Result<studio::Solved> {
    for (int k = 0; k < 2000 && interior == studio::Interior::Job && !gone->load(); ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return stubSolved(resolution, interior);
  };
  const json answer = session.solveLive(solve, 100, false, 7, "design", gone);
  EXPECT_TRUE(answer["refining"].get<bool>()) << answer;
  gone->store(true);
  const std::string events = eventsUntilResult(session, 100);
  EXPECT_NE(events.find("\"type\":\"result\""), std::string::npos) << events;
  EXPECT_NE(events.find("\"seq\":7"), std::string::npos) << events;
}

// The progress events of a refinement whose solver iterates every 2 ms for `iterating`, counted
// with the time from the request to the result.
std::pair<long, std::chrono::steady_clock::duration> progressEvents(
    std::chrono::milliseconds iterating) {
  studio::PieceInput a{"a.json", "", test::startEllipse(120, 70, "a.json")};
  studio::PieceInput b{"b.json", "", test::startEllipse(110, 82.305579, "b.json")};
  studio::Session session(a, b);
  const studio::SolveAt solve = [&](int resolution, studio::Interior interior,
                                    const RunHooks& hooks) -> Result<studio::Solved> {
    if (interior == studio::Interior::Job) {
      const auto until = std::chrono::steady_clock::now() + iterating;
      for (int k = 0; std::chrono::steady_clock::now() < until; ++k) {
        IterationSummary it;
        it.iteration = k;
        hooks.onIteration("stub", it);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
    }
    return stubSolved(resolution, interior);
  };
  const auto asked = std::chrono::steady_clock::now();
  const json answer = session.solveLive(solve, 100, false, 3, "design", nullptr);
  EXPECT_TRUE(answer["refining"].get<bool>()) << answer;
  const std::string events = eventsUntilResult(session, 200);
  const auto elapsed = std::chrono::steady_clock::now() - asked;
  EXPECT_NE(events.find("\"type\":\"result\""), std::string::npos) << events;
  long progress = 0;
  for (std::size_t at = events.find("\"type\":\"progress\""); at != std::string::npos;
       at = events.find("\"type\":\"progress\"", at + 1))
    ++progress;
  return {progress, elapsed};
}

// A refinement reports its progress once it has run a second, then at most four times a second,
// however often its solver iterates: each event repaints the page.
TEST(StudioSession, ARefinementsProgressComesAfterASecondAtMostFourTimesASecond) {
  const auto [progress, elapsed] = progressEvents(std::chrono::milliseconds(2000));
  // Every event came between the request and the result, the first a second after the
  // refinement began, each later one a quarter second after the one before.
  EXPECT_GE(progress, 1);
  EXPECT_LE(progress, (elapsed - std::chrono::seconds(1)) / std::chrono::milliseconds(250) + 1);
}

// A refinement shorter than a second shows the preview's "refining..." until its result: no
// progress event repaints the page meanwhile.
TEST(StudioSession, AShortRefinementSendsNoProgress) {
  EXPECT_EQ(progressEvents(std::chrono::milliseconds(500)).first, 0);
}

// During a drag every position cancels the refinement of the one before: the worker starts a
// refinement only once the live requests have paused for kRefinementQuiet, so a drag costs the
// page no CPU for refinements it will never see. The stub's refinement returns at once; asked
// for 25 positions 10 ms apart, the old worker ran one after nearly every position.
TEST(StudioSession, ARefinementWaitsForTheLiveRequestsToPause) {
  studio::PieceInput a{"a.json", "", test::startEllipse(120, 70, "a.json")};
  studio::PieceInput b{"b.json", "", test::startEllipse(110, 82.305579, "b.json")};
  studio::Session session(a, b);
  using Clock = std::chrono::steady_clock;
  std::mutex mutex;
  std::vector<Clock::time_point> refinements;
  const studio::SolveAt solve = [&](int resolution, studio::Interior interior,
                                    const RunHooks&) -> Result<studio::Solved> {
    if (interior == studio::Interior::Job) {
      const std::lock_guard<std::mutex> lock(mutex);
      refinements.push_back(Clock::now());
    }
    return stubSolved(resolution, interior);
  };
  const Clock::time_point asked = Clock::now();
  ASSERT_TRUE(session.solveLive(solve, 100, false, 1, "design", nullptr)["refining"].get<bool>());
  ASSERT_NE(eventsUntilResult(session, 50).find("\"type\":\"result\""), std::string::npos);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    ASSERT_EQ(refinements.size(), 1u);
    EXPECT_GE(refinements[0] - asked, studio::Session::kRefinementQuiet);
    refinements.clear();
  }
  for (long seq = 2; seq <= 26; ++seq) {
    session.solveLive(solve, 100, false, seq, "design", nullptr);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  for (int k = 0; k < 100; ++k) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      if (!refinements.empty() &&
          Clock::now() - refinements.back() > std::chrono::milliseconds(300))
        break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const std::lock_guard<std::mutex> lock(mutex);
  EXPECT_GE(refinements.size(), 1u);  // the last position's
  EXPECT_LE(refinements.size(), 3u);  // a pause of the test's own thread may let another start
}

// A released drag settles the page's input: the last position's refinement starts at once, not
// kRefinementQuiet after its live request, whether that request was answered before the release
// or is still on its way; a settle older than the newest request, or a newer request after it,
// keeps the wait.
TEST(StudioSession, ASettledInputIsRefinedWithoutTheQuietWait) {
  studio::PieceInput a{"a.json", "", test::startEllipse(120, 70, "a.json")};
  studio::PieceInput b{"b.json", "", test::startEllipse(110, 82.305579, "b.json")};
  studio::Session session(a, b);
  const studio::SolveAt solve = [](int resolution, studio::Interior interior,
                                   const RunHooks&) -> Result<studio::Solved> {
    return stubSolved(resolution, interior);
  };
  using Clock = std::chrono::steady_clock;
  const auto waits = [&](Clock::time_point asked) {
    return session.refinementDue() >= asked + studio::Session::kRefinementQuiet;
  };
  Clock::time_point asked = Clock::now();
  session.solveLive(solve, 100, false, 1, "design", nullptr);
  EXPECT_TRUE(waits(asked));
  session.settle(1);  // released after its answer
  EXPECT_LE(session.refinementDue(), Clock::now());

  asked = Clock::now();
  session.solveLive(solve, 100, false, 2, "design", nullptr);
  EXPECT_TRUE(waits(asked));
  session.settle(1);  // older than the newest request
  EXPECT_TRUE(waits(asked));

  session.settle(3);  // released while its request is on its way
  EXPECT_LE(session.refinementDue(), Clock::now());
  session.solveLive(solve, 100, false, 3, "design", nullptr);
  EXPECT_LE(session.refinementDue(), Clock::now());
  const std::string events = eventsUntilResult(session, 50, "\"seq\":3");
  EXPECT_NE(events.find("\"seq\":3"), std::string::npos) << events;  // its refinement

  asked = Clock::now();
  session.solveLive(solve, 100, false, 4, "design", nullptr);  // a new drag
  EXPECT_TRUE(waits(asked));
}

TEST(StudioSession, TheWorkerYieldsToTheLiveSolves) {
  const auto workers = [] {
    const std::vector<int> nice = threadNiceValues();
    return std::count(nice.begin(), nice.end(), studio::Session::kWorkerNice);
  };
  const long before = workers();
  studio::PieceInput a{"a.json", "", test::startEllipse(120, 70, "a.json")};
  studio::PieceInput b{"b.json", "", test::startEllipse(110, 82.305579, "b.json")};
  {
    studio::Session session(a, b);
    // Its worker lowers its own priority as it starts.
    for (int k = 0; k < 500 && workers() == before; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    EXPECT_EQ(workers(), before + 1);
  }
  EXPECT_EQ(workers(), before);  // joined with the session
}

}  // namespace
}  // namespace dform
