// dform studio's strip of alternative starts: one card per start of B (and B turned over),
// filled in as the server's worker solves them, with cards whose shapes agree (the symmetric
// duplicates: height, volume and largest curvature equal to 0.1 %) grouped into one.
"use strict";

function decodeF64(text) { return new Float64Array(decodeBytes(text)); }
function decodeU32(text) { return new Uint32Array(decodeBytes(text)); }
function decodeBytes(text) {
  var binary = atob(text), bytes = new Uint8Array(binary.length);
  for (var i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

// Height (z extent) and enclosed volume of a closed two-piece shape.
function shapeFigures(pieces) {
  var zMin = Infinity, zMax = -Infinity, volume = 0;
  pieces.forEach(function (p) {
    var s = p.shape, f = p.faces;
    for (var i = 2; i < s.length; i += 3) { zMin = Math.min(zMin, s[i]); zMax = Math.max(zMax, s[i]); }
    for (var t = 0; t < f.length; t += 3) {
      var a = 3 * f[t], b = 3 * f[t + 1], c = 3 * f[t + 2];
      volume += (s[a] * (s[b + 1] * s[c + 2] - s[b + 2] * s[c + 1]) - s[a + 1] * (s[b] * s[c + 2] - s[b + 2] * s[c]) +
                 s[a + 2] * (s[b] * s[c + 1] - s[b + 1] * s[c])) / 6;
    }
  });
  return { height: zMax - zMin, volume: Math.abs(volume) };
}

// `status` says how far the run is: the cards are provisional (a group may grow, a card may
// join one) until every start is in.
function Strip(container, thumbnailCanvas, onPick, status) {
  this.container = container;
  this.status = status;
  this.total = 0;
  this.received = 0;
  this.view = null;
  this.canvas = thumbnailCanvas;
  this.onPick = onPick;
  this.cards = [];
  this.seq = -1;
}

Strip.prototype.reset = function (seq, total) {
  this.seq = seq;
  this.cards = [];
  this.total = total;
  this.received = 0;
  this.container.innerHTML = "";
  this.setState("computing");
};

Strip.prototype.setState = function (state) {
  this.container.setAttribute("data-state", state);
  this.status.textContent = state === "computing" ? "solving starts: " + this.received + " of " + this.total + "…"
    : state === "scheduled" ? "waiting for the design to settle…"
    : this.received + " starts, " + this.cards.length + " shapes";
};

// A new run is due: the running one's late cards and its end are no longer this strip's.
Strip.prototype.cancel = function () {
  this.seq = -1;
  this.setState("scheduled");
};

Strip.prototype.same = function (a, b) {
  function close(x, y) { return Math.abs(x - y) <= 1e-3 * Math.max(Math.abs(x), Math.abs(y), 1e-9); }
  return close(a.height, b.height) && close(a.volume, b.volume) && close(a.curvature, b.curvature);
};

Strip.prototype.add = function (event) {
  if (event.seq !== this.seq) return;
  var card = { start_b: event.start_b, flip: event.flip, error: event.error };
  this.received += 1;
  if (event.result) {
    var pieces = event.result.pieces.map(function (p) {
      return { shape: decodeF64(p.shape), faces: decodeU32(p.faces), seam: p.seam, creases: p.creases };
    });
    var f = shapeFigures(pieces);
    card.height = f.height; card.volume = f.volume; card.curvature = event.result.figures.angle_defect_max_rad || 0;
    card.model = event.result.model.name;
    card.passed = event.result.gate.passed;
    if (!this.view) this.view = new View3D(this.canvas, { axes: false });
    this.view.setModel(pieces);
    card.picture = this.canvas.toDataURL("image/png");
  }
  for (var i = 0; i < this.cards.length; ++i) {
    var other = this.cards[i];
    if (!card.error && !other.error && this.same(card, other)) { other.also.push(card); this.render(); this.setState("computing"); return; }
  }
  card.also = [];
  this.cards.push(card);
  this.render();
  this.setState("computing");
};

Strip.prototype.done = function (event) {
  if (event.seq !== this.seq) return;
  this.setState("done");
  this.render();
};

function startName(card) { return card.start_b.toFixed(3) + (card.flip ? " flipped" : ""); }

Strip.prototype.render = function () {
  var self = this;
  this.container.innerHTML = "";
  this.cards.forEach(function (card) {
    var el = document.createElement("button");
    el.className = "card" + (card.error ? " failed" : card.passed ? "" : " gate-failed");
    el.setAttribute("data-start-b", card.start_b);
    el.setAttribute("data-flip", card.flip);
    if (card.picture) { var img = document.createElement("img"); img.src = card.picture; img.alt = startName(card); el.appendChild(img); }
    var text = document.createElement("span");
    var final = self.container.getAttribute("data-state") === "done";
    text.textContent = "B " + startName(card) + (card.also.length ? "  ×" + (card.also.length + 1) + (final ? "" : " so far") : "") +
      (card.error ? " — " + card.error : "  h " + card.height.toFixed(0) + " mm");
    el.title = (card.also.length ? "the same shape from B " + card.also.map(startName).join(", ") + "\n" : "") +
      (card.error || ("height " + card.height.toFixed(1) + " mm, volume " + (card.volume / 1000).toFixed(0) + " cm³, " + card.model));
    el.appendChild(text);
    el.addEventListener("click", function () { self.onPick(card); });
    self.container.appendChild(el);
  });
};
