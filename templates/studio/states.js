// dform studio's strip of states: where the ruled engine found that the card can sit more than
// one way, a card per state (its shape, bending energy and largest fold), least ranking energy
// first (the bending energy the engine orders them by), the first being the answer. Clicking one
// shows that state in the 3D view; the figures and the gate stay the answer's, and the page says
// which state is on screen.
"use strict";

// onShow(pieces, index): draw that state's pieces.
function States(section, container, thumbnailCanvas, note, onShow) {
  this.section = section;
  this.container = container;
  this.canvas = thumbnailCanvas;
  this.note = note;
  this.onShow = onShow;
  this.view = null;
  this.list = [];
  this.shown = 0;
  this.generation = 0;  // of the list: pictures made for an older one are dropped
}

// r.states as the server sends them ([] from a model other than ruled); `answer`: the answer's
// decoded pieces; decode(piecesJson) decodes another state's. The cards come at once and their
// pictures after the answer's frame: drawing and encoding them (software WebGL, PNG) takes about
// 100 ms on two cores, which the shape need not wait for.
States.prototype.set = function (states, answer, decode) {
  var self = this, generation = ++this.generation;
  this.list = (states || []).map(function (s, i) {
    return { start: s.start, bending: s.bending_energy, fold: s.largest_fold_deg,
             pieces: i === 0 ? answer : s.pieces ? decode(s.pieces) : null };
  });
  this.shown = 0;
  this.render();
  if (this.list.length < 2) return;
  requestAnimationFrame(function () {
    setTimeout(function () {
      if (generation !== self.generation) return;
      self.pictures();
      self.render();
    }, 0);
  });
};

States.prototype.pictures = function () {
  if (!this.view) this.view = new View3D(this.canvas, { axes: false });
  var view = this.view, canvas = this.canvas;
  this.list.forEach(function (s) {
    if (!s.pieces) return;
    view.setModel(s.pieces);
    s.picture = canvas.toDataURL("image/png");
  });
};

States.prototype.show = function (i) {
  var s = this.list[i];
  if (!s || !s.pieces || i === this.shown) return;
  this.shown = i;
  this.onShow(s.pieces, i);
  this.render();
};

function bendingText(x) { return x == null ? "—" : (+x).toPrecision(4); }

States.prototype.render = function () {
  var self = this;
  this.section.hidden = this.list.length < 2;
  this.container.innerHTML = "";
  this.list.forEach(function (s, i) {
    var el = document.createElement("button");
    el.className = "card" + (i === self.shown ? " shown" : "") + (s.pieces ? "" : " failed");
    el.setAttribute("data-index", i);
    el.setAttribute("aria-pressed", i === self.shown);
    if (s.picture) { var img = document.createElement("img"); img.src = s.picture; img.alt = "state " + (i + 1); el.appendChild(img); }
    var text = document.createElement("span");
    text.textContent = (i === 0 ? "the answer" : "another way") + " — bending " + bendingText(s.bending);
    el.title = "from " + s.start + "; largest fold " + (s.fold == null ? "—" : s.fold.toFixed(1) + "°") +
      (s.pieces ? "" : "; its shape could not be meshed");
    el.appendChild(text);
    el.addEventListener("click", function () { self.show(i); });
    self.container.appendChild(el);
  });
  this.note.textContent = this.list.length < 2 ? "" : this.shown === 0
    ? "The 3D view shows the answer, the way of least bending."
    : "The 3D view shows another way the card can sit (bending " + bendingText(this.list[this.shown].bending) +
      "); the figures and the gate are the answer's. Click the first card to go back.";
};
