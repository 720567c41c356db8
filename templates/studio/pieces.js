// dform studio's flat pieces: one SVG panel per piece with its outline, holes and drawn creases
// as read, the seam's numbered ticks from the start, the found creases, the seam point that
// breaks convexity, and the start handle, dragged along the joined boundary. What a drag or a new
// result changes (ticks, found creases, marks, the handle) is drawn in a second SVG laid over the
// first (its own compositing layer): a browser that rasterises on the GPU then redraws only that
// layer as the handle moves, not the outline (Chromium on SwiftShader: 33 instead of 67 ms a
// frame for a moved handle).
"use strict";

var SVG_NS = "http://www.w3.org/2000/svg";

function svgNode(tag, attributes, parent) {
  var n = document.createElementNS(SVG_NS, tag);
  for (var k in attributes) n.setAttribute(k, attributes[k]);
  if (parent) parent.appendChild(n);
  return n;
}

// A closed loop [x0, y0, x1, y1, ...] (mm) with its cumulative arc lengths.
function Loop(points) {
  this.points = points;
  this.n = points.length / 2;
  this.cumulative = [0];
  for (var i = 0; i < this.n; ++i) {
    var j = (i + 1) % this.n;
    this.cumulative.push(this.cumulative[i] + Math.hypot(points[2 * j] - points[2 * i], points[2 * j + 1] - points[2 * i + 1]));
  }
  this.length = this.cumulative[this.n];
}

// The point at arc-length fraction f from the first point, counter-clockwise.
Loop.prototype.at = function (f) {
  var s = ((f % 1) + 1) % 1 * this.length, lo = 0, hi = this.n;
  while (hi - lo > 1) { var mid = (lo + hi) >> 1; if (this.cumulative[mid] <= s) lo = mid; else hi = mid; }
  var j = (lo + 1) % this.n, t = (s - this.cumulative[lo]) / Math.max(1e-12, this.cumulative[lo + 1] - this.cumulative[lo]);
  var p = this.points;
  return [p[2 * lo] + t * (p[2 * j] - p[2 * lo]), p[2 * lo + 1] + t * (p[2 * j + 1] - p[2 * lo + 1])];
};

// The arc-length fraction of the loop point nearest to (x, y).
Loop.prototype.nearest = function (x, y) {
  var best = Infinity, bestS = 0, p = this.points;
  for (var i = 0; i < this.n; ++i) {
    var j = (i + 1) % this.n, ax = p[2 * i], ay = p[2 * i + 1], dx = p[2 * j] - ax, dy = p[2 * j + 1] - ay;
    var len2 = dx * dx + dy * dy, t = len2 > 0 ? Math.max(0, Math.min(1, ((x - ax) * dx + (y - ay) * dy) / len2)) : 0;
    var d = Math.hypot(ax + t * dx - x, ay + t * dy - y);
    if (d < best) { best = d; bestS = this.cumulative[i] + t * (this.cumulative[i + 1] - this.cumulative[i]); }
  }
  return bestS / this.length % 1;
};

function pathOf(points, closed) {
  var d = "";
  for (var i = 0; i < points.length; i += 2) d += (i ? "L" : "M") + points[i].toFixed(3) + " " + (-points[i + 1]).toFixed(3);
  return d + (closed ? "Z" : "");
}

