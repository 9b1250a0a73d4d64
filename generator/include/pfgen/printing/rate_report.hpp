#pragma once
// The report of a filter whose observation is a rate, dy = h dt + noise (continuous and delayed
// observations): dm = m_drift dt + K (dy - h dt), the gain's entries, and each dP as its three
// parts in turn, E[(x-m)f^T] + E[f(x-m)^T], then E[g g^T], then the correction, so it reads like
// the published equations; JSON gives each entry combined. An observation module derives its report
// part from RateReport and says what its observation adds through the hooks below.
#include <string>
#include <vector>

#include "pfgen/printing/observation_report.hpp"

namespace pfgen {

class RateReport : public ObservationReport {
 public:
  std::string text(const Model& model, const FilterEquations& eq, std::ostream* sink) const override;
  std::string latex(const Model& model, const FilterEquations& eq) const override;
  Json json(const Model& model, const FilterEquations& eq) const override;

 protected:
  // The correction's words in the text header's dP terms ("P A^T (B B^T)^-1 A P").
  virtual std::string correction_words_text(const FilterEquations& eq) const = 0;
  // The same in the unscented filter's LaTeX paragraph ("P A^T (B B^T)^{-1} A P" by default).
  virtual std::string sigma_point_correction_latex(const FilterEquations& eq) const;
  // What the observation adds, nothing by default: text lines after the variables line and
  // equations after the dP ones (each line ending in "\n"); a LaTeX paragraph after the exactness
  // diagnostic and align* lines after the dP ones; JSON fields after P_drift.
  virtual std::string header_text(const FilterEquations& eq) const;
  virtual std::string trailing_text(const FilterEquations& eq) const;
  virtual std::string paragraph_latex(const FilterEquations& eq) const;
  virtual std::vector<std::string> trailing_latex(const FilterEquations& eq) const;
  virtual void add_json(const FilterEquations& eq, Json& out) const;
};

}  // namespace pfgen
