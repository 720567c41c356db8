// SPDX-License-Identifier: GPL-3.0-or-later
#include "test_util.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
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

// Plain string scanning, not std::regex: libstdc++'s regex executor recurses once per character
// it matches, and a pattern's long path data overflowed the stack under AddressSanitizer.

// The value of attribute `name` in the start tag `element`, "" when it has none.
std::string attribute(const std::string& element, const std::string& name) {
  const std::string key = name + "=\"";
  for (std::size_t at = element.find(key); at != std::string::npos;
       at = element.find(key, at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(element[at - 1]))) continue;
    const std::size_t start = at + key.size(), end = element.find('"', start);
    return end == std::string::npos ? std::string() : element.substr(start, end - start);
  }
  return std::string();
}

// The value of `key` in a CSS declaration list "a:1;b:2", "" when it has none.
std::string styleValue(const std::string& style, const std::string& key) {
  std::istringstream declarations(style);
  std::string declaration;
  while (std::getline(declarations, declaration, ';'))
    if (declaration.rfind(key + ":", 0) == 0) return declaration.substr(key.size() + 1);
  return std::string();
}

}  // namespace

SvgDoc readSvg(const std::string& path) {
  const std::string text = readText(path);
  SvgDoc doc;
  std::string layer;
  // Every <svg ...>, <g ...> and <path ...> start tag, in order.
  for (std::size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 1)) {
    std::size_t nameEnd = at + 1;
    while (nameEnd < text.size() && std::isalpha(static_cast<unsigned char>(text[nameEnd])))
      ++nameEnd;
    const std::string tag = text.substr(at + 1, nameEnd - at - 1);
    if ((tag != "svg" && tag != "g" && tag != "path") || nameEnd == text.size() ||
        !std::isspace(static_cast<unsigned char>(text[nameEnd])))
      continue;
    const std::size_t close = text.find('>', nameEnd);
    if (close == std::string::npos) break;
    const std::string e = text.substr(at, close - at + 1);
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

double parseMm(const std::string& s) {
  EXPECT_EQ(s.substr(s.size() < 2 ? 0 : s.size() - 2), "mm") << s;
  return s.size() < 2 ? -1 : std::stod(s.substr(0, s.size() - 2));
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

double solvedPerimeter(const Piece& piece) {
  Polyline seam;
  for (int v : piece.seam) seam.push_back(piece.flat.row(v).transpose());
  return length(seam, true);
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

std::pair<Eigen::Vector3d, double> seamPoint3d(const Piece& piece, const Polyline& outline,
                                               const Vec2& q) {
  double best = 1e300;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  const size_t n = outline.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = outline[i], ab = outline[(i + 1) % n] - a;
    const double f = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double dist = (a + f * ab - q).norm();
    if (dist < best) {
      best = dist;
      at = (1 - f) * piece.shape.row(piece.seam[i]).transpose() +
           f * piece.shape.row(piece.seam[(i + 1) % n]).transpose();
    }
  }
  return {at, best};
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

namespace {

// The tokens of a PDF content stream: numbers and operators; strings, names, arrays and
// dictionaries (operands of text and marked-content operators) come back as "?".
std::vector<std::string> contentTokens(const std::string& text) {
  std::vector<std::string> tokens;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '%') {
      while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
    } else if (c == '(') {  // a string, with nesting and escapes
      int depth = 0;
      for (; i < text.size(); ++i) {
        if (text[i] == '\\')
          ++i;
        else if (text[i] == '(')
          ++depth;
        else if (text[i] == ')' && --depth == 0)
          break;
      }
      ++i;
      tokens.push_back("?");
    } else if (c == '<' || c == '>' || c == '[' || c == ']' || c == '{' || c == '}') {
      ++i;
      if (c == '<' && i < text.size() && text[i] != '<')  // a hex string
        while (i < text.size() && text[i] != '>') ++i;
      tokens.push_back("?");
    } else {
      const size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
             std::string("()<>[]{}/%").find(text[i]) == std::string::npos)
        ++i;
      if (i == start) {  // a name: '/' and its characters
        ++i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) &&
               std::string("()<>[]{}/%").find(text[i]) == std::string::npos)
          ++i;
        tokens.push_back(text.substr(start, i - start));
      } else {
        tokens.push_back(text.substr(start, i - start));
      }
    }
  }
  return tokens;
}

// Affine map [a b c d e f] as PDF writes it: (x, y) -> (a x + c y + e, b x + d y + f).
using Affine = std::array<double, 6>;
Affine then(const Affine& m, const Affine& n) {  // m first, then n
  return {m[0] * n[0] + m[1] * n[2],        m[0] * n[1] + m[1] * n[3],
          m[2] * n[0] + m[3] * n[2],        m[2] * n[1] + m[3] * n[3],
          m[4] * n[0] + m[5] * n[2] + n[4], m[4] * n[1] + m[5] * n[3] + n[5]};
}

}  // namespace

