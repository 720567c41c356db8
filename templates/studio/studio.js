// dform studio's page: the design's state, the calls to the server, the live drag loop (one solve
// in flight; the newest input is sent when it answers), undo and redo, the strip, downloads.
// window.studio exposes the state for tests and the latency benchmark.
"use strict";

(function () {
  var TOKEN = document.querySelector('meta[name="dform-token"]').content;
  var $ = function (id) { return document.getElementById(id); };
  // An element's text or class set only where it changes: a drag's answers repeat most of the
  // panel's words, and each write costs a layout and a repaint of the panel.
  function setText(el, text) { if (el.textContent !== text) el.textContent = text; }
  function setClass(el, name) { if (el.className !== name) el.className = name; }
  // answers and verdicts: every shape shown (its model, preview or not, seam points, start of B)
  // and every verdict shown, for the browser test.
  var studio = window.studio = { latencies: [], breakdown: [], shown: null, errors: [], answers: [], verdicts: [] };
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
  // B's resolved start where B is turned over is a fraction of its mirrored outline, whose points
  // run the other way round: the same point's fraction on the outline as read (and as drawn).
  function asRead(f, flipped) {
    var loop = views[1].loop;
    if (!flipped || !loop) return f;
    var g = (loop.cumulative[loop.n - 1] / loop.length - f) % 1;
    return g < 0 ? g + 1 : g;
  }
  function startFraction(i) {
    var f = settings()[i ? "start_b" : "start_a"];
    return typeof f === "number" ? f : resolvedStarts[i];
  }

  function api(path, body, binary) {
    return fetch(path, { method: "POST", headers: { "Content-Type": "application/json", "X-Dform-Token": TOKEN },
                         body: JSON.stringify(Object.assign({ session: session }, body)) })
      .then(function (res) {
        if (binary && res.ok) return res.blob().then(function (b) {
          var missing = res.headers.get("X-Dform-Missing");
          b.missing = missing ? decodeURIComponent(missing) : "";
          return b;
        });
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
  function remember() { history.push(snapshot()); if (history.length > 200) history.shift(); future = []; updateUndo(); clearNotices(); }
  // A refused file leaves the design as it was: its message stands until the design next changes.
  function clearNotices() { ["error-a", "error-b", "curve-error"].forEach(function (id) { $(id).textContent = ""; }); }
  function updateUndo() { $("undo").disabled = !history.length; $("redo").disabled = !future.length; }
  function restore(text) {
    var old = state;
    state = JSON.parse(text);
    if (old.mode !== state.mode) { clearNotices(); enterMode(); return Promise.resolve(); }
    var loads = [0, 1].map(function (i) {
      return JSON.stringify(old.pieces[i]) === JSON.stringify(state.pieces[i]) ? null : loadPiece(i, state.pieces[i], false);
    });
    clearNotices();
    return Promise.all(loads).then(function () {
      [0, 1].forEach(function (i) { sliders(i); }); syncControls(); refreshPieces(); solve(); scheduleStrip();
    });
  }
  $("undo").onclick = function () { if (history.length) { future.push(snapshot()); restore(history.pop()); updateUndo(); } };
  $("redo").onclick = function () { if (future.length) { history.push(snapshot()); restore(future.pop()); updateUndo(); } };
  // A box one types in (text, number) undoes its own typing; a slider, a checkbox or the page
  // undoes the design.
  function typing(target) {
    return target.isContentEditable || target.tagName === "TEXTAREA" ||
      (target.tagName === "INPUT" && ["range", "checkbox", "radio", "button", "file"].indexOf(target.type) < 0);
  }
  document.addEventListener("keydown", function (e) {
    var key = (e.key || "").toLowerCase();
    if ((e.ctrlKey || e.metaKey) && (key === "z" || key === "y") && !typing(e.target)) {
      e.preventDefault();
      (key === "y" || e.shiftKey ? $("redo") : $("undo")).click();
    }
    if (e.key === "?" && !typing(e.target) && !e.ctrlKey && !e.metaKey) {
      e.preventDefault();
      if ($("help").open) $("help").close(); else $("help").showModal();
    }
  });
  $("help-open").onclick = function () { $("help").showModal(); };

  // ---- outlines ---------------------------------------------------------------------------------
  // The outlines last asked for, loaded or on their way (the strip's design: a slider's release
  // may come before its outline is back).
  var askedPieces = [null, null];
  function loadPiece(i, source, record) {
    askedPieces[i] = source;
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
      if (askedPieces[i] === source) askedPieces[i] = state.pieces[i];
      $("error-" + "ab"[i]).textContent = e.message;
      studio.errors.push(e.message);
      throw e;
    });
  }

  // A number box's keys: up and down nudge by its step, with Shift by ten steps (`apply` takes the
  // new value); Enter applies what was typed.
  function nudging(input, step, apply) {
    input.addEventListener("keydown", function (e) {
      if (e.key !== "ArrowUp" && e.key !== "ArrowDown") return;
      e.preventDefault();
      apply(+input.value + (e.key === "ArrowUp" ? 1 : -1) * (e.shiftKey ? 10 : 1) * step());
    });
    input.addEventListener("change", function () { if (input.value !== "") apply(+input.value); });
  }

  // Each parameter of a built-in outline: a slider and a number box beside it, with its unit. A
  // count moves in whole steps (odd counts, Reuleaux sides, in steps of two).
  function sliders(i) {
    var box = $("sliders-" + "ab"[i]), source = state.pieces[i];
    box.innerHTML = "";
    if (!source || source.kind == null) return;
    var kind = kinds.filter(function (k) { return k.name === source.kind; })[0];
    kind.parameters.forEach(function (p) {
      var label = document.createElement("label"), input = document.createElement("input"), field = document.createElement("input");
      var unit = document.createElement("span");
      label.textContent = p.name + " ";
      unit.className = "unit"; unit.textContent = p.unit;
      var step = p.step || (p.max - p.min > 20 ? 1 : (p.max - p.min) / 200);
      // A value in range, on the slider's steps from min (a count's whole steps).
      var snap = function (x) {
        x = Math.max(p.min, Math.min(p.max, x));
        return p.step ? p.min + Math.round((x - p.min) / p.step) * p.step : +x.toFixed(6);
      };
      input.type = "range"; input.min = p.min; input.max = p.max; input.step = step;
      field.type = "number"; field.min = p.min; field.max = p.max; field.step = step;
      field.id = "value-" + "ab"[i] + "-" + p.name;
      input.value = field.value = snap(source.values[p.name] != null ? source.values[p.name] : p.value);
      var set = function (x) {
        x = snap(x);
        input.value = field.value = x;
        var values = Object.assign({}, state.pieces[i].values); values[p.name] = x;
        loadPiece(i, { name: source.kind, kind: source.kind, values: values }, false)
          .then(function () { refreshPieces(); solve(); }).catch(function () {});
      };
      input.oninput = function () { set(+input.value); };
      input.onchange = function () { scheduleStrip(); };
      input.onpointerdown = function () { remember(); };
      input.addEventListener("keydown", function (e) { if (e.key.indexOf("Arrow") === 0) remember(); });
      nudging(field, function () { return step; }, function (x) { remember(); set(x); scheduleStrip(); });
      label.appendChild(input); label.appendChild(field); label.appendChild(unit); box.appendChild(label);
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
  var pending = null, inFlight = false, nextSeq = 1, shownSeq = 0, inputTime = {}, askedSettings = {};
  studio.idle = function () { return pending == null && !inFlight; };
  studio.inputsWaiting = function () { return Object.keys(inputTime).length; };
  var views = [0, 1].map(function (i) {
    return new PieceView($("svg-" + "ab"[i]), "AB"[i], function (f, e) {
      settings()[i ? "start_b" : "start_a"] = f;
      showStartField(i);
      solve(e.timeStamp, e.getCoalescedEvents ? e.getCoalescedEvents() : []);
    }, function () { settle(); scheduleStrip(); });
  });
  studio.views = views;
  // Each start as a length (mm) along its boundary from the outline's first point, the way the
  // handle's fraction runs: typed, or nudged by 1 mm (Shift: 10 mm).
  function showStartField(i) {
    var loop = views[i].loop;
    if (loop && document.activeElement !== $("start-mm-" + "ab"[i])) $("start-mm-" + "ab"[i]).value = (startFraction(i) * loop.length).toFixed(1);
  }
  [0, 1].forEach(function (i) {
    nudging($("start-mm-" + "ab"[i]), function () { return 1; }, function (mm) {
      var loop = views[i].loop;
      if (!loop || !isFinite(mm)) return;
      var f = ((mm / loop.length) % 1 + 1) % 1;
      studio.setStart(i, f);
      $("start-mm-" + "ab"[i]).value = (f * loop.length).toFixed(1);
    });
  });
  // A start set as a drag ending there sets it (scripts and tests).
  studio.setStart = function (i, f) {
    remember();
    settings()[i ? "start_b" : "start_a"] = f;
    views[i].setFraction(f);
    showStartField(i);
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
      showStartField(i);
    });
    $("fit-note").textContent = summaries[0] && summaries[1]
      ? "A " + summaries[0].perimeter.toFixed(1) + " mm, B " + summaries[1].perimeter.toFixed(1) + " mm" : "";
  }

  // studio.moves: every drag move (its seq and pointer event time); studio.frames: every shape's
  // frame (its seq and time). A move whose shape was never drawn (a newer move's was) is shown by
  // the first frame of a newer seq: tests/bench/studio_latency.py counts it there.
  studio.moves = []; studio.frames = [];
  // A drag's pointer event may stand for several moves the browser coalesced (`coalesced`: their
  // events, the event's own last): each is a move, and only the last one's position is sent.
  function solve(eventTime, coalesced) {
    var seq = nextSeq++;
    inputTime[seq] = eventTime != null ? eventTime : performance.now();
    if (eventTime != null) {
      var all = coalesced && coalesced.length ? coalesced : [{ timeStamp: eventTime }];
      all.forEach(function (m, k) { studio.moves.push({ seq: seq, time: m.timeStamp, sent: k === all.length - 1 }); });
    }
    pending = seq;
    if (!inFlight) send();
  }

  // A released drag: its last position is final, and the server refines it at once instead of
  // waiting for the pause that tells a drag's positions apart. A failed settle costs only that
  // wait (and the next solve shows why the server refused).
  function settle() {
    if (nextSeq > 1) api("/api/settle", { seq: nextSeq - 1 }).catch(function () {});
  }

  function send() {
    if (pending == null) return;
    var seq = pending; pending = null; inFlight = true;
    var path = state.mode === "inverse" ? "/api/inverse" : "/api/solve";
    var body = Object.assign({ seq: seq, mode: state.mode }, settings());
    askedSettings[seq] = Object.assign({}, settings());
    var sent = performance.now();
    api(path, body).then(function (r) {
      if (r.arrival) r.arrival.sent = sent;
      // The next position goes to the server before this answer is drawn: its solve overlaps the
      // drawing.
      inFlight = false;
      send();
      if (!r.superseded) show(r);
    }).catch(function (e) { inFlight = false; solveFailed(seq, e.message); send(); });
  }

  // No shape for the design on screen: the last one's shape, model, figures and verdict go with
  // it, so that nothing shown belongs to another design. The error says why.
  function clearShape() {
    studio.shown = null;
    view3d.setModel([]);
    overlay.show(null);
    states.set([]);
    picking.reset();
    views.forEach(function (v) { v.clearResult(); });
    ["model", "reason", "warnings", "checks", "figures"].forEach(function (id) { $(id).textContent = ""; });
    $("status").className = "status";
  }
  function solveFailed(seq, text) {
    if (seq < shownSeq) return;
    shownSeq = seq;
    clearShape();
    showError(text);
    studio.frameSeq = seq;
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
    if (r.seq < shownSeq || (r.mode && r.mode !== state.mode)) return;
    if (r.error) { solveFailed(r.seq, r.error); return; }
    shownSeq = r.seq;
    var asked = askedSettings[r.seq] || Object.assign({}, settings());
    Object.keys(askedSettings).forEach(function (k) { if (+k < r.seq) delete askedSettings[k]; });
    var pieces = decodePieces(r);
    studio.answers.push({ seq: r.seq, model: r.model.name, preview: !!r.preview, seam: r.pieces[0].seam.length, start_b: r.start_b });
    var extra = [];
    if (r.target) extra.push({ points: decodeF64(r.target), colour: [0.1, 0.5, 0.2], loop: true });
    view3d.setModel(pieces, extra);
    r.decoded = pieces;
    overlay.show(null);  // the new shape's comes with its figures
    states.set(r.states, pieces, function (p) { return decodePieces({ pieces: p }); });
    var brk = /at seam point (\d+)/.exec(r.model.reason);
    if (state.mode === "inverse") [0, 1].forEach(function (i) {
      views[i].setSolvedPiece(pieces[i]);
      $("name-" + "ab"[i]).textContent = "piece " + "AB"[i] + " as cut, unfolded from the curve";
    });
    if (state.mode === "forward") {
      resolvedStarts = [r.start_a, asRead(r.start_b, asked.flip)];
      r.startsAsRead = [0, 1].map(function (i) {
        var f = asked[i ? "start_b" : "start_a"];
        return typeof f === "number" ? f : resolvedStarts[i];
      });
      [0, 1].forEach(function (i) {
        views[i].setFraction(startFraction(i));
        views[i].setResult(pieces[i], i === 0 || asked.flip ? 1 : -1, brk ? +brk[1] : null,
                           placement(pieces[i], summaries[i]));
      });
    }
    facts(r);
    var time = inputTime[r.seq];
    // Positions the drag moved past before they were sent (one a raw pointer update) are never shown.
    Object.keys(inputTime).forEach(function (k) { if (+k <= r.seq) delete inputTime[k]; });
    studio.shown = { seq: r.seq, result: r, pieces: pieces, settings: asked };
    picking.reset();
    var drawn = performance.now();
    requestAnimationFrame(function () {
      studio.frames.push({ seq: r.seq, time: performance.now(), preview: !!r.preview });
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
    if (verdict) { r.figures = verdict.figures; r.gate = gate; if (verdict.overlay) r.overlay = verdict.overlay; }
    // Another of the ruled engine's states on screen: the answer's overlay waits for the answer.
    overlay.show(r.decoded, gate && states.shown === 0 ? r.overlay : null, r.figures);
    if (gate) studio.verdicts.push({ seq: r.seq, preview: !!r.preview, passed: gate.passed });
    setClass(status, "status " + (gate ? (gate.passed ? "pass" : "fail") : verdict && verdict.error ? "error" : ""));
    setText(status, (verdict && verdict.error ? verdict.error : !gate ? "measuring, checking the gate…"
                     : gate.passed ? "gate passed" : "gate failed: " + gate.failed + " check(s)") +
      (r.preview ? " — preview at " + studio.previewResolution + " seam points, refining…" : ""));
    setRows($("checks"), "li", (gate ? gate.checks : []).map(function (c) {
      var sites = c.verdict === "fail" ? overlay.sites(c.name) : null;
      return [{ className: c.verdict, text: c.name + ": " + c.verdict + (c.verdict === "fail" ? " — " + c.detail +
        (sites == null ? " (not located on the shape)" : " (" + sites + " marked on the shape)") : "") }];
    }));
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
    if (r.startsAsRead) rows.push(["B scaled by", number(r.scale_b, 6)], ["starts", "A " + r.startsAsRead[0].toFixed(4) + ", B " + r.startsAsRead[1].toFixed(4)]);
    if (r.curve_match) rows.push(["D_error", number(r.curve_match.D_error)], ["round trip max", number(r.curve_match.roundtrip_max_rel)],
                                 ["on hull", r.on_hull.on_hull ? "yes" : "no: " + r.on_hull.summary]);
    rows.push(["solve", (1000 * r.timings.total).toFixed(0) + " ms"]);
    setRows($("figures"), "tr", rows.map(function (row) {
      return row.map(function (cell) { return { text: cell }; });
    }));
  }

  // A list's rows (each an array of cells {text, className}: a <tr> of <td>s, or an <li> of one
  // cell) made as `rows` says, each row and cell kept where it stays the same.
  function setRows(list, tag, rows) {
    while (list.children.length > rows.length) list.lastChild.remove();
    rows.forEach(function (cells, k) {
      var row = list.children[k];
      if (!row) row = list.appendChild(document.createElement(tag));
      if (tag === "li") { setClass(row, cells[0].className || ""); setText(row, cells[0].text); return; }
      while (row.children.length > cells.length) row.lastChild.remove();
      cells.forEach(function (cell, j) {
        var td = row.children[j] || row.appendChild(document.createElement("td"));
        setText(td, cell.text);
      });
    });
  }

  // Verdicts that came before their shape's answer, by seq; only the shown shape's is ever shown.
  var earlyVerdicts = {};
  function facts(r) {
    showVerdict(r, r.gate ? { figures: r.figures, gate: r.gate } : earlyVerdicts[r.seq]);
    earlyVerdicts = {};
    setText($("model"), r.model.name + (r.model.found_creases.length ? ", " + r.model.found_creases.length + " found crease(s)" : ""));
    setText($("reason"), r.model.reason);
    setText($("warnings"), (r.warnings || []).join("\n"));
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
  }, $("strip-status"));
  studio.strip = strip;
  // B's start snaps to the strip's distinct shapes: for each card, the first of its starts turned
  // over as B is now.
  views[1].snapTargets = function () {
    var out = [];
    strip.cards.forEach(function (c) {
      var same = [c].concat(c.also).filter(function (m) { return !m.error && m.flip === settings().flip; })[0];
      if (same) out.push({ fraction: same.start_b, name: "alternative" + (c.also.length ? " ×" + (c.also.length + 1) : "") });
    });
    return out;
  };
  // The strip solves every start of B, turned over and not, for the design's outlines and
  // settings: B's start, its flip and the export's settings change nothing in it, and a strip
  // made or under way for the same design (`stripDesign`) stays.
  var stripTimer = null, stripSeq = 0, STRIP_STARTS = 16, stripDesign = null;
  function scheduleStrip() {
    schedulePreview();
    if (state.mode !== "forward") return;
    var solved = Object.assign({}, settings());
    delete solved.start_b; delete solved.flip; delete solved.export;
    var design = JSON.stringify([askedPieces, solved]);
    if (design === stripDesign) return;
    stripDesign = design;
    clearTimeout(stripTimer);
    strip.cancel();
    stripTimer = setTimeout(function () {
      var seq = ++stripSeq;
      strip.reset(seq, 2 * STRIP_STARTS);
      api("/api/strip", Object.assign({ seq: seq, starts: STRIP_STARTS, both_flips: true }, settings())).catch(function (e) {
        stripDesign = null;  // asked again at the next change
        showError(e.message);
      });
    }, 300);
  }
  function cancelStrip() { clearTimeout(stripTimer); strip.cancel(); stripDesign = null; }

  // ---- inverse ----------------------------------------------------------------------------------
  // The page as the mode has it: nothing of the other mode's design stays on screen (its shape,
  // pieces, figures, sliders, strip) until this mode's answer comes.
  function enterMode() {
    syncControls();
    clearShape();
    schedulePreview();
    if (state.mode === "forward") {
      [0, 1].forEach(function (i) {
        $("name-" + "ab"[i]).textContent = summaries[i].name + " — perimeter " + summaries[i].perimeter.toFixed(1) + " mm";
      });
      $("status").textContent = "solving…";
      refreshPieces(); scheduleStrip();
    } else {
      cancelStrip();
      views.forEach(function (v) { v.clear(); });
      [0, 1].forEach(function (i) { $("name-" + "ab"[i]).textContent = state.curve ? "" : "piece " + "AB"[i] + ": open a seam curve below"; });
      $("status").textContent = state.curve ? "solving…" : "open or drop a closed 3D seam curve";
    }
    if (state.mode === "forward" || state.curve) solve();
  }
  function setMode(mode) {
    if (mode === state.mode) return;
    remember(); state.mode = mode; enterMode();
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
        solve(); schedulePreview();
      }).catch(function (e) { $("curve-error").textContent = e.message; studio.errors.push(e.message); });
    };
    reader.readAsText(file);
  }
  $("curve-file").onchange = function () { if ($("curve-file").files[0]) readCurve($("curve-file").files[0]); $("curve-file").value = ""; };
  $("curve-drop").addEventListener("dragover", function (e) { e.preventDefault(); });
  $("curve-drop").addEventListener("drop", function (e) { e.preventDefault(); if (e.dataTransfer.files[0]) readCurve(e.dataTransfer.files[0]); });

  // ---- downloads --------------------------------------------------------------------------------
  var downloads = new Downloads({ api: api, settings: settings, remember: remember, showError: showError, studio: studio,
                  body: function () { return Object.assign({ mode: state.mode }, settings()); },
                  onOpen: function () { preview.schedule(0); } });
  // The print preview while its panel or the Export dialog is open: a new layout once the design
  // or the dialog's settings settle (each is a whole export run on the server).
  var preview = studio.preview = new Preview({ api: api, body: downloads.previewBody, studio: studio });
  function previewWanted() { return $("preview").open || $("export-dialog").open; }
  function schedulePreview(delay) { if (previewWanted()) preview.schedule(delay); }
  $("preview").addEventListener("toggle", function () { schedulePreview(0); });
  downloads.onDialogChange(function () { schedulePreview(300); });

  // ---- start ------------------------------------------------------------------------------------
  var view3d = studio.view3d = new View3D($("view3d"));
  var overlay = studio.overlay = new Overlay(view3d, $("overlay-legend"));
  $("overlay").onchange = function () { overlay.setMode($("overlay").value); };
  $("mark-failures").onchange = function () { overlay.setFailures($("mark-failures").checked); };
  // The ruled engine's other states: one shown in 3D without the answer's overlay (its strain and
  // failures are the answer's); the answer again with it.
  var states = studio.states = new States($("states"), $("state-cards"), $("state-thumbnail"), $("states-note"),
    function (pieces, i) {
      var r = studio.shown && studio.shown.result;
      view3d.setModel(pieces);
      if (i === 0 && r) overlay.show(r.decoded, r.gate ? r.overlay : null, r.figures); else overlay.show(null);
    });
  var picking = studio.picking = new Picking({ views: views, view3d: view3d, shown: function () { return studio.shown; },
                                               button: $("measure"), readout: $("measure-readout") });
  window.addEventListener("resize", function () { view3d.draw(); });
  // The scale bar: a round length in mm and its width on screen at the view's scale.
  view3d.onScale(function (scale) {
    $("scale-bar-line").style.width = (scale.barMm * scale.pixelsPerMm).toFixed(1) + "px";
    $("scale-bar-text").textContent = scale.barMm + " mm";
  });
  $("reset-view").onclick = function () { view3d.resetView(); };
  $("axes").onchange = function () { view3d.setAxes($("axes").checked); };
  $("fixed-scale").onchange = function () { view3d.setFixedScale($("fixed-scale").checked); };
  api("/api/session", {}).then(function (s) {
    session = s.session; kinds = studio.kinds = s.kinds; studio.session = session; studio.previewResolution = s.preview_resolution;
    state.byMode = s.settings;
    state.mode = s.mode;
    Object.keys(s.placeholders).forEach(function (k) { $(k).placeholder = s.placeholders[k]; });
    s.profiles.forEach(function (p) { var o = document.createElement("option"); o.value = o.textContent = p; $("profile").appendChild(o); });
    downloads.fillLists(s.choices);
    [0, 1].forEach(function (i) {
      summaries[i] = s.pieces[i];
      state.pieces[i] = askedPieces[i] = { name: s.pieces[i].name, text: s.pieces[i].text };
      delete s.pieces[i].text;
      fillKinds(i);
      $("name-" + "ab"[i]).textContent = s.pieces[i].name + " — perimeter " + s.pieces[i].perimeter.toFixed(1) + " mm";
    });
    if (s.curve) { state.curve = { name: "curve" }; $("curve-name").textContent = s.curve.length.toFixed(1) + " mm"; }
    var events = new EventSource("/api/events?session=" + session + "&token=" + TOKEN);
    events.onmessage = function (m) {
      var e = JSON.parse(m.data);
      e.arrival = { parsed: performance.now() };  // the bench times the page's part from here
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
