// dform studio's linked picking and measure tool. The seam point under the pointer, on either
// piece's panel or in the 3D view, is marked on both panels (seam point k of A meets seam point k
// of B) and in 3D. The measure tool picks two points of the shape in the 3D view (the nearest
// vertex drawn within 10 px of a click, the front-most of those) and gives their distance in mm.
// page: {views (the two PieceViews), view3d, shown() (the shape on screen: {pieces} or null),
// button, readout (elements)}.
"use strict";

function Picking(page) {
  var self = this;
  this.picked = null;       // the seam index under the pointer, or null
  this.measuring = false;
  this.points = [];         // the measure's picked points (xyz), at most two
  this.distance = null;     // their distance (mm) once there are two
  var HOVER = [0.05, 0.65, 0.55], MEASURE = [0.1, 0.1, 0.1];

  function pieces() { var s = page.shown(); return s ? s.pieces : null; }
  function vertex(piece, v) { return [piece.shape[3 * v], piece.shape[3 * v + 1], piece.shape[3 * v + 2]]; }

  // Seam point k (or none) marked on both panels and, on A's 3D seam, in the view.
  this.pick = function (k) {
    var p = pieces();
    if (!p || k == null || p[0].seam[k] == null) k = null;
    this.picked = k;
    page.views.forEach(function (v) { v.highlight(k); });
    page.view3d.setMarks("hover", k == null ? [] : [vertex(p[0], p[0].seam[k])], HOVER, false);
  };

  // The seam point of A's 3D seam drawn nearest (x, y) within `pixels`, or null.
  function seamPointAt(x, y, pixels) {
    var p = pieces(), best = null, bestD = pixels;
    if (!p) return null;
    p[0].seam.forEach(function (v, k) {
      var q = vertex(p[0], v), s = page.view3d.project(q[0], q[1], q[2]), d = Math.hypot(s[0] - x, s[1] - y);
      if (d <= bestD) { bestD = d; best = k; }
    });
    return best;
  }

  // The vertex of either piece drawn within `pixels` of (x, y), the front-most of those.
  function vertexAt(x, y, pixels) {
    var p = pieces(), best = null, depth = Infinity;
    (p || []).forEach(function (piece) {
      for (var v = 0; v < piece.shape.length / 3; ++v) {
        var q = vertex(piece, v), s = page.view3d.project(q[0], q[1], q[2]);
        if (Math.hypot(s[0] - x, s[1] - y) <= pixels && s[2] < depth) { depth = s[2]; best = q; }
      }
    });
    return best;
  }

  page.views.forEach(function (view) { view.onHover = function (k) { self.pick(k); }; });
  page.view3d.onHover(function (x, y) { self.pick(x == null ? null : seamPointAt(x, y, 10)); });
  page.view3d.onClick(function (x, y) {
    if (!self.measuring) return;
    var q = vertexAt(x, y, 10);
    if (!q) return;
    if (self.points.length === 2) self.points = [];
    self.points.push(q);
    self.showMeasure();
  });

  this.showMeasure = function () {
    var a = this.points[0], b = this.points[1];
    this.distance = b ? Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) : null;
    page.view3d.setMarks("measure", this.points, MEASURE, true);
    page.readout.textContent = !this.measuring ? "" : !a ? "click two points of the shape"
      : !b ? "click a second point" : "distance " + this.distance.toFixed(2) + " mm";
  };

  page.button.onclick = function () {
    self.measuring = !self.measuring;
    page.button.classList.toggle("active", self.measuring);
    self.points = [];
    self.showMeasure();
  };

  // A new shape: the marks go with the old one (a point picked there may be elsewhere now).
  this.reset = function () {
    this.pick(null);
    this.points = [];
    this.showMeasure();
  };
}
