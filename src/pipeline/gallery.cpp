// SPDX-License-Identifier: GPL-3.0-or-later
// gallery.html: the sweep's shapes side by side, one card per row of sweep.json.
#include <cstdio>
#include <string>

#include "dform/core/message_text.h"
#include "dform/pipeline/sweep.h"

namespace dform {

namespace {

// A folder name as one segment of a relative URL: every byte but letters, digits and "-._~"
// written %XX, so that a name with '#', '?', '%', a space or bytes that are not UTF-8 links to
// the folder of exactly that name.
std::string urlSegment(const std::string& name) {
  static const char* const kHex = "0123456789ABCDEF";
  std::string out;
  for (const char c : name) {
    const unsigned char b = static_cast<unsigned char>(c);
    const bool letter = (b | 32) >= 'a' && (b | 32) <= 'z', digit = b >= '0' && b <= '9';
    if (letter || digit || c == '-' || c == '.' || c == '_' || c == '~') {
      out += c;
    } else {
      out += '%';
      out += kHex[b >> 4];
      out += kHex[b & 15];
    }
  }
  return out;
}

std::string number(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// The sort keys: each a data- attribute of every card and a button in the header.
struct Key {
  const char* attribute;
  const char* label;
};
constexpr Key kKeys[] = {{"order", "order"},   {"height", "height"},
                         {"volume", "volume"}, {"curvature", "max |curvature|"},
                         {"passed", "gate"},   {"seconds", "time"}};

constexpr const char* kStyle = R"(
body{font-family:system-ui,sans-serif;margin:1.5em;color:#222}
h1{font-size:1.3em}
.sort button{margin:0 .3em .8em 0;padding:.3em .7em;border:1px solid #888;background:#f4f4f4;cursor:pointer}
.sort button.on{background:#333;color:#fff}
.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(260px,1fr));gap:12px}
.card{border:1px solid #ccc;border-radius:6px;padding:8px;background:#fff}
.card a{color:inherit;text-decoration:none}
.card .pic{height:200px;display:flex;align-items:center;justify-content:center}
.card .pic svg{max-width:100%;max-height:200px}
.card table{font-size:.85em;border-collapse:collapse;width:100%}
.card td{padding:1px 4px}
.card td:last-child{text-align:right}
.card td[colspan]{text-align:left}
.card.failed{opacity:.55;filter:grayscale(1);background:#eee}
.card .why{font-size:.8em;color:#a00;word-break:break-word}
)";

// Sorts the cards by a key; a second click on the same key reverses the order.
constexpr const char* kScript = R"(
(function(){
  var grid=document.getElementById('cards'),key=null,up=true;
  document.querySelectorAll('.sort button').forEach(function(b){
    b.addEventListener('click',function(){
      var k=b.getAttribute('data-key');up=k===key?!up:true;key=k;
      document.querySelectorAll('.sort button').forEach(function(o){o.classList.toggle('on',o===b);});
      var cards=Array.prototype.slice.call(grid.children);
      cards.sort(function(x,y){
        var a=parseFloat(x.getAttribute('data-'+k)),c=parseFloat(y.getAttribute('data-'+k));
        if(isNaN(a))a=Infinity;if(isNaN(c))c=Infinity;
        return up?a-c:c-a;});
      cards.forEach(function(c){grid.appendChild(c);});
    });
  });
})();
)";

}  // namespace

std::string galleryHtml(const std::string& title, const std::vector<SweepRow>& rows) {
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
                     escapeXml(utf8Text(title)) + "</title>\n<style>" + kStyle +
                     "</style></head>\n<body>\n<h1>" + escapeXml(utf8Text(title)) + "</h1>\n<p>" +
                     std::to_string(rows.size()) +
                     " results; click a card for its report, a button to sort.</p>\n"
                     "<div class=\"sort\">sort by ";
  for (const Key& key : kKeys)
    html += std::string("<button type=\"button\" data-key=\"") + key.attribute + "\">" + key.label +
            "</button>";
  html += "</div>\n<div class=\"grid\" id=\"cards\">\n";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const SweepRow& r = rows[k];
    const bool ok = r.solved && r.passed;
    const std::string nan = "NaN";
    html += std::string("<div class=\"card") + (ok ? "" : " failed") + "\" data-subfolder=\"" +
            escapeXml(utf8Text(r.subfolder)) + "\" data-order=\"" + std::to_string(k) +
            "\" data-height=\"" + (r.solved ? number("%.17g", r.heightMm) : nan) +
            "\" data-volume=\"" + (r.solved ? number("%.17g", r.volumeMm3) : nan) +
            "\" data-curvature=\"" + (r.solved ? number("%.17g", r.maxCurvature) : nan) +
            "\" data-passed=\"" + (ok ? "0" : "1") + "\" data-seconds=\"" +
            number("%.17g", r.seconds) + "\">\n";
    // A card links to its result's page only where the result is there (an empty subfolder: the
    // folder is not one the run made, and nothing is linked).
    const bool linked = !r.subfolder.empty();
    if (linked) html += "<a href=\"" + urlSegment(r.subfolder) + "/report.html\">";
    html += "<div class=\"pic\">" + (r.solved ? r.svg : std::string("<span>no shape</span>")) +
            "</div>\n<table>";
    const auto line = [&](const std::string& name, const std::string& value) {
      html += "<tr><td>" + name + "</td><td>" + value + "</td></tr>";
    };
    html += "<tr><td colspan=\"2\"><b>" + escapeXml(utf8Text(r.label)) + "</b></td></tr>";
    if (r.solved) {
      line("model", escapeXml(utf8Text(r.model)));
      line("height", number("%.1f mm", r.heightMm));
      line("volume", number("%.4g", r.volumeMm3 / 1000) + " cm&sup3;");
      line("max |curvature|", number("%.3g rad", r.maxCurvature));
    }
    line("gate", ok ? "passed" : r.solved ? "FAILED" : "not solved");
    line("time", number("%.2f s", r.seconds));
    html += linked ? "</table></a>\n" : "</table>\n";
    if (!ok) html += "<div class=\"why\">" + escapeXml(utf8Text(r.reason)) + "</div>\n";
    html += "</div>\n";
  }
  html += std::string("</div>\n<script>") + kScript + "</script>\n</body></html>\n";
  return html;
}

}  // namespace dform
