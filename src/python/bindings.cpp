// The bkquake Python module's compiled part, bkquake._bkquake (pybind11): a thin layer above
// app, beside cli, that calls what the command line calls (Scene and its declarations,
// app/run's run_scene, app/fit's fit_catalog, io's readers) and adds no physics. The
// Python-facing API (bkquake.run, bkquake.load, bkquake.Scene, Run) is bkquake/__init__.py.
//
// bkq::Error (bad input) becomes ValueError with the same one-line message the command
// line prints. A run releases the GIL; SIGINT during a run is caught by the run's own stop
// handler (app/stop_signals.hpp), which checkpoints and returns 130, and the caller raises
// KeyboardInterrupt from that.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <optional>
#include <ostream>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

#include "app/fit.hpp"
#include "app/run.hpp"
#include "app/spectrum.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/terminal_text.hpp"
#include "io/column_table.hpp"
#include "io/histogram_csv.hpp"
#include "io/ini.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"

namespace py = pybind11;

namespace bkq {
namespace {

// A vector handed to numpy without a copy: the array owns the vector through a capsule.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({owned->size()}, {sizeof(T)}, owned->data(), free);
}

// The table as a list of (name, array) in the file's column order; the table's storage
// moves into the arrays.
py::list table_to_python(ColumnTable&& t) {
  py::list out;
  for (TableColumn& c : t.columns) {
    py::object a = c.integer ? py::object(to_numpy(std::move(c.i))) : to_numpy(std::move(c.x));
    out.append(py::make_tuple(c.name, a));
  }
  return out;
}

ColumnTable read_catalog_released(const std::string& path) {
  py::gil_scoped_release release;
  return read_catalog_table(path);
}

// What Scene values look like in Python: numbers as numbers, flags as bools, `auto` and
// words as text.
py::object scene_value(const Scene& s, const ParamSpec& p) {
  const std::string& text = s.text(p.key);
  switch (p.type) {
    case ParamType::Real:
      if (p.allow_auto && !s.real_or_auto(p.key)) return py::str(text);
      return py::float_(s.real(p.key));
    case ParamType::Integer:
      return py::int_(s.integer(p.key));
    case ParamType::Boolean:
      return py::bool_(s.flag(p.key));
    case ParamType::Choice:
    case ParamType::Path:
      break;
  }
  return py::str(text);
}

// An ostream that discards (fit_catalog's printed table; the caller reads the JSON).
struct NullBuffer : std::streambuf {
  int overflow(int c) override { return c; }
};

// bkq::Error as ValueError, with its message.
void bind_errors() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      // Valid UTF-8 always (a message may quote a file's raw bytes): Python would otherwise
      // fail to decode it and raise a ValueError with no message at all.
      PyErr_SetString(PyExc_ValueError, printable_text(e.what()).c_str());
    }
  });
}

// The scene keys' declarations.
void bind_parameters(py::module_& m) {
  py::class_<ParamSpec>(m, "ParamSpec")
      .def_readonly("key", &ParamSpec::key)
      .def_readonly("default", &ParamSpec::default_value)
      .def_readonly("units", &ParamSpec::units)
      .def_readonly("doc", &ParamSpec::doc)
      .def_property_readonly("choices", [](const ParamSpec& p) { return p.allowed_choices(); })
      .def_property_readonly("type",
                             [](const ParamSpec& p) {
                               switch (p.type) {
                                 case ParamType::Real:
                                   return "real";
                                 case ParamType::Integer:
                                   return "integer";
                                 case ParamType::Choice:
                                   return "choice";
                                 case ParamType::Boolean:
                                   return "boolean";
                                 case ParamType::Path:
                                   return "path";
                               }
                               return "";
                             })
      .def_property_readonly("allowed", [](const ParamSpec& p) { return allowed_text(p); });
  m.def(
      "parameter_table", [] { return parameter_table(); },
      "Every scene key's declaration (the table --dump-defaults prints).");
}