std::vector<PdfPath> readPdfPaths(const std::string& pdf) {
  std::string pages;
  if (run("qpdf --show-pages " + pdf, &pages) != 0) {
    ADD_FAILURE() << "qpdf cannot list the pages of " << pdf << ": " << pages;
    return {};
  }
  // "page 1: 2 0 R" then its content streams, "    4 0 R".
  std::vector<std::pair<int, std::vector<int>>> pageContents;
  std::istringstream lines(pages);
  for (std::string line; std::getline(lines, line);) {
    int page = 0, object = 0;
    if (std::sscanf(line.c_str(), "page %d: %d 0 R", &page, &object) == 2)
      pageContents.push_back({object, {}});
    else if (std::sscanf(line.c_str(), " %d 0 R", &object) == 1 && !pageContents.empty())
      pageContents.back().second.push_back(object);
  }
  constexpr double kMmPerPt = 25.4 / 72.0;
  std::vector<PdfPath> paths;
  for (size_t p = 0; p < pageContents.size(); ++p) {
    std::string page;
    run("qpdf --show-object=" + std::to_string(pageContents[p].first) + " " + pdf, &page);
    double box[4] = {0, 0, 0, 0};
    const size_t at = page.find("/MediaBox");
    if (at == std::string::npos || std::sscanf(page.c_str() + at, "/MediaBox [ %lf %lf %lf %lf",
                                               &box[0], &box[1], &box[2], &box[3]) != 4) {
      ADD_FAILURE() << pdf << " page " << p + 1 << " has no MediaBox: " << page;
      return {};
    }
    std::vector<Affine> saved;
    Affine ctm{1, 0, 0, 1, 0, 0};
    std::vector<double> operands;
    Eigen::Vector3d strokeColor = Eigen::Vector3d::Zero(), fillColor = Eigen::Vector3d::Zero();
    std::string name, strokeSpace, fillSpace;  // the last name operand; the colour spaces
    std::vector<PdfPath> current;              // the path being built, one entry per subpath
    auto point = [&](double x, double y) {
      const double X = ctm[0] * x + ctm[2] * y + ctm[4], Y = ctm[1] * x + ctm[3] * y + ctm[5];
      return Vec2((X - box[0]) * kMmPerPt, (box[3] - Y) * kMmPerPt);
    };
    auto startSubpath = [&](const Vec2& q) {
      PdfPath path;
      path.page = int(p) + 1;
      path.points.push_back(q);
      current.push_back(path);
    };
    for (int object : pageContents[p].second) {
      std::string content;
      run("qpdf --show-object=" + std::to_string(object) + " --filtered-stream-data " + pdf,
          &content);
      for (const std::string& token : contentTokens(content)) {
        char* end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        if (token != "?" && end == token.c_str() + token.size()) {
          operands.push_back(value);
          continue;
        }
        if (token[0] == '/') {  // a name operand ("/CS1 CS")
          name = token.substr(1);
          continue;
        }
        const auto& o = operands;
        const size_t n = o.size();
        if (token == "q") {
          saved.push_back(ctm);
        } else if (token == "Q" && !saved.empty()) {
          ctm = saved.back();
          saved.pop_back();
        } else if (token == "cm" && n >= 6) {
          ctm = then({o[n - 6], o[n - 5], o[n - 4], o[n - 3], o[n - 2], o[n - 1]}, ctm);
        } else if (token == "m" && n >= 2) {
          startSubpath(point(o[n - 2], o[n - 1]));
        } else if ((token == "l" && n >= 2) || (token == "c" && n >= 6) ||
                   ((token == "v" || token == "y") && n >= 4)) {
          if (!current.empty()) current.back().points.push_back(point(o[n - 2], o[n - 1]));
        } else if (token == "h" && !current.empty()) {
          current.back().closed = true;
        } else if (token == "re" && n >= 4) {
          const double x = o[n - 4], y = o[n - 3], w = o[n - 2], h = o[n - 1];
          startSubpath(point(x, y));
          for (const Vec2& q : {point(x + w, y), point(x + w, y + h), point(x, y + h)})
            current.back().points.push_back(q);
          current.back().closed = true;
        } else if ((token == "RG" || token == "rg") && n >= 3) {
          (token == "RG" ? strokeColor : fillColor) = Eigen::Vector3d(o[n - 3], o[n - 2], o[n - 1]);
          (token == "RG" ? strokeSpace : fillSpace).clear();
        } else if (token == "CS" || token == "cs") {
          (token == "CS" ? strokeSpace : fillSpace) = name;
        } else if (std::string(" S s f F f* B B* b b* n ").find(" " + token + " ") !=
                   std::string::npos) {
          const bool stroked = token == "S" || token == "s" || token[0] == 'B' || token[0] == 'b';
          for (PdfPath& path : current) {
            path.color = stroked ? strokeColor : fillColor;
            path.space = stroked ? strokeSpace : fillSpace;
            if (token == "s" || token == "b" || token == "b*") path.closed = true;
            // A closed subpath drawn back to its start: the start once.
            if (path.points.size() > 2 &&
                (path.points.front() - path.points.back()).norm() < 1e-9) {
              path.points.pop_back();
              path.closed = true;
            }
            if (token != "n") paths.push_back(path);
          }
          current.clear();
        }
        operands.clear();
      }
    }
  }
  return paths;
}

