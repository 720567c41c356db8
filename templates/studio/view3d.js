// dform studio's 3D view: both pieces of the D-Form in WebGL 1, shaded by piece, the seam and the
// creases drawn on top, turned by dragging and zoomed by the wheel. Buffers are kept and
// refilled in place while the mesh keeps its size, so a live drag uploads vertices only.
"use strict";

// Whether this browser's WebGL draws on the CPU (SwiftShader, Mesa's llvmpipe, Windows' basic
// render driver): asked once, of a context made for the question and then let go.
var softwareWebGL = (function () {
  var answer = null;
  return function () {
    if (answer !== null) return answer;
    var gl = document.createElement("canvas").getContext("webgl");
    var info = gl && gl.getExtension("WEBGL_debug_renderer_info");
    var renderer = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : "";
    answer = /swiftshader|llvmpipe|softpipe|basic render driver/i.test(renderer);
    var lose = gl && gl.getExtension("WEBGL_lose_context");
    if (lose) lose.loseContext();
    return answer;
  };
})();

// options: {axes: false} for a view without axes (the strip's thumbnails).
function View3D(canvas, options) {
  // Multisampling on a software rasteriser multiplies each frame's fragment work by its samples
  // (on SwiftShader, 4 samples of this view cost its every frame about 18 ms of CPU more, taken
  // from the solve of the next shape): there the view draws without it.
  var gl = canvas.getContext("webgl", { antialias: !softwareWebGL(), preserveDrawingBuffer: true });
  if (!gl) throw new Error("this browser has no WebGL");
  if (!gl.getExtension("OES_element_index_uint")) throw new Error("WebGL lacks 32-bit indices");
  // Faceted shading from the screen-space derivatives of the view position (each triangle its
  // own plane, as the sheet is between mesh vertices): no normals to compute or upload per frame.
  if (!gl.getExtension("OES_standard_derivatives")) throw new Error("WebGL lacks standard derivatives");
  var VERTEX = [
    "attribute vec3 position, tint;",
    "uniform mat3 turn;",
    "uniform vec3 centre, scale;",
    "uniform float pointSize;",
    "varying vec3 viewPosition, vertexTint;",
    "void main() {",
    "  vec3 p = scale * (turn * (position - centre));",
    "  viewPosition = p;",
    "  vertexTint = tint;",
    "  gl_PointSize = pointSize;",
    "  gl_Position = vec4(p.xy, -p.z * 0.5, 1.0);",
    "}"].join("\n");
  var FRAGMENT = [
    "#extension GL_OES_standard_derivatives : enable",
    "precision mediump float;",
    "uniform vec3 colour;",
    "uniform float lit, tinted;",
    "varying vec3 viewPosition, vertexTint;",
    "void main() {",
    "  float shade = 1.0;",
    // Lines and points have no plane (their derivatives' cross product is zero): unlit.
    "  if (lit > 0.5) {",
    "    vec3 n = normalize(cross(dFdx(viewPosition), dFdy(viewPosition)));",
    "    shade = 0.2 + 0.8 * abs(dot(n, normalize(vec3(-0.6, 0.7, 0.45))));",
    "  }",
    "  gl_FragColor = vec4(mix(colour, vertexTint, tinted) * shade, 1.0);",
    "}"].join("\n");
  // Both shaders compiled and linked into one program; a compiler's log becomes the error.
  var program = gl.createProgram();
  [[gl.VERTEX_SHADER, VERTEX], [gl.FRAGMENT_SHADER, FRAGMENT]].forEach(function (stage) {
    var compiled = gl.createShader(stage[0]);
    gl.shaderSource(compiled, stage[1]);
    gl.compileShader(compiled);
    if (!gl.getShaderParameter(compiled, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(compiled));
    gl.attachShader(program, compiled);
  });
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  gl.useProgram(program);
  var loc = {};
  loc.position = gl.getAttribLocation(program, "position");
  loc.tint = gl.getAttribLocation(program, "tint");
  ["turn", "centre", "scale", "colour", "lit", "tinted", "pointSize"].forEach(function (n) { loc[n] = gl.getUniformLocation(program, n); });

  var COLOURS = [[0.93, 0.62, 0.27], [0.36, 0.6, 0.85]];
  var MARKER = View3D.MARKER;
  var HOME = { azimuth: 30, elevation: 25, zoom: 1 };
  var camera = Object.assign({}, HOME);
  // Fixed scale: the fit (centre, radius, ground) kept from the shape on screen when it was
  // turned on, so that a change of size shows; a ground grid and the scale bar give the size.
  var fixed = false, ground = 0, grid = { count: 0 }, onScale = null, bounds = null;
  var parts = [];   // per piece: buffers and counts
  var lines = [];   // seam and creases: {buffer, count, colour, loop}
  var centre = [0, 0, 0], radius = 1;
  // What is drawn on the shape (setOverlay): per piece a colour per vertex ({pos, tint} buffers),
  // coloured line segments (strain), markers (points drawn over everything: the gate's failures).
  var overlay = { tints: [], lines: { pos: {}, tint: {}, count: 0 }, markers: { pos: {}, count: 0 } };

  // A buffer refilled in place when its size is unchanged.
  function fill(slot, target, data) {
    if (!slot.buffer) slot.buffer = gl.createBuffer();
    gl.bindBuffer(target, slot.buffer);
    if (slot.bytes === data.byteLength) gl.bufferSubData(target, 0, data);
    else gl.bufferData(target, data, gl.DYNAMIC_DRAW);
    slot.bytes = data.byteLength;
  }

  function lineBuffer(points3, index) {
    var out = new Float32Array(index.length * 3);
    for (var i = 0; i < index.length; ++i)
      for (var k = 0; k < 3; ++k) out[3 * i + k] = points3[3 * index[i] + k];
    return out;
  }

  // pieces: [{shape: Float64Array (#V*3), faces: Uint32Array, seam: [..], creases: [[..]]}],
  // extra: optional [{points: Float64Array (#P*3), colour, loop}] (a target curve)
  var model = [];
  this.setModel = function (pieces, extra) {
    model = pieces;
    var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    pieces.forEach(function (piece, i) {
      var p = new Float32Array(piece.shape);
      for (var v = 0; v < p.length; ++v) { lo[v % 3] = Math.min(lo[v % 3], p[v]); hi[v % 3] = Math.max(hi[v % 3], p[v]); }
      var part = parts[i] || (parts[i] = { pos: {}, idx: {} });
      fill(part.pos, gl.ARRAY_BUFFER, p);
      fill(part.idx, gl.ELEMENT_ARRAY_BUFFER, piece.faces);
      part.count = piece.faces.length;
      part.colour = COLOURS[i];
    });
    parts.length = pieces.length;
    var wanted = [];
    if (pieces.length) wanted.push({ points: pieces[0].shape, index: pieces[0].seam, colour: [0.76, 0.09, 0.36], loop: true });
    pieces.forEach(function (piece) {
      piece.creases.forEach(function (c) { wanted.push({ points: piece.shape, index: c, colour: [0.1, 0.2, 0.55], loop: false }); });
    });
    (extra || []).forEach(function (e) {
      var index = []; for (var i = 0; i < e.points.length / 3; ++i) index.push(i);
      wanted.push({ points: e.points, index: index, colour: e.colour, loop: e.loop });
    });
    wanted.forEach(function (w, i) {
      var line = lines[i] || (lines[i] = {});
      fill(line, gl.ARRAY_BUFFER, lineBuffer(w.points, w.index));
      line.count = w.index.length; line.colour = w.colour; line.loop = w.loop;
    });
    lines.length = wanted.length;
    if (isFinite(lo[0])) bounds = { lo: lo, hi: hi };
    if (!fixed) refit();
    makeAxes();
    clearOverlay();  // an overlay belongs to the shape it was made for
    this.draw();
  };
  function clearOverlay() { overlay.tints = []; overlay.lines.count = 0; overlay.markers.count = 0; }
  function overlayEmpty() { return !overlay.tints.length && !overlay.lines.count && !overlay.markers.count; }

  // o: null (none), or {tints: [Float32Array (#V*3) per piece, or null], lines: {positions,
  // colours} (Float32Array, xyz and rgb per end), markers: Float32Array (xyz per point)}.
  this.setOverlay = function (o) {
    if (!o && overlayEmpty()) return;  // nothing to take away: no frame to draw
    o = o || {};
    overlay.tints = (o.tints || []).map(function (t, i) {
      if (!t) return null;
      var slot = overlay.tints[i] || {};
      fill(slot, gl.ARRAY_BUFFER, t);
      return slot;
    });
    var l = o.lines || { positions: new Float32Array(0), colours: new Float32Array(0) };
    if (l.positions.length) { fill(overlay.lines.pos, gl.ARRAY_BUFFER, l.positions); fill(overlay.lines.tint, gl.ARRAY_BUFFER, l.colours); }
    overlay.lines.count = l.positions.length / 3;
    var m = o.markers || new Float32Array(0);
    if (m.length) fill(overlay.markers.pos, gl.ARRAY_BUFFER, m);
    overlay.markers.count = m.length / 3;
    this.draw();
  };
  this.overlayCounts = function () {
    return { tinted: overlay.tints.filter(Boolean).length, lines: overlay.lines.count / 2, markers: overlay.markers.count };
  };

  // The view fitted to the shape on screen: its centre, radius and lowest point.
  function refit() {
    if (!bounds) return;
    var lo = bounds.lo, hi = bounds.hi;
    centre = [0, 1, 2].map(function (k) { return (lo[k] + hi[k]) / 2; });
    radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    ground = lo[2];
  }

  // Lines every `step` mm (the scale bar's length, or a fifth of it) on the plane z = ground,
  // a square of about three radii round the centre.
  function makeGrid() {
    var step = niceLength(radius / 3), half = Math.ceil(1.5 * radius / step) * step, out = [];
    var cx = Math.round(centre[0] / step) * step, cy = Math.round(centre[1] / step) * step;
    for (var d = -half; d <= half + 1e-9; d += step) {
      out.push(cx + d, cy - half, ground, cx + d, cy + half, ground, cx - half, cy + d, ground, cx + half, cy + d, ground);
    }
    fill(grid, gl.ARRAY_BUFFER, new Float32Array(out));
    grid.count = out.length / 3;
    grid.step = step;
  }

  // The largest of 1, 2 and 5 times a power of ten that is at most `mm`.
  function niceLength(mm) {
    var p = Math.pow(10, Math.floor(Math.log10(mm))), best = p;
    [2, 5, 10].forEach(function (k) { if (k * p <= mm) best = k * p; });
    return best;
  }

  // Screen pixels (CSS) per millimetre of the model at the view's scale.
  function pixelsPerMm() {
    var w = canvas.clientWidth, h = canvas.clientHeight, s = camera.zoom * 0.9 / radius;
    return w > h ? s * h / 2 : s * w / 2;
  }

  this.setFixedScale = function (on) {
    fixed = on;
    refit();
    if (on) makeGrid();
    this.draw();
  };
  this.resetView = function () { Object.assign(camera, HOME); this.draw(); };
  // onScale({pixelsPerMm, barMm}) after each frame: for the scale bar.
  this.onScale = function (f) { onScale = f; };
  this.pixelsPerMm = pixelsPerMm;
  this.gridLines = function () { return fixed ? grid.count / 2 : 0; };
  this.fixedScale = function () { return fixed; };

  function turnMatrix() {
    var a = camera.azimuth * Math.PI / 180, e = camera.elevation * Math.PI / 180;
    var ca = Math.cos(a), sa = Math.sin(a), ce = Math.cos(e), se = Math.sin(e);
    // columns of the model-to-view rotation (z up in the model; x right, y up, z to the viewer)
    return new Float32Array([ca, -sa * se, sa * ce, -sa, -ca * se, ca * ce, 0, ce, se]);
  }

  // The vertex shader's scale per axis: the fit, the zoom and the canvas's aspect.
  function scaleVector() {
    var s = camera.zoom * 0.9 / radius, aspect = canvas.width / Math.max(1, canvas.height);
    return aspect > 1 ? [s / aspect, s, s * 0.9] : [s, s * aspect, s * 0.9];
  }

  // A model point where the view draws it: [x, y] in CSS pixels from the canvas's top left, and
  // its depth (smaller is nearer), as the vertex shader places it.
  this.project = function (x, y, z) {
    var t = turnMatrix(), d = [x - centre[0], y - centre[1], z - centre[2]], sc = scaleVector();
    var v = [0, 1, 2].map(function (r) { return t[r] * d[0] + t[3 + r] * d[1] + t[6 + r] * d[2]; });
    return [(sc[0] * v[0] + 1) / 2 * canvas.clientWidth, (1 - sc[1] * v[1]) / 2 * canvas.clientHeight, -0.5 * sc[2] * v[2]];
  };

  // Marks drawn over everything, by name: points (xyz arrays) in a colour, joined by a line or not
  // (the seam point under the pointer; the measure's two points).
  var marks = {};

  // Axes from the shape's lowest corner (its bounding box's least x, y and z): x red, y green,
  // z blue, each as long as the scale bar, named by labels over the canvas where their tips are.
  var axes = { on: !(options && options.axes === false), pos: {}, tint: {}, labels: null, length: 0, origin: null };
  function makeAxes() {
    if (!bounds) return;
    var o = bounds.lo, L = niceLength(radius / 2), pos = [], tint = [];
    [[1, 0, 0], [0, 1, 0], [0, 0, 1]].forEach(function (e, k) {
      var colour = [[0.85, 0.1, 0.1], [0.1, 0.6, 0.1], [0.1, 0.25, 0.9]][k];
      pos.push(o[0], o[1], o[2], o[0] + L * e[0], o[1] + L * e[1], o[2] + L * e[2]);
      tint.push.apply(tint, colour.concat(colour));
    });
    fill(axes.pos, gl.ARRAY_BUFFER, new Float32Array(pos));
    fill(axes.tint, gl.ARRAY_BUFFER, new Float32Array(tint));
    axes.length = L; axes.origin = o.slice();
  }
  function placeAxisLabels() {
    if (!axes.on && !axes.labels) return;
    if (!axes.labels) {
      axes.labels = ["x", "y", "z"].map(function (name) {
        var span = document.createElement("span");
        span.className = "axis-label axis-" + name;
        canvas.parentNode.appendChild(span);
        return span;
      });
    }
    axes.labels.forEach(function (span, k) {
      var show = axes.on && axes.origin && parts.length;
      span.hidden = !show;
      if (!show) return;
      var tip = axes.origin.slice();
      tip[k] += axes.length;
      var p = self.project(tip[0], tip[1], tip[2]);
      span.style.left = (canvas.offsetLeft + p[0]).toFixed(1) + "px";
      span.style.top = (canvas.offsetTop + p[1]).toFixed(1) + "px";
      span.textContent = "xyz"[k] + (k === 0 ? " " + axes.length + " mm" : "");
    });
  }
  this.setAxes = function (on) { axes.on = on; this.draw(); };
  // The axes as drawn: their origin, length (mm) and the labels' text and place (tests).
  this.axes = function () {
    return { on: axes.on, origin: axes.origin, length: axes.length, labels: (axes.labels || []).map(function (l) {
      return { text: l.textContent, hidden: l.hidden, left: parseFloat(l.style.left), top: parseFloat(l.style.top) };
    }) };
  };
  this.setMarks = function (name, points, colour, joined) {
    if (!points.length && !(marks[name] && marks[name].count)) return;  // none before, none now
    var m = marks[name] || (marks[name] = {});
    var flat = [];
    points.forEach(function (p) { flat.push(p[0], p[1], p[2]); });
    if (flat.length) fill(m, gl.ARRAY_BUFFER, new Float32Array(flat));
    m.count = points.length; m.colour = colour; m.joined = joined; m.points = points;
    this.draw();
  };
  this.marks = function (name) { return marks[name] ? marks[name].points : []; };

  this.draw = function () {
    var w = canvas.clientWidth, h = canvas.clientHeight;
    var dpr = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.96, 0.97, 0.98, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.uniformMatrix3fv(loc.turn, false, turnMatrix());
    gl.uniform3fv(loc.centre, centre);
    gl.uniform3fv(loc.scale, scaleVector());
    gl.uniform1f(loc.lit, 1);
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    gl.uniform1f(loc.pointSize, 1);
    parts.forEach(function (part, i) {
      gl.uniform3fv(loc.colour, part.colour);
      gl.bindBuffer(gl.ARRAY_BUFFER, part.pos.buffer);
      gl.enableVertexAttribArray(loc.position);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      tintWith(overlay.tints[i]);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, part.idx.buffer);
      gl.drawElements(gl.TRIANGLES, part.count, gl.UNSIGNED_INT, 0);
    });
    tintWith(null);
    gl.disable(gl.POLYGON_OFFSET_FILL);
    gl.uniform1f(loc.lit, 0);
    if (fixed && grid.count) {
      gl.uniform3fv(loc.colour, [0.78, 0.81, 0.85]);
      gl.bindBuffer(gl.ARRAY_BUFFER, grid.buffer);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      gl.drawArrays(gl.LINES, 0, grid.count);
    }
    lines.forEach(function (line) {
      gl.uniform3fv(loc.colour, line.colour);
      gl.bindBuffer(gl.ARRAY_BUFFER, line.buffer);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      gl.drawArrays(line.loop ? gl.LINE_LOOP : gl.LINE_STRIP, 0, line.count);
    });
    if (axes.on && axes.origin && parts.length) {
      gl.bindBuffer(gl.ARRAY_BUFFER, axes.pos.buffer);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      tintWith(axes.tint);
      gl.drawArrays(gl.LINES, 0, 6);
      tintWith(null);
    }
    drawOverlay();
    placeAxisLabels();
    if (onScale) {
      var perMm = pixelsPerMm();
      onScale({ pixelsPerMm: perMm, barMm: niceLength(120 / perMm) });
    }
  };

  // The vertices' own colours from `slot` (a buffer of rgb per vertex), or the uniform colour.
  function tintWith(slot) {
    if (slot) {
      gl.bindBuffer(gl.ARRAY_BUFFER, slot.buffer);
      gl.enableVertexAttribArray(loc.tint);
      gl.vertexAttribPointer(loc.tint, 3, gl.FLOAT, false, 0, 0);
    } else {
      gl.disableVertexAttribArray(loc.tint);
    }
    gl.uniform1f(loc.tinted, slot ? 1 : 0);
  }

  // The strain's coloured edges on the surface, then the markers over everything.
  function drawOverlay() {
    if (overlay.lines.count) {
      gl.bindBuffer(gl.ARRAY_BUFFER, overlay.lines.pos.buffer);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      tintWith(overlay.lines.tint);
      gl.drawArrays(gl.LINES, 0, overlay.lines.count);
      tintWith(null);
    }
    if (overlay.markers.count) {
      gl.disable(gl.DEPTH_TEST);
      gl.uniform3fv(loc.colour, MARKER);
      gl.uniform1f(loc.pointSize, 7 * (window.devicePixelRatio || 1));
      gl.bindBuffer(gl.ARRAY_BUFFER, overlay.markers.pos.buffer);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      gl.drawArrays(gl.POINTS, 0, overlay.markers.count);
      gl.uniform1f(loc.pointSize, 1);
      gl.enable(gl.DEPTH_TEST);
    }
    gl.disable(gl.DEPTH_TEST);
    Object.keys(marks).forEach(function (name) {
      var m = marks[name];
      if (!m.count) return;
      gl.uniform3fv(loc.colour, m.colour);
      gl.bindBuffer(gl.ARRAY_BUFFER, m.buffer);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      if (m.joined && m.count > 1) gl.drawArrays(gl.LINE_STRIP, 0, m.count);
      gl.uniform1f(loc.pointSize, 10 * (window.devicePixelRatio || 1));
      gl.drawArrays(gl.POINTS, 0, m.count);
      gl.uniform1f(loc.pointSize, 1);
    });
    gl.enable(gl.DEPTH_TEST);
  }

  // Turned by dragging; a press released where it began (within 3 px) is a click: onClick(x, y),
  // CSS pixels in the canvas. A move without a button held: onHover(x, y); leaving: onHover(null).
  var self = this, drag = null, onClick = null, onHover = null;
  this.onClick = function (f) { onClick = f; };
  this.onHover = function (f) { onHover = f; };
  function inCanvas(e) { var b = canvas.getBoundingClientRect(); return [e.clientX - b.left, e.clientY - b.top]; }
  canvas.addEventListener("pointerdown", function (e) {
    drag = { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointerleave", function () { if (!drag && onHover) onHover(null); });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) { if (onHover) onHover.apply(null, inCanvas(e)); return; }
    camera.azimuth -= (e.clientX - drag.x) * 0.5;
    camera.elevation = Math.max(-89, Math.min(89, camera.elevation + (e.clientY - drag.y) * 0.5));
    drag = { x: e.clientX, y: e.clientY };
    self.draw();
  });
  canvas.addEventListener("pointerup", function (e) {
    var click = drag && Math.hypot(e.clientX - drag.x0, e.clientY - drag.y0) <= 3;
    drag = null;
    if (click && onClick) onClick.apply(null, inCanvas(e));
  });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    camera.zoom = Math.max(0.2, Math.min(8, camera.zoom * Math.exp(-e.deltaY * 0.001)));
    self.draw();
  }, { passive: false });
  this.camera = camera;
  this.model = function () { return model; };  // the pieces on screen
  this.partCount = function () { return parts.length; };
}
// The colour of the gate's failures drawn on the shape (magenta-black, apart from every map).
View3D.MARKER = [0.55, 0, 0.45];
