#pragma once
// `pfgen estimate MODEL --data FILE`: the model's filters run over a record of observations; per
// data time each filter's m, standard deviations (or all of P), predicted observation, innovation
// and normalised innovation as CSV (-o), a plot of the estimates with their 2-sigma bands (--plot),
// and per filter the scores: the log-likelihood, the normalised innovations' mean square against
// its 95 % band, their whiteness, and a verdict in words. A filter that fails part way (a moment
// filter leaving its realisable set) stops there and is reported as stopped, as `simulate` counts
// its stops; the others go on. Only when every filter has failed is it an error.
#include <string>
#include <vector>

#include "pfgen_runtime/innovation_scores.hpp"
#include "record_job.hpp"

namespace pfgen::cli {

struct EstimateOptions {
  RecordJobOptions record;
  std::string csv_path;   // -o
  std::string plot_path;  // --plot FILE.png|svg
  bool full_covariance = false;
  // The API's: the CSV kept here, as -o writes it (with or without -o).
  std::string* csv_text = nullptr;
};

struct FilterScores {
  std::string filter;
  pfgen_runtime::InnovationSummary summary;
  double increment_log_density = 0;  // continuous data only
  // Where and why the filter stopped before the record's end ("dw.csv:462: its moments left the
  // realisable set at t = 4.6 (...)"); empty when it ran through. Its scores then count the rows
  // up to that one (whose innovation is scored before the step that fails), and its CSV cells are
  // empty from that row on.
  std::string stopped;
};

struct EstimateOutcome {
  std::string report;  // what the command prints on stdout
  std::vector<FilterScores> scores;
  std::string time_column;                       // the record's, as the CSV names it
  std::vector<std::string> observation_columns;  // the record's, in the model's order
  std::vector<std::string> columns;              // the CSV's header
};

EstimateOutcome estimate(const EstimateOptions& options);
int run_estimate(const EstimateOptions& options);

}  // namespace pfgen::cli
