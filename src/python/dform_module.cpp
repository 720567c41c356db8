// SPDX-License-Identifier: GPL-3.0-or-later
// The compiled part `dform._dform` of the Python package `dform` (docs/python.md; dform/__init__.py
// wraps its runs into picklable results): forward and inverse runs from numpy arrays, their meshes
// and figures back as numpy arrays and dicts, and the whole result folder written as the command
// writes it. A thin shell like the cli: the pipeline does the work, the settings are keyword
// arguments read through the settings table (pipeline/settings.h), errors become dform.Error with
// the command's exit code and a message that names a setting by its Python keyword; Ctrl-C stops
// a solve.
#include <Python.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dform/io/curve_reader.h"
#include "dform/io/outline_reader.h"
#include "dform/pipeline/report.h"
#include "dform/pipeline/run.h"

namespace py = pybind11;

namespace dform {
namespace {

using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// dform.Error, raised for every Status that is not ok.
PyObject* errorType = nullptr;

// How Python names a setting a message mentions (core/setting.h): its keyword ("fit_perimeter"),
// a weight as its entry of the dict weights ("weights['smooth_3d']"), one without a keyword by
// its job-file key.
std::string pythonWords(const std::string& key) {
  for (const SettingRow& row : settingRows())
    if (row.key == key)
      return row.type == SettingType::Weight ? row.keyword + "['" + row.weightName() + "']"
                                             : row.keyword;
  return key;
}

std::string inPythonTerms(const std::string& text) { return wordSettings(text, pythonWords); }

[[noreturn]] void raise(const Status& status) {
  py::object error = py::reinterpret_borrow<py::object>(errorType)(inPythonTerms(status.text()));
  error.attr("exit_code") = exitCode(status.code());
  PyErr_SetObject(errorType, error.ptr());
  throw py::error_already_set();
}

template <typename T>
T valueOrRaise(Result<T> result) {
  if (!result.isOk()) raise(result.status());
  return std::move(result).value();
}

// A list of points as JSON, every coordinate written so that it reads back to the same double.
std::string jsonPoints(const RowPoints& P, int columns, const std::string& what) {
  if (P.cols() != columns)
    raise({ErrorCode::Usage, what + " must be an array of shape (n, " + std::to_string(columns) +
                                 "), got " + std::to_string(P.cols()) + " columns"});
  if (!P.allFinite())
    raise({ErrorCode::InputInvalid, what + " has a coordinate that is not a finite number"});
  std::string text = "[";
  char number[32];
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    text += i ? ",[" : "[";
    for (int c = 0; c < columns; ++c) {
      std::snprintf(number, sizeof number, "%.17g", P(i, c));
      text += (c ? "," : "") + std::string(number);
    }
    text += "]";
  }
  return text + "]";
}

std::string jsonPointLists(const std::vector<RowPoints>& lists, const std::string& what) {
  std::string text = "[";
  for (std::size_t k = 0; k < lists.size(); ++k)
    text += (k ? "," : "") + jsonPoints(lists[k], 2, what);
  return text + "]";
}

// A piece from arrays, read and checked as a JSON outline file would be (orientation, crossings,
// holes inside the outline, creases from boundary to boundary).
Shape2 shapeFromArrays(const RowPoints& outline, const std::vector<RowPoints>& holes,
                       const std::vector<RowPoints>& creases, const std::string& name) {
  const std::string text = "{\"points\": " + jsonPoints(outline, 2, name + " outline") +
                           ", \"holes\": " + jsonPointLists(holes, name + " hole") +
                           ", \"creases\": " + jsonPointLists(creases, name + " crease") + "}";
  Shape2 shape = valueOrRaise(parseOutline(text, name));
  shape.outer.source = name;
  return shape;
}

// Runs `solve` with the GIL released; Ctrl-C in Python stops it at the next solver iteration.
template <typename Solve>
auto solveInterruptibly(Solve solve) {
  std::atomic<bool> stop{false};
  RunHooks hooks;
  hooks.interrupted = &stop;
  hooks.onIteration = [&](const char*, const IterationSummary&) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) stop = true;
  };
  MessageSink sink;
  auto result = [&] {
    py::gil_scoped_release release;
    return solve(sink, hooks);
  }();
  if (stop && PyErr_Occurred()) throw py::error_already_set();  // KeyboardInterrupt
  return std::make_pair(valueOrRaise(std::move(result)), sink.messages());
}

