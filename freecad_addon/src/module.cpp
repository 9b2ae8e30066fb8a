// _sweepcore: the Python binding of the sweep core, used by the FreeCAD addon (sweep_freecad).
//
// Thin on purpose: a spec goes in as JSON text or a dict, the solid comes out as BRep text with
// the report v1 as a dict. Shapes cross the boundary only as BRep text, so no OCCT type appears
// here and any FreeCAD shape (Part.Shape.exportBrepToString()) can be the entity.
// InputError and ComputeError become the Python exceptions of the same names, with the messages
// sweepvol prints.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"

namespace py = pybind11;

namespace {

/// Python exception classes, created once at import.
PyObject* g_input_error = nullptr;
PyObject* g_compute_error = nullptr;
/// set by cancel(), cleared when a run starts
std::atomic<bool> g_cancel{false};

/// The stop request of one run: cancel() from another thread, or the time limit (seconds, 0: none).
std::function<std::string()> stop_request(double time_limit) {
  g_cancel = false;
  return sweep::occt::stop_after(time_limit, [] { return std::string(g_cancel ? "cancelled" : ""); });
}

/// Raises InputError with the attributes `pointer`, `line` and `column` set.
[[noreturn]] void raise_input_error(const sweep::InputError& e, const std::string& source) {
  const std::string msg = e.describe(e.line() > 0 ? source : "");
  py::object cls = py::reinterpret_borrow<py::object>(g_input_error);
  py::object inst = cls(msg);
  inst.attr("pointer") = e.pointer();
  inst.attr("line") = e.line();
  inst.attr("column") = e.column();
  PyErr_SetObject(g_input_error, inst.ptr());
  throw py::error_already_set();
}

/// The spec as JSON text. A dict is dumped; text (or bytes) is taken as is. `positional` tells
/// whether line:column positions in error messages refer to something the caller wrote.
std::string spec_text(const py::handle& spec, bool* positional) {
  if (py::isinstance<py::str>(spec)) {
    *positional = true;
    return spec.cast<std::string>();
  }
  if (py::isinstance<py::bytes>(spec)) {
    *positional = true;
    return std::string(spec.cast<py::bytes>());
  }
  if (py::isinstance<py::dict>(spec)) {
    *positional = false;
    py::object dumps = py::module_::import("json").attr("dumps");
    try {
      return dumps(spec, py::arg("allow_nan") = false).cast<std::string>();
    } catch (py::error_already_set& err) {
      throw sweep::InputError("", "the spec dict is not JSON data: " + std::string(py::str(err.value())));
    }
  }
  throw py::type_error("spec must be JSON text (str) or a dict, not " +
                       std::string(py::str(py::type::handle_of(spec).attr("__name__"))));
}

/// A BRep text written to a private temporary file, removed when this goes out of scope.
class TempBrep {
 public:
  explicit TempBrep(const std::string& text) {
    const char* dir = std::getenv("TMPDIR");
    std::string tmpl = std::string(dir && *dir ? dir : "/tmp") + "/sweep_entity_XXXXXX.brep";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    const int fd = mkstemps(buf.data(), 5);
    if (fd < 0) throw sweep::ComputeError("cannot create a temporary file for the entity in " + tmpl);
    ::close(fd);
    path_ = buf.data();
    std::ofstream o(path_, std::ios::binary);
    o << text;
    if (!o) {
      std::remove(path_.c_str());
      throw sweep::ComputeError("cannot write the entity to " + path_);
    }
  }
  ~TempBrep() { std::remove(path_.c_str()); }
  TempBrep(const TempBrep&) = delete;
  TempBrep& operator=(const TempBrep&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// The override that makes the entity the BRep file at `path`, keeping the spec's `placement`.
std::string entity_override(const std::string& text, const std::string& path) {
  nlohmann::json entity = {{"kind", "brep"}, {"file", path}};
  try {
    const nlohmann::json doc = nlohmann::json::parse(text);
    if (doc.is_object() && doc.contains("entity") && doc["entity"].is_object() &&
        doc["entity"].contains("placement"))
      entity["placement"] = doc["entity"]["placement"];
  } catch (const nlohmann::json::exception&) {
    // Malformed text: parse_spec reports it with its position.
  }
  return "/entity=" + entity.dump();
}

/// Everything run() and check() share: parses the spec, with the entity replaced by
/// `entity_brep` when given, and maps InputError to the Python exception.
struct Prepared {
  sweep::Spec spec;
  std::unique_ptr<TempBrep> entity_file;
};

Prepared prepare(const py::handle& spec, const std::string& base_dir, std::vector<std::string> overrides,
                 const std::optional<std::string>& entity_brep, const std::string& source) {
  bool positional = true;
  const std::string text = spec_text(spec, &positional);
  Prepared p;
  try {
    if (entity_brep) {
      p.entity_file = std::make_unique<TempBrep>(*entity_brep);
      overrides.push_back(entity_override(text, p.entity_file->path()));
    }
    p.spec = sweep::parse_spec(text, base_dir, overrides);
  } catch (sweep::InputError& e) {
    if (!positional) e.set_position(0, 0);
    raise_input_error(e, source.empty() ? std::string("spec") : source);
  }
  return p;
}

/// The spec after overrides, naming the entity BRep text rather than its temporary file.
nlohmann::json spec_json(const Prepared& p) {
  nlohmann::json j = p.spec.json;
  if (p.entity_file && j.contains("entity") && j["entity"].is_object()) j["entity"]["file"] = "<entity_brep>";
  return j;
}

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

/// Runs the sweep with the GIL released; input errors name what the caller passed.
sweep::occt::RunResult guarded_run(const Prepared& p, const sweep::occt::RunOptions& opt, const std::string& source,
                                   std::string* brep) {
  sweep::occt::RunResult r;
  try {
    py::gil_scoped_release unlocked;
    r = sweep::occt::run_sweep(p.spec, opt);
    if (r.shape && brep) *brep = sweep::occt::shape_to_brep_string(*r.shape);
  } catch (const sweep::InputError& e) {
    if (p.entity_file && e.pointer().rfind("/entity", 0) == 0) {
      // The temporary file is ours, not the caller's: name what they passed instead.
      std::string msg = e.what();
      for (std::size_t at; (at = msg.find(p.entity_file->path())) != std::string::npos;)
        msg.replace(at, p.entity_file->path().size(), "<entity_brep>");
      raise_input_error(sweep::InputError("/entity", msg), source);
    }
    raise_input_error(e, source);
  } catch (const std::exception&) {
    throw;
  } catch (...) {
    throw sweep::ComputeError("the geometry kernel failed with an unexpected exception");
  }
  return r;
}

py::dict run(const py::handle& spec, const std::string& base_dir, const std::vector<std::string>& overrides,
             const std::optional<std::string>& entity_brep, bool verify, std::size_t mc_samples,
             std::uint64_t mc_seed, const std::string& source, double time_limit) {
  Prepared p = prepare(spec, base_dir, overrides, entity_brep, source);
  sweep::occt::RunOptions opt;
  opt.stop = stop_request(time_limit);
  opt.verify = verify;
  opt.settings.mc_samples = mc_samples;
  opt.settings.seed = mc_seed;
  std::string brep;
  sweep::occt::RunResult r = guarded_run(p, opt, source, &brep);
  py::dict out;
  out["report"] = to_python(r.report.to_json());
  out["brep"] = r.shape && r.report.ok() ? py::object(py::str(brep)) : py::object(py::none());
  out["spec"] = to_python(spec_json(p));
  return out;
}

py::dict varieties(const py::handle& spec, const std::string& base_dir, const std::vector<std::string>& overrides,
                   const std::optional<std::string>& entity_brep, const std::string& source, double time_limit) {
  Prepared p = prepare(spec, base_dir, overrides, entity_brep, source);
  sweep::occt::RunOptions opt;
  opt.stop = stop_request(time_limit);
  std::vector<sweep::occt::Variety> vars;
  std::shared_ptr<const sweep::occt::Shape> faces;
  opt.varieties = &vars;
  opt.variety_faces = &faces;
  sweep::occt::RunResult r = guarded_run(p, opt, source, nullptr);
  nlohmann::json list = nlohmann::json::array();
  for (const auto& v : vars) list.push_back(v.to_json());
  py::dict out;
  out["report"] = to_python(r.report.to_json());
  out["varieties"] = to_python(list);
  out["brep"] = faces && r.report.ok() ? py::object(py::str(sweep::occt::shape_to_brep_string(*faces)))
                                       : py::object(py::none());
  return out;
}

py::dict check(const py::handle& spec, const std::string& base_dir, const std::vector<std::string>& overrides,
               const std::optional<std::string>& entity_brep, const std::string& source) {
  Prepared p = prepare(spec, base_dir, overrides, entity_brep, source);
  py::dict out;
  out["entity"] = sweep::to_string(p.spec.entity.kind);
  out["dimension"] = p.spec.entity.dimension();
  out["motion"] = sweep::to_string(p.spec.motion.kind);
  out["joints"] = p.spec.motion.motion.dof();
  out["spec"] = to_python(spec_json(p));
  return out;
}

double file_volume(const std::string& path) {
  try {
    py::gil_scoped_release unlocked;
    return sweep::occt::file_volume(path);
  } catch (const sweep::InputError& e) {
    raise_input_error(e, "");
  }
}

}  // namespace

PYBIND11_MODULE(_sweepcore, m) {
  m.doc() = "Exact swept volumes (the sweep core): run a spec v1, get the solid as BRep text and the report v1.";
  m.attr("__version__") = SWEEP_VERSION;

  g_input_error = PyErr_NewExceptionWithDoc(
      "_sweepcore.InputError",
      "Invalid input: the message names the JSON pointer (and line:column in the spec text when known), "
      "as sweepvol prints it. Attributes: pointer, line, column.",
      PyExc_ValueError, nullptr);
  g_compute_error = PyErr_NewExceptionWithDoc(
      "_sweepcore.ComputeError", "The computation failed, or its result failed validation.", PyExc_RuntimeError,
      nullptr);
  m.attr("InputError") = py::handle(g_input_error);
  m.attr("ComputeError") = py::handle(g_compute_error);

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sweep::InputError& e) {
      PyErr_SetString(g_input_error, e.describe("").c_str());
    } catch (const sweep::ComputeError& e) {
      PyErr_SetString(g_compute_error, e.what());
    } catch (const sweep::InternalError& e) {
      PyErr_SetString(PyExc_RuntimeError, (std::string("internal error: ") + e.what()).c_str());
    }
  });

  m.def("run", &run, py::arg("spec"), py::arg("base_dir") = std::string(),
        py::arg("overrides") = std::vector<std::string>(), py::arg("entity_brep") = py::none(),
        py::arg("verify") = false, py::arg("mc_samples") = sweep::Settings().mc_samples,
        py::arg("mc_seed") = sweep::Settings().seed, py::arg("source") = std::string(),
        py::arg("time_limit") = 0.0,
        R"(Computes the solid swept by a spec v1.

spec: JSON text or a dict. base_dir: directory that relative file names are resolved against.
overrides: "/json/pointer=value" strings, as sweepvol's --set. entity_brep: BRep text that
replaces the spec's entity (its placement is kept). verify: add the Monte Carlo volume.
source: name used in error messages for text specs (a file name). time_limit: seconds after which
the run stops (0: none). The GIL is released while it computes; cancel() from another thread
stops it.

Returns {"report": report v1 dict, "brep": BRep text of the solid or None unless the status is
"ok", "spec": the spec after overrides}. A computation that fails is a report with status
"failed" and a message, not an exception. Raises InputError for invalid input.)");
  m.def("check", &check, py::arg("spec"), py::arg("base_dir") = std::string(),
        py::arg("overrides") = std::vector<std::string>(), py::arg("entity_brep") = py::none(),
        py::arg("source") = std::string(),
        R"(Validates a spec only. Returns {"entity", "dimension", "motion", "joints", "spec"}.
Raises InputError for invalid input.)");
  m.def("varieties", &varieties, py::arg("spec"), py::arg("base_dir") = std::string(),
        py::arg("overrides") = std::vector<std::string>(), py::arg("entity_brep") = py::none(),
        py::arg("source") = std::string(), py::arg("time_limit") = 0.0,
        R"(The boundary varieties of every stage. Returns {"report", "varieties" (list of dicts: stage, joint,
type, what, fixed, free, faces, area, and for the last stage boundary_area and volume), "brep" (the last
stage's candidate faces as BRep text, or None when the sweep failed)}.)");
  m.def("cancel", [] { g_cancel = true; },
        R"(Stops the run or varieties call computing now (from another thread): it returns a report with
status "failed" and message "stopped: cancelled" within a few seconds. A call that starts later is
not affected.)");
  m.def("file_volume", &file_volume, py::arg("path"), "Volume of the shapes in a STEP or BREP file.");
}
