// python/shadowlab_module.cpp — the compiled half of the Python module `shadowlab`
// (docs/python.md; the Python half: python/shadowlab/__init__.py). Every call goes through the
// command line's own code: its parser (registry/cli.h parse) reads the options the Python side
// spells as render's, compare's and bench's arguments, and registry/commands.h, measure/bench.h
// and measure/sweep.h do the work, so a row from Python equals the CLI's for the same options.
//
// Threads: the GIL is released while C++ works, and one lock (glLock) makes the process's GL
// work one call at a time, so Python threads (a Dask worker's) may call in freely.
// Errors: InputError -> ValueError with the CLI's one-line message; GlError -> shadowlab.GLError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <mutex>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/image.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "measure/bench.h"
#include "measure/sweep.h"
#include "registry/cli.h"
#include "registry/commands.h"
#include "registry/registry.h"

namespace py = pybind11;

namespace sl::python {
namespace {

// The process's one GL: every call that renders holds it (DESIGN.md: no globals except the GL
// context; this lock is that context's).
std::mutex& glLock() {
  static std::mutex lock;
  return lock;
}

// Runs `work` without the GIL and with the GL lock, `command` recorded as what made its outputs
// (the JSON lines' "command"). Python objects are made after it returns, with the GIL.
template <class Work>
auto withGl(const std::string& command, Work&& work) {
  py::gil_scoped_release release;
  std::lock_guard<std::mutex> lock(glLock());
  recordCommand(command);
  return work();
}

// The command line `shadowlab COMMAND ARGS...` parsed as the CLI parses it.
cli::Args parseCommand(const std::string& command, const std::vector<std::string>& arguments) {
  std::vector<std::string> words = {"shadowlab", command};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  try {
    return cli::parse(int(words.size()), argv.data());
  } catch (const cli::HelpRequested&) {
    throw InputError("--help is not an option of the Python module (see help(shadowlab))");
  }
}

// The JSON fields as text (json.loads on the Python side); invalid UTF-8 becomes U+FFFD.
std::string jsonText(const nlohmann::json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// An image as uint8, rows top-down, shape (h, w, c): the bytes --out's PNG holds.
py::array_t<std::uint8_t> bytesArray(const Image& image) {
  const std::vector<unsigned char> rows = quantizedRows(image, 8);
  py::array_t<std::uint8_t> out(
      {py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)});
  std::memcpy(out.mutable_data(), rows.data(), rows.size());
  return out;
}

// An image as float32, rows top-down, unquantised: shape (h, w) for one channel (`squeeze`),
// else (h, w, c).
py::array_t<float> floatArray(const Image& image, bool squeeze) {
  std::vector<py::ssize_t> shape = {py::ssize_t(image.height), py::ssize_t(image.width)};
  if (!(squeeze && image.channels == 1)) shape.push_back(image.channels);
  py::array_t<float> out(shape);
  const size_t row = size_t(image.width) * image.channels;
  float* dst = out.mutable_data();
  for (int y = 0; y < image.height; ++y)  // storage is bottom-up
    std::memcpy(dst + row * y, image.data.data() + row * (image.height - 1 - y),
                row * sizeof(float));
  return out;
}

py::list techniquesInfo() {
  py::list list;
  for (const Technique& t : allTechniques()) {
    py::dict reads;
    reads["shadow_map"] = readsOption(t, CommonOption::kShadowMap);
    reads["filter"] = readsOption(t, CommonOption::kFilter);
    reads["precision"] = readsOption(t, CommonOption::kPrecision);
    reads["imaging"] = readsOption(t, CommonOption::kImaging);
    py::list params;
    for (const ParamSpec& p : t.params) {
      py::dict d;
      d["key"] = p.key;
      d["kind"] = paramKindName(p.kind);
      d["default"] = p.defaultText();
      d["choices"] = p.choices;
      d["meaning"] = p.meaning;
      d["description"] = describeParam(p);
      params.append(d);
    }
    py::dict d;
    d["name"] = t.name;
    d["paper"] = t.paper;
    d["summary"] = t.summary;
    d["status"] = t.status;
    d["reads"] = reads;
    d["params"] = params;
    list.append(d);
  }
  return list;
}

py::list scenesInfo() {
  py::list list;
  for (const std::string& s : builtinSceneNames()) {
    py::dict d;
    d["name"] = s;
    d["source"] = "built in";
    list.append(d);
  }
  for (const std::string& s : sceneFileNames()) {
    py::dict d;
    d["name"] = s;
    d["source"] = "assets/scenes";
    list.append(d);
  }
  return list;
}

// render: the JSON line's text, the image, the mask and, when asked, the pass buffers.
py::tuple render(const std::vector<std::string>& arguments, const std::string& command,
                 bool passes) {
  const RenderRun run = withGl(command, [&] {
    RenderRequest request = prepareRender(parseCommand("render", arguments));
    request.params.capturePasses = passes;
    RenderRun r = runRender(request);
    if (!r.frame.color.empty() && !allFinite(r.frame.color))
      throw GlError("the image has NaN or Inf");
    if (!allFinite(r.frame.visibility)) throw GlError("the visibility mask has NaN or Inf");
    return r;
  });
  py::list buffers;
  for (const PassImage& p : run.frame.intermediates)
    buffers.append(py::make_tuple(p.name, p.caption, floatArray(p.image, false)));
  return py::make_tuple(jsonText(run.line), bytesArray(run.frame.color),
                        floatArray(run.frame.visibility, true), buffers);
}

// compare: the JSON line's text and the warnings the CLI prints on stderr.
py::tuple compare(const std::vector<std::string>& arguments, const std::string& command) {
  std::vector<std::string> warnings;
  const std::string line = withGl(command, [&] {
    const CompareRequest request = prepareCompare(parseCommand("compare", arguments));
    warnings = request.warnings;
    return jsonText(runCompare(request).line);
  });
  return py::make_tuple(line, warnings);
}

// The bench CSV's text (measure/bench.h writeCsvRows) at full double precision.
std::string csvText(const std::vector<figures::BenchRow>& rows) {
  constexpr int kRoundTripDigits = 17;  // every double reads back exactly
  std::ostringstream out;
  out.precision(kRoundTripDigits);
  figures::writeCsvRows(out, rows);
  return out.str();
}

// bench: `shadowlab bench`'s rows (sorted and ranked as it sorts and ranks them) as CSV text.
std::string bench(const std::vector<std::string>& arguments, const std::string& command,
                  bool progress) {
  return withGl(command, [&] {
    figures::BenchOptions options = figures::parseBenchOptions(parseCommand("bench", arguments));
    options.progress = progress;
    std::ostringstream jsonLines;  // the CLI's stdout; the CSV carries the same rows
    return csvText(figures::runBenchmark(options, jsonLines).rows);
  });
}

// sweep: the plan's rows (what each measures) as JSON text.
std::string sweepPlan(const std::string& specJson) {
  const figures::SweepPlan plan = withGl("", [&] {
    nlohmann::json spec;
    try {
      spec = nlohmann::json::parse(specJson);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(std::string("sweep: the spec is not JSON: ") + e.what());
    }
    return figures::planSweep(spec);
  });
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < plan.rows.size(); ++i) {
    const figures::SweepRow& r = plan.rows[i];
    const figures::SweepView& v = plan.views[r.view];
    rows.push_back({{"row", i},
                    {"view", r.view},
                    {"scene", v.scene},
                    {"width", v.width},
                    {"height", v.height},
                    {"orbit", v.orbit ? nlohmann::json(*v.orbit) : nlohmann::json()},
                    {"technique", r.technique->name},
                    {"variant", r.variant}});
  }
  return jsonText(rows);
}

// sweep: the rows at `indices`, measured in this process, as CSV text.
std::string sweepMeasure(const std::string& specJson, const std::vector<size_t>& indices,
                         const std::string& command, figures::SweepReferenceCache& cache) {
  return withGl(command, [&] {
    const figures::SweepPlan plan = figures::planSweep(nlohmann::json::parse(specJson));
    return csvText(figures::measureSweepRows(plan, indices, cache));
  });
}

// The Pareto ranks of a sweep's rows (measure/sweep.h assignSweepParetoRanks) from its columns.
std::vector<int> paretoRanks(const std::vector<std::string>& groups,
                             const std::vector<std::string>& techniques,
                             const std::vector<std::string>& statuses,
                             const std::vector<std::string>& references,
                             const std::vector<double>& frameMs,
                             const std::vector<double>& hardRmse,
                             const std::vector<double>& softRmse) {
  const size_t n = groups.size();
  for (size_t size : {techniques.size(), statuses.size(), references.size(), frameMs.size(),
                      hardRmse.size(), softRmse.size()})
    if (size != n) throw InputError("pareto ranks: columns of different lengths");
  std::vector<figures::BenchRow> rows(n);
  for (size_t i = 0; i < n; ++i) {
    rows[i].technique = techniques[i];
    rows[i].status = statuses[i];
    rows[i].primaryReference = references[i];
    rows[i].frameMs = frameMs[i];
    rows[i].hard.all.rmse = hardRmse[i];
    rows[i].soft.all.rmse = softRmse[i];
  }
  figures::assignSweepParetoRanks(rows, groups);
  std::vector<int> ranks;
  for (const figures::BenchRow& r : rows) ranks.push_back(r.paretoRank);
  return ranks;
}

}  // namespace
}  // namespace sl::python

