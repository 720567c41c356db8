// dform studio's overlay on the 3D shape: the strain of every edge (L per edge, (L3 - L2) / L2) or
// the curvature at every vertex (its angle defect), from the figures the server measured on the
// shape on screen, and the places where the gate's failing checks fail. The colour scale is the
// server's figure (L_max, the largest angle defect), so the most strained edge and the most
// curved vertex take the scale's end colours.
"use strict";

// A diverging map: -1 blue, 0 grey, +1 red (t clamped; a NaN or infinite value is +1).
function divergingColour(t) {
  t = isFinite(t) ? Math.max(-1, Math.min(1, t)) : 1;
  var mid = [0.86, 0.86, 0.86], end = t < 0 ? [0.15, 0.3, 0.85] : [0.8, 0.05, 0.1], a = Math.abs(t);
  return [0, 1, 2].map(function (k) { return mid[k] + a * (end[k] - mid[k]); });
}

// view3d: the View3D; legend: the element the scale is written in.
function Overlay(view3d, legend) {
  this.view3d = view3d;
  this.legend = legend;
  this.mode = "none";      // "none", "strain" or "curvature"
  this.failures = true;    // mark the gate's failing checks on the shape
  this.data = null;        // {pieces (decoded, 3D), overlay (the server's), figures}
  this.made = null;        // what was last drawn, for tests: {mode, scale, colours, markers}
}

// The shown shape's overlay as the server sent it with the shape's figures; null: none (yet).
Overlay.prototype.show = function (pieces, overlay, figures) {
  this.data = overlay ? { pieces: pieces, overlay: overlay, figures: figures || {} } : null;
  this.render();
};
Overlay.prototype.setMode = function (mode) { this.mode = mode; this.render(); };
Overlay.prototype.setFailures = function (on) { this.failures = on; this.render(); };

// How many places of a failing check are marked ("" when the check is not located on the shape).
Overlay.prototype.sites = function (check) {
  if (!this.data) return null;
  var f = this.data.overlay.failing.filter(function (x) { return x.check === check; })[0];
  if (!f) return null;
  var per = f.kind === "edges" ? 2 : 1;
  return f.kind === "seam_points" ? f.items[0].length : (f.items[0].length + f.items[1].length) / per;
};

Overlay.prototype.render = function () {
  var d = this.data, self = this;
  this.made = null;
  if (!d) { this.view3d.setOverlay(null); this.legend.textContent = ""; return; }
  var o = { tints: [], lines: null, markers: null }, scale = null, colours = [];
  var strains = d.overlay.pieces.map(function (p) { return decodeF64(p.strain); });
  var edges = d.overlay.pieces.map(function (p) { return decodeU32(p.edges); });
  if (this.mode === "strain") {
    scale = d.figures.L_max;
    var count = 0;
    strains.forEach(function (s) { count += s.length; });
    var positions = new Float32Array(6 * count), tint = new Float32Array(6 * count), n = 0;
    d.pieces.forEach(function (piece, i) {
      for (var e = 0; e < strains[i].length; ++e) {
        var c = divergingColour(scale > 0 ? strains[i][e] / scale : 0);
        colours.push(c);
        [edges[i][2 * e], edges[i][2 * e + 1]].forEach(function (v) {
          for (var k = 0; k < 3; ++k) { positions[3 * n + k] = piece.shape[3 * v + k]; tint[3 * n + k] = c[k]; }
          ++n;
        });
      }
    });
    o.lines = { positions: positions, colours: tint };
    this.legend.textContent = "strain (L3 − L2) / L2: blue −" + percent(scale) + ", grey 0, red +" + percent(scale);
  } else if (this.mode === "curvature") {
    scale = d.figures.angle_defect_max_rad;
    o.tints = d.overlay.pieces.map(function (p) {
      var k = decodeF64(p.curvature), t = new Float32Array(3 * k.length);
      for (var v = 0; v < k.length; ++v) {
        var c = divergingColour(scale > 0 ? k[v] / scale : 0);
        colours.push(c);
        t.set(c, 3 * v);
      }
      return t;
    });
    this.legend.textContent = "angle defect: blue −" + (+scale).toPrecision(3) + " rad, grey 0, red +" + (+scale).toPrecision(3) + " rad";
  } else {
    this.legend.textContent = "";
  }
  if (this.failures) o.markers = this.markers();
  this.view3d.setOverlay(o);
  this.made = { mode: this.mode, scale: scale, colours: colours, markers: o.markers ? o.markers.length / 3 : 0 };
  function percent(x) { return (100 * x).toPrecision(3) + " %"; }
};

// A point at each place a failing check fails: an edge's midpoint, a vertex, a seam point (A's).
Overlay.prototype.markers = function () {
  var d = this.data, out = [];
  function at(i, v) { return [0, 1, 2].map(function (k) { return d.pieces[i].shape[3 * v + k]; }); }
  d.overlay.failing.forEach(function (f) {
    [0, 1].forEach(function (i) {
      var items = f.items[i];
      if (f.kind === "edges") {
        for (var k = 0; k + 1 < items.length; k += 2) {
          var a = at(i, items[k]), b = at(i, items[k + 1]);
          out.push((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
        }
      } else if (f.kind === "vertices") {
        items.forEach(function (v) { out.push.apply(out, at(i, v)); });
      } else if (i === 0) {
        items.forEach(function (s) { out.push.apply(out, at(0, d.pieces[0].seam[s])); });
      }
    });
  });
  return new Float32Array(out);
};
