// SPDX-License-Identifier: GPL-3.0-or-later
// What Cairo cannot write into pattern.pdf, added as incremental updates (PDF 32000-1 §7.5.6):
// objects appended after Cairo's bytes, each update with its own cross-reference section and a
// trailer pointing back to the previous one, so Cairo's bytes stay as they are. The catalog asks
// viewers to print at 100 %; a spot-colour layer (a RIP's CutContour) is drawn in its Separation
// colour space, which Cairo has no API for: a content stream of its own appended to each page that
// shows it, the page's resources naming the colour space.
//
// Post-processing with qpdf is the other way: the qpdf program at run time (a dependency of the
// installed dform, and a second process per export) or libqpdf (Debian's libqpdf29, 2.9 MB
// installed, a C++ library that parses and rewrites the whole file) for what needs a dozen short
// objects; Cairo 1.16 writes its page and resource dictionaries uncompressed, so they are found
// and rewritten here as text, and qpdf checks the result in the tests.
#include <cstdio>
#include <cstdlib>
#include <set>

#include "internal.h"

namespace dform::fab {

namespace {

constexpr double kPointsPerMm = 72.0 / 25.4;

// The number after `key` in `text` from `from` on ("/Root 11 0 R" -> 11), or -1.
long numberAfter(const std::string& text, const std::string& key, std::size_t from) {
  const std::size_t at = text.find(key, from);
  if (at == std::string::npos) return -1;
  return std::strtol(text.c_str() + at + key.size(), nullptr, 10);
}

// The newest definition of object `n` (its dictionary "<< ... >>"), or "" when there is none.
std::string objectBody(const std::string& pdf, long n) {
  const std::string header = "\n" + std::to_string(n) + " 0 obj\n";
  const std::size_t object = pdf.rfind(header);
  if (object == std::string::npos) return std::string();
  const std::size_t end = pdf.find("endobj", object);
  const std::size_t open = pdf.find("<<", object);
  const std::size_t close = end == std::string::npos ? end : pdf.rfind(">>", end);
  if (end == std::string::npos || open > close) return std::string();
  return pdf.substr(open, close + 2 - open);
}

// `pdf` with `objects` (number, body) appended as one incremental update whose trailer has
// /Size `size` and the previous trailer's /Root and /Info.
Result<std::string> appendUpdate(std::string pdf,
                                 const std::vector<std::pair<long, std::string>>& objects,
                                 long size) {
  const std::size_t trailer = pdf.rfind("trailer");
  const std::size_t startxref = pdf.rfind("startxref");
  if (trailer == std::string::npos || startxref == std::string::npos || startxref < trailer)
    return Status(ErrorCode::Internal, "pattern.pdf: Cairo wrote no trailer");
  const long root = numberAfter(pdf, "/Root ", trailer), info = numberAfter(pdf, "/Info ", trailer),
             previous = numberAfter(pdf, "startxref", startxref);
  if (root < 0 || previous < 0)
    return Status(ErrorCode::Internal, "pattern.pdf: Cairo's trailer is not as expected");
  std::string xref = "xref\n";
  for (const auto& [n, body] : objects) {
    const std::size_t at = pdf.size() + 1;  // after the newline below
    pdf += "\n" + std::to_string(n) + " 0 obj\n" + body + "\nendobj\n";
    char entry[32];
    std::snprintf(entry, sizeof entry, "%010zu 00000 n \n", at);
    xref += std::to_string(n) + " 1\n" + entry;
  }
  const std::size_t xrefAt = pdf.size();
  pdf += xref + "trailer\n<< /Size " + std::to_string(size) + " /Root " + std::to_string(root) +
         " 0 R" + (info >= 0 ? " /Info " + std::to_string(info) + " 0 R" : std::string()) +
         " /Prev " + std::to_string(previous) + " >>\nstartxref\n" + std::to_string(xrefAt) +
         "\n%%EOF\n";
  return pdf;
}

// The page objects' numbers, in page order (Cairo writes one /Pages node with every /Kids).
std::vector<long> pageObjects(const std::string& pdf) {
  std::vector<long> pages;
  const std::size_t kids = pdf.find("/Kids [");
  if (kids == std::string::npos) return pages;
  const std::size_t end = pdf.find(']', kids);
  for (std::size_t at = kids + 7; at < end;) {
    char* next = nullptr;
    const long n = std::strtol(pdf.c_str() + at, &next, 10);
    if (next == pdf.c_str() + at) break;
    pages.push_back(n);
    const std::size_t r = pdf.find(" R", std::size_t(next - pdf.c_str()));
    if (r == std::string::npos || r > end) break;
    at = r + 2;
  }
  return pages;
}

std::string pdfNumber(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", x);
  return buf;
}

// The content stream drawing `layer`'s paths that the page shows, in colour space resource
// `name` at full tint, in the page's default user space (points, y up); "" when it shows none.
std::string spotStream(const Layer& layer, const PageView& page, const std::string& name) {
  const Box shown = Box::spanning(page.origin + Vec2(page.clipX0, page.clipY0),
                                  page.origin + Vec2(page.clipX1, page.clipY1));
  const double k = kPointsPerMm;
  auto point = [&](const Vec2& q) {
    const Vec2 p = q - page.origin;
    return pdfNumber(p.x() * k) + " " + pdfNumber((page.height - p.y()) * k);
  };
  std::string paths;
  for (const Path& path : layer.paths) {
    if (!shown.overlaps(boxOf(path.parts))) continue;
    for (const Polyline& part : path.parts) {
      for (size_t i = 0; i < part.size(); ++i) paths += point(part[i]) + (i == 0 ? " m\n" : " l\n");
      if (path.closed && !part.empty()) paths += "h\n";
    }
    paths += "S\n";
  }
  if (paths.empty()) return std::string();
  // Cairo's stream ran inside "q" (the page's first stream): back to the page's own state, then
  // the page's window clipped as Cairo clips it.
  return "Q\nq\n" + pdfNumber(page.clipX0 * k) + " " + pdfNumber((page.height - page.clipY1) * k) +
         " " + pdfNumber((page.clipX1 - page.clipX0) * k) + " " +
         pdfNumber((page.clipY1 - page.clipY0) * k) + " re W n\n/" + name + " CS 1 SCN\n" +
         pdfNumber(layer.widthMm * k) + " w 1 J 1 j\n" + paths + "Q\n";
}

std::string stream(const std::string& content) {
  return "<< /Length " + std::to_string(content.size()) + " >>\nstream\n" + content + "\nendstream";
}

}  // namespace

Result<std::string> withPrintScalingNone(std::string pdf) {
  const std::size_t trailer = pdf.rfind("trailer");
  if (trailer == std::string::npos)
    return Status(ErrorCode::Internal, "pattern.pdf: Cairo wrote no trailer");
  const long root = numberAfter(pdf, "/Root ", trailer), size = numberAfter(pdf, "/Size ", trailer);
  std::string catalog = objectBody(pdf, root);
  if (root < 0 || size < 0 || catalog.empty())
    return Status(ErrorCode::Internal,
                  "pattern.pdf: Cairo's catalog or trailer is not as expected");
  catalog.insert(2, " /ViewerPreferences << /PrintScaling /None >>");
  return appendUpdate(std::move(pdf), {{root, catalog}}, size);
}

Result<std::string> withSpotLayers(std::string pdf, const PatternBuild& pattern) {
  const Layer* spot = nullptr;
  for (const Layer& layer : pattern.drawing.layers)
    if (!layer.spot.empty()) spot = &layer;
  if (!spot) return pdf;
  const std::size_t trailer = pdf.rfind("trailer");
  long size = trailer == std::string::npos ? -1 : numberAfter(pdf, "/Size ", trailer);
  const std::vector<long> pages = pageObjects(pdf);
  if (size < 0 || pages.size() < pattern.pages.size())
    return Status(ErrorCode::Internal, "pattern.pdf: Cairo's pages are not as expected");
  // The colour space: the spot colour by name, magenta (its usual screen colour) where a device
  // has no such ink; and a stream that opens the state Cairo's streams then run in.
  const long colourSpace = size++, open = size++;
  std::vector<std::pair<long, std::string>> objects{
      {colourSpace, "[ /Separation /" + spot->spot +
                        " /DeviceCMYK << /FunctionType 2 /Domain [ 0 1 ] /C0 [ 0 0 0 0 ] "
                        "/C1 [ 0 1 0 0 ] /N 1 >> ]"},
      {open, stream("q")}};
  std::set<long> resourcesDone;
  for (size_t k = 0; k < pattern.pages.size(); ++k) {
    const std::string content = spotStream(*spot, pattern.pages[k], "CS1");
    if (content.empty()) continue;
    std::string page = objectBody(pdf, pages[k]);
    const long contents = numberAfter(page, "/Contents ", 0),
               resources = numberAfter(page, "/Resources ", 0);
    const std::size_t at = page.find("/Contents ");
    if (page.empty() || contents < 0 || resources < 0 || at == std::string::npos)
      return Status(ErrorCode::Internal, "pattern.pdf: a page of Cairo's is not as expected");
    const long drawn = size++;
    objects.emplace_back(drawn, stream(content));
    const std::string reference = "/Contents " + std::to_string(contents) + " 0 R";
    page.replace(at, reference.size(),
                 "/Contents [ " + std::to_string(open) + " 0 R " + std::to_string(contents) +
                     " 0 R " + std::to_string(drawn) + " 0 R ]");
    objects.emplace_back(pages[k], page);
    if (!resourcesDone.insert(resources).second) continue;
    std::string dictionary = objectBody(pdf, resources);
    if (dictionary.empty() || dictionary.find("/ColorSpace") != std::string::npos)
      return Status(ErrorCode::Internal, "pattern.pdf: a page's resources are not as expected");
    dictionary.insert(2, " /ColorSpace << /CS1 " + std::to_string(colourSpace) + " 0 R >>");
    objects.emplace_back(resources, dictionary);
  }
  return appendUpdate(std::move(pdf), objects, size);
}

}  // namespace dform::fab