// A scene: built, overridden and checked as bkquake run does.
void bind_scene(py::module_& m) {
  py::class_<Scene>(m, "SceneCore")
      .def(py::init<>())
      .def_static("from_file", &Scene::from_file, py::arg("path"))
      .def("copy", [](const Scene& s) { return Scene(s); })
      .def("apply_override", &Scene::apply_override, py::arg("assignment"),
           "Applies 'section.key=value' exactly as --set does (same checks, same messages).")
      .def("get",
           [](const Scene& s, const std::string& key) {
             const ParamSpec* p = find_param(key);
             if (!p) throw py::key_error(key);
             return scene_value(s, *p);
           })
      .def("text", &Scene::text)
      .def("is_set", &Scene::is_set)
      .def("applies", &Scene::applies)
      .def(
          "checked",
          [](const Scene& s) {
            // What bkquake run does after the overrides: drop the keys that do not apply
            // (warnings), then the cross-key checks. On a copy: the scene itself stays as given.
            Scene c = s;
            std::vector<std::string> warnings = c.drop_inapplicable();
            c.validate();
            return py::make_tuple(c, warnings);
          },
          "(the scene as a run takes it, warnings); ValueError where bkquake run refuses it.")
      .def("to_ini", [](const Scene& s) { return s.to_ini(); })
      .def_readwrite("origin", &Scene::origin)
      .def("__eq__", [](const Scene& a, const Scene& b) { return a == b; });
}

// bkquake run.
void bind_run(py::module_& m) {
  m.def(
      "run_scene",
      [](const Scene& scene, const std::string& out, bool resume, bool force, bool quiet) {
        RunRequest r;
        r.scene = scene;
        r.out_dir = out;
        r.resume = resume;
        r.force = force;
        r.quiet = quiet;
        py::gil_scoped_release release;
        return run_scene(r);
      },
      py::arg("scene"), py::arg("out"), py::arg("resume") = false, py::arg("force") = false,
      py::arg("quiet") = false,
      "Runs a checked scene into the folder `out` (app/run_scene); returns the exit status: 0 "
      "finished, 130 or 143 stopped by SIGINT or SIGTERM after a checkpoint.");
}

// The readers of a run folder's files.
void bind_readers(py::module_& m) {
  m.def(
      "read_catalog",
      [](const std::string& path) { return table_to_python(read_catalog_released(path)); },
      py::arg("path"), "catalog.csv or catalog.h5 as [(column, numpy array)], schema dtypes.");
  m.def(
      "read_histogram",
      [](const std::string& path) {
        ColumnTable t;
        {
          py::gil_scoped_release release;
          t = read_csv_table(path, histogram_schema());
        }
        return table_to_python(std::move(t));
      },
      py::arg("path"), "histogram.csv as [(column, numpy array)].");
  m.def(
      "read_table",
      [](const std::string& path) {
        ColumnTable t;
        {
          py::gil_scoped_release release;
          t = read_csv_table(path, Schema{});
        }
        return table_to_python(std::move(t));
      },
      py::arg("path"), "Any headed numeric CSV as [(column, float64 array)].");
  m.def("read_run_scene", &read_run_scene, py::arg("scene_ini"),
        "A run folder's scene.ini as a scene (keys this bkquake does not know are skipped).");
  m.def(
      "unknown_scene_keys",
      [](const std::string& path) {
        std::vector<std::string> unknown;
        for (const IniEntry& e : parse_ini(read_text_file(path, "scene"), "in " + path))
          if (!find_param(e.key)) unknown.push_back(e.key);
        return unknown;
      },
      py::arg("scene_ini"), "The keys of a scene file that read_run_scene skips.");
}

// bkquake fit.
void bind_fit(py::module_& m) {
  m.def(
      "fit_catalog",
      [](const std::string& catalog, const std::string& json_out, std::optional<double> mu_min,
         std::optional<double> mu_max, std::optional<double> bin_width, const std::string& measure,
         std::optional<double> x_min, std::optional<double> x_max) {
        // Each argument checked against the scene key it stands for, as bkquake fit does.
        const auto check = [](const char* name, const char* key, std::optional<double> v) {
          if (v) option_value(std::string("fit: ") + name, key, format_real(*v));
          return v;
        };
        FitRequest r;
        r.catalog = catalog;
        r.mu_min = check("mu_min", "stats.mu_min", mu_min);
        r.mu_max = check("mu_max", "stats.mu_max", mu_max);
        if (r.mu_min && r.mu_max && !(*r.mu_max > *r.mu_min))
          throw Error("fit: mu_max must be greater than mu_min");
        if (bin_width) r.bin_width = *check("bin_width", "stats.bin_width", bin_width);
        r.json = json_out;
        if (measure != "moment" && measure != "blocks" && measure != "topplings" &&
            measure != "area" && measure != "duration")
          throw Error(
              "fit: measure: expected one of moment, blocks, topplings, area, duration, "
              "got '" +
              measure + "'");
        r.measure = measure;
        // A power law's range: sizes > 0, x_max above x_min, for a measure other than moment.
        for (const auto& [name, v] : {std::pair{"x_min", x_min}, std::pair{"x_max", x_max}}) {
          if (!v) continue;
          if (measure == "moment")
            throw Error(std::string("fit: ") + name + " = " + format_real(*v) +
                        ": a power law's range, for measure blocks, topplings, area or "
                        "duration (the moment's window is mu_min, mu_max)");
          if (!(std::isfinite(*v) && *v > 0))
            throw Error(std::string("fit: ") + name + " = " + format_real(*v) +
                        ": allowed: a finite size > 0");
        }
        if (x_min && x_max && !(*x_max > *x_min))
          throw Error("fit: x_max = " + format_real(*x_max) +
                      ": allowed: greater than x_min = " + format_real(*x_min));
        r.x_min = x_min;
        r.x_max = x_max;
        py::gil_scoped_release release;
        NullBuffer null;
        std::ostream discard(&null);
        fit_catalog(r, discard);
      },
      py::arg("catalog"), py::arg("json_out"), py::arg("mu_min") = py::none(),
      py::arg("mu_max") = py::none(), py::arg("bin_width") = py::none(),
      py::arg("measure") = "moment", py::arg("x_min") = py::none(), py::arg("x_max") = py::none(),
      "bkquake fit CATALOG --json JSON_OUT [--mu-min A] [--mu-max B] [--bin-width W] "
      "[--measure M], with a power law's range [x_min, x_max] given.");
}

