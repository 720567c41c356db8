// dform studio's downloads: Save job (dform-job.zip) and the Export dialog (dform-export.zip). An
// export whose zip lacks the cutting files it asked for keeps the dialog open with the server's
// reason (X-Dform-Missing) and offers that zip as what it is.
// page: {api, settings() (the mode's settings, changed in place), body() (a request's), remember
// (an undo step), showError, studio (window.studio: lastDownload for tests)}.
"use strict";

function Downloads(page) {
  var $ = function (id) { return document.getElementById(id); };
  function download(blob, name) {
    var a = document.createElement("a");
    a.href = URL.createObjectURL(blob); a.download = name;
    document.body.appendChild(a); a.click(); a.remove();
    setTimeout(function () { URL.revokeObjectURL(a.href); }, 10000);
  }
  // The export dialog shows and sets the export settings of the current mode; an empty field is
  // a setting not given (the profile's, or the export's default, which its placeholder shows).
  // The lists (material, numbers, hinge) hold their choices as JSON, the empty one unset.
  var exportFields = ["profile", "page", "sheet", "scale"], exportLists = ["material", "numbers", "hinge"];
  // The lists' options from the session's `choices` (the settings table's).
  this.fillLists = function (choices) {
    exportLists.forEach(function (k) {
      var unset = document.createElement("option");
      unset.value = ""; unset.textContent = choices[k].unset; $(k).appendChild(unset);
      choices[k].choices.forEach(function (c) {
        var o = document.createElement("option");
        o.value = JSON.stringify(c); o.textContent = c === true ? "on" : c === false ? "off" : c;
        $(k).appendChild(o);
      });
    });
  };
  function fillExportDialog() {
    var e = page.settings().export || {};
    exportFields.forEach(function (k) { $(k).value = e[k] != null ? e[k] : (k === "profile" ? "laser" : ""); });
    exportLists.forEach(function (k) { $(k).value = e[k] != null ? JSON.stringify(e[k]) : ""; });
    $("export-anyway").checked = !!e.export_anyway;
  }
  // The export settings as the dialog has them.
  function dialogExport() {
    var e = Object.assign({}, page.settings().export || {});
    exportFields.forEach(function (k) { e[k] = $(k).value === "" ? null : $(k).value; });
    exportLists.forEach(function (k) { e[k] = $(k).value === "" ? null : JSON.parse($(k).value); });
    e.export_anyway = $("export-anyway").checked;
    return e;
  }
  function readExportDialog() { page.settings().export = dialogExport(); }
  // A request's body for the print preview: the design with the dialog's export settings while
  // it is open (what Download zip would send), else the design's.
  this.previewBody = function () {
    var body = page.body();
    if ($("export-dialog").open) body.export = dialogExport();
    return body;
  };
  // Each change of the dialog's fields asks for a new preview (`onChange`).
  this.onDialogChange = function (onChange) {
    exportFields.concat(exportLists, ["export-anyway"]).forEach(function (k) {
      $(k).addEventListener("input", onChange); $(k).addEventListener("change", onChange);
    });
  };
  $("save-job").onclick = function () {
    page.api("/api/job", page.body(), true).then(function (b) { page.studio.lastDownload = b; download(b, "dform-job.zip"); })
      .catch(function (e) { page.showError(e.message); });
  };
  $("export").onclick = function () {
    fillExportDialog(); $("export-state").textContent = ""; $("export-partial").hidden = true; $("export-dialog").showModal();
    if (page.onOpen) page.onOpen();
  };
  $("export-cancel").onclick = function () { $("export-dialog").close(); };
  $("export-go").onclick = function (e) {
    e.preventDefault();
    $("export-state").textContent = "exporting…";
    page.remember();
    readExportDialog();
    $("export-partial").hidden = true;
    page.api("/api/export", page.body(), true).then(function (b) {
      // A zip without the cutting files asked for is not handed over silently: the dialog stays,
      // says why and what to do, and offers that zip as what it is.
      if (b.missing) {
        $("export-state").textContent = b.missing;
        $("export-partial").hidden = false;
        $("export-partial").onclick = function () {
          page.studio.lastDownload = b; $("export-dialog").close(); download(b, "dform-export-without-cutting-files.zip");
        };
        return;
      }
      page.studio.lastDownload = b; $("export-state").textContent = ""; $("export-dialog").close(); download(b, "dform-export.zip");
    }).catch(function (err) { $("export-state").textContent = err.message; });
  };
}
