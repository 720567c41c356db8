// report.html's interactive 3D view: both pieces of the D-Form in WebGL 1, orthographic like the
// still pictures, coloured by curvature or by piece, the seam on top and the pattern's tick numbers
// as labels. Inlined into the page by dform (src/report/html_report.cpp); it fetches nothing.
// The outcome goes into #viewer's data-viewer ("ok ...", "no-webgl" or "error: ...") for tests.
(function () {
  "use strict";
  var root = document.getElementById("viewer");
  var status = function (text) { root.setAttribute("data-viewer", text); };
  window.addEventListener("error", function (e) { status("error: " + e.message); });

  var model = JSON.parse(document.getElementById("viewer-model").textContent);
  var canvas = document.getElementById("viewer-canvas");
  var labels = document.getElementById("viewer-labels");
  var gl = canvas.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });
  if (!gl) {
    root.classList.add("no-webgl");
    status("no-webgl");
    return;
  }

  // The still pictures' first view (front, above): azimuth about the vertical z axis, elevation.
  var HOME = { azimuth: 30, elevation: 25, zoom: 1 };
  var BACKGROUND = [228 / 255, 238 / 255, 246 / 255];
  var SEAM = [0xc2 / 255, 0x18 / 255, 0x5b / 255];
  var camera = { azimuth: HOME.azimuth, elevation: HOME.elevation, zoom: HOME.zoom };
  var colourBy = /pieces/.test(location.hash) ? "pieces" : "curvature";

  var VERTEX = [
    "attribute vec3 position, normal, colour;",
    "uniform mat3 turn;",  // model to view: x right, y up, z away from the viewer
    "uniform vec3 centre, scale;",
    "uniform float lit;",
    "varying vec3 shaded;",
    "void main() {",
    "  gl_Position = vec4(scale * (turn * (position - centre)), 1.0);",
    // A light from the upper left in front, both sides lit, as in the still pictures.
    "  float light = abs(dot(normalize(turn * normal), normalize(vec3(-0.4, 0.5, -1.0))));",
    "  shaded = colour * mix(1.0, 0.35 + 0.65 * light, lit);",
    "}"].join("\n");
  var FRAGMENT = [
    "precision mediump float;",
    "varying vec3 shaded;",
    "void main() { gl_FragColor = vec4(shaded, 1.0); }"].join("\n");

  function shader(type, text) {
    var s = gl.createShader(type);
    gl.shaderSource(s, text);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  var program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER, VERTEX));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER, FRAGMENT));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  gl.useProgram(program);
  var attribute = {};
  ["position", "normal", "colour"].forEach(function (n) { attribute[n] = gl.getAttribLocation(program, n); });
  var uniform = {};
  ["turn", "centre", "scale", "lit"].forEach(function (n) { uniform[n] = gl.getUniformLocation(program, n); });

  function buffer(target, array) {
    var b = gl.createBuffer();
    gl.bindBuffer(target, b);
    gl.bufferData(target, array, gl.STATIC_DRAW);
    return b;
  }

  // Area-weighted vertex normals: a piece's own, so the seam stays a sharp ridge.
  function normals(position, index) {
    var n = new Float32Array(position.length);
    for (var f = 0; f < index.length; f += 3) {
      var i = index[f] * 3, j = index[f + 1] * 3, k = index[f + 2] * 3;
      var ux = position[j] - position[i], uy = position[j + 1] - position[i + 1], uz = position[j + 2] - position[i + 2];
      var vx = position[k] - position[i], vy = position[k + 1] - position[i + 1], vz = position[k + 2] - position[i + 2];
      var cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
      [i, j, k].forEach(function (v) { n[v] += cx; n[v + 1] += cy; n[v + 2] += cz; });
    }
    return n;
  }

  var uintIndices = gl.getExtension("OES_element_index_uint");
  var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  var triangles = 0;
  var pieces = model.pieces.map(function (p) {
    var position = new Float32Array(p.position);
    for (var v = 0; v < position.length; ++v) {
      lo[v % 3] = Math.min(lo[v % 3], position[v]);
      hi[v % 3] = Math.max(hi[v % 3], position[v]);
    }
    var curvature = new Float32Array(position.length), flat = new Float32Array(position.length);
    p.curvature.forEach(function (rgb, v) {
      curvature.set([(rgb >> 16) / 255, ((rgb >> 8) & 255) / 255, (rgb & 255) / 255], 3 * v);
      flat.set(p.colour, 3 * v);
    });
    var wide = position.length / 3 > 65535;
    if (wide && !uintIndices) throw new Error("no 32-bit indices for " + position.length / 3 + " vertices");
    var index = wide ? new Uint32Array(p.index) : new Uint16Array(p.index);
    triangles += index.length / 3;
    var normal = normals(position, index);
    return {
      position: buffer(gl.ARRAY_BUFFER, position),
      normal: buffer(gl.ARRAY_BUFFER, normal),
      curvature: buffer(gl.ARRAY_BUFFER, curvature),
      pieces: buffer(gl.ARRAY_BUFFER, flat),
      index: buffer(gl.ELEMENT_ARRAY_BUFFER, index),
      count: index.length,
      type: wide ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT,
      vertices: position,
      normals: normal
    };
  });
  var seam = buffer(gl.ARRAY_BUFFER, new Float32Array(model.seam));
  var centre = [0, 1, 2].map(function (d) { return 0.5 * (lo[d] + hi[d]); });
  var radius = 0.5 * Math.max(1e-9, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));

  // A tick's number is dimmed when the surface on both sides of its seam point faces away.
  var ticks = model.ticks.map(function (t) {
    var label = document.createElement("span");
    label.textContent = t.label;
    labels.appendChild(label);
    var faces = pieces.map(function (p) {
      var best = 0, bestDistance = Infinity;
      for (var v = 0; v < p.vertices.length; v += 3) {
        var d = Math.hypot(p.vertices[v] - t.at[0], p.vertices[v + 1] - t.at[1], p.vertices[v + 2] - t.at[2]);
        if (d < bestDistance) { bestDistance = d; best = v; }
      }
      return [p.normals[best], p.normals[best + 1], p.normals[best + 2]];
    });
    return { at: t.at, faces: faces, label: label };
  });

  // Rows of the model-to-view turn (column-major for WebGL): the still pictures' ShapeCamera,
  // x right, y up (model z tilted), z the depth away from the viewer.
  function turn() {
    var a = camera.azimuth * Math.PI / 180, e = camera.elevation * Math.PI / 180;
    var ca = Math.cos(a), sa = Math.sin(a), ce = Math.cos(e), se = Math.sin(e);
    var x = [ca, sa, 0], y = [-se * sa, se * ca, ce], z = [-ce * sa, ce * ca, -se];
    return { x: x, y: y, z: z, matrix: [x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]] };
  }

  function attribute3(name, b) {
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.enableVertexAttribArray(attribute[name]);
    gl.vertexAttribPointer(attribute[name], 3, gl.FLOAT, false, 0, 0);
  }

  function draw() {
    var w = canvas.clientWidth, h = canvas.clientHeight, ratio = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
      canvas.width = Math.round(w * ratio);
      canvas.height = Math.round(h * ratio);
    }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    // The bounding sphere fills nine tenths of the shorter side at zoom 1, whatever the turn.
    var pixels = camera.zoom * 0.45 * Math.min(w, h) / radius;
    var t = turn();
    gl.uniformMatrix3fv(uniform.turn, false, t.matrix);
    gl.uniform3fv(uniform.centre, centre);
    gl.uniform3fv(uniform.scale, [2 * pixels / w, 2 * pixels / h, 1 / radius]);
    // The surface pushed back a little, so that the seam on it wins the depth test.
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    gl.uniform1f(uniform.lit, 1);
    pieces.forEach(function (p) {
      attribute3("position", p.position);
      attribute3("normal", p.normal);
      attribute3("colour", colourBy === "pieces" ? p.pieces : p.curvature);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, p.index);
      gl.drawElements(gl.TRIANGLES, p.count, p.type, 0);
    });
    gl.disable(gl.POLYGON_OFFSET_FILL);
    gl.uniform1f(uniform.lit, 0);
    attribute3("position", seam);
    gl.disableVertexAttribArray(attribute.normal);
    gl.disableVertexAttribArray(attribute.colour);
    gl.vertexAttrib3f(attribute.normal, 0, 0, 1);
    gl.vertexAttrib3fv(attribute.colour, SEAM);
    gl.drawArrays(gl.LINE_LOOP, 0, model.seam.length / 3);

    ticks.forEach(function (tick) {
      var d = [0, 1, 2].map(function (k) { return tick.at[k] - centre[k]; });
      var dot = function (r, v) { return r[0] * v[0] + r[1] * v[1] + r[2] * v[2]; };
      tick.label.style.left = (0.5 * w + pixels * dot(t.x, d)).toFixed(1) + "px";
      tick.label.style.top = (0.5 * h - pixels * dot(t.y, d)).toFixed(1) + "px";
      var inSight = tick.faces.some(function (n) { return dot(t.z, n) < 0; });
      tick.label.className = inSight ? "" : "hidden";
    });
  }

  var pending = false;
  function redraw() {
    if (pending) return;
    pending = true;
    window.requestAnimationFrame(function () { pending = false; draw(); });
  }

  // Drag to turn, wheel or two fingers to zoom, double-click to go back to the first view.
  var pointers = {};
  canvas.addEventListener("pointerdown", function (e) {
    canvas.setPointerCapture(e.pointerId);
    pointers[e.pointerId] = { x: e.clientX, y: e.clientY };
  });
  canvas.addEventListener("pointermove", function (e) {
    var last = pointers[e.pointerId];
    if (!last) return;
    var ids = Object.keys(pointers);
    if (ids.length === 1) {
      camera.azimuth += 0.5 * (e.clientX - last.x);
      camera.elevation = Math.max(-89, Math.min(89, camera.elevation + 0.5 * (e.clientY - last.y)));
    } else if (ids.length === 2) {
      var other = pointers[ids[0] === String(e.pointerId) ? ids[1] : ids[0]];
      var before = Math.hypot(last.x - other.x, last.y - other.y);
      var after = Math.hypot(e.clientX - other.x, e.clientY - other.y);
      if (before > 0) camera.zoom = Math.max(0.2, Math.min(20, camera.zoom * after / before));
    }
    pointers[e.pointerId] = { x: e.clientX, y: e.clientY };
    redraw();
  });
  var release = function (e) { delete pointers[e.pointerId]; };
  canvas.addEventListener("pointerup", release);
  canvas.addEventListener("pointercancel", release);
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    camera.zoom = Math.max(0.2, Math.min(20, camera.zoom * Math.exp(-0.001 * e.deltaY)));
    redraw();
  }, { passive: false });
  canvas.addEventListener("dblclick", function () {
    camera.azimuth = HOME.azimuth;
    camera.elevation = HOME.elevation;
    camera.zoom = HOME.zoom;
    redraw();
  });

  var coloursButton = document.getElementById("viewer-colours");
  var showColours = function () {
    coloursButton.textContent = colourBy === "pieces" ? "curvature colours" : "piece colours";
  };
  coloursButton.addEventListener("click", function () {
    colourBy = colourBy === "pieces" ? "curvature" : "pieces";
    showColours();
    redraw();
  });
  // The full window: #view3d in the address (a link to it opens the view that way).
  var fullButton = document.getElementById("viewer-full");
  var setFull = function (full) {
    root.classList.toggle("full", full);
    document.documentElement.classList.toggle("viewer-full", full);  // no page scroll bar beside it
    fullButton.textContent = full ? "back to the page" : "full window";
    redraw();
  };
  fullButton.addEventListener("click", function () { setFull(!root.classList.contains("full")); });
  window.addEventListener("keydown", function (e) { if (e.key === "Escape") setFull(false); });
  window.addEventListener("resize", redraw);

  showColours();
  setFull(/^#view3d/.test(location.hash));
  draw();
  status("ok triangles=" + triangles + " ticks=" + ticks.length + " colours=" + colourBy);
})();
