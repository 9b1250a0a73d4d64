#include "pfgen_runtime/gnuplot_plot.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "pfgen_runtime/results_csv.hpp"
#include "pfgen_support/atomic_file.hpp"
#include "pfgen_support/process.hpp"

#include <unistd.h>

namespace pfgen_runtime {

namespace {

// Colour-blind-safe (Okabe-Ito), fixed, so plots do not change between runs.
const char* const colors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"};

// Filters' errors often coincide, and a curve drawn over another of the same width hides it. So
// each filter has its own dash type and width as well as its colour: the first filter is drawn
// first, solid and widest (its colour stays as a rim around the others), each later one narrower
// and broken by its own dashes, through which the curves beneath show. None is dt 2 (dashed),
// which is the particle reference's (black, on top). Eight dash types, then they repeat.
const char* const dash_types[] = {"1", "4", "5", "(20,5)", "3", "(20,5,5,5)", "(30,5,2,5,2,5)", "(10,4,4,4)"};
constexpr double widest = 6.0, narrowest = 2.0;

// Line width of filter f of `count`: from `widest` (the first) down to `narrowest` (the last) in
// equal steps, so no two filters share one; a lone filter is drawn `narrowest` wide.
double line_width(std::size_t f, std::size_t count) {
  if (count < 2) return narrowest;
  return widest - (widest - narrowest) * static_cast<double>(f) / static_cast<double>(count - 1);
}

// "lw W dt D lc rgb 'C'": a line of filter f's dash type and colour, `width` wide.
std::string line_style(const std::string& width, std::size_t f) {
  return "lw " + width + " dt " + dash_types[f % 8] + " lc rgb '" + colors[f % 8] + "'";
}

// Filter f's own line, its width with at most 3 decimals (a pure function of f and count).
std::string filter_line_style(std::size_t f, std::size_t count) {
  char width[32];
  std::snprintf(width, sizeof width, "%.3g", line_width(f, count));
  return line_style(width, f);
}

// A gnuplot single-quoted string: nothing is interpreted inside except '' for a quote.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\n' || c == '\r') c = ' ';
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

std::string terminal_for(const std::string& plot_path, int width, int height) {
  std::string extension;
  const auto dot = plot_path.find_last_of('.');
  if (dot != std::string::npos && plot_path.find('/', dot) == std::string::npos) extension = plot_path.substr(dot + 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  // noenhanced: filter and state names print as written (no '_' subscripts).
  if (extension == "png") return "pngcairo" + size + " noenhanced font 'Sans,10'";
  if (extension == "svg") return "svg" + size + " noenhanced font 'Sans,10' background '#ffffff'";
  throw std::invalid_argument("plot '" + plot_path + "': the file name must end in .png or .svg");
}

// A double as gnuplot reads it back exactly. %.17g, not the shortest form
// (pfgen_support::shortest_double): the script is kept beside the plot, and its text is stable.
std::string exact(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// 1-based position of a CSV column, for gnuplot's `using`.
std::size_t column(const std::vector<std::string>& columns, const std::string& name) {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end()) throw std::logic_error("plot: no CSV column " + name);
  return static_cast<std::size_t>(it - columns.begin()) + 1;
}

// Runs gnuplot on the script (pfgen_support::run_program: no shell, stdin /dev/null); returns its
// exit status (128 + the signal that ended it) and collects its output, where its errors go.
int run_gnuplot(const std::string& script, std::string& errors) {
  using pfgen_support::ProcessError;
  pfgen_support::ProcessResult result;
  try {
    result = pfgen_support::run_program({"gnuplot", script});
  } catch (const ProcessError& e) {
    const std::string reason = std::strerror(e.error_number());
    switch (e.stage()) {
      case ProcessError::Stage::pipe: throw std::runtime_error("plot: pipe failed: " + reason);
      case ProcessError::Stage::spawn:
        if (e.error_number() == ENOENT)
          throw std::runtime_error("gnuplot is not on PATH: install gnuplot (scripts/install-deps.sh installs "
                                   "gnuplot-nox) to draw plots");
        throw std::runtime_error("plot: cannot start gnuplot: " + reason);
      case ProcessError::Stage::wait: break;
    }
    throw std::runtime_error("plot: waiting for gnuplot failed: " + reason);
  }
  errors += result.output;
  return result.signal ? 128 + result.signal : result.exit_status;
}

}  // namespace

std::string gnuplot_error_script(const std::string& plot_path, const std::string& csv_path,
                                 const MonteCarloResult& result, const std::vector<std::string>& state_names,
                                 const std::string& title, double y_limit) {
  if (!(y_limit >= 0) || !std::isfinite(y_limit)) throw std::invalid_argument("plot: the y limit must be finite and >= 0");
  const std::vector<std::string> columns = results_csv_columns(result, state_names);  // checks state_names
  const int panel_height = 320, width = 1000;
  const auto panels = static_cast<int>(2 * result.n);
  std::ostringstream out;
  out << "# pfgen simulate: estimation errors x - m of every filter against time.\n"
      << "# Data: " << csv_path << " (pfgen results CSV; columns by position, header skipped).\n"
      << "set terminal " << terminal_for(plot_path, width, panel_height * panels + 40) << "\n"
      << "set output " << quoted(plot_path) << "\n"
      << "set datafile separator comma\n"  // an empty cell (a stopped run) is a missing point
      << "set multiplot layout " << panels << ",1 title " << quoted(title) << "\n"
      << "set grid\nset xlabel 't'\nset lmargin 12\nset rmargin 4\n"
      // The key below each panel, in rows, so the curves get the whole width; samples long enough
      // to show each dash type; height 1 keeps its first row clear of the x label.
      << "set key outside below center horizontal Left reverse samplen 5 height 1\n"
      << "set xrange [" << exact(result.grid.t0) << ":" << exact(result.grid.end()) << "]\n";
  // A diverging filter's errors would otherwise set the scale and flatten everyone else's.
  if (y_limit > 0) out << "set yrange [" << exact(-y_limit) << ":" << exact(y_limit) << "]\n";
  const std::string clipped = y_limit > 0 ? " (clipped at +-" + exact(y_limit) + ")" : "";
  const std::string data = quoted(csv_path);
  for (std::size_t i = 0; i < result.n; ++i) {
    const std::string& x = state_names[i];
    out << "set ylabel " << quoted(x + " - m") << "\n";
    out << "set title " << quoted(x + ": run " + std::to_string(result.series.shown_run) + clipped) << "\n";
    if (result.filters.empty()) out << "plot 0 with lines notitle\n";
    const std::size_t count = result.filters.size();
    for (std::size_t f = 0; f < count; ++f) {
      const std::string& name = result.filters[f].name;
      out << (f == 0 ? "plot " : ", \\\n     ") << data << " skip 1 using 1:" << column(columns, name + "_err_" + x)
          << " with lines " << filter_line_style(f, count) << " title " << quoted(name);
    }
    // The particle reference's x - m_ref beside them: how far from the conditional mean they are.
    if (result.reference && !result.filters.empty())
      out << ", \\\n     " << data << " skip 1 using 1:"
          << column(columns, "reference_err_" + x) << " with lines lw 1.5 dt 2 lc rgb '#000000' title "
          << quoted("reference (N=" + std::to_string(result.reference->particles) + ")");
    out << "\n";
    out << "set title " << quoted(x + ": median over " + std::to_string(result.runs) + " runs, 5-95 % band" + clipped) << "\n";
    if (result.filters.empty()) out << "plot 0 with lines notitle\n";
    // The bands, then the medians over them in the order and styles above. Filled bands of
    // filters that track each other stack into one grey area whose owner no one can tell, so
    // only the first filter's band is filled; every other filter's band is its two edges, thin,
    // in its own colour and dash type. Each band has its key entry ("NAME 5-95 %").
    for (std::size_t f = 0; f < count; ++f) {
      const std::string stem = result.filters[f].name + "_err_" + x;
      const std::string band = quoted(result.filters[f].name + " 5-95 %");
      out << (f == 0 ? "plot " : ", \\\n     ") << data << " skip 1 using 1:";
      if (f == 0) {
        out << column(columns, stem + "_q05") << ":" << column(columns, stem + "_q95")
            << " with filledcurves fs transparent solid 0.2 noborder lc rgb '" << colors[f % 8] << "' title " << band;
        continue;
      }
      const std::string edge = " with lines " + line_style("1", f);
      out << column(columns, stem + "_q05") << edge << " title " << band << ", \\\n     " << data
          << " skip 1 using 1:" << column(columns, stem + "_q95") << edge << " notitle";
    }
    for (std::size_t f = 0; f < count; ++f) {
      const std::string& name = result.filters[f].name;
      out << ", \\\n     " << data << " skip 1 using 1:" << column(columns, name + "_err_" + x + "_q50")
          << " with lines " << filter_line_style(f, count) << " title " << quoted(name);
    }
    out << "\n";
  }
  out << "unset multiplot\nset output\n";
  return out.str();
}

std::string gnuplot_script_path(const std::string& plot_path) { return plot_path + ".gp"; }

bool gnuplot_on_path() {
  // As execvp searches: each PATH entry in turn (an empty one is the current directory).
  const char* path = std::getenv("PATH");
  std::string entries = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t begin = 0;
  while (begin <= entries.size()) {
    std::size_t end = entries.find(':', begin);
    if (end == std::string::npos) end = entries.size();
    const std::string directory = end > begin ? entries.substr(begin, end - begin) : ".";
    const std::string candidate = directory + "/gnuplot";
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) return true;
    begin = end + 1;
  }
  return false;
}

void require_gnuplot() {
  if (gnuplot_on_path()) return;
  throw std::runtime_error("--plot: gnuplot is not on PATH: install gnuplot (scripts/install-deps.sh installs "
                           "gnuplot-nox), or leave --plot out");
}

void write_gnuplot_plot(const std::string& plot_path,
                        const std::function<std::string(const std::string& drawn_path)>& script_for) {
  // gnuplot draws into a temporary beside the plot (same extension, so the same terminal), run from
  // a script of its own; only a whole plot then reaches plot_path, through write_file_atomically,
  // which replaces a file and writes into a device without replacing it. The script kept for the
  // user names plot_path itself.
  const std::string script_path = gnuplot_script_path(plot_path);
  const std::string drawn =
      pfgen_support::unique_temporary_path(plot_path) + std::filesystem::path(plot_path).extension().string();
  const std::string drawing_script = pfgen_support::unique_temporary_path(script_path);
  auto write = [](const std::string& path, const std::string& text, const std::string& what) {
    try {
      pfgen_support::write_file_atomically(path, text);
    } catch (const pfgen_support::AtomicWriteError& e) {
      throw std::runtime_error("cannot write the " + what + ": " + e.what());
    }
  };
  write(script_path, script_for(plot_path), "gnuplot script");
  struct Cleanup {
    std::vector<std::string> paths;
    ~Cleanup() {
      for (const auto& path : paths) std::remove(path.c_str());
    }
  } cleanup{{drawing_script, drawn}};
  write(drawing_script, script_for(drawn), "gnuplot script");
  std::string errors;
  const int status = run_gnuplot(drawing_script, errors);
  std::ifstream in(drawn, std::ios::binary);
  const std::string plot((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (status != 0 || plot.empty()) {
    std::ostringstream message;
    message << "gnuplot failed on '" << script_path << "' (exit status " << status << ")";
    if (status == 0) message << " and wrote no plot '" << plot_path << "'";
    // gnuplot's own first line that is not a warning (else its first line), so that the message
    // stays one line; the script is kept to rerun.
    std::istringstream lines(errors);
    std::string line, first, error;
    while (std::getline(lines, line)) {
      if (line.find_first_not_of(" \t\r^") == std::string::npos) continue;
      if (first.empty()) first = line;
      if (line.find("warning:") == std::string::npos) {
        error = line;
        break;
      }
    }
    if (!first.empty()) message << ": " << (error.empty() ? first : error).substr(0, 300);
    throw std::runtime_error(message.str());
  }
  write(plot_path, plot, "plot");
}

std::string gnuplot_terminal(const std::string& plot_path, int width, int height) {
  return terminal_for(plot_path, width, height);
}

std::string gnuplot_string(const std::string& text) { return quoted(text); }

void write_error_plot(const std::string& plot_path, const std::string& csv_path, const MonteCarloResult& result,
                      const std::vector<std::string>& state_names, const std::string& title, double y_limit) {
  write_gnuplot_plot(plot_path, [&](const std::string& drawn) {
    return gnuplot_error_script(drawn, csv_path, result, state_names, title, y_limit);
  });
}

}  // namespace pfgen_runtime