// One piece's panel. onStart(fraction, event) is called as the handle is dragged; the property
// onHover(k), when set, as the pointer comes near seam point k of the result (within 12 px) or
// leaves it (null).
function PieceView(svg, label, onStart, onRelease) {
  this.svg = svg;
  var stack = document.createElement("div");
  stack.className = "piece-stack";
  svg.parentNode.insertBefore(stack, svg);
  stack.appendChild(svg);
  this.marks = svgNode("svg", { id: svg.id + "-marks", class: "piece-marks", "aria-hidden": "true" }, stack);
  this.label = label;
  this.shape = null;
  this.loop = null;
  this.fraction = 0;
  var self = this, dragging = false;
  // The start under the pointer: the nearest point of the boundary, or the nearest snap target
  // within 10 px of the pointer of the first kind that has one: a corner, one of the property
  // snapTargets() ([{fraction, name}]), where a mirror axis crosses the outline (corners and
  // axes: the server's lists). Alt held: no snapping.
  function fractionAt(e) {
    var ctm = self.svg.getScreenCTM(), p = self.svg.createSVGPoint();
    p.x = e.clientX; p.y = e.clientY;
    var q = p.matrixTransform(ctm.inverse()), reach = 10 / Math.abs(ctm.a);
    var kinds = [self.corners.map(function (c) { return { fraction: c, name: "corner" }; }),
                 self.snapTargets ? self.snapTargets() : [],
                 self.axes.map(function (c) { return { fraction: c, name: "symmetry axis" }; })];
    self.snapped = null;
    if (!e.altKey) kinds.some(function (targets) {
      targets.forEach(function (t) {
        var at = self.loop.at(t.fraction), d = Math.hypot(at[0] - q.x, at[1] + q.y);
        if (d <= reach) { reach = d; self.snapped = t.fraction; self.snapName = t.name; }
      });
      return self.snapped != null;
    });
    return self.snapped != null ? self.snapped : self.loop.nearest(q.x, -q.y);
  }
  svg.addEventListener("pointerdown", function (e) {
    if (!self.loop || self.fixed || !e.target.classList.contains("handle-target")) return;
    dragging = true;
    svg.setPointerCapture(e.pointerId);
    e.preventDefault();
  });
  // A drag takes each move as the browser gets it (pointerrawupdate, where there is one) rather
  // than once a frame: the position goes to the solver up to a frame sooner.
  var raw = "onpointerrawupdate" in window;
  function dragTo(e) { self.setFraction(fractionAt(e)); onStart(self.fraction, e); }
  if (raw) svg.addEventListener("pointerrawupdate", function (e) { if (dragging) dragTo(e); });
  svg.addEventListener("pointermove", function (e) {
    if (!dragging) { if (self.onHover) self.onHover(self.seamPointNear(e.clientX, e.clientY, 12)); return; }
    if (!raw) dragTo(e);
  });
  svg.addEventListener("pointerleave", function () { if (!dragging && self.onHover) self.onHover(null); });
  svg.addEventListener("pointerup", function () { if (dragging) { dragging = false; onRelease(); } });
}

// shape: the server's summary of the outline; join: "outer" or "inner"
PieceView.prototype.setShape = function (shape, join) {
  this.shape = shape;
  var hole = join === "inner" && shape.holes.length === 1;
  this.loop = new Loop(hole ? shape.holes[0] : shape.outer);
  this.corners = (hole ? (shape.hole_corners || [])[0] : shape.corners) || [];
  this.axes = (hole ? [] : shape.axes) || [];
  this.snapped = null;
  var pad = 0.08 * Math.max(shape.max[0] - shape.min[0], shape.max[1] - shape.min[1]);
  var box = [shape.min[0] - pad, -shape.max[1] - pad, shape.max[0] - shape.min[0] + 2 * pad,
             shape.max[1] - shape.min[1] + 2 * pad].join(" ");
  this.svg.setAttribute("viewBox", box);
  this.marks.setAttribute("viewBox", box);
  this.unit = (shape.max[0] - shape.min[0] + 2 * pad) / 300;  // one screen pixel of a 300-px panel, in mm
  this.result = null;
  this.fixed = false;
  this.render();
};

// An inverse result's flat piece (no outline was read): its seam loop drawn as the outline,
// with its ticks and creases, and no handle (the seam's start is the curve's first point).
PieceView.prototype.setSolvedPiece = function (piece) {
  var outer = [];
  piece.seam.forEach(function (v) { outer.push(piece.flat[2 * v], piece.flat[2 * v + 1]); });
  var xs = outer.filter(function (_, k) { return k % 2 === 0; }), ys = outer.filter(function (_, k) { return k % 2 === 1; });
  this.setShape({ outer: outer, holes: [], creases: [], min: [Math.min.apply(null, xs), Math.min.apply(null, ys)],
                  max: [Math.max.apply(null, xs), Math.max.apply(null, ys)] }, "outer");
  this.fraction = 0;
  this.result = { piece: piece, direction: 1, breakPoint: null, scale: [1, 1], offset: [0, 0] };
  this.fixed = true;
  this.render();
};