PYBIND11_MODULE(_shadowlab, m) {
  using namespace sl::python;
  m.doc() = "shadowlab's compiled core; use the package `shadowlab` (docs/python.md)";
  static py::exception<sl::GlError> glError(m, "GLError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sl::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const sl::GlError& e) {
      glError(e.what());
    }
  });
  m.def("commit", &sl::buildCommit, "the commit this module was built from");
  m.def("techniques", &techniquesInfo);
  m.def("scenes", &scenesInfo);
  m.def("render", &render, py::arg("arguments"), py::arg("command"), py::arg("passes"));
  m.def("compare", &compare, py::arg("arguments"), py::arg("command"));
  m.def("bench", &bench, py::arg("arguments"), py::arg("command"), py::arg("progress"));
  m.def("sweep_plan", &sweepPlan, py::arg("spec_json"));
  py::class_<sl::figures::SweepReferenceCache>(m, "ReferenceCache")
      .def(py::init<>())
      .def(
          "views",
          [](const sl::figures::SweepReferenceCache& c) {
            std::lock_guard<std::mutex> lock(glLock());
            return c.size();
          },
          py::call_guard<py::gil_scoped_release>(), "views whose references it holds");
  m.def("sweep_measure", &sweepMeasure, py::arg("spec_json"), py::arg("indices"),
        py::arg("command"), py::arg("cache"));
  m.def("pareto_ranks", &paretoRanks);
}
