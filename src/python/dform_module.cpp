// The compiled part `dform._dform` of the Python package `dform` (docs/python.md; dform/__init__.py
// wraps its runs into picklable results): forward and inverse runs from numpy arrays, their meshes
// and figures back as numpy arrays and dicts, and the whole result folder written as the command
// writes it. A thin shell like the cli: the pipeline does the work, errors become dform.Error with
// the command's exit code and a message that names the Python keyword, not the command's option;
// Ctrl-C stops a solve.
#include <Python.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <regex>
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

// A message of the pipeline in Python terms: each command-line option it names becomes the
// keyword argument of dform.forward, dform.inverse or Result.export that sets the same thing.
std::string inPythonTerms(std::string text) {
  static const std::vector<std::pair<std::regex, std::string>> keywords = [] {
    std::vector<std::pair<std::regex, std::string>> k;
    for (const auto& [option, keyword] : std::vector<std::pair<std::string, std::string>>{
             {"--fit-perimeter", "fit_perimeter=True"},
             {"--flip", "flip=True"},
             {"--interior-edge, interior_edge in a job file", "interior_edge"},
             {"--model ([a-z]+)", "model=\"$1\""},
             {"--join ([a-z]+(,[a-z]+)?)", "join=\"$1\""},
             {"--join", "join"},
             {"--sheet WxHmm", "sheet=\"WxHmm\""},
             {"--sheet", "sheet"},
             {"--page", "page"},
             {"--scale", "scale"},
             {"--joint", "joint"},
             {"--material", "material"},
             {"--kerf", "kerf"},
             {"--hole-spacing", "hole_spacing"},
             {"--hole-diameter", "hole_diameter"},
             {"--hole-edge", "hole_edge"},
             {"--slot-length", "slot_length"},
             {"--gate", "gate"},
             {"--no-export", "cutting_files=False"}})
      k.emplace_back(std::regex(option + "\\b"), keyword);
    return k;
  }();
  for (const auto& [option, keyword] : keywords) text = std::regex_replace(text, option, keyword);
  return text;
}

[[noreturn]] void raise(const Status& status) {
  py::object error = py::reinterpret_borrow<py::object>(errorType)(inPythonTerms(status.message()));
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
  std::optional<ForwardRun> forward;
  std::optional<InverseRun> inverse;
  std::vector<Message> messages;

  const DForm& model() const { return forward ? forward->model : inverse->model; }
  const ModelUsed& modelUsed() const { return forward ? forward->modelUsed : inverse->modelUsed; }
};

py::dict figures(const Made& made) {
  py::object json = py::module_::import("json");
  const CurveMatch* curve = made.inverse ? &made.inverse->curveMatch : nullptr;
  const Metrics& metrics = made.forward ? made.forward->metrics : made.inverse->metrics;
  return json.attr("loads")(metricsJsonText(metrics, curve));
}

py::list messageList(const Made& made) {
  py::list list;
  for (const Message& m : made.messages)
    list.append(py::make_tuple(levelName(m.level), inPythonTerms(m.text)));
  return list;
}

// Made.export(out_dir, ...): the result folder as `dform forward` writes it.
py::dict exportMade(const Made& made, const std::string& outDir, const std::string& profile,
                    const std::string& gate, bool exportAnyway, bool exportFiles,
                    const std::string& sheet, const std::string& page, const std::string& scale,
                    const std::string& joint, const std::string& material,
                    std::optional<double> kerf, std::optional<double> holeSpacing,
                    std::optional<double> holeDiameter, std::optional<double> holeEdge,
                    std::optional<double> slotLength) {
  OutputOptions output;
  output.outDir = outDir;
  output.profile = profile;
  output.gate = gate;
  output.exportAnyway = exportAnyway;
  output.exportFiles = exportFiles;
  output.sheet = sheet;
  output.page = page;
  output.scale = scale;
  output.joint = joint;
  output.material = material;
  output.kerfMm = kerf;
  output.holeSpacingMm = holeSpacing;
  output.holeDiameterMm = holeDiameter;
  output.holeEdgeMm = holeEdge;
  output.slotLengthMm = slotLength;
  const RunSettings settings = valueOrRaise(checkOutput(output));
  MessageSink sink;
  for (const Message& m : made.messages) sink.emit(m.level, m.text);  // kept in report.json
  const WrittenResult written = valueOrRaise(
      made.forward ? writeResult(made.job.forward, *made.forward, output, settings, sink)
                   : writeResult(made.job.inverse, *made.inverse, output, settings, sink));
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
  outcome["cutting_files"] = exportFiles && written.exported.isOk() &&
                             (!written.gate || written.gate->passed() || exportAnyway);
  if (!written.exported.isOk()) outcome["export_error"] = inPythonTerms(written.exported.message());
  return outcome;
}

