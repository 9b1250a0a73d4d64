#include "pfgen/codegen/moment_form.hpp"

#include <utility>
#include <vector>

namespace pfgen::codegen {

std::size_t MomentForm::moment(const Monomial& a) {
  if (auto it = nodes_.find(a); it != nodes_.end()) return it->second;
  const std::size_t node = builder_.polynomial(moments_.of_monomial(a));
  nodes_.emplace(a, node);
  return node;
}

std::size_t MomentForm::expectation(const Polynomial& q) {
  std::vector<std::pair<GiNaC::ex, std::size_t>> terms;
  for (const auto* entry : q.ordered_view()) {
    const auto& [a, coefficient] = *entry;
    terms.emplace_back(coefficient, a.is_one() ? GraphBuilder::kOne : moment(a));
  }
  return builder_.combination(terms);
}

}  // namespace pfgen::codegen
