#pragma once
// A simulate job's `simulation:` values, merged once: each field the command line's value, else
// the model file's, else pfgen's default. The merge keeps beside each value the place it came
// from, so that a rule the values break (model/simulation_rules) is named where the user wrote it:
// the option, the file's line, or the option whose default it is.
#include <map>
#include <string>

#include "pfgen/model/model.hpp"

namespace pfgen::cli {

struct SimulationOverrides;

struct MergedSimulation {
  // Every field set but filters (unset: every filter of the model); report times and windows of
  // the file beyond a shorter --T left out.
  SimulationSection values;
  // Field ("dt") -> its place in messages: "--dt", "m.yaml:12:3: simulation.dt" or
  // "--dt (default 0.001)".
  std::map<std::string, std::string> places;
  // The file's report times and windows left out, said on stderr once the job is accepted (an
  // error line is the only line a refused job prints).
  std::string notes;
};

// Throws CliValueError when neither the command line nor the file gives T, or when the text of
// --filters, --report-times or --windows does not parse; checks nothing else.
MergedSimulation merge_simulation_settings(const Model& model, const SimulationOverrides& command_line);

}  // namespace pfgen::cli
