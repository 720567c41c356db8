// dform studio's print preview: what Export would lay out for the chosen profile and page or
// sheet, made by the same run as Export (the server's /api/preview) once the design settles or
// the export's settings change: the pages (tiles and page maps numbered on a plan of the sheets),
// each sheet as its pattern.svg draws it (pieces, ticks, tabs, marks), or, where Export would
// refuse or hold the cutting files back, its message (a sheet too small names the largest scale
// that fits).
// page: {api, body() (the request: the design and its export settings), studio}.
"use strict";

function Preview(page) {
  var $ = function (id) { return document.getElementById(id); };
  var timer = null, inFlight = false, again = false, seq = 0;
  var self = this;
  this.shown = null;  // the last preview's answer, with its seq

  // Asked again after `delay` ms of quiet (the design or the export's settings changed).
  this.schedule = function (delay) {
    clearTimeout(timer);
    $("preview-state").textContent = $("export-preview").textContent = "waiting for the design to settle…";
    $("preview-pages").classList.add("stale");  // the last layout is another design's
    timer = setTimeout(function () { timer = null; run(); }, delay == null ? 600 : delay);
  };
  // No layout asked for or under way (tests wait for it).
  this.idle = function () { return timer == null && !inFlight; };

  function run() {
    if (inFlight) { again = true; return; }
    inFlight = true;
    var mine = ++seq;
    $("preview-state").textContent = $("export-preview").textContent = "laying out…";
    page.api("/api/preview", page.body()).then(function (p) {
      p.seq = mine;
      show(p);
    }).catch(function (e) {
      show({ seq: mine, error: e.message });
    }).then(function () {
      inFlight = false;
      if (again) { again = false; run(); }
    });
  }

  function show(p) {
    self.shown = p;
    var pages = p.pages || [], sheets = p.sheets || [];
    $("preview-missing").textContent = p.error || p.missing || "";
    $("preview-state").textContent = p.error ? "Export would fail"
      : !p.pages ? "no cutting files"
      : pages.length + (pages.length === 1 ? " page" : " pages") + " on " + sheets.length + (sheets.length === 1 ? " sheet" : " sheets") +
        ", " + p.profile + ", scale " + (100 * p.scale).toFixed(1) + " %" + (p.failed_gate ? ", marked FAILED GATE" : "");
    $("export-preview").textContent = "Preview: " + $("preview-state").textContent + ($("preview-missing").textContent ? ". " + $("preview-missing").textContent : "");
    var box = $("preview-pages");
    box.innerHTML = "";
    box.classList.toggle("stale", !!timer || again);
    if (!p.pages) return;
    box.appendChild(plan(sheets, pages));
    (p.svg || []).forEach(function (text, k) {
      var img = document.createElement("img");
      img.className = "preview-sheet";
      img.alt = "sheet " + (k + 1);
      img.src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(thin(text));
      box.appendChild(img);
    });
  }

  // A sheet's SVG with every line one screen pixel wide: a cutter's hairlines (0.01 mm) vanish at
  // the preview's scale, and a print's 0.35 mm lines would too.
  function thin(svg) {
    return svg.replace(/<svg\b[^>]*>/, "$&<style>* { vector-effect: non-scaling-stroke; stroke-width: 1px !important; }</style>");
  }

  // The sheets (grey) and each page's window on them (numbered rectangles), canvas mm, y down.
  function plan(sheets, pages) {
    var lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    function grow(x0, y0, x1, y1) {
      lo = [Math.min(lo[0], x0, x1), Math.min(lo[1], y0, y1)]; hi = [Math.max(hi[0], x0, x1), Math.max(hi[1], y0, y1)];
    }
    sheets.forEach(function (s) { grow(s.origin[0], s.origin[1], s.origin[0] + s.width, s.origin[1] + s.height); });
    pages.forEach(function (p) { grow(p.window[0][0], p.window[0][1], p.window[1][0], p.window[1][1]); });
    var pad = 0.02 * Math.max(hi[0] - lo[0], hi[1] - lo[1], 1);
    var svg = svgNode("svg", { class: "preview-plan", viewBox: [lo[0] - pad, lo[1] - pad, hi[0] - lo[0] + 2 * pad, hi[1] - lo[1] + 2 * pad].join(" ") });
    var unit = Math.max(hi[0] - lo[0], hi[1] - lo[1]) / 260;
    sheets.forEach(function (s) {
      svgNode("rect", { x: s.origin[0], y: s.origin[1], width: s.width, height: s.height, class: "plan-sheet", "stroke-width": unit }, svg);
    });
    pages.forEach(function (p, k) {
      var x0 = Math.min(p.window[0][0], p.window[1][0]), y0 = Math.min(p.window[0][1], p.window[1][1]);
      var w = Math.abs(p.window[1][0] - p.window[0][0]), h = Math.abs(p.window[1][1] - p.window[0][1]);
      svgNode("rect", { x: x0, y: y0, width: w, height: h, class: "plan-page plan-" + p.kind, "stroke-width": 1.5 * unit }, svg);
      var t = svgNode("text", { x: x0 + w / 2, y: y0 + h / 2, "font-size": 14 * unit, class: "plan-number" }, svg);
      t.textContent = k + 1;
    });
    return svg;
  }
}
