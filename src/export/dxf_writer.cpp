// SPDX-License-Identifier: GPL-3.0-or-later
// The cutting DXF, written through dxflib (Debian's libdxflib-dev): R2000 (AC1015), millimetres
// ($INSUNITS 4), one LWPOLYLINE per drawn polyline (closed flag on closed cut paths), on the layers
// CUT, SCORE and ENGRAVE (REGMARKS for a print-and-cut sheet's marks, FAILED-GATE for the stamp of
// a pattern that failed its gate). DXF's y axis points up: a point (x, y) of the y-down drawing is
// written at (x, H - y), H the drawing's height, so the sheet's corner (0, 0) is its lower left
// and nothing is mirrored.
//
// dxflib writes every section, table and entity. Its ASCII writer (DL_WriterA) only streams to a
// file it opens itself; the export renders every file in memory first and writes each atomically,
// so a subclass here collects the group codes dxflib emits into a string instead.
#include <dxflib/dl_dxf.h>
#include <dxflib/dl_writer_ascii.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <string>

#include "internal.h"

namespace dform::fab {

namespace {

// dxflib's DL_WriterA, its output collected in memory. The group-code layout is DXF's ASCII
// form: the code right-aligned in three columns, the value on the next line.
class StringWriter : public DL_WriterA {
 public:
  explicit StringWriter(std::string* out) : DL_WriterA("", DL_Codes::AC1015), out_(out) {}

  void dxfReal(int gc, double value) const override {
    char buf[64];
    // Fixed notation (no exponent, which some cutter software cannot read), 1e-9 mm steps,
    // locale-independent; trailing zeros trimmed to one decimal.
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, 9);
    std::string s = ec == std::errc() ? std::string(buf, end) : std::string("0.0");
    while (s.size() > 1 && s.back() == '0' && s[s.size() - 2] != '.') s.pop_back();
    if (s == "-0.0") s = "0.0";
    put(gc, s);
  }
  void dxfInt(int gc, int value) const override { put(gc, std::to_string(value)); }
  void dxfHex(int gc, int value) const override {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%X", unsigned(value));
    put(gc, buf);
  }
  void dxfString(int gc, const char* value) const override { put(gc, value ? value : ""); }
  void dxfString(int gc, const std::string& value) const override { put(gc, value); }

 private:
  void put(int gc, const std::string& value) const {
    char code[16];
    std::snprintf(code, sizeof code, "%3d\n", gc);
    *out_ += code;
    *out_ += value;
    *out_ += '\n';
  }
  std::string* out_;
};

// The DXF layer of a drawing layer: the operation a cutter's software maps it to.
std::string dxfLayerName(const std::string& layer) {
  if (layer == "Cut") return "CUT";
  if (layer == "Score" || layer == "Fold") return "SCORE";
  if (layer == "Regmarks") return "REGMARKS";
  if (layer == kFailedGateLayer) return "FAILED-GATE";  // the stamp: no operation at all
  return "ENGRAVE";  // Engrave, Labels, Title, and print-and-cut's printed artwork (Print)
}

// The AutoCAD colour index nearest to #RRGGBB among the seven basic ones (1 red .. 7 black/white),
// for programs that read only the index; the exact colour goes with it as a true colour.
int nearestAci(int rgb) {
  static const int basic[7] = {0xFF0000, 0xFFFF00, 0x00FF00, 0x00FFFF,
                               0x0000FF, 0xFF00FF, 0x000000};
  int best = 7;
  long bestD = -1;
  for (int i = 0; i < 7; ++i) {
    long d = 0;
    for (int shift : {16, 8, 0}) {
      const long c = ((rgb >> shift) & 0xFF) - ((basic[i] >> shift) & 0xFF);
      d += c * c;
    }
    if (bestD < 0 || d < bestD) bestD = d, best = i + 1;
  }
  return best;
}

struct DxfLayer {
  std::string name;
  int rgb = 0;
};

// The DXF layers in drawing order, each once, with the colour of the first drawing layer mapped
// to it; CUT, SCORE and ENGRAVE always exist (a sheet may have nothing to score).
std::vector<DxfLayer> dxfLayers(const Drawing& drawing) {
  std::vector<DxfLayer> layers;
  auto add = [&](const std::string& name, int rgb) {
    for (const DxfLayer& l : layers)
      if (l.name == name) return;
    layers.push_back({name, rgb});
  };
  for (const Layer& layer : drawing.layers)
    add(dxfLayerName(layer.name), int(std::stoul(layer.color.substr(1), nullptr, 16)));
  add("CUT", 0xFF0000);
  add("SCORE", 0x0000FF);
  add("ENGRAVE", 0x000000);
  return layers;
}

void writeVariable(const DL_WriterA& dw, const char* name, double x, double y) {
  dw.dxfString(9, name);
  dw.dxfReal(10, x);
  dw.dxfReal(20, y);
}

}  // namespace