py::dict pieceDict(const Piece& piece) {
  py::dict d;
  d["name"] = piece.name;
  d["flat"] = Points2(piece.flat);
  d["shape"] = Points3(piece.shape);
  d["faces"] = Faces(piece.F);
  d["seam"] = py::array_t<int>(static_cast<py::ssize_t>(piece.seam.size()), piece.seam.data());
  return d;
}

// A solved run and what writing it needs: the job (settings and input names) and its messages.
struct Made {
  Job job;
  std::optional<SolvedRun> run;
  std::vector<Message> messages;

  const DForm& model() const { return solvedModel(*run); }
  const ModelUsed& modelUsed() const { return solvedModelUsed(*run); }
};

py::dict figures(const Made& made) {
  py::object json = py::module_::import("json");
  return json.attr("loads")(metricsJsonText(solvedMetrics(*made.run), solvedCurveMatch(*made.run)));
}

py::list messageList(const Made& made) {
  py::list list;
  for (const Message& m : made.messages)
    list.append(py::make_tuple(levelName(m.level), inPythonTerms(m.text)));
  return list;
}

// A keyword argument's value as JSON text, as a job file would hold it: numpy's numbers as the
// numbers they are (an integer type by its __index__), a tuple as a list.
std::string jsonValue(const py::handle& value) {
  const py::object dumps = py::module_::import("json").attr("dumps");
  const py::cpp_function plain([](const py::object& o) -> py::object {
    if (py::hasattr(o, "__index__")) return py::int_(o);
    return py::float_(o);
  });
  try {
    return dumps(value, py::arg("default") = plain, py::arg("allow_nan") = false)
        .cast<std::string>();
  } catch (const py::error_already_set&) {
    return "\"" + py::str(value).cast<std::string>() + "\"";  // refused by its row: not a value
  }
}

// Sets each keyword argument on `job` through its row of the settings table (`scopes` are the
// rows the function takes; the dict `weights` holds one row per weight): the one range check,
// its refusal raised as dform.Error naming the keyword.
void applyKeywords(Job& job, const py::kwargs& keywords, std::initializer_list<SettingScope> scopes,
                   const char* function) {
  const auto taken = [&](const SettingRow& row) {
    return std::find(scopes.begin(), scopes.end(), row.scope) != scopes.end();
  };
  // In the table's order, so that a join sets the weights' defaults before a weight is set.
  std::vector<std::string> known;
  for (const SettingRow* row : settingRows(job.isForward())) {
    if (!taken(*row)) continue;
    if (known.empty() || known.back() != row->keyword) known.push_back(row->keyword);
    if (!keywords.contains(row->keyword.c_str())) continue;
    const py::object value = keywords[row->keyword.c_str()];
    if (row->type == SettingType::Weight) {
      if (!py::isinstance<py::dict>(value))
        raise({ErrorCode::Usage, "weights must be a dict of term names and weights"});
      const py::dict weights = value;
      if (!weights.contains(row->weightName().c_str())) continue;
      if (Status s = setSetting(job, *row, jsonValue(weights[row->weightName().c_str()]));
          !s.isOk())
        raise(s);
    } else if (Status s = setSetting(job, *row, jsonValue(value)); !s.isOk()) {
      raise(s);
    }
  }
  for (const auto& [name, value] : keywords) {
    const std::string keyword = py::str(name);
    if (std::find(known.begin(), known.end(), keyword) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      raise({ErrorCode::Usage, std::string(function) + "() got an unexpected keyword argument '" +
                                   keyword + "' (its settings: " + list + ")"});
    }
    if (keyword != "weights") continue;
    for (const auto& entry : py::reinterpret_borrow<py::dict>(value)) {
      const std::string term = std::string(py::str(entry.first));
      if (!findSetting(std::string(settingKey(Setting::Weight)) + "." + term, job.isForward()))
        raise({ErrorCode::Usage, "unknown weight '" + term + "'"});
    }
  }
}

// Made.export(out_dir, **settings): the result folder as `dform forward` writes it.
py::dict exportMade(const Made& made, const std::string& outDir, const py::kwargs& keywords) {
  Job job = made.job;
  applyKeywords(job, keywords, {SettingScope::Export, SettingScope::Output}, "export");
  const RunSettings settings = valueOrRaise(checkOutput(job.exporting));
  OutputOptions output;
  output.outDir = outDir;
  MessageSink sink;
  for (const Message& m : made.messages) sink.emit(m.level, m.text);  // kept in report.json
  const WrittenResult written = valueOrRaise(writeResult(job, *made.run, output, settings, sink));
  py::dict outcome;
  outcome["folder"] = outDir;
  outcome["gate_passed"] = written.gate ? py::cast(written.gate->passed()) : py::none();
  py::list checks;
  if (written.gate)
    for (const CheckResult& c : written.gate->checks)
      checks.append(py::dict(py::arg("name") = c.name, py::arg("value") = c.value,
                             py::arg("limit") = c.limit,
                             py::arg("verdict") = verdictName(c.verdict),
                             py::arg("detail") = inPythonTerms(c.detail)));
  outcome["checks"] = checks;
  outcome["cutting_files"] =
      job.exporting.cuttingFiles && written.exported.isOk() &&
      (!written.gate || written.gate->passed() || job.exporting.exportAnyway);
  if (!written.exported.isOk()) outcome["export_error"] = inPythonTerms(written.exported.text());
  return outcome;
}

