// pfgen._pfgen: the C++ API (pfgen/pfgen.hpp) for Python, kept thin; the package pfgen
// (pfgen/__init__.py) makes it Pythonic (dicts, numpy arrays, SymPy, Jupyter's LaTeX).
// Every call that does work releases the GIL: other Python threads run while pfgen derives,
// generates or simulates (pfgen itself runs one call at a time; pfgen.hpp says why).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "pfgen/pfgen.hpp"

namespace py = pybind11;
namespace api = pfgen::api;

namespace {

// The GIL released for a call, and taken back after it, as pybind11's gil_scoped_release does, but
// for one case: a daemon thread whose call ends while the interpreter is exiting. CPython ends such
// a thread inside PyEval_RestoreThread with pthread_exit, whose unwinding must be let through (a
// noexcept destructor, as gil_scoped_release's, aborts the process there: "terminate called
// without an active exception"); pybind11's dispatcher rethrows it. A thread that sees the exit
// begun waits for it instead, which ends it.
class ReleasedGil {
 public:
  ReleasedGil() : state_(PyEval_SaveThread()) {}
  ~ReleasedGil() noexcept(false) {
    while (_Py_IsFinalizing()) pause();
    PyEval_RestoreThread(state_);
  }
  ReleasedGil(const ReleasedGil&) = delete;
  ReleasedGil& operator=(const ReleasedGil&) = delete;

 private:
  PyThreadState* state_;
};

using Released = py::call_guard<ReleasedGil>;

// A read-only property whose getter releases the GIL: it waits for pfgen's lock when another
// thread is in pfgen, and must not stop the other Python threads meanwhile.
template <typename Getter>
py::cpp_function released_getter(Getter getter) {
  return py::cpp_function(getter, Released());
}

// What a simulation's progress bar has drawn and Python has not yet shown. The simulation's
// threads append to it without the GIL (api::SimulationOptions::progress); a Python thread takes
// it, with the GIL, and writes it to sys.stderr: no thread of pfgen ever waits for the GIL.
class ProgressText {
 public:
  void add(const std::string& text) {
    const std::lock_guard<std::mutex> lock(mutex_);
    text_ += text;
  }
  std::string take() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(text_, {});
  }

 private:
  std::mutex mutex_;
  std::string text_;
};

// Numbers as a numpy array (a copy), faster than a list of floats for a long series.
py::array_t<double> numpy_vector(const api::Vector& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

// A record in memory from its header and an N x K array (the package checks the shapes).
api::RecordData record_data(const std::vector<std::string>& columns,
                            const py::array_t<double, py::array::c_style | py::array::forcecast>& values) {
  api::RecordData data;
  data.columns = columns;
  const auto cells = values.unchecked<2>();
  data.rows.resize(static_cast<std::size_t>(cells.shape(0)));
  for (py::ssize_t r = 0; r < cells.shape(0); ++r)
    data.rows[static_cast<std::size_t>(r)].assign(cells.data(r, 0), cells.data(r, 0) + cells.shape(1));
  return data;
}

}  // namespace