// The handle and the ticks are drawn again only when they would change (an answer for B's drag
// leaves A's start where it was).
PieceView.prototype.setFraction = function (f) {
  if (f !== this.snapped) this.snapped = null;
  this.fraction = f;
  var drawn = this.drawnHandle;
  if (drawn && drawn.handle === this.handle && drawn.fraction === f && drawn.snapped === this.snapped &&
      drawn.snapName === this.snapName) return;
  this.renderHandle();
};

// No result for the outline (the design's solve failed): the outline as read, nothing solved on it.
PieceView.prototype.clearResult = function () {
  if (!this.result || this.fixed) return;
  this.result = null;
  this.render();
};

// Nothing to show (the inverse mode before its curve's pieces).
PieceView.prototype.clear = function () {
  this.shape = null; this.loop = null; this.result = null; this.handle = null;
  this.render();
};

// A result over the outline as read: the way its seam runs (ticks), its found creases and the
// seam point that breaks convexity, its flat piece placed by `place` ({scale, offset}).
// A new result redraws only what depends on it (the ticks' direction, the found creases and the
// break point): the outline as read stays, so that a drag redraws little.
PieceView.prototype.setResult = function (piece, direction, breakPoint, place) {
  var turned = !this.result || this.result.direction !== direction;
  this.result = { piece: piece, direction: direction, breakPoint: breakPoint, scale: place.scale, offset: place.offset };
  if (!this.found) { this.render(); return; }
  if (turned) {
    while (this.ticks.firstChild) this.ticks.removeChild(this.ticks.firstChild);
    this.renderTicks();
  }
  this.renderFound();
};

// Seam point k of the result where the panel draws it (mm, y up), or null.
PieceView.prototype.seamPoint = function (k) {
  var r = this.result, v = r && r.piece.seam[k];
  if (v == null) return null;
  return [r.piece.flat[2 * v] * r.scale[0] + r.offset[0], r.piece.flat[2 * v + 1] * r.scale[1] + r.offset[1]];
};

// The result's seam point nearest the screen point (clientX, clientY) within `pixels`, or null.
PieceView.prototype.seamPointNear = function (clientX, clientY, pixels) {
  if (!this.result) return null;
  var m = this.svg.getScreenCTM(), p = this.svg.createSVGPoint();
  p.x = clientX; p.y = clientY;
  var q = p.matrixTransform(m.inverse()), best = null, bestD = pixels / Math.abs(m.a);
  for (var k = 0; k < this.result.piece.seam.length; ++k) {
    var s = this.seamPoint(k), d = Math.hypot(s[0] - q.x, s[1] + q.y);
    if (d <= bestD) { bestD = d; best = k; }
  }
  return best;
};

// Seam point k marked on the panel (its partner carries the same k), or no mark (null).
PieceView.prototype.highlight = function (k) {
  this.picked = k;
  this.renderPicked();
};
PieceView.prototype.renderPicked = function () {
  if (this.pickedNode) { this.pickedNode.remove(); this.pickedNode = null; }
  var p = this.picked == null ? null : this.seamPoint(this.picked);
  if (!p || !this.found) return;
  this.pickedNode = svgNode("circle", { cx: p[0], cy: -p[1], r: 5 * this.unit, class: "picked", "stroke-width": 2 * this.unit }, this.found);
  this.pickedNode.setAttribute("data-seam-point", this.picked);
};