Made forward(const RowPoints& outlineA, const RowPoints& outlineB,
             const std::vector<RowPoints>& holesA, const std::vector<RowPoints>& holesB,
             const std::vector<RowPoints>& creasesA, const std::vector<RowPoints>& creasesB,
             const std::string& nameA, const std::string& nameB, const py::kwargs& keywords) {
  ForwardJob inputs;
  inputs.pieceA = nameA;
  inputs.pieceB = nameB;
  Made made{Job(inputs), std::nullopt, {}};
  applyKeywords(made.job, keywords, {SettingScope::Forward, SettingScope::Solve}, "forward");
  const ForwardJob& job = std::get<ForwardJob>(made.job.run);
  Shape2 a = shapeFromArrays(outlineA, holesA, creasesA, nameA);
  Shape2 b = shapeFromArrays(outlineB, holesB, creasesB, nameB);
  auto [run, messages] = solveInterruptibly([&](MessageSink& sink, const RunHooks& hooks) {
    return makeDForm(std::move(a), std::move(b), job, sink, hooks);
  });
  made.run = SolvedRun(std::move(run));
  made.messages = std::move(messages);
  return made;
}

Made inverse(const RowPoints& points, const std::string& name, const py::kwargs& keywords) {
  InverseJob inputs;
  inputs.curve = name;
  Made made{Job(inputs), std::nullopt, {}};
  applyKeywords(made.job, keywords, {SettingScope::Inverse, SettingScope::Solve}, "inverse");
  const InverseJob& job = std::get<InverseJob>(made.job.run);
  // Read and checked as a JSON curve file would be; closed, as a seam is.
  CurveReadOptions closed;
  closed.forceClosed = true;
  Curve3 curve =
      valueOrRaise(parseCurve("{\"points\": " + jsonPoints(points, 3, name) + "}", name, closed));
  curve.source = name;
  auto [run, messages] = solveInterruptibly([&](MessageSink& sink, const RunHooks& hooks) {
    return makePieces(std::move(curve), job, sink, hooks);
  });
  made.run = SolvedRun(std::move(run));
  made.messages = std::move(messages);
  return made;
}

// The settings a call of `function` ("forward", "inverse", "export") with `keywords` would use,
// as a job file's settings (a dict), without solving: the keywords checked as the call checks
// them (dform.Error naming the keyword when one is refused).
py::object jobSettings(const std::string& function, const py::kwargs& keywords) {
  Job job = function == "inverse" ? Job(InverseJob()) : Job(ForwardJob());
  if (function == "export")
    applyKeywords(job, keywords, {SettingScope::Export, SettingScope::Output}, "export");
  else
    applyKeywords(job, keywords,
                  {function == "inverse" ? SettingScope::Inverse : SettingScope::Forward,
                   SettingScope::Solve},
                  function.c_str());
  return py::module_::import("json").attr("loads")(settingsJson(job));
}

// The settings table's rows a function takes ("forward", "inverse", "export"), as dicts: the
// package builds its docstrings from them and its tests walk them.
py::list settingRowsOf(const std::string& function) {
  const bool forward = function != "inverse";
  const std::vector<SettingScope> scopes =
      function == "export" ? std::vector<SettingScope>{SettingScope::Export, SettingScope::Output}
      : forward            ? std::vector<SettingScope>{SettingScope::Forward, SettingScope::Solve}
                           : std::vector<SettingScope>{SettingScope::Inverse, SettingScope::Solve};
  py::object loads = py::module_::import("json").attr("loads");
  py::list rows;
  for (const SettingRow* row : settingRows(forward)) {
    if (std::find(scopes.begin(), scopes.end(), row->scope) == scopes.end()) continue;
    py::list choices;
    for (const SettingChoice& c : row->choices) choices.append(c.name);
    rows.append(py::dict(py::arg("keyword") = row->keyword, py::arg("key") = row->key,
                         py::arg("weight") = row->weightName(), py::arg("flag") = row->flag,
                         py::arg("default") = loads(settingDefault(*row, forward)),
                         py::arg("unset") = row->unset, py::arg("range") = row->rangeText(),
                         py::arg("choices") = choices, py::arg("unit") = row->unit,
                         py::arg("help") = row->help));
  }
  return rows;
}

