#include "pfgen_runtime/gnuplot_plot.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pfgen_runtime/results_csv.hpp"

extern char** environ;

namespace pfgen_runtime {

namespace {

// Colour-blind-safe (Okabe-Ito), fixed, so plots do not change between runs.
const char* const colors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"};

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

// A double as gnuplot reads it back exactly.
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

// Runs gnuplot on the script; returns its exit status and collects its error output.
int run_gnuplot(const std::string& script, std::string& errors) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw std::runtime_error(std::string("plot: pipe failed: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], 1);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], 2);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[1]);
  char program[] = "gnuplot";
  std::string script_argument = script;
  char* argv[] = {program, script_argument.data(), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  if (spawned != 0) {
    close(pipe_ends[0]);
    if (spawned == ENOENT)
      throw std::runtime_error("gnuplot is not on PATH: install gnuplot (scripts/install-deps.sh installs gnuplot-nox) "
                               "to draw plots");
    throw std::runtime_error(std::string("plot: cannot start gnuplot: ") + std::strerror(spawned));
  }
  char buffer[4096];
  for (;;) {  // read to EOF before waiting, so a chatty gnuplot cannot block on a full pipe
    const ssize_t count = read(pipe_ends[0], buffer, sizeof buffer);
    if (count > 0)
      errors.append(buffer, static_cast<std::size_t>(count));
    else if (count == 0 || errno != EINTR)
      break;
  }
  close(pipe_ends[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error(std::string("plot: waiting for gnuplot failed: ") + std::strerror(errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
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
      << "set grid\nset key outside right top\nset xlabel 't'\nset lmargin 12\nset rmargin 24\n"
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
    for (std::size_t f = 0; f < result.filters.size(); ++f) {
      const std::string& name = result.filters[f].name;
      out << (f == 0 ? "plot " : ", \\\n     ") << data << " skip 1 using 1:" << column(columns, name + "_err_" + x)
          << " with lines lw 1.5 lc rgb '" << colors[f % 8] << "' title " << quoted(name);
    }
    out << "\n";
    out << "set title " << quoted(x + ": median over " + std::to_string(result.runs) + " runs, 5-95 % band" + clipped) << "\n";
    if (result.filters.empty()) out << "plot 0 with lines notitle\n";
    for (std::size_t f = 0; f < result.filters.size(); ++f) {
      const std::string& name = result.filters[f].name, stem = name + "_err_" + x;
      out << (f == 0 ? "plot " : ", \\\n     ") << data << " skip 1 using 1:" << column(columns, stem + "_q05") << ":"
          << column(columns, stem + "_q95") << " with filledcurves fs transparent solid 0.2 noborder lc rgb '"
          << colors[f % 8] << "' notitle, \\\n     " << data << " skip 1 using 1:" << column(columns, stem + "_q50")
          << " with lines lw 1.5 lc rgb '" << colors[f % 8] << "' title " << quoted(name);
    }
    out << "\n";
  }
  out << "unset multiplot\nset output\n";
  return out.str();
}

void write_error_plot(const std::string& plot_path, const std::string& csv_path, const MonteCarloResult& result,
                      const std::vector<std::string>& state_names, const std::string& title, double y_limit) {
  const std::string script = gnuplot_error_script(plot_path, csv_path, result, state_names, title, y_limit);
  const std::string script_path = plot_path + ".gp";
  {
    std::ofstream file(script_path, std::ios::binary | std::ios::trunc);
    file << script;
    file.close();
    if (!file) throw std::runtime_error("cannot write the gnuplot script '" + script_path + "'");
  }
  std::remove(plot_path.c_str());  // so a stale plot cannot pass for this one
  std::string errors;
  const int status = run_gnuplot(script_path, errors);
  struct stat info {};
  const bool written = stat(plot_path.c_str(), &info) == 0 && info.st_size > 0;
  if (status != 0 || !written) {
    std::remove(plot_path.c_str());
    std::ostringstream message;
    message << "gnuplot failed on '" << script_path << "' (exit status " << status << ")";
    if (status == 0) message << " and wrote no plot '" << plot_path << "'";
    if (!errors.empty()) message << ":\n" << errors;
    throw std::runtime_error(message.str());
  }
}

}  // namespace pfgen_runtime