PieceView.prototype.render = function () {
  var svg = this.svg, marks = this.marks, shape = this.shape, u = this.unit;
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  while (marks.firstChild) marks.removeChild(marks.firstChild);
  this.found = null;
  if (!shape) return;
  var d = pathOf(shape.outer, true);
  shape.holes.forEach(function (h) { d += pathOf(h, true); });
  svgNode("path", { d: d, class: "cut", "fill-rule": "evenodd", "stroke-width": 1.5 * u }, svg);
  shape.creases.forEach(function (c) { svgNode("path", { d: pathOf(c, false), class: "drawn-crease", "stroke-width": 1.5 * u }, svg); });
  svgNode("path", { d: pathOf(this.loop.points, true), class: "handle-target", "stroke-width": 14 * u }, svg);
  this.ticks = svgNode("g", { class: "ticks" }, marks);
  this.renderTicks();
  this.found = svgNode("g", {}, marks);
  if (this.result) this.renderFound();
  if (this.fixed) { this.handle = null; return; }
  // Pressed through the marks' layer: the outline's handle target lies under it.
  this.handle = svgNode("circle", { r: 7 * u, class: "handle", "stroke-width": 2 * u }, marks);
  this.handleLabel = svgNode("text", { class: "handle-label", "font-size": 12 * u }, marks);
  this.renderHandle();
};

// Ticks every 20 mm of seam from the start, numbered every fifth, running the way the seam runs.
PieceView.prototype.renderTicks = function () {
  var g = this.ticks, u = this.unit, loop = this.loop, dir = this.result ? this.result.direction : 1;
  var count = Math.floor(loop.length / 20);
  for (var k = 1; k < count; ++k) {
    var f = this.fraction + dir * k * 20 / loop.length, p = loop.at(f), q = loop.at(f + 0.002);
    var tx = q[0] - p[0], ty = q[1] - p[1], t = Math.hypot(tx, ty) || 1, nx = -ty / t, ny = tx / t;
    var size = (k % 5 === 0 ? 9 : 5) * u;
    svgNode("line", { x1: p[0], y1: -p[1], x2: p[0] + nx * size, y2: -(p[1] + ny * size), "stroke-width": u }, g);
    if (k % 5 === 0) {
      var text = svgNode("text", { x: p[0] + nx * 2 * size, y: -(p[1] + ny * 2 * size), "font-size": 10 * u }, g);
      text.textContent = k;
    }
  }
};

// Found creases, drawn where the result's flat piece lies over the outline as read.
PieceView.prototype.renderFound = function () {
  var r = this.result, flat = r.piece.flat, u = this.unit, svg = this.found;
  while (svg.firstChild) svg.removeChild(svg.firstChild);
  r.piece.creases.forEach(function (c) {
    var pts = [];
    c.forEach(function (v) { pts.push(flat[2 * v] * r.scale[0] + r.offset[0], flat[2 * v + 1] * r.scale[1] + r.offset[1]); });
    svgNode("path", { d: pathOf(pts, false), class: "found-crease", "stroke-width": 2 * u }, svg);
  });
  if (r.breakPoint != null && r.piece.seam[r.breakPoint] != null) {
    var v = r.piece.seam[r.breakPoint];
    svgNode("circle", { cx: flat[2 * v] * r.scale[0] + r.offset[0], cy: -(flat[2 * v + 1] * r.scale[1] + r.offset[1]),
                        r: 6 * u, class: "break-point", "stroke-width": 2 * u }, svg);
  }
  this.pickedNode = null;
  this.renderPicked();
};

PieceView.prototype.renderHandle = function () {
  if (!this.handle) return;
  var p = this.loop.at(this.fraction);
  this.handle.setAttribute("cx", p[0]);
  this.handle.setAttribute("cy", -p[1]);
  // The label on the side of the handle away from the nearer edges, so that the panel does not
  // clip it: left of a handle in the right half, below one in the top half.
  var box = this.svg.viewBox.baseVal, right = p[0] > box.x + box.width / 2, top = -p[1] < box.y + box.height / 2;
  this.handleLabel.setAttribute("x", p[0] + (right ? -10 : 10) * this.unit);
  this.handleLabel.setAttribute("y", -p[1] + (top ? 18 : -10) * this.unit);
  this.handleLabel.setAttribute("text-anchor", right ? "end" : "start");
  this.handleLabel.textContent = this.label + " start " + this.fraction.toFixed(3) + (this.snapped != null ? " (" + this.snapName + ")" : "");
  this.handle.classList.toggle("snapped", this.snapped != null);
  while (this.ticks.firstChild) this.ticks.removeChild(this.ticks.firstChild);
  this.renderTicks();
  this.drawnHandle = { handle: this.handle, fraction: this.fraction, snapped: this.snapped, snapName: this.snapName };
};
