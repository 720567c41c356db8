// dform studio's 3D view: both pieces of the D-Form in WebGL 1, shaded by piece, the seam and the
// creases drawn on top, turned by dragging and zoomed by the wheel. Buffers are kept and
// refilled in place while the mesh keeps its size, so a live drag uploads vertices only.
"use strict";

function View3D(canvas) {
  var gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });
  if (!gl) throw new Error("this browser has no WebGL");
  if (!gl.getExtension("OES_element_index_uint")) throw new Error("WebGL lacks 32-bit indices");
  // Faceted shading from the screen-space derivatives of the view position (each triangle its
  // own plane, as the sheet is between mesh vertices): no normals to compute or upload per frame.
  if (!gl.getExtension("OES_standard_derivatives")) throw new Error("WebGL lacks standard derivatives");
  var VERTEX = [
    "attribute vec3 position;",
    "uniform mat3 turn;",
    "uniform vec3 centre, scale;",
    "varying vec3 viewPosition;",
    "void main() {",
    "  vec3 p = scale * (turn * (position - centre));",
    "  viewPosition = p;",
    "  gl_Position = vec4(p.xy, -p.z * 0.5, 1.0);",
    "}"].join("\n");
  var FRAGMENT = [
    "#extension GL_OES_standard_derivatives : enable",
    "precision mediump float;",
    "uniform vec3 colour;",
    "uniform float lit;",
    "varying vec3 viewPosition;",
    "void main() {",
    "  vec3 n = normalize(cross(dFdx(viewPosition), dFdy(viewPosition)));",
    "  float light = abs(dot(n, normalize(vec3(-0.6, 0.7, 0.45))));",
    "  gl_FragColor = vec4(colour * mix(1.0, 0.2 + 0.8 * light, lit), 1.0);",
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
  ["turn", "centre", "scale", "colour", "lit"].forEach(function (n) { loc[n] = gl.getUniformLocation(program, n); });

  var COLOURS = [[0.93, 0.62, 0.27], [0.36, 0.6, 0.85]];
  var HOME = { azimuth: 30, elevation: 25, zoom: 1 };
  var camera = Object.assign({}, HOME);
  // Fixed scale: the fit (centre, radius, ground) kept from the shape on screen when it was
  // turned on, so that a change of size shows; a ground grid and the scale bar give the size.
  var fixed = false, ground = 0, grid = { count: 0 }, onScale = null, bounds = null;
  var parts = [];   // per piece: buffers and counts
  var lines = [];   // seam and creases: {buffer, count, colour, loop}
  var centre = [0, 0, 0], radius = 1;

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
  this.setModel = function (pieces, extra) {
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
    this.draw();
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
    var s = camera.zoom * 0.9 / radius, aspect = canvas.width / Math.max(1, canvas.height);
    gl.uniformMatrix3fv(loc.turn, false, turnMatrix());
    gl.uniform3fv(loc.centre, centre);
    gl.uniform3fv(loc.scale, aspect > 1 ? [s / aspect, s, s * 0.9] : [s, s * aspect, s * 0.9]);
    gl.uniform1f(loc.lit, 1);
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    parts.forEach(function (part) {
      gl.uniform3fv(loc.colour, part.colour);
      gl.bindBuffer(gl.ARRAY_BUFFER, part.pos.buffer);
      gl.enableVertexAttribArray(loc.position);
      gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, part.idx.buffer);
      gl.drawElements(gl.TRIANGLES, part.count, gl.UNSIGNED_INT, 0);
    });
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
    if (onScale) {
      var perMm = pixelsPerMm();
      onScale({ pixelsPerMm: perMm, barMm: niceLength(120 / perMm) });
    }
  };

  var self = this, drag = null;
  canvas.addEventListener("pointerdown", function (e) { drag = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) return;
    camera.azimuth -= (e.clientX - drag.x) * 0.5;
    camera.elevation = Math.max(-89, Math.min(89, camera.elevation + (e.clientY - drag.y) * 0.5));
    drag = { x: e.clientX, y: e.clientY };
    self.draw();
  });
  canvas.addEventListener("pointerup", function () { drag = null; });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    camera.zoom = Math.max(0.2, Math.min(8, camera.zoom * Math.exp(-e.deltaY * 0.001)));
    self.draw();
  }, { passive: false });
  this.camera = camera;
  this.partCount = function () { return parts.length; };
}
