// pfgen::api::Filter: one derived filter, printed, evaluated, and given as expressions.
#include <sstream>

#include "api_impl.hpp"
#include "commands.hpp"
#include "pfgen/notation/polynomial_writer.hpp"
#include "pfgen/notation/text_printer.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "pfgen/printing/json_writer.hpp"
#include "pfgen/printing/noise_report.hpp"

namespace pfgen::api {

Filter::Filter(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

const std::string& Filter::name() const { return impl_->equations.name; }

std::string Filter::text() const {
  return guarded([&] { return equations_text(impl_->model->model, impl_->equations); });
}

std::string Filter::latex() const {
  return guarded([&] { return noise_latex(impl_->model->model) + equations_latex(impl_->model->model, impl_->equations); });
}

std::string Filter::json() const {
  return guarded([&] { return equations_json(impl_->model->model, impl_->equations).dump(); });
}

namespace {

std::string list_text(const Vector& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? "," : "") + number_text(values[i]);
  return text;
}

// --P's syntax: rows separated by ';'.
std::string matrix_text(const Matrix& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ";" : "") + list_text(values[i]);
  return text;
}

}  // namespace

Evaluation Filter::eval(const Point& point) const {
  return guarded([&] {
    // The point as `pfgen eval`'s options, read by the command's own code: the same numbers,
    // the same checks and the same messages.
    // Sizes first: a P of a million entries is refused before any of it is written as text.
    std::vector<std::size_t> row_sizes;
    for (const Vector& row : point.P) row_sizes.push_back(row.size());
    check_point_shape(impl_->model->model.n(), point.m.size(), row_sizes);
    cli::EvalOptions options;
    options.filter = impl_->equations.name;
    options.t = number_text(point.t);
    options.m = list_text(point.m);
    options.P = matrix_text(point.P);
    options.assignments = assignment_texts(point.parameters);
    options.m_delayed = list_text(point.m_delayed);
    options.x_star = list_text(point.x_star);
    options.x_star_delayed = list_text(point.x_star_delayed);
    options.phi = list_text(point.phi);
    options.moments = assignment_texts(point.moments, "--moment");
    const cli::EvalOutcome outcome = cli::evaluate_filter(impl_->model->model, options, &impl_->equations);
    const EvaluatedFilter& value = outcome.value;
    Evaluation out;
    out.json = outcome.json;
    out.m_drift = value.m_drift;
    out.gain = value.gain;
    out.P_drift = value.P_drift;
    out.P_dt2 = value.P_dt2;
    out.innovation_covariance = value.innovation_covariance;
    out.predicted_observation = value.predicted_observation;
    out.m_delayed = value.m_delayed;
    out.phi = value.phi;
    out.x_star = value.x_star;
    out.x_star_drift = value.x_star_drift;
    out.P_gain = value.P_gain;
    out.moment_names = value.moment_names;
    out.moment_drift = value.moment_drift;
    out.moment_gain = value.moment_gain;
    out.P_after_update = value.P_after_update;
    out.moments_after_update = value.moments_after_update;
    return out;
  });
}

namespace {

// The text output's spelling (deterministic, unlike GiNaC's own printing, whose term order follows
// memory addresses), with Python's power operator.
std::string python_syntax(std::string text) {
  std::string out;
  for (char c : text) out += c == '^' ? std::string("**") : std::string(1, c);
  return out;
}

}  // namespace

Expressions Filter::expressions() const {
  return guarded([&] {
    const FilterEquations& eq = impl_->equations;
    const std::vector<GiNaC::ex>& symbols = eq.variables.symbols();
    const TextPrinter printer;
    PolynomialWriter writer(printer, [&](std::uint32_t v) { return eq.variables.text_name(v); });
    auto text = [&](const Polynomial& p) { return python_syntax(writer.print(p)); };
    const std::size_t n = eq.n();
    Expressions out;
    for (std::size_t i = 0; i < n; ++i) {
      out.m_drift.push_back(text(eq.m_drift[i]));
      out.m_names.push_back(eq.variables.text_name(eq.variables.m(i)));
      std::vector<std::string> gain_row, P_row, name_row;
      if (i < eq.gain.size())  // a sampled filter has none: its update is at the samples
        for (const Polynomial& entry : eq.gain[i]) gain_row.push_back(text(entry));
      for (std::size_t j = 0; j < n; ++j) {
        P_row.push_back(text(eq.P_drift(i, j)));
        name_row.push_back(eq.variables.text_name(eq.variables.P(i, j)));
      }
      out.gain.push_back(gain_row);
      out.P_drift.push_back(P_row);
      out.P_names.push_back(name_row);
    }
    for (const Polynomial& y : eq.predicted_observation) out.predicted_observation.push_back(text(y));
    for (std::size_t r = 0; r < eq.p && !eq.P_gain.empty(); ++r) {
      std::vector<std::vector<std::string>> L(n, std::vector<std::string>(n));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) L[i][j] = text(eq.P_gain[eq.variables.upper_index(i, j)][r]);
      out.P_gain.push_back(std::move(L));
    }
    for (std::size_t q = 0; q < eq.higher_drift.size(); ++q) {
      const std::uint32_t moment = eq.variables.first_higher_moment() + static_cast<std::uint32_t>(q);
      out.moment_names.push_back(eq.variables.text_name(moment));
      out.moment_drift.push_back(text(eq.higher_drift[q]));
      std::vector<std::string> gain_row;
      if (q < eq.higher_gain.size())  // a sampled filter's moments have no dy term
        for (const Polynomial& entry : eq.higher_gain[q]) gain_row.push_back(text(entry));
      out.moment_gain.push_back(std::move(gain_row));
    }
    for (const GiNaC::ex& symbol : symbols) out.names.push_back(GiNaC::ex_to<GiNaC::symbol>(symbol).get_name());
    for (const Parameter& parameter : impl_->model->model.parameters) out.names.push_back(parameter.symbol.get_name());
    out.names.push_back(impl_->model->model.time.get_name());
    for (const FilterDefinition& definition : eq.definitions) {
      out.definitions.emplace_back(definition.name.get_name(), python_syntax(printer.print(definition.value)));
      out.names.push_back(definition.name.get_name());
    }
    return out;
  });
}

}  // namespace pfgen::api
