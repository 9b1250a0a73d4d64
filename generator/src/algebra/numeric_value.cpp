#include "pfgen/algebra/numeric_value.hpp"

#include <algorithm>
#include <vector>

namespace pfgen {
namespace {

using GiNaC::ex;
using GiNaC::numeric;

// Smallest magnitude first (the real part's, then the imaginary part's), then by value: a total
// order on the numbers themselves, blind to where GiNaC put them.
bool comes_before(const numeric& a, const numeric& b) {
  const numeric ar = GiNaC::abs(a.real()), br = GiNaC::abs(b.real());
  if (int c = ar.compare(br)) return c < 0;
  const numeric ai = GiNaC::abs(a.imag()), bi = GiNaC::abs(b.imag());
  if (int c = ai.compare(bi)) return c < 0;
  if (int c = a.real().compare(b.real())) return c < 0;
  return a.imag().compare(b.imag()) < 0;
}

// A number, evaluated to a float only where it is not one exactly (sqrt(2), sin(1), Pi).
ex settled(const ex& value) {
  if (GiNaC::is_a<numeric>(value)) return value;
  const ex approximate = value.evalf();
  return GiNaC::is_a<numeric>(approximate) ? approximate : value;
}

ex value_of(const ex& e, const GiNaC::exmap& values) {
  if (GiNaC::is_a<numeric>(e)) return e;
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto it = values.find(e);
    return it == values.end() ? e : value_of(it->second, {});
  }
  if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
    const bool sum = GiNaC::is_a<GiNaC::add>(e);
    std::vector<numeric> numbers;
    GiNaC::exvector rest;
    for (std::size_t k = 0; k < e.nops(); ++k) {
      const ex operand = value_of(e.op(k), values);
      if (GiNaC::is_a<numeric>(operand))
        numbers.push_back(GiNaC::ex_to<numeric>(operand));
      else
        rest.push_back(operand);
    }
    std::sort(numbers.begin(), numbers.end(), comes_before);
    numeric total = sum ? numeric(0) : numeric(1);
    for (const numeric& number : numbers) total = sum ? total + number : total * number;
    if (rest.empty()) return total;
    // A symbol without a value remains: the result is not a number, and its order does not matter.
    rest.push_back(total);
    return sum ? ex(GiNaC::add(rest)) : ex(GiNaC::mul(rest));
  }
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const ex base = value_of(e.op(0), values), exponent = value_of(e.op(1), values);
    if (GiNaC::is_a<numeric>(base) && GiNaC::is_a<numeric>(exponent)) {
      // 0 to a negative power is thrown here: GiNaC's pow() would throw from inside its evaluation
      // and leak the power it had allocated.
      const numeric& b = GiNaC::ex_to<numeric>(base);
      const numeric& x = GiNaC::ex_to<numeric>(exponent);
      if (b.is_zero() && x.is_real() && x.is_negative()) throw GiNaC::pole_error("numeric_value: division by zero", 1);
      return settled(GiNaC::pow(base, exponent));
    }
    return GiNaC::pow(base, exponent);
  }
  if (GiNaC::is_a<GiNaC::function>(e)) {
    ex call = e;
    bool numbers = true;
    for (std::size_t k = 0; k < e.nops(); ++k) {
      call.let_op(k) = value_of(e.op(k), values);
      numbers = numbers && GiNaC::is_a<numeric>(call.op(k));
    }
    if (!numbers) return call;
    // lgamma is C's log|Gamma(x)|, which the generated code calls; GiNaC's is the complex
    // log Gamma(x), not real where Gamma(x) < 0 (x in (-1, 0), (-3, -2), ...).
    if (GiNaC::ex_to<GiNaC::function>(e).get_name() == "lgamma" && GiNaC::ex_to<numeric>(call.op(0)).is_real())
      return settled(GiNaC::log(GiNaC::abs(GiNaC::tgamma(call.op(0)))));
    return settled(call.eval());
  }
  if (GiNaC::is_a<GiNaC::constant>(e)) return e.evalf();
  return e.subs(values).evalf();  // nothing else reaches here from a model; kept total
}

}  // namespace

GiNaC::ex numeric_value(const GiNaC::ex& e, const GiNaC::exmap& values) { return value_of(e, values); }

}  // namespace pfgen