std::string dxfDocument(const Drawing& full) {
  // The printed tint (layer Bleed) is for the printer alone: a DXF holds what a machine cuts,
  // scores or engraves.
  Drawing drawing = full;
  drawing.layers.erase(std::remove_if(drawing.layers.begin(), drawing.layers.end(),
                                      [](const Layer& l) { return l.name == "Bleed"; }),
                       drawing.layers.end());
  std::string out;
  StringWriter dw(&out);
  DL_Dxf dxf;
  const double h = drawing.height;
  auto up = [h](const Vec2& q) { return Vec2(q.x(), h - q.y()); };

  Box extents;
  for (const Layer& layer : drawing.layers)
    for (const Path& path : layer.paths)
      for (const Polyline& part : path.parts)
        if (part.size() >= 2)
          for (const Vec2& q : part) extents.add(up(q));
  if (extents.lo.x() > extents.hi.x()) extents = Box::spanning(Vec2(0, 0), Vec2(0, 0));

  dxf.writeComment(dw, "dform flat pattern, mm, y up");
  dxf.writeHeader(dw);
  dw.dxfString(9, "$INSUNITS");
  dw.dxfInt(70, 4);  // millimetres
  dw.dxfString(9, "$MEASUREMENT");
  dw.dxfInt(70, 1);                    // metric
  writeVariable(dw, "$LIMMIN", 0, 0);  // the sheet
  writeVariable(dw, "$LIMMAX", drawing.width, drawing.height);
  writeVariable(dw, "$EXTMIN", extents.lo.x(), extents.lo.y());  // what is drawn on it
  writeVariable(dw, "$EXTMAX", extents.hi.x(), extents.hi.y());
  dw.sectionEnd();

  const std::vector<DxfLayer> layers = dxfLayers(drawing);
  dw.sectionTables();
  dxf.writeVPort(dw);
  dw.tableLinetypes(3);
  dxf.writeLinetype(dw, DL_LinetypeData("BYBLOCK", "BYBLOCK", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("BYLAYER", "BYLAYER", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("CONTINUOUS", "Continuous", 0, 0, 0.0));
  dw.tableEnd();
  dw.tableLayers(int(layers.size()) + 1);
  dxf.writeLayer(dw, DL_LayerData("0", 0), DL_Attributes("", 7, -1, 0, "CONTINUOUS"));
  for (const DxfLayer& l : layers)  // hairline (lineweight 0), the profile's colour
    dxf.writeLayer(dw, DL_LayerData(l.name, 0),
                   DL_Attributes("", nearestAci(l.rgb), l.rgb, 0, "CONTINUOUS"));
  dw.tableEnd();
  dw.tableStyle(1);
  // "Standard" exactly: dxflib takes the handle the dimension style points at (group 340) from
  // the style of that name; under any other name it writes an unset value.
  dxf.writeStyle(dw, DL_StyleData("Standard", 0, 2.5, 1.0, 0.0, 0, 2.5, "txt", ""));
  dw.tableEnd();
  dxf.writeView(dw);
  dxf.writeUcs(dw);
  dw.tableAppid(1);
  dxf.writeAppid(dw, "ACAD");
  dw.tableEnd();
  dxf.writeDimStyle(dw, 1, 1, 1, 1, 1);
  dxf.writeBlockRecord(dw);
  dw.tableEnd();
  dw.sectionEnd();

  dw.sectionBlocks();
  for (const char* block : {"*Model_Space", "*Paper_Space", "*Paper_Space0"}) {
    dxf.writeBlock(dw, DL_BlockData(block, 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(dw, block);
  }
  dw.sectionEnd();

  // Entities in the drawing's order (holes and perforations before outer cuts), colour and
  // lineweight by layer. A filled path (the registration square) is its closed outline: DXF
  // carries geometry for a machine, not print fills. Dashes are the SVG's and PDF's styling; a
  // DXF fold or score line is the whole line.
  dw.sectionEntities();
  for (const Layer& layer : drawing.layers) {
    const DL_Attributes attributes(dxfLayerName(layer.name), 256, -1, -1, "BYLAYER");
    for (const Path& path : layer.paths)
      for (const Polyline& part : path.parts) {
        size_t n = part.size();
        // A closed polyline's last vertex joins its first by the closed flag, not a repeat.
        if (path.closed && n > 2 && (part.front() - part.back()).norm() < 1e-12) --n;
        if (n < 2) continue;
        dxf.writePolyline(dw, DL_PolylineData(int(n), 0, 0, path.closed ? 1 : 0), attributes);
        for (size_t i = 0; i < n; ++i) {
          const Vec2 q = up(part[i]);
          dxf.writeVertex(dw, DL_VertexData(q.x(), q.y(), 0.0, 0.0));
        }
        dxf.writePolylineEnd(dw);
      }
  }
  dw.sectionEnd();
  dxf.writeObjects(dw);
  dxf.writeObjectsEnd(dw);
  dw.dxfEOF();
  return out;
}

}  // namespace dform::fab
