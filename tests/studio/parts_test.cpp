// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's parts without a server: the stored zip (read back by Python's zipfile), the
// request guard, upload names, the parametric outlines (read by io as the studio reads them) and
// the corners a start snaps to.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"
#include "studio/guard.h"
#include "studio/outlines.h"
#include "studio/wire.h"
#include "studio/zip.h"

namespace dform {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(StudioZip, PythonReadsTheArchiveBack) {
  const std::string binary("\x00\x01\xff\r\n", 5);
  const std::string zip =
      studio::storedZip({{"job.json", "{}\n"}, {"result/pattern.svg", "<svg/>"}, {"bin", binary}});
  const fs::path path = fs::temp_directory_path() / "dform-studio-zip-test.zip";
  std::ofstream(path, std::ios::binary) << zip;
  const std::string check =
      std::string(DFORM_PYTHON3) +
      " -c \"import zipfile,sys; z=zipfile.ZipFile(sys.argv[1]); assert z.testzip() is None; "
      "assert z.namelist()==['job.json','result/pattern.svg','bin'], z.namelist(); "
      "assert z.read('bin')==bytes([0,1,255,13,10]); assert z.read('job.json')==b'{}\\\\n'\" " +
      path.string();
  EXPECT_EQ(std::system(check.c_str()), 0);
  fs::remove(path);
}

TEST(StudioZip, Crc32IsTheStandardOne) {
  EXPECT_EQ(studio::crc32("123456789"), 0xCBF43926ul);  // the check value of CRC-32/ISO-HDLC
  EXPECT_EQ(studio::crc32(""), 0ul);
}

TEST(StudioGuard, TokenHostAndOrigin) {
  const std::string token = "0123456789abcdef0123456789abcdef";
  studio::RequestFacts ok{"127.0.0.1:8000", "", "", token, "", ""};
  EXPECT_EQ(studio::refusal(ok, 8000, token), "");
  auto with = [&](auto change) {
    studio::RequestFacts r = ok;
    change(r);
    return studio::refusal(r, 8000, token);
  };
  EXPECT_NE(with([](auto& r) { r.queryToken = ""; }), "");
  EXPECT_NE(with([&](auto& r) { r.queryToken = token.substr(1) + "0"; }), "");
  EXPECT_NE(with([&](auto& r) { r.queryToken = token + "0"; }), "");
  EXPECT_EQ(with([&](auto& r) {
              r.queryToken = "";
              r.headerToken = token;
            }),
            "");
  EXPECT_EQ(with([&](auto& r) {
              r.queryToken = "";
              r.cookie = "a=b; dform_studio_8000=" + token;
            }),
            "");
  EXPECT_NE(with([&](auto& r) {
              r.queryToken = "";
              r.cookie = "dform_studio_8001=" + token;
            }),
            "");
  EXPECT_EQ(with([](auto& r) { r.host = "localhost:8000"; }), "");
  EXPECT_EQ(with([](auto& r) { r.host = "[::1]:8000"; }), "");
  EXPECT_NE(with([](auto& r) { r.host = "127.0.0.1"; }), "");
  EXPECT_NE(with([](auto& r) { r.host = "attacker.example:8000"; }), "");
  EXPECT_EQ(with([](auto& r) { r.origin = "http://127.0.0.1:8000"; }), "");
  EXPECT_NE(with([](auto& r) { r.origin = "https://127.0.0.1:8000"; }), "");
  EXPECT_NE(with([](auto& r) { r.origin = "http://attacker.example"; }), "");
  EXPECT_NE(with([](auto& r) { r.fetchSite = "cross-site"; }), "");
  EXPECT_EQ(with([](auto& r) { r.fetchSite = "same-origin"; }), "");
}

TEST(StudioGuard, TokensAreRandomHex) {
  const std::string a = studio::randomToken(), b = studio::randomToken();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
}

TEST(StudioGuard, UploadNamesAreFileNamesOnly) {
  const std::vector<std::string> ext = {".svg", ".json"};
  EXPECT_EQ(studio::safeFileName("../../etc/passwd.svg", ext, "x.svg"), "passwd.svg");
  EXPECT_EQ(studio::safeFileName("C:\\a\\b.json", ext, "x.svg"), "b.json");
  EXPECT_EQ(studio::safeFileName("my piece.svg", ext, "x.svg"), "my-piece.svg");
  EXPECT_EQ(studio::safeFileName(".hidden.svg", ext, "x.svg"), "hidden.svg");
  EXPECT_EQ(studio::safeFileName("job.json", ext, "x.svg"), "x.svg");
  EXPECT_EQ(studio::safeFileName("notes.txt", ext, "x.svg"), "x.svg");
  EXPECT_EQ(studio::safeFileName("..", ext, "x.svg"), "x.svg");
}

// Every kind at its defaults and at both ends of every slider is an outline io accepts, with
// the perimeter its formula gives where there is one.
TEST(StudioOutlines, EveryKindReadsAtEveryExtreme) {
  for (const studio::OutlineKind& kind : studio::outlineKinds()) {
    std::vector<std::map<std::string, double>> settings = {{}};
    for (const studio::Parameter& p : kind.parameters) {
      settings.push_back({{p.name, p.min}});
      settings.push_back({{p.name, p.max}});
    }
    for (const auto& values : settings) {
      Result<Shape2> shape =
          parseOutline(studio::parametricOutline(kind.name, values), kind.name + ".json");
      EXPECT_TRUE(shape.isOk()) << kind.name << ": " << shape.status().message();
    }
  }
  auto perimeter = [](const std::string& kind, std::map<std::string, double> values) {
    const Points2 p =
        parseOutline(studio::parametricOutline(kind, values), "x.json").value().outer.points;
    double length = 0;
    for (Eigen::Index i = 0; i < p.rows(); ++i)
      length += (p.row((i + 1) % p.rows()) - p.row(i)).norm();
    return length;
  };
  const double pi = std::acos(-1.0);
  EXPECT_NEAR(perimeter("ellipse", {{"a", 100}, {"b", 100}}), 2 * pi * 100, 1e-3);
  EXPECT_NEAR(perimeter("polygon", {{"sides", 6}, {"radius", 50}}), 300, 1e-9);
  // A Reuleaux polygon of width w has perimeter pi w (Barbier's theorem).
  const double width = 2 * 100 * std::cos(pi / 6);  // the Reuleaux triangle of circumradius 100
  EXPECT_NEAR(perimeter("reuleaux", {{"sides", 3}, {"radius", 100}}), pi * width, 1e-2);
  EXPECT_NEAR(perimeter("rounded_rectangle", {{"width", 200}, {"height", 100}, {"radius", 20}}),
              2 * (160 + 60) + 2 * pi * 20, 1e-2);
  EXPECT_EQ(studio::parametricOutline("heart", {}), "");
}

// The corners an outline's answer lists (where a dragged start snaps): a regular polygon's and a
// Reuleaux polygon's vertices, evenly spaced in arc length from the first; a smooth ellipse none.
// A request's seq: 0 where it has none (most requests may omit it), required by those that
// name an input (/api/settle), and a whole number wherever it is given.
TEST(StudioWire, ARequestsSeqIsAWholeNumber) {
  using nlohmann::json;
  EXPECT_EQ(studio::sequence(json{{"seq", 12}}), 12);
  EXPECT_EQ(studio::sequence(json{{"seq", 12}}, true), 12);
  EXPECT_EQ(studio::sequence(json::object()), 0);
  EXPECT_THROW(studio::sequence(json::object(), true), studio::RequestError);
  for (const json& bad : {json(2.5), json("3"), json(nullptr), json::array({1})}) {
    EXPECT_THROW(studio::sequence(json{{"seq", bad}}), studio::RequestError) << bad;
    EXPECT_THROW(studio::sequence(json{{"seq", bad}}, true), studio::RequestError) << bad;
  }
}

TEST(StudioWire, TheCornersAreTheOutlinesSharpTurns) {
  const auto corners = [](const std::string& kind, std::map<std::string, double> values) {
    const Shape2 shape = parseOutline(studio::parametricOutline(kind, values), "x.json").value();
    return studio::shapeJson(shape)["corners"].get<std::vector<double>>();
  };
  for (const auto& [kind, n] : {std::pair<std::string, int>{"polygon", 6}, {"reuleaux", 3}}) {
    const std::vector<double> c = corners(kind, {{"sides", n}, {"radius", 100}});
    ASSERT_EQ(c.size(), std::size_t(n)) << kind;
    for (int k = 0; k < n; ++k) EXPECT_NEAR(c[std::size_t(k)], double(k) / n, 1e-3) << kind;
  }
  EXPECT_TRUE(corners("ellipse", {{"a", 110}, {"b", 80}}).empty());
}

// Where the mirror axes cross an outline (where a dragged start snaps too): an ellipse's two axes
// at its four vertices, a hexagon's six at its corners and sides' middles, each point on its axis;
// a circle (every line through its centre) and a lopsided outline none.
TEST(StudioWire, TheAxesAreWhereMirrorAxesCrossTheOutline) {
  const auto axes = [](const std::string& kind, std::map<std::string, double> values) {
    const Shape2 shape = parseOutline(studio::parametricOutline(kind, values), "x.json").value();
    const json j = studio::shapeJson(shape);
    return std::make_pair(j["axes"].get<std::vector<double>>(), shape.outer.points);
  };
  const auto [ellipse, e] = axes("ellipse", {{"a", 110}, {"b", 80}});
  ASSERT_EQ(ellipse.size(), 4u);
  for (const double f : ellipse) {
    const Eigen::Vector2d p = resampleAtFractions(e, {f}).row(0).transpose();
    EXPECT_LT(std::min(std::abs(p.x()), std::abs(p.y())), 0.05) << f << ": " << p.transpose();
  }
  const auto [hexagon, h] = axes("polygon", {{"sides", 6}, {"radius", 100}});
  ASSERT_EQ(hexagon.size(), 12u);
  for (int k = 0; k < 12; ++k) EXPECT_NEAR(hexagon[std::size_t(k)], k / 12.0, 1e-3);
  EXPECT_TRUE(axes("ellipse", {{"a", 100}, {"b", 100}}).first.empty());
  // A triangle with three different sides: no mirror.
  const Shape2 lopsided =
      parseOutline(R"({"points": [[0, 0], [100, 0], [30, 60]], "units": "mm"})", "t.json").value();
  EXPECT_TRUE(studio::shapeJson(lopsided)["axes"].empty());
}

}  // namespace
}  // namespace dform
