// dform studio's page: the design's state, the calls to the server, the live drag loop (one solve
// in flight; the newest input is sent when it answers), undo and redo, the strip, downloads.
// window.studio exposes the state for tests and the latency benchmark.
"use strict";

(function () {
  var TOKEN = document.querySelector('meta[name="dform-token"]').content;
  var $ = function (id) { return document.getElementById(id); };
  var studio = window.studio = { latencies: [], breakdown: [], shown: null, errors: [] };
  var session = null, kinds = [];
  var state = {
    mode: "forward",
    // Each mode's settings as the server's settings table writes them (the session's answer):
    // the page changes the ones it has controls for and sends back all of them.
    byMode: { forward: {}, inverse: {} },
    pieces: [null, null],   // {name, kind, values} or {name, text}: what made each outline
    curve: null,
  };
  var summaries = [null, null], history = [], future = [];
  function settings() { return state.byMode[state.mode]; }
  // Where each seam starts as the last shape solved it: a start given as the outline point
  // nearest a point (a job file's "near") is drawn there until it is dragged.
  var resolvedStarts = [0, 0];
  function startFraction(i) {
    var f = settings()[i ? "start_b" : "start_a"];
    return typeof f === "number" ? f : resolvedStarts[i];
  }

  function api(path, body, binary) {
    return fetch(path, { method: "POST", headers: { "Content-Type": "application/json", "X-Dform-Token": TOKEN },
                         body: JSON.stringify(Object.assign({ session: session }, body)) })
      .then(function (res) {
        if (binary && res.ok) return res.blob();
        var headers = performance.now();
        return res.json().then(function (j) {
          if (!res.ok) throw new Error(j.error || res.statusText);
          j.arrival = { headers: headers, parsed: performance.now(), server: res.headers.get("Server-Timing") };
          return j;
        });
      });
  }

  // ---- undo / redo: snapshots of the state, outlines included -----------------------------------
  function snapshot() { return JSON.stringify(state); }
  function remember() { history.push(snapshot()); if (history.length > 200) history.shift(); future = []; updateUndo(); }
  function updateUndo() { $("undo").disabled = !history.length; $("redo").disabled = !future.length; }
  function restore(text) {
    var old = state;
    state = JSON.parse(text);
    var loads = [0, 1].map(function (i) {
      return JSON.stringify(old.pieces[i]) === JSON.stringify(state.pieces[i]) ? null : loadPiece(i, state.pieces[i], false);
    });
    return Promise.all(loads).then(function () { syncControls(); refreshPieces(); solve(); scheduleStrip(); });
  }
  $("undo").onclick = function () { if (history.length) { future.push(snapshot()); restore(history.pop()); updateUndo(); } };
  $("redo").onclick = function () { if (future.length) { history.push(snapshot()); restore(future.pop()); updateUndo(); } };
  document.addEventListener("keydown", function (e) {
    if ((e.ctrlKey || e.metaKey) && e.key === "z") { e.preventDefault(); (e.shiftKey ? $("redo") : $("undo")).click(); }
    if ((e.ctrlKey || e.metaKey) && e.key === "y") { e.preventDefault(); $("redo").click(); }
  });

  // ---- outlines ---------------------------------------------------------------------------------
  function loadPiece(i, source, record) {
    var request = source.text != null
      ? api("/api/outline", { piece: "ab"[i], name: source.name, text: source.text })
      : api("/api/parametric", { piece: "ab"[i], kind: source.kind, values: source.values });
    return request.then(function (summary) {
      if (record) remember();
      state.pieces[i] = source;
      summaries[i] = summary;
      $("error-" + "ab"[i]).textContent = "";
      $("name-" + "ab"[i]).textContent = summary.name + " — perimeter " + summary.perimeter.toFixed(1) + " mm";
      return summary;
    }).catch(function (e) {
      $("error-" + "ab"[i]).textContent = e.message;
      studio.errors.push(e.message);
      throw e;
    });
  }

  function sliders(i) {
    var box = $("sliders-" + "ab"[i]), source = state.pieces[i];
    box.innerHTML = "";
    if (!source || source.kind == null) return;
    var kind = kinds.filter(function (k) { return k.name === source.kind; })[0];
    kind.parameters.forEach(function (p) {
      var label = document.createElement("label"), input = document.createElement("input"), out = document.createElement("output");
      label.textContent = p.name + " ";
      input.type = "range"; input.min = p.min; input.max = p.max;
      input.step = p.max - p.min > 20 ? 1 : (p.max - p.min) / 200;
      input.value = source.values[p.name] != null ? source.values[p.name] : p.value;
      out.textContent = (+input.value).toFixed(2).replace(/\.?0+$/, "");
      input.oninput = function () {
        out.textContent = (+input.value).toFixed(2).replace(/\.?0+$/, "");
        var values = Object.assign({}, state.pieces[i].values); values[p.name] = +input.value;
        loadPiece(i, { name: source.kind, kind: source.kind, values: values }, false)
          .then(function () { refreshPieces(); solve(); }).catch(function () {});
      };
      input.onchange = function () { scheduleStrip(); };
      input.onpointerdown = function () { remember(); };
      label.appendChild(input); label.appendChild(out); box.appendChild(label);
    });
  }

  function fillKinds(i) {
    var select = $("kind-" + "ab"[i]);
    select.innerHTML = "";
    var first = document.createElement("option"); first.value = ""; first.textContent = "outline…"; select.appendChild(first);
    kinds.forEach(function (k) { var o = document.createElement("option"); o.value = k.name; o.textContent = k.label; select.appendChild(o); });
    select.onchange = function () {
      if (!select.value) return;
      var kind = kinds.filter(function (k) { return k.name === select.value; })[0], values = {};
      kind.parameters.forEach(function (p) { values[p.name] = p.value; });
      loadPiece(i, { name: kind.name, kind: kind.name, values: values }, true)
        .then(function () { sliders(i); refreshPieces(); solve(); scheduleStrip(); }).catch(function () {});
    };
  }

  function readFile(i, file) {
    var reader = new FileReader();
    reader.onload = function () {
      loadPiece(i, { name: file.name, text: reader.result }, true)
        .then(function () { $("kind-" + "ab"[i]).value = ""; sliders(i); refreshPieces(); solve(); scheduleStrip(); })
        .catch(function () {});
    };
    reader.readAsText(file);
  }
  [0, 1].forEach(function (i) {
    var panel = $("panel-" + "ab"[i]), input = $("file-" + "ab"[i]);
    input.onchange = function () { if (input.files[0]) readFile(i, input.files[0]); input.value = ""; };
    panel.addEventListener("dragover", function (e) { e.preventDefault(); panel.classList.add("drop"); });
    panel.addEventListener("dragleave", function () { panel.classList.remove("drop"); });
    panel.addEventListener("drop", function (e) {
      e.preventDefault(); panel.classList.remove("drop");
      if (e.dataTransfer.files[0]) readFile(i, e.dataTransfer.files[0]);
    });
  });

  // ---- the pieces and the live drag -------------------------------------------------------------
  var pending = null, inFlight = false, nextSeq = 1, shownSeq = 0, inputTime = {};
  studio.idle = function () { return pending == null && !inFlight; };
  var views = [0, 1].map(function (i) {
    return new PieceView($("svg-" + "ab"[i]), "AB"[i], function (f, e) {
      settings()[i ? "start_b" : "start_a"] = f;
      solve(e.timeStamp);
    }, function () { scheduleStrip(); });
  });
  studio.views = views;
  // A start set as a drag ending there sets it (scripts and tests).
  studio.setStart = function (i, f) {
    remember();
    settings()[i ? "start_b" : "start_a"] = f;
    views[i].setFraction(f);
    solve(); scheduleStrip();
  };
  [0, 1].forEach(function (i) { $("svg-" + "ab"[i]).addEventListener("pointerdown", function (e) {
    if (e.target.classList.contains("handle-target")) remember();
  }, true); });

  function joinOf(i) { return settings().join.split(",")[i]; }
  function refreshPieces() {
    [0, 1].forEach(function (i) {
      if (!summaries[i]) return;
      views[i].setShape(summaries[i], joinOf(i));
      views[i].setFraction(startFraction(i));
    });
    $("fit-note").textContent = summaries[0] && summaries[1]
      ? "A " + summaries[0].perimeter.toFixed(1) + " mm, B " + summaries[1].perimeter.toFixed(1) + " mm" : "";
  }

  function solve(eventTime) {
    var seq = nextSeq++;
    inputTime[seq] = eventTime != null ? eventTime : performance.now();
    pending = seq;
    if (!inFlight) send();
  }

  function send() {
    if (pending == null) return;
    var seq = pending; pending = null; inFlight = true;
    var path = state.mode === "inverse" ? "/api/inverse" : "/api/solve";
    var body = Object.assign({ seq: seq, mode: state.mode }, settings());
    var sent = performance.now();
    api(path, body).then(function (r) {
      if (r.arrival) r.arrival.sent = sent;
      inFlight = false;
      if (!r.superseded) show(r);
      send();
    }).catch(function (e) { inFlight = false; showError(e.message); send(); });
  }

  function showError(text) {
    $("status").textContent = text;
    $("status").className = "status error";
    studio.errors.push(text);
  }

  function decodePieces(r) {
    return r.pieces.map(function (p) {
      return { flat: decodeF64(p.flat), shape: decodeF64(p.shape), faces: decodeU32(p.faces), seam: p.seam, creases: p.creases };
    });
  }

  // The flat piece as solved laid over the outline as read (B may be scaled to A's perimeter
  // and turned over): a scale per axis and an offset from the two bounding boxes.
  function placement(piece, summary) {
    var lo = [Infinity, Infinity], hi = [-Infinity, -Infinity], f = piece.flat;
    for (var k = 0; k < f.length; ++k) { lo[k % 2] = Math.min(lo[k % 2], f[k]); hi[k % 2] = Math.max(hi[k % 2], f[k]); }
    var s = [(summary.max[0] - summary.min[0]) / (hi[0] - lo[0]), (summary.max[1] - summary.min[1]) / (hi[1] - lo[1])];
    return { scale: s, offset: [summary.min[0] - lo[0] * s[0], summary.min[1] - lo[1] * s[1]] };
  }

  function show(r) {
    if (r.seq < shownSeq) return;
    if (r.error) { showError(r.error); return; }
    shownSeq = r.seq;
    var pieces = decodePieces(r);
    var extra = [];
    if (r.target) extra.push({ points: decodeF64(r.target), colour: [0.1, 0.5, 0.2], loop: true });
    view3d.setModel(pieces, extra);
    var brk = /at seam point (\d+)/.exec(r.model.reason);
    if (state.mode === "inverse") [0, 1].forEach(function (i) {
      views[i].setSolvedPiece(pieces[i]);
      $("name-" + "ab"[i]).textContent = "piece " + "AB"[i] + " as cut, unfolded from the curve";
    });
    if (state.mode === "forward") {
      resolvedStarts = [r.start_a, r.start_b];
      [0, 1].forEach(function (i) {
        views[i].setFraction(startFraction(i));
        views[i].setResult(pieces[i], i === 0 || settings().flip ? 1 : -1, brk ? +brk[1] : null,
                           placement(pieces[i], summaries[i]));
      });
    }
    facts(r);
    var time = inputTime[r.seq];
    delete inputTime[r.seq];
    studio.shown = { seq: r.seq, result: r, pieces: pieces, settings: Object.assign({}, settings()) };
    var drawn = performance.now();
    requestAnimationFrame(function () {
      if (time != null && !r.preview) {
        studio.latencies.push(performance.now() - time);
        if (r.arrival) studio.breakdown.push(breakdown(r, time, drawn, performance.now()));
      }
      studio.frameSeq = r.seq;
    });
  }

  // Where a drag frame's time goes (ms), for tests/bench/studio_latency.py: waiting for the
  // solve in flight, the request's round trip (the server's share and the solve's within it),
  // reading and parsing the answer, showing it (decode, buffers, panels) and the frame.
  function breakdown(r, time, drawn, frame) {
    var a = r.arrival, server = {};
    (a.server || "").split(",").forEach(function (m) {
      var d = /^\s*(\w+);dur=([\d.]+)/.exec(m);
      if (d) server[d[1]] = +d[2];
    });
    return { queued: a.sent - time, round_trip: a.headers - a.sent, server: server.total, solve: 1000 * r.timings.total, made: 1000 * r.timings.made, answer: 1000 * r.timings.answer,
             server_handle: server.handle, body_and_parse: a.parsed - a.headers, show: drawn - a.parsed, frame: frame - drawn };
  }

  function number(x, digits) { return x == null ? "—" : (+x).toPrecision(digits || 3); }
  // A shape's figures and the gate's verdict on them ({figures, gate}, or {error}), which arrive
  // with a refined result or as an event after the shape; none yet: still measuring.
  function showVerdict(r, verdict) {
    var gate = verdict && verdict.gate, status = $("status");
    if (verdict) { r.figures = verdict.figures; r.gate = gate; }
    status.className = "status " + (gate ? (gate.passed ? "pass" : "fail") : verdict && verdict.error ? "error" : "");
    status.textContent = (verdict && verdict.error ? verdict.error : !gate ? "measuring, checking the gate…"
                          : gate.passed ? "gate passed" : "gate failed: " + gate.failed + " check(s)") +
      (r.preview ? " — preview at " + studio.previewResolution + " seam points, refining…" : "");
    $("checks").innerHTML = "";
    (gate ? gate.checks : []).forEach(function (c) {
      var li = document.createElement("li");
      li.className = c.verdict; li.textContent = c.name + ": " + c.verdict + (c.verdict === "fail" ? " — " + c.detail : "");
      $("checks").appendChild(li);
    });
    studio.gate = gate;
    showFigures(r, r.figures || {});  // an inverse answer has its figures before its verdict
  }

  function showFigures(r, f) {
    var percent = function (x) { return x == null ? "—" : (100 * x).toFixed(3) + " %"; };
    var rows = [
      ["L_error", percent(f.L_error)], ["L_max", percent(f.L_max)],
      ["B_error", number(f.B_error)], ["seam gap", number(f.seam_gap_mm) + " mm"],
      ["angle defect max", number(f.angle_defect_max_rad) + " rad"], ["3D seam", number(f.seam_length_3d_mm, 5) + " mm"],
    ];
    if (r.scale_b != null) rows.push(["B scaled by", number(r.scale_b, 6)], ["starts", "A " + r.start_a.toFixed(4) + ", B " + r.start_b.toFixed(4)]);
    if (r.curve_match) rows.push(["D_error", number(r.curve_match.D_error)], ["round trip max", number(r.curve_match.roundtrip_max_rel)],
                                 ["on hull", r.on_hull.on_hull ? "yes" : "no: " + r.on_hull.summary]);
    rows.push(["solve", (1000 * r.timings.total).toFixed(0) + " ms"]);
    $("figures").innerHTML = "";
    rows.forEach(function (row) {
      var tr = document.createElement("tr");
      row.forEach(function (cell) { var td = document.createElement("td"); td.textContent = cell; tr.appendChild(td); });
      $("figures").appendChild(tr);
    });
  }

  // Verdicts that came before their shape's answer, by seq; only the shown shape's is ever shown.
  var earlyVerdicts = {};
  function facts(r) {
    showVerdict(r, r.gate ? { figures: r.figures, gate: r.gate } : earlyVerdicts[r.seq]);
    earlyVerdicts = {};
    $("model").textContent = r.model.name + (r.model.found_creases.length ? ", " + r.model.found_creases.length + " found crease(s)" : "");
    $("reason").textContent = r.model.reason;
    $("warnings").textContent = (r.warnings || []).join("\n");
  }

  // ---- settings ---------------------------------------------------------------------------------
  function syncControls() {
    var s = settings();
    $("flip").checked = s.flip; $("join").value = s.join; $("model-choice").value = s.model;
    $("resolution").value = s.resolution; $("fit").checked = s.fit_perimeter;
    document.body.setAttribute("data-mode", state.mode);
    $("mode-forward").classList.toggle("active", state.mode === "forward");
    $("mode-inverse").classList.toggle("active", state.mode === "inverse");
  }
  function setting(id, key, read) {
    $(id).onchange = function () {
      remember();
      settings()[key] = read($(id));
      refreshPieces(); solve(); scheduleStrip();
    };
  }
  setting("flip", "flip", function (e) { return e.checked; });
  setting("join", "join", function (e) { return e.value; });
  setting("model-choice", "model", function (e) { return e.value; });
  setting("resolution", "resolution", function (e) { return Math.max(8, Math.min(1000, +e.value | 0)); });
  setting("fit", "fit_perimeter", function (e) { return e.checked; });

  // ---- the strip --------------------------------------------------------------------------------
  var strip = new Strip($("strip-cards"), $("thumbnail"), function (card) {
    remember();
    settings().start_b = card.start_b; settings().flip = card.flip;
    syncControls(); refreshPieces(); solve();
  });
  studio.strip = strip;
  var stripTimer = null, stripSeq = 0;
  function scheduleStrip() {
    if (state.mode !== "forward") return;
    clearTimeout(stripTimer);
    strip.cancel();
    stripTimer = setTimeout(function () {
      var seq = ++stripSeq;
      strip.reset(seq);
      api("/api/strip", Object.assign({ seq: seq, starts: 16, both_flips: true }, settings())).catch(function (e) { showError(e.message); });
    }, 300);
  }

  // ---- inverse ----------------------------------------------------------------------------------
  function setMode(mode) {
    remember(); state.mode = mode; syncControls();
    if (mode === "forward") {
      [0, 1].forEach(function (i) {
        $("name-" + "ab"[i]).textContent = summaries[i].name + " — perimeter " + summaries[i].perimeter.toFixed(1) + " mm";
      });
      refreshPieces(); scheduleStrip();
    }
    if (mode === "forward" || state.curve) solve();
  }
  $("mode-forward").onclick = function () { setMode("forward"); };
  $("mode-inverse").onclick = function () { setMode("inverse"); };
  function readCurve(file) {
    var reader = new FileReader();
    reader.onload = function () {
      api("/api/curve", { name: file.name, text: reader.result, closed: $("closed").checked }).then(function (c) {
        state.curve = { name: c.name };
        $("curve-error").textContent = "";
        $("curve-name").textContent = c.name + " — " + c.length.toFixed(1) + " mm";
        solve();
      }).catch(function (e) { $("curve-error").textContent = e.message; studio.errors.push(e.message); });
    };
    reader.readAsText(file);
  }
  $("curve-file").onchange = function () { if ($("curve-file").files[0]) readCurve($("curve-file").files[0]); $("curve-file").value = ""; };
  $("curve-drop").addEventListener("dragover", function (e) { e.preventDefault(); });
  $("curve-drop").addEventListener("drop", function (e) { e.preventDefault(); if (e.dataTransfer.files[0]) readCurve(e.dataTransfer.files[0]); });

  // ---- downloads --------------------------------------------------------------------------------
  function download(blob, name) {
    var a = document.createElement("a");
    a.href = URL.createObjectURL(blob); a.download = name;
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(function () { URL.revokeObjectURL(a.href); }, 10000);
  }
  function jobBody() { return Object.assign({ mode: state.mode }, settings()); }
  // The export dialog shows and sets the export settings of the current mode; an empty field is
  // a setting not given (the profile's, or the export's default, which its placeholder shows).
  var exportFields = ["profile", "page", "sheet", "scale"];
  function fillExportDialog() {
    var e = settings().export || {};
    exportFields.forEach(function (k) { $(k).value = e[k] != null ? e[k] : (k === "profile" ? "laser" : ""); });
    $("export-anyway").checked = !!e.export_anyway;
  }
  function readExportDialog() {
    var e = Object.assign({}, settings().export || {});
    exportFields.forEach(function (k) { e[k] = $(k).value === "" ? null : $(k).value; });
    e.export_anyway = $("export-anyway").checked;
    settings().export = e;
  }
  $("save-job").onclick = function () {
    api("/api/job", jobBody(), true).then(function (b) { studio.lastDownload = b; download(b, "dform-job.zip"); })
      .catch(function (e) { showError(e.message); });
  };
  $("export").onclick = function () { fillExportDialog(); $("export-dialog").showModal(); };
  $("export-cancel").onclick = function () { $("export-dialog").close(); };
  $("export-go").onclick = function (e) {
    e.preventDefault();
    $("export-state").textContent = "exporting…";
    remember();
    readExportDialog();
    api("/api/export", jobBody(), true).then(function (b) {
      studio.lastDownload = b; $("export-state").textContent = ""; $("export-dialog").close(); download(b, "dform-export.zip");
    }).catch(function (err) { $("export-state").textContent = err.message; });
  };

  // ---- start ------------------------------------------------------------------------------------
  var view3d = studio.view3d = new View3D($("view3d"));
  window.addEventListener("resize", function () { view3d.draw(); });
  api("/api/session", {}).then(function (s) {
    session = s.session; kinds = s.kinds; studio.session = session; studio.previewResolution = s.preview_resolution;
    state.byMode = s.settings;
    state.mode = s.mode;
    Object.keys(s.placeholders).forEach(function (k) { $(k).placeholder = s.placeholders[k]; });
    s.profiles.forEach(function (p) { var o = document.createElement("option"); o.value = o.textContent = p; $("profile").appendChild(o); });
    [0, 1].forEach(function (i) {
      summaries[i] = s.pieces[i];
      state.pieces[i] = { name: s.pieces[i].name, text: s.pieces[i].text };
      delete s.pieces[i].text;
      fillKinds(i);
      $("name-" + "ab"[i]).textContent = s.pieces[i].name + " — perimeter " + s.pieces[i].perimeter.toFixed(1) + " mm";
    });
    if (s.curve) { state.curve = { name: "curve" }; $("curve-name").textContent = s.curve.length.toFixed(1) + " mm"; }
    var events = new EventSource("/api/events?session=" + session + "&token=" + TOKEN);
    events.onmessage = function (m) {
      var e = JSON.parse(m.data);
      if (e.type === "progress" && e.seq === shownSeq) $("status").textContent = "refining: " + e.stage + " step " + e.iteration;
      if (e.type === "result" && e.seq >= shownSeq && pending == null && !inFlight) show(e);
      // The shown shape's own verdict only: not a newer shape's, nor its preview's once refined.
      var shown = studio.shown && studio.shown.result;
      if (e.type === "gate" && shown && e.seq === shown.seq && !!e.preview === !!shown.preview) showVerdict(shown, e);
      if (e.type === "gate" && e.seq > shownSeq) earlyVerdicts[e.seq] = e;  // before its shape's answer
      if (e.type === "strip") strip.add(e);
      if (e.type === "strip_done") strip.done(e);
    };
    syncControls(); refreshPieces(); solve(); scheduleStrip(); updateUndo();
    studio.ready = true;
  }).catch(function (e) { showError("cannot start a session: " + e.message); });
})();
