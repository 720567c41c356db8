#include "test_util.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace dform::test {

namespace fs = std::filesystem;

const SvgPath* SvgDoc::find(const std::string& id) const {
  for (const auto& p : paths)
    if (p.id == id) return &p;
  return nullptr;
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {
std::string attribute(const std::string& element, const std::string& name) {
  const std::regex re("\\s" + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(element, m, re) ? m[1].str() : std::string();
}

std::string styleValue(const std::string& style, const std::string& key) {
  const std::regex re("(^|;)" + key + ":([^;]*)");
  std::smatch m;
  return std::regex_search(style, m, re) ? m[2].str() : std::string();
}
}  // namespace

SvgDoc readSvg(const std::string& path) {
  const std::string text = readText(path);
  SvgDoc doc;
  const std::regex element("<(svg|g|path)\\s[^>]*>");
  std::string layer;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), element);
       it != std::sregex_iterator(); ++it) {
    const std::string e = it->str();
    const std::string tag = (*it)[1].str();
    if (tag == "svg") {
      doc.width = attribute(e, "width");
      doc.height = attribute(e, "height");
      doc.viewBox = attribute(e, "viewBox");
    } else if (tag == "g") {
      if (attribute(e, "inkscape:groupmode") == "layer") {
        layer = attribute(e, "inkscape:label");
        doc.layers.push_back(layer);
      }
    } else {
      SvgPath p;
      p.id = attribute(e, "id");
      p.layer = layer;
      p.style = attribute(e, "style");
      p.fill = styleValue(p.style, "fill");
      p.stroke = styleValue(p.style, "stroke");
      const std::string w = styleValue(p.style, "stroke-width");
      p.strokeWidth = w.empty() ? 0 : std::stod(w);
      std::istringstream d(attribute(e, "d"));
      std::string token;
      while (d >> token) {
        if (token == "M") {
          p.parts.emplace_back();
        } else if (token == "Z") {
          p.closed = true;
          continue;
        } else if (token != "L") {
          p.unknownCommand = true;
          continue;
        }
        if (token == "M" || token == "L") {
          double x = 0, y = 0;
          d >> x >> y;
          p.parts.back().emplace_back(x, y);
        }
      }
      doc.paths.push_back(p);
    }
  }
  return doc;
}

ExportOptions options(const std::string& profile) {
  ExportOptions o;
  o.profile = profile;
  o.templatesDir = DFORM_TEMPLATES_DIR;
  o.jobName = "test-job";
  return o;
}

Exported exportTo(const std::string& name, const DForm& model, const ExportOptions& o) {
  Exported e;
  e.dir = freshDir(name);
  auto result = exportAll(model, o, e.dir);
  EXPECT_TRUE(result.isOk()) << result.status().message();
  if (!result.isOk()) return e;
  e.summary = result.value();
  e.svg = readSvg(e.dir + "/pattern.svg");
  e.sidecar = nlohmann::json::parse(readText(e.dir + "/pattern.json"));
  return e;
}

fab::PatternBuild build(const DForm& model, const ExportOptions& o) {
  auto profile = fab::resolveProfile(o);
  EXPECT_TRUE(profile.isOk()) << profile.status().message();
  auto pattern = fab::buildPattern(model, o, profile.value());
  EXPECT_TRUE(pattern.isOk()) << pattern.status().message();
  return pattern.isOk() ? pattern.value() : fab::PatternBuild{};
}

Polyline toPolyline(const nlohmann::json& j) {
  Polyline p;
  for (const auto& q : j) p.emplace_back(q[0].get<double>(), q[1].get<double>());
  return p;
}

double length(const Polyline& p, bool closed) {
  double len = 0;
  for (size_t i = 0; i + 1 < p.size(); ++i) len += (p[i + 1] - p[i]).norm();
  if (closed && p.size() > 1) len += (p.front() - p.back()).norm();
  return len;
}

std::pair<double, double> arcLengthOf(const Polyline& loop, const Vec2& q) {
  double best = 1e300, bestS = 0, acc = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    const Vec2 ab = b - a;
    const double t =
        ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
    const double dist = (a + t * ab - q).norm();
    if (dist < best) {
      best = dist;
      bestS = acc + t * ab.norm();
    }
    acc += ab.norm();
  }
  return {bestS, best};
}

bool inside(const Polyline& poly, const Vec2& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y() > q.y()) != (poly[j].y() > q.y()) &&
        q.x() < (poly[j].x() - poly[i].x()) * (q.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) +
                    poly[i].x())
      in = !in;
  }
  return in;
}

bool crossing(const Polyline& loop, const Vec2& a, const Vec2& b, Vec2* at) {
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2 c = loop[i], d = loop[(i + 1) % loop.size()];
    const Vec2 r = b - a, s = d - c;
    const double den = r.x() * s.y() - r.y() * s.x();
    if (std::abs(den) < 1e-15) continue;
    const Vec2 ca = c - a;
    const double t = (ca.x() * s.y() - ca.y() * s.x()) / den;
    const double u = (ca.x() * r.y() - ca.y() * r.x()) / den;
    if (t >= 0 && t <= 1 && u >= 0 && u <= 1) {
      *at = a + t * r;
      return true;
    }
  }
  return false;
}

int run(const std::string& command, std::string* out) {
  std::string text;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) text.append(buf.data(), n);
  const int status = pclose(pipe);
  if (out) *out = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool haveProgram(const std::string& name) { return run("command -v " + name + " >/dev/null") == 0; }

// This process's scratch root, removed when the test program exits.
struct ScratchRoot {
  const fs::path path =
      fs::temp_directory_path() / ("dform-export-test-" + std::to_string(::getpid()));
  ~ScratchRoot() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string freshDir(const std::string& name) {
  static const ScratchRoot root;
  const fs::path dir = root.path / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

}  // namespace dform::test
