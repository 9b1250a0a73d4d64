#pragma once
// What the printers need of an observation model, in two parts chosen from its axes apart: its
// filters' reports (ObservationReport, chosen as the derivation's part is, so a linear h's filters
// print as A0 + A x's), and what the standalone document and the coefficient form say of the
// observation as the model wrote it (ObservationStatement: a linear h is shown as rows h). Each
// module in observations/ implements both (observations/<kind>/<kind>_report); equation_report,
// latex_document and coefficient_report call the model's parts and never ask which kind it is. The
// continuous, polynomial and delayed modules write the rate form dm = ... + K (dy - h dt) through
// rate_report.hpp; the sampled one writes its own.
#include <iosfwd>
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

// The names of the observation's two terms in the coefficient form: E and E1 of a rate E + E1 x,
// or a sampled observation's C0 and C; as text, and in LaTeX (the matrix's entries' name too).
struct CoefficientNames {
  std::string offset, matrix;                               // "E", "E1"
  std::string offset_latex, matrix_latex, entries_latex;    // "E", "E_{1}", "(E_{1})"
};

class ObservationReport {
 public:
  virtual ~ObservationReport() = default;

  // One filter's report (equation_report.hpp): the text, or with a sink the part of it not yet
  // written there; the LaTeX fragment; the JSON.
  virtual std::string text(const Model& model, const FilterEquations& eq, std::ostream* sink) const = 0;
  virtual std::string latex(const Model& model, const FilterEquations& eq) const = 0;
  virtual Json json(const Model& model, const FilterEquations& eq) const = 0;
};

class ObservationStatement {
 public:
  virtual ~ObservationStatement() = default;

  // The standalone document (latex_document.hpp): the observation's equation in the model's display
  // beside dx's, its matrices as the last lines of the model's align* (no line break after the
  // last), and the notation paragraph before the filters.
  virtual std::string equation_latex(const Model& model) const = 0;
  virtual std::string matrices_latex(const Model& model) const = 0;
  virtual std::string notation_latex() const = 0;

  // The coefficient form (coefficient_report.hpp): the observation's line of text ("observation:
  // ...\n"), its LaTeX sentence, its terms' names, and its JSON fields besides kind and the terms.
  virtual std::string coefficients_text(const Model& model) const = 0;
  virtual std::string coefficients_latex(const Model& model) const = 0;
  virtual CoefficientNames coefficient_names() const = 0;
  virtual void add_coefficients_json(const Model& model, Json& observation) const = 0;
};

// The modules' parts (observations/<kind>/<kind>_report.cpp), and the model's, composed from its
// axes: samples, a delay, then the rate: for the filters' reports its affine case (a linear h's
// filters are A0 + A x's, field for field), for the statement the rate as the model wrote it.
const ObservationReport& continuous_observation_report();
const ObservationReport& sampled_observation_report();
const ObservationReport& delayed_observation_report();
const ObservationReport& polynomial_observation_report();
const ObservationReport& observation_report(const ObservationModel& observation);
const ObservationStatement& continuous_observation_statement();
const ObservationStatement& sampled_observation_statement();
const ObservationStatement& delayed_observation_statement();
const ObservationStatement& polynomial_observation_statement();
const ObservationStatement& observation_statement(const ObservationModel& observation);

}  // namespace pfgen
