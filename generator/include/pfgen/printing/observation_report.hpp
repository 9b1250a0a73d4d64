#pragma once
// What the printers need of an observation model: its filters' reports and what the standalone
// document and the coefficient form say of it. Each module in observations/ implements it
// (observations/<kind>/<kind>_report); equation_report, latex_document and coefficient_report call
// the model's part and never ask which kind it is. The continuous and delayed modules write the
// rate form dm = ... + K (dy - h dt) through rate_report.hpp; the sampled one writes its own.
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
  virtual std::string latex(const FilterEquations& eq) const = 0;
  virtual Json json(const Model& model, const FilterEquations& eq) const = 0;

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

// The modules' parts (observations/<kind>/<kind>_report.cpp), and the model's, by kind.
const ObservationReport& continuous_observation_report();
const ObservationReport& sampled_observation_report();
const ObservationReport& delayed_observation_report();
const ObservationReport& polynomial_observation_report();
const ObservationReport& observation_report(ObservationKind kind);

}  // namespace pfgen