PYBIND11_MODULE(_pfgen, m) {
  m.doc() = "pfgen's C++ API; use the package pfgen";

  // pfgen.Error: its message is the line the command prints after "pfgen: ".
  static py::exception<api::Error> error(m, "Error");
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const api::Error& e) {
      // The whole line, as a Python str (c_str() would stop at a NUL the message quotes); bytes
      // that are not UTF-8 (a file name's) as \x escapes.
      const std::string line = pfgen_support::one_line(e.report());
      const py::object text = py::reinterpret_steal<py::object>(
          PyUnicode_DecodeUTF8(line.data(), static_cast<Py_ssize_t>(line.size()), "backslashreplace"));
      PyErr_SetObject(error.ptr(), text.ptr());
    }
  });

  m.def("version", &api::version);

  py::class_<api::Evaluation>(m, "Evaluation").def_readonly("json", &api::Evaluation::json);

  py::class_<api::Expressions>(m, "Expressions")
      .def_readonly("m_drift", &api::Expressions::m_drift)
      .def_readonly("gain", &api::Expressions::gain)
      .def_readonly("P_drift", &api::Expressions::P_drift)
      .def_readonly("predicted_observation", &api::Expressions::predicted_observation)
      .def_readonly("P_gain", &api::Expressions::P_gain)
      .def_readonly("moment_names", &api::Expressions::moment_names)
      .def_readonly("moment_drift", &api::Expressions::moment_drift)
      .def_readonly("moment_gain", &api::Expressions::moment_gain)
      .def_readonly("definitions", &api::Expressions::definitions)
      .def_readonly("m_names", &api::Expressions::m_names)
      .def_readonly("P_names", &api::Expressions::P_names)
      .def_readonly("names", &api::Expressions::names);

  py::class_<api::Filter>(m, "Filter")
      .def_property_readonly("name", &api::Filter::name)
      .def("text", &api::Filter::text, Released())
      .def("latex", &api::Filter::latex, Released())
      .def("json", &api::Filter::json, Released())
      .def("expressions", &api::Filter::expressions, Released())
      .def(
          "eval",
          [](const api::Filter& filter, double t, const api::Vector& m, const api::Matrix& P,
             const std::map<std::string, double>& parameters, const api::Vector& m_delayed,
             const api::Vector& x_star, const api::Vector& x_star_delayed, const api::Vector& phi,
             const std::map<std::string, double>& moments) {
            const api::Point point{t, m, P, parameters, m_delayed, x_star, x_star_delayed, phi, moments};
            return filter.eval(point);
          },
          Released());

  py::class_<api::CodeFile>(m, "CodeFile")
      .def_readonly("path", &api::CodeFile::path)
      .def_readonly("contents", &api::CodeFile::contents);

  py::class_<api::CodegenOptions>(m, "CodegenOptions")
      .def(py::init<>())
      .def_readwrite("filters", &api::CodegenOptions::filters)
      .def_readwrite("language", &api::CodegenOptions::language)
      .def_readwrite("scalar", &api::CodegenOptions::scalar)
      .def_readwrite("name_space", &api::CodegenOptions::name_space)
      .def_readwrite("eigen", &api::CodegenOptions::eigen)
      .def_readwrite("dt", &api::CodegenOptions::dt);

  py::class_<api::SimulationOptions>(m, "SimulationOptions")
      .def(py::init<>())
      .def_readwrite("runs", &api::SimulationOptions::runs)
      .def_readwrite("T", &api::SimulationOptions::T)
      .def_readwrite("dt", &api::SimulationOptions::dt)
      .def_readwrite("filters", &api::SimulationOptions::filters)
      .def_readwrite("seed", &api::SimulationOptions::seed)
      .def_readwrite("reference", &api::SimulationOptions::reference)
      .def_readwrite("scheme", &api::SimulationOptions::scheme)
      .def_readwrite("x0", &api::SimulationOptions::x0)
      .def_readwrite("stepping", &api::SimulationOptions::stepping)
      .def_readwrite("record_points", &api::SimulationOptions::record_points)
      .def_readwrite("shown_run", &api::SimulationOptions::shown_run)
      .def_readwrite("bound", &api::SimulationOptions::bound)
      .def_readwrite("risk_epsilon", &api::SimulationOptions::risk_epsilon)
      .def_readwrite("report_times", &api::SimulationOptions::report_times)
      .def_readwrite("windows", &api::SimulationOptions::windows)
      .def_readwrite("parameters", &api::SimulationOptions::parameters)
      .def_readwrite("threads", &api::SimulationOptions::threads)
      .def_readwrite("batch", &api::SimulationOptions::batch)
      .def_readwrite("cache_dir", &api::SimulationOptions::cache_dir)
      .def_readwrite("compiler", &api::SimulationOptions::compiler)
      .def("report_progress_to", [](api::SimulationOptions& options, std::shared_ptr<ProgressText> text) {
        options.progress = [text = std::move(text)](const std::string& part) { text->add(part); };
      });

  py::class_<ProgressText, std::shared_ptr<ProgressText>>(m, "ProgressText")
      .def(py::init<>())
      .def("take", &ProgressText::take);

  py::class_<api::FilterSummary>(m, "FilterSummary")
      .def_readonly("name", &api::FilterSummary::name)
      .def_readonly("completed", &api::FilterSummary::completed)
      .def_readonly("diverged", &api::FilterSummary::diverged)
      .def_readonly("psd_losses", &api::FilterSummary::psd_losses)
      .def_readonly("unrealisable", &api::FilterSummary::unrealisable)
      .def_readonly("too_stiff", &api::FilterSummary::too_stiff)
      .def_readonly("undefined", &api::FilterSummary::undefined)
      .def_readonly("rms", &api::FilterSummary::rms)
      .def_readonly("rms_se", &api::FilterSummary::rms_se)
      .def_readonly("peak_median", &api::FilterSummary::peak_median)
      .def_readonly("peak_q95", &api::FilterSummary::peak_q95)
      .def_readonly("reference_distance", &api::FilterSummary::reference_distance)
      .def_readonly("reference_distance_se", &api::FilterSummary::reference_distance_se)
      .def_readonly("own_error", &api::FilterSummary::own_error);

  py::class_<api::SimulationResult>(m, "SimulationResult")
      .def_readonly("report", &api::SimulationResult::report)
      .def_readonly("notes", &api::SimulationResult::notes)
      .def_readonly("csv", &api::SimulationResult::csv)
      .def_readonly("columns", &api::SimulationResult::columns)
      .def_readonly("series", &api::SimulationResult::series)
      .def_readonly("filters", &api::SimulationResult::filters)
      .def_readonly("runs", &api::SimulationResult::runs)
      .def_readonly("steps", &api::SimulationResult::steps)
      .def_readonly("shown_run", &api::SimulationResult::shown_run)
      .def_readonly("reference_particles", &api::SimulationResult::reference_particles);

  py::class_<api::RecordOptions>(m, "RecordOptions")
      .def(py::init<>())
      .def_readwrite("data_path", &api::RecordOptions::data_path)
      .def("set_data", [](api::RecordOptions& options, const std::vector<std::string>& columns,
                          const py::array_t<double, py::array::c_style | py::array::forcecast>& values) {
        options.data = record_data(columns, values);
      })
      .def_readwrite("time_column", &api::RecordOptions::time_column)
      .def_readwrite("columns", &api::RecordOptions::columns)
      .def_readwrite("data_form", &api::RecordOptions::data_form)
      .def_readwrite("substeps", &api::RecordOptions::substeps)
      .def_readwrite("t0", &api::RecordOptions::t0)
      .def_readwrite("parameters", &api::RecordOptions::parameters)
      .def_readwrite("cache_dir", &api::RecordOptions::cache_dir)
      .def_readwrite("compiler", &api::RecordOptions::compiler);

  py::class_<api::EstimateOptions>(m, "EstimateOptions")
      .def(py::init<>())
      .def_readwrite("record", &api::EstimateOptions::record)
      .def_readwrite("filters", &api::EstimateOptions::filters)
      .def_readwrite("full_covariance", &api::EstimateOptions::full_covariance)
      .def_readwrite("series", &api::EstimateOptions::series);

  py::class_<api::RecordScores>(m, "RecordScores")
      .def_readonly("name", &api::RecordScores::name)
      .def_readonly("log_likelihood", &api::RecordScores::log_likelihood)
      .def_readonly("increment_log_density", &api::RecordScores::increment_log_density)
      .def_readonly("stopped", &api::RecordScores::stopped)
      .def_readonly("count", &api::RecordScores::count)
      .def_readonly("mean_square", &api::RecordScores::mean_square)
      .def_readonly("band_low", &api::RecordScores::band_low)
      .def_readonly("band_high", &api::RecordScores::band_high)
      .def_readonly("ljung_box_lags", &api::RecordScores::ljung_box_lags)
      .def_readonly("ljung_box_statistic", &api::RecordScores::ljung_box_statistic)
      .def_readonly("ljung_box_p", &api::RecordScores::ljung_box_p)
      .def_readonly("consistent", &api::RecordScores::consistent)
      .def_readonly("white", &api::RecordScores::white)
      .def_readonly("verdict", &api::RecordScores::verdict);

  py::class_<api::EstimateResult>(m, "EstimateResult")
      .def_readonly("report", &api::EstimateResult::report)
      .def_readonly("filters", &api::EstimateResult::filters)
      .def_readonly("time_column", &api::EstimateResult::time_column)
      .def_readonly("observation_columns", &api::EstimateResult::observation_columns)
      .def_readonly("csv", &api::EstimateResult::csv)
      .def_readonly("columns", &api::EstimateResult::columns)
      .def_property_readonly("series", [](const api::EstimateResult& result) {
        py::list out;
        for (const api::Vector& column : result.series) out.append(numpy_vector(column));
        return out;
      });

  py::class_<api::Bound>(m, "Bound")
      .def(py::init([](const std::string& name, double low, double high) { return api::Bound{name, low, high}; }));

  py::class_<api::FitOptions>(m, "FitOptions")
      .def(py::init<>())
      .def_readwrite("record", &api::FitOptions::record)
      .def_readwrite("filter", &api::FitOptions::filter)
      .def_readwrite("estimate", &api::FitOptions::estimate)
      .def_readwrite("bounds", &api::FitOptions::bounds)
      .def_readwrite("starts", &api::FitOptions::starts)
      .def_readwrite("seed", &api::FitOptions::seed)
      .def_readwrite("profile", &api::FitOptions::profile);

  py::class_<api::FittedParameter>(m, "FittedParameter")
      .def_readonly("name", &api::FittedParameter::name)
      .def_readonly("estimate", &api::FittedParameter::estimate)
      .def_readonly("std_error", &api::FittedParameter::std_error)
      .def_readonly("wald_low", &api::FittedParameter::wald_low)
      .def_readonly("wald_high", &api::FittedParameter::wald_high)
      .def_readonly("profile_low", &api::FittedParameter::profile_low)
      .def_readonly("profile_high", &api::FittedParameter::profile_high)
      .def_readonly("at_bound", &api::FittedParameter::at_bound)
      .def_readonly("profile_low_fails_beyond", &api::FittedParameter::profile_low_fails_beyond)
      .def_readonly("profile_high_fails_beyond", &api::FittedParameter::profile_high_fails_beyond);

  py::class_<api::FitResult>(m, "FitResult")
      .def_readonly("report", &api::FitResult::report)
      .def_readonly("json", &api::FitResult::json)
      .def_readonly("converged", &api::FitResult::converged)
      .def_readonly("stop_reason", &api::FitResult::stop_reason)
      .def_readonly("parameters", &api::FitResult::parameters)
      .def_readonly("log_likelihood", &api::FitResult::log_likelihood)
      .def_readonly("aic", &api::FitResult::aic)
      .def_readonly("evaluations", &api::FitResult::evaluations)
      .def_readonly("at_edge", &api::FitResult::at_edge)
      .def_readonly("note", &api::FitResult::note);

  py::class_<api::Model>(m, "Model")
      .def_static("load", &api::Model::load, Released())
      .def_static("from_yaml", &api::Model::from_yaml, Released())
      .def_property_readonly("name", &api::Model::name)
      .def_property_readonly("source", &api::Model::source)
      .def_property_readonly("state_names", &api::Model::state_names)
      .def_property_readonly("parameter_names", released_getter(&api::Model::parameter_names))
      .def_property_readonly("kinds", released_getter(&api::Model::kinds))
      .def_property_readonly("default_kinds", released_getter(&api::Model::default_kinds))
      .def("derive", &api::Model::derive, Released())
      .def("latex_document", &api::Model::latex_document, Released())
      .def("codegen_files", py::overload_cast<const api::CodegenOptions&>(&api::Model::codegen, py::const_),
           Released())
      .def("codegen_to",
           py::overload_cast<const std::string&, const api::CodegenOptions&>(&api::Model::codegen, py::const_),
           Released())
      .def("simulate", &api::Model::simulate, Released())
      .def("estimate", &api::Model::estimate, Released())
      .def("fit", &api::Model::fit, Released());
}
