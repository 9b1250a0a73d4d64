// pfgen's C++ API on recorded data (<pfgen/pfgen.hpp>, docs/guide/cpp-api.md): the local-level
// model's two variances fitted to the Nile's yearly flow (examples/records/nile.csv) by maximum
// likelihood, then its filter run at the fitted values over ten years held in memory, one of them
// missing.
//   build/examples/api_records               from the source directory
//   build/examples/api_records DIRECTORY     nile.yaml and nile.csv from another directory
#include <cmath>
#include <cstdio>
#include <iostream>

#include <pfgen/pfgen.hpp>

namespace api = pfgen::api;

int main(int argc, char** argv) {
  const std::string directory = argc > 1 ? argv[1] : "examples/records";
  try {
    const api::Model model = api::Model::load(directory + "/nile.yaml");
    api::FitOptions fit;
    fit.record.data_path = directory + "/nile.csv";
    fit.record.time_column = "year";
    fit.estimate = {"q", "h"};
    fit.bounds = {{"q", 0, HUGE_VAL}, {"h", 0, HUGE_VAL}};
    const api::FitResult fitted = model.fit(fit);
    std::cout << fitted.report;  // what `pfgen fit` prints
    if (!fitted.converged) return 1;

    // 1871-1880 in memory, 1875 missing (NaN): the filter predicts over it.
    api::EstimateOptions run;
    run.record.data = api::RecordData::from_arrays(
        {1871, 1872, 1873, 1874, 1875, 1876, 1877, 1878, 1879, 1880},
        {{1120}, {1160}, {963}, {1210}, {NAN}, {1160}, {813}, {1230}, {1370}, {1140}}, {"volume"}, "year");
    run.record.time_column = "year";
    for (const api::FittedParameter& p : fitted.parameters) run.record.parameters[p.name] = p.estimate;
    run.filters = {"cd-optimal"};
    run.series = true;
    const api::EstimateResult estimated = model.estimate(run);
    std::cout << "\n" << estimated.report;  // what `pfgen estimate` prints
    const auto column = [&](const std::string& name) {
      for (std::size_t k = 0; k < estimated.columns.size(); ++k)
        if (estimated.columns[k] == name) return estimated.series[k];
      return api::Vector{};
    };
    const api::Vector years = column("year"), m = column("cd-optimal_m_x"), sd = column("cd-optimal_sd_x");
    std::printf("\nyear   level  std. dev.\n");
    for (std::size_t k = 0; k < years.size(); ++k) std::printf("%4.0f %7.1f %10.1f\n", years[k], m[k], sd[k]);
  } catch (const api::Error& e) {
    std::cerr << "api_records: " << e.report() << "\n";
    return 1;
  }
  return 0;
}
