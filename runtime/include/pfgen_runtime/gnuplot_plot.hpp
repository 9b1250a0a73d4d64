#pragma once
// The estimation errors of all filters against time, drawn by gnuplot from the results CSV.
#include <functional>
#include <string>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime {

// The gnuplot script that draws, per state component, two panels: the shown run's errors x - m
// of every filter (like the papers' figures), and each filter's median error over the runs with
// its 5-95 % band (transparent). It reads csv_path as write_results_csv writes it (columns by
// position) and writes plot_path with the pngcairo or svg terminal, by plot_path's extension
// (.png or .svg, any case; std::invalid_argument otherwise). Each filter has its own colour, dash
// type and line width, the first drawn first, solid and widest, each later one narrower on top, so
// that coinciding curves all stay visible; the particle reference is black and dashed, drawn last;
// the key sits below each panel. Fixed size, fonts and styles, so the same inputs give the same
// script (and the same SVG). y_limit > 0 fixes every panel's y range to [-y_limit, y_limit]
// (curves beyond it are clipped, and the titles say so); 0 autoscales.
std::string gnuplot_error_script(const std::string& plot_path, const std::string& csv_path,
                                 const MonteCarloResult& result, const std::vector<std::string>& state_names,
                                 const std::string& title, double y_limit = 0);

// Where write_error_plot keeps the script: plot_path + ".gp" (the command line checks that it
// is neither an input nor another output).
std::string gnuplot_script_path(const std::string& plot_path);

// Writes that script to gnuplot_script_path(plot_path) and runs gnuplot (pfgen_support::run_program:
// no shell) on a copy that draws into a temporary; only a whole plot reaches plot_path, by
// pfgen_support::write_file_atomically (a device or a link to one is written into, never replaced),
// and a failure leaves plot_path as it was.
// std::runtime_error when gnuplot is not on PATH (install it: scripts/install-deps.sh), when it
// fails (with its error output), or when it leaves no plot file.
void write_error_plot(const std::string& plot_path, const std::string& csv_path, const MonteCarloResult& result,
                      const std::vector<std::string>& state_names, const std::string& title, double y_limit = 0);

// What write_error_plot does with any script: script_for(path) is the script that draws into path;
// it is kept at gnuplot_script_path(plot_path) naming plot_path, and run on a temporary, so that
// only a whole plot reaches plot_path. Same errors as write_error_plot.
void write_gnuplot_plot(const std::string& plot_path,
                        const std::function<std::string(const std::string& drawn_path)>& script_for);

// Whether an executable gnuplot is on PATH, searched as execvp searches it; require_gnuplot throws
// std::runtime_error naming --plot when not: called before any work, so that a run asked for a plot
// it cannot draw writes nothing.
bool gnuplot_on_path();
void require_gnuplot();

// The terminal line's text for plot_path (.png: pngcairo, .svg: svg; std::invalid_argument
// otherwise), and a gnuplot single-quoted string.
std::string gnuplot_terminal(const std::string& plot_path, int width, int height);
std::string gnuplot_string(const std::string& text);

}  // namespace pfgen_runtime