namespace {

// The largest distance from a point of `from` to the closed polyline `to`.
double farthestFrom(const Polyline& from, const Polyline& to) {
  double worst = 0.0;
  for (const Vec2& q : from) {
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < to.size(); ++k) {
      const Vec2 a = to[k], d = to[(k + 1) % to.size()] - a;
      const double t =
          d.squaredNorm() > 0 ? std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, (a + t * d - q).norm());
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace

double closestDrawing(const std::vector<PdfPath>& paths, const Polyline& loop) {
  auto box = [](const Polyline& points) {
    Vec2 lo = points.front(), hi = points.front();
    for (const Vec2& q : points) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    return std::make_pair(lo, hi);
  };
  double best = std::numeric_limits<double>::infinity();
  if (loop.empty()) return best;
  const auto [lo, hi] = box(loop);
  for (const PdfPath& path : paths) {
    if (!path.closed || path.points.size() < 3) continue;
    const auto [plo, phi] = box(path.points);
    if (((phi - plo) - (hi - lo)).cwiseAbs().maxCoeff() > 1.0) continue;  // another shape
    Polyline moved = path.points;
    for (Vec2& q : moved) q += lo - plo;
    best = std::min(best, std::max(farthestFrom(moved, loop), farthestFrom(loop, moved)));
  }
  return best;
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

int checkDxf(const std::string& dir, std::string* out, const std::string& extra) {
  const int code =
      run(std::string(DFORM_PYTHON3) + " '" + DFORM_DXF_CHECKER + "' '" + dir + "' " + extra, out);
  ::testing::Test::RecordProperty("check_dxf", *out);
  return code;
}

void expectDxfChecks(const std::string& dir, const std::string& extra) {
  std::string out;
  EXPECT_EQ(checkDxf(dir, &out, extra), 0) << out;
  std::printf("%s", out.c_str());  // the differences measured, for the log
}

// The best similarity (scale, turn, shift) taking points `from` onto `to` (as many, in the same
// order; Umeyama without reflection), and the largest distance it leaves, relative to the span
// of `to`.
namespace {

double similarityResidual(const std::vector<Vec2>& from, const std::vector<Vec2>& to) {
  Vec2 mf = Vec2::Zero(), mt = Vec2::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    mf += from[i];
    mt += to[i];
  }
  mf /= double(from.size());
  mt /= double(to.size());
  double a = 0, b = 0, norm = 0;  // to ~ s R from, R = [[c, -d], [d, c]]: s c = a / n, s d = b / n
  for (size_t i = 0; i < from.size(); ++i) {
    const Vec2 p = from[i] - mf, q = to[i] - mt;
    a += p.dot(q);
    b += p.x() * q.y() - p.y() * q.x();
    norm += p.squaredNorm();
  }
  if (norm <= 0) return 1e300;
  const double c = a / norm, d = b / norm;
  double worst = 0, span = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    const Vec2 p = from[i] - mf;
    const Vec2 mapped = mt + Vec2(c * p.x() - d * p.y(), d * p.x() + c * p.y());
    worst = std::max(worst, (mapped - to[i]).norm());
    span = std::max(span, (to[i] - mt).norm());
  }
  return span > 0 ? worst / span : 1e300;
}

}  // namespace

// Whether the text path's first strokes write `words`: the Hershey strokes of `words`, stroke for
// stroke and point for point, up to a similarity (its position, height and direction).
bool startsWithText(const fab::Path& path, const std::string& words, const fab::StrokeFont& font) {
  const std::vector<Polyline> expected = font.layout(words, Vec2::Zero(), Vec2(1, 0), 1.0);
  if (expected.empty() || path.parts.size() < expected.size()) return false;
  std::vector<Vec2> from, to;
  for (size_t k = 0; k < expected.size(); ++k) {
    if (path.parts[k].size() != expected[k].size()) return false;
    from.insert(from.end(), expected[k].begin(), expected[k].end());
    to.insert(to.end(), path.parts[k].begin(), path.parts[k].end());
  }
  return similarityResidual(from, to) < 1e-6;
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