// bkquake spectrum.
void bind_spectrum(py::module_& m) {
  m.def(
      "spectrum",
      [](const std::string& run_dir, const std::string& signal, std::optional<std::int64_t> segment,
         std::optional<double> from, std::optional<double> to, const std::string& window, int peaks,
         double f_min, const std::string& out) {
        // The checks bkquake spectrum makes of its options, in its words.
        if (segment && (from || to))
          throw Error("spectrum: segment and from/to exclude each other");
        if (window != "hann" && window != "rectangular")
          throw Error("spectrum: window = " + window + ": expected hann or rectangular");
        if (peaks < 0)
          throw Error("spectrum: peaks = " + std::to_string(peaks) + ": expected >= 0");
        SpectrumRequest req;
        req.run_dir = run_dir;
        req.signal = signal;
        req.segment = segment;
        req.from = from;
        req.to = to;
        req.window = window == "hann" ? Window::Hann : Window::Rectangular;
        req.peaks = peaks;
        req.f_min = f_min;
        req.out = out;
        SpectrumReport r;
        {
          py::gil_scoped_release release;
          r = spectrum_of_run(req);
        }
        py::list found, linear;
        for (const Peak& p : r.peaks) found.append(py::make_tuple(p.frequency, p.amplitude));
        for (const Eigenmode& e : r.linear) {
          py::dict mode;
          mode["family"] = to_string(e.family);
          mode["index"] = e.index;
          mode["growth"] = e.growth();
          mode["frequency"] = e.frequency();
          linear.append(mode);
        }
        py::dict natural;
        natural["pad"] = r.natural.pad;
        natural["pad_damped"] = r.natural.pad_damped;
        natural["block"] = r.natural.block;
        py::dict d;
        d["frequency"] = to_numpy(std::move(r.spectrum.frequency));
        d["amplitude"] = to_numpy(std::move(r.spectrum.amplitude));
        d["resolution"] = r.spectrum.resolution;
        d["peaks"] = found;
        d["natural"] = natural;
        d["linear_modes"] = linear;
        d["signal"] = r.signal;
        d["file"] = r.out;
        d["t_from"] = r.t_from;
        d["t_to"] = r.t_to;
        d["dt"] = r.dt;
        d["samples"] = r.samples;
        if (r.speed >= 0) d["speed"] = r.speed;
        return d;
      },
      py::arg("run_dir"), py::arg("signal") = "pad_position", py::arg("segment") = py::none(),
      py::arg("from_") = py::none(), py::arg("to") = py::none(), py::arg("window") = "hann",
      py::arg("peaks") = 6, py::arg("f_min") = 0.0, py::arg("out") = "",
      "bkquake spectrum RUN_DIR: the amplitude spectrum of a continuous run's signal (writes "
      "spectrum.csv, or `out`), its peaks and the natural frequencies, as a dict.");
}

}  // namespace
}  // namespace bkq

PYBIND11_MODULE(_bkquake, m) {
  using namespace bkq;
  m.doc() = "bkquake's compiled core; use the bkquake package (bkquake.run, bkquake.load).";
  m.attr("__version__") = kVersion;
  m.attr("git_revision") = kGitRevision;

  bind_errors();
  bind_parameters(m);
  bind_scene(m);
  bind_run(m);
  bind_readers(m);
  bind_fit(m);
  bind_spectrum(m);
}