Made forward(const RowPoints& outlineA, const RowPoints& outlineB,
             const std::vector<RowPoints>& holesA, const std::vector<RowPoints>& holesB,
             const std::vector<RowPoints>& creasesA, const std::vector<RowPoints>& creasesB,
             int resolution, const std::string& model, double startA, double startB, bool flip,
             bool fitPerimeter, double interiorEdge, const std::string& join,
             const std::map<std::string, double>& weights, const std::string& nameA,
             const std::string& nameB) {
  Made made;
  ForwardJob& job = made.job.forward;
  job.pieceA = nameA;
  job.pieceB = nameB;
  job.resolution = resolution;
  job.startA.fraction = startA;
  job.startB.fraction = startB;
  job.flip = flip;
  job.fitPerimeter = fitPerimeter;
  job.interiorEdgeFactor = interiorEdge;
  if (!parseModelChoice(model, job.model))
    raise({ErrorCode::Usage,
           "model must be auto, exact, ruled, paper or general, got '" + model + "'"});
  if (!parseJoin(join, job.joinA, job.joinB))
    raise({ErrorCode::Usage,
           "join must be 'outer,outer', 'inner,inner', 'outer,inner' or "
           "'inner,outer', got '" +
               join + "'"});
  job.weights = defaultWeights(job.joinA, job.joinB);
  for (const auto& [name, value] : weights)
    if (!setNamedWeight(made.job, name, value))
      raise({ErrorCode::Usage, "unknown weight '" + name + "'"});
  Shape2 a = shapeFromArrays(outlineA, holesA, creasesA, nameA);
  Shape2 b = shapeFromArrays(outlineB, holesB, creasesB, nameB);
  auto [run, messages] = solveInterruptibly([&](MessageSink& sink, const RunHooks& hooks) {
    return makeDForm(std::move(a), std::move(b), job, sink, hooks);
  });
  made.forward = std::move(run);
  made.messages = std::move(messages);
  return made;
}

Made inverse(const RowPoints& points, int resolution, const std::map<std::string, double>& weights,
             const std::string& name) {
  Made made;
  made.job.mode = Job::Mode::Inverse;
  InverseJob& job = made.job.inverse;
  job.curve = name;
  job.resolution = resolution;
  for (const auto& [weight, value] : weights)
    if (!setNamedWeight(made.job, weight, value))
      raise({ErrorCode::Usage, "unknown weight '" + weight + "'"});
  // Read and checked as a JSON curve file would be; closed, as a seam is.
  CurveReadOptions closed;
  closed.forceClosed = true;
  Curve3 curve =
      valueOrRaise(parseCurve("{\"points\": " + jsonPoints(points, 3, name) + "}", name, closed));
  curve.source = name;
  auto [run, messages] = solveInterruptibly([&](MessageSink& sink, const RunHooks& hooks) {
    return makePieces(std::move(curve), job, sink, hooks);
  });
  made.inverse = std::move(run);
  made.messages = std::move(messages);
  return made;
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
  static py::exception<std::runtime_error> error(m, "Error");
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
            if (!r.inverse) return std::nullopt;
            return r.inverse->target.points;
          },
          "inverse: the resampled curve the seam follows (n, 3), else None")
      .def("export", &exportMade, arg("out_dir"), py::kw_only(), arg("profile") = "laser",
           arg("gate") = "default", arg("export_anyway") = false, arg("cutting_files") = true,
           arg("sheet") = "", arg("page") = "", arg("scale") = "", arg("joint") = "",
           arg("material") = "", arg("kerf") = py::none(), arg("hole_spacing") = py::none(),
           arg("hole_diameter") = py::none(), arg("hole_edge") = py::none(),
           arg("slot_length") = py::none(),
           "writes the result folder as `dform forward` does: meshes, report.json, report.html "
           "and, when the gate passes, the cutting files; returns the gate's verdict");

  m.def("forward", &forward, arg("outline_a"), arg("outline_b"), py::kw_only(),
        arg("holes_a") = std::vector<RowPoints>(), arg("holes_b") = std::vector<RowPoints>(),
        arg("creases_a") = std::vector<RowPoints>(), arg("creases_b") = std::vector<RowPoints>(),
        arg("resolution") = 100, arg("model") = "auto", arg("start_a") = 0.0, arg("start_b") = 0.0,
        arg("flip") = false, arg("fit_perimeter") = false, arg("interior_edge") = 1.0,
        arg("join") = "outer,outer", arg("weights") = std::map<std::string, double>(),
        arg("name_a") = "piece A", arg("name_b") = "piece B",
        "two flat outlines (n, 2) in mm -> the D-Form they make (docs/python.md)");
  m.def("inverse", &inverse, arg("curve"), py::kw_only(), arg("resolution") = 100,
        arg("weights") = std::map<std::string, double>(), arg("name") = "curve",
        "a closed 3D seam curve (n, 3) in mm -> the two flat pieces that make it");
  m.def("read_outline", &readOutlineAsDict, arg("path"),
        "an SVG or JSON outline file -> {'outline', 'holes', 'creases'} in mm");
  m.def("read_curve", &readCurvePoints, arg("path"),
        "an OBJ, JSON or Bezier curve file -> its points (n, 3) in mm");
}