py::dict readOutlineAsDict(const std::string& path) {
  const Shape2 shape = valueOrRaise(readOutline(path));
  py::dict d;
  d["outline"] = shape.outer.points;
  py::list holes, creases;
  for (const Outline2& hole : shape.holes) holes.append(hole.points);
  for (const CreaseLine& crease : shape.creases) creases.append(crease.points);
  d["holes"] = holes;
  d["creases"] = creases;
  return d;
}

RowPoints readCurvePoints(const std::string& path) { return valueOrRaise(readCurve(path)).points; }

}  // namespace
}  // namespace dform

PYBIND11_MODULE(_dform, m) {
  using namespace dform;
  using py::arg;
  m.doc() = "D-Forms: two flat pieces zipped along their boundaries, and the 3D shape they make";
  m.attr("__version__") = DFORM_VERSION;
  // A RuntimeError, as the stubs (dform/__init__.pyi) and docs/python.md say.
  static py::exception<std::runtime_error> error(m, "Error", PyExc_RuntimeError);
  error.attr("__module__") = "dform";
  errorType = error.ptr();

  py::class_<Made>(m, "Run", "a solved D-Form as the pipeline made it (dform.Result wraps it)")
      .def_property_readonly(
          "model", [](const Made& r) { return r.modelUsed().name; },
          "'exact' or 'paper': which model made the shape")
      .def_property_readonly("model_reason",
                             [](const Made& r) { return inPythonTerms(r.modelUsed().reason); })
      .def_property_readonly(
          "piece_a", [](const Made& r) { return pieceDict(r.model().a); },
          "dict: name, flat (n, 2) mm, shape (n, 3) mm, faces (m, 3), seam")
      .def_property_readonly("piece_b", [](const Made& r) { return pieceDict(r.model().b); })
      .def_property_readonly("figures", &figures, "the figures report.json records ('metrics')")
      .def_property_readonly("messages", &messageList, "[(level, text)] as the run said them")
      .def_property_readonly(
          "target",
          [](const Made& r) -> std::optional<Points3> {
            const InverseRun* inverse = std::get_if<InverseRun>(&*r.run);
            if (!inverse) return std::nullopt;
            return inverse->target.points;
          },
          "inverse: the resampled curve the seam follows (n, 3), else None")
      .def("export", &exportMade, arg("out_dir"),
           "writes the result folder as `dform forward` does: meshes, report.json, report.html "
           "and, when the gate passes, the cutting files; returns the gate's verdict. Its "
           "keyword arguments are the export settings (setting_rows('export'))");

  // The settings are keyword arguments read through the settings table (setting_rows), which
  // the package's docstrings list.
  m.def("forward", &forward, arg("outline_a"), arg("outline_b"), py::kw_only(),
        arg("holes_a") = std::vector<RowPoints>(), arg("holes_b") = std::vector<RowPoints>(),
        arg("creases_a") = std::vector<RowPoints>(), arg("creases_b") = std::vector<RowPoints>(),
        arg("name_a") = "piece A", arg("name_b") = "piece B",
        "two flat outlines (n, 2) in mm -> the D-Form they make (docs/python.md); its other "
        "keyword arguments are the forward settings (setting_rows('forward'))");
  m.def("inverse", &inverse, arg("curve"), py::kw_only(), arg("name") = "curve",
        "a closed 3D seam curve (n, 3) in mm -> the two flat pieces that make it; its other "
        "keyword arguments are the inverse settings (setting_rows('inverse'))");
  m.def("job_settings", &jobSettings, arg("function"),
        "the settings (a job file's) a call of dform.forward, dform.inverse or Result.export "
        "('forward', 'inverse', 'export') with these keyword arguments would use, checked as "
        "the call checks them, without solving");
  m.def("setting_rows", &settingRowsOf, arg("function"),
        "the settings table's rows that dform.forward, dform.inverse or Result.export takes "
        "('forward', 'inverse', 'export'): keyword, key, weight, flag, default, unset, range, "
        "choices, unit, help");
  m.def("read_outline", &readOutlineAsDict, arg("path"),
        "an SVG or JSON outline file -> {'outline', 'holes', 'creases'} in mm");
  m.def("read_curve", &readCurvePoints, arg("path"),
        "an OBJ, JSON or Bezier curve file -> its points (n, 3) in mm");
}
