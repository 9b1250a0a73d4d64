// The bounds on a derivation's work (pfgen/model/expansion_bound.hpp and
// pfgen/derivation/derivation_budget.hpp): each count is checked against the real expansion it
// predicts, against a sequence known independently, and at the edges of its limit.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "pfgen/derivation/closed_expectation.hpp"
#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/model/expansion_bound.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/dense_cubic_model.hpp"

using namespace pfgen;

namespace {

Monomial monomial(const std::vector<std::uint32_t>& exponents) {
  Monomial m;
  for (std::uint32_t i = 0; i < exponents.size(); ++i)
    if (exponents[i] > 0) m = m * Monomial::variable(i, exponents[i]);
  return m;
}

// A model with the given drift rows over states x1..xn, identity noise, all states observed.
Model model_with_drift(const std::vector<std::string>& drift_text, std::size_t observed) {
  const std::size_t n = drift_text.size();
  ModelBuilder b("budget");
  std::vector<GiNaC::symbol> x;
  GiNaC::symtab table;
  for (std::size_t i = 0; i < n; ++i) {
    x.push_back(b.state("x" + std::to_string(i + 1)));
    table[x.back().get_name()] = x.back();
  }
  GiNaC::parser reader(table);
  ExVector f;
  for (const auto& text : drift_text) f.push_back(reader(text));
  ExMatrix G(n, ExVector(n, 0)), A(observed, ExVector(n, 0)), B(observed, ExVector(observed, 0));
  for (std::size_t i = 0; i < n; ++i) G[i][i] = 1;
  for (std::size_t r = 0; r < observed; ++r) A[r][r] = B[r][r] = 1;
  b.drift(f).diffusion_covariance(G).observation(ExVector(observed, 0), A, B);
  return b.build();
}

}  // namespace

TEST_CASE("gaussian_moment_terms counts the terms GaussianExpectation gives", "[derivation_budget][unit]") {
  const FilterVariables vars(3);
  GaussianExpectation E(vars);
  for (std::uint32_t a = 0; a <= 6; ++a)
    for (std::uint32_t b = 0; a + b <= 6; ++b)
      for (std::uint32_t c = 0; a + b + c <= 6; ++c) {
        const Monomial m = monomial({a, b, c});
        INFO("x1^" << a << " x2^" << b << " x3^" << c);
        CHECK(gaussian_moment_terms(m) == static_cast<double>(E.of_monomial(m).terms().size()));
      }
  const FilterVariables two(2);
  GaussianExpectation E2(two);
  CHECK(gaussian_moment_terms(monomial({12, 9})) == static_cast<double>(E2.of_monomial(monomial({12, 9})).terms().size()));
}

TEST_CASE("gaussian_moment_terms of distinct states are the involution numbers", "[derivation_budget][unit]") {
  // E[x1 x2 ... xk]: one term per partial matching of k factors (OEIS A000085).
  const std::vector<double> involutions = {1, 1, 2, 4, 10, 26, 76, 232, 764, 2620, 9496, 35696, 140152};
  for (std::size_t k = 0; k < involutions.size(); ++k)
    CHECK(gaussian_moment_terms(monomial(std::vector<std::uint32_t>(k, 1))) == involutions[k]);
  // E[x^80 y^80], the example that took 16 s: 45961 terms itself.
  CHECK(gaussian_moment_terms(monomial({80, 80})) == 45961);
  // Beyond the stopping point only "more than" is promised, cheaply.
  CHECK(gaussian_moment_terms(monomial(std::vector<std::uint32_t>(40, 1)), 1e6) > 1e6);
}

TEST_CASE("expanded_terms_bound is never below the real expansion", "[derivation_budget][unit]") {
  GiNaC::symbol x("x"), y("y"), z("z"), a("a"), t("t");
  const std::vector<GiNaC::ex> cases = {
      pow(x + y + 1, 5), pow(x + 1, 30), pow(x + y + z, 4) * pow(x - y, 3), (x + y) * (x - y) + pow(a * x + sin(t), 3),
      pow(pow(x + 1, 2) + y, 3), 3 * x * y * z, pow(x + a, 2) / (a + 1), pow(1 + x + y + z + a + t, 3) - pow(x, 2)};
  for (const auto& e : cases) {
    INFO(e);
    CHECK(expanded_terms_bound(e) >= static_cast<double>(GiNaC::is_a<GiNaC::add>(e.expand()) ? e.expand().nops() : 1));
  }
  // Exact for a power of a sum of distinct variables: C(k + 2, 2) for three terms.
  CHECK(expanded_terms_bound(pow(x + y + 1, 1000)) == Approx(501501));
  // Capped by the degrees: (x + 1)^1000 has 1001 terms, not C(1001, 1000) of two "terms".
  CHECK(expanded_terms_bound(pow(x + 1, 1000)) == Approx(1001));
}

TEST_CASE("the derivation budget refuses what would run away and passes the dense benchmarks",
          "[derivation_budget][integration]") {
  // The examples: E[x^80 y^80] needs 2.8 million intermediate terms.
  try {
    derive_filter(model_with_drift({"-x1^80*x2^80", "-x2"}, 1), FilterKind::Optimal);
    FAIL("x1^80 x2^80 was derived");
  } catch (const ModelError& e) {
    CHECK(e.field() == "drift");
    CHECK(e.row() == 1);
    CHECK(std::string(e.what()).find("more than 250000 terms") != std::string::npos);
  }
  // The extended filter evaluates at m: no expectations, nothing to refuse.
  CHECK_NOTHROW(derive_filter(model_with_drift({"-x1^80*x2^80", "-x2"}, 1), FilterKind::Ekf));
  // Just inside: degree 40 in each.
  CHECK_NOTHROW(derive_filter(model_with_drift({"-x1^40*x2^40", "-x2"}, 1), FilterKind::Optimal));

  // The covariance equations of 64 fully observed states: 2080 entries of 4096 observation terms.
  std::vector<std::string> linear;
  for (int i = 1; i <= 64; ++i) linear.push_back("-x" + std::to_string(i));
  try {
    derive_filter(model_with_drift(linear, 64), FilterKind::Optimal);
    FAIL("64 fully observed states were derived");
  } catch (const ModelError& e) {
    CHECK(e.field() == "states");
    CHECK(std::string(e.what()).find("would have up to 8519680 terms, above the limit of 2000000") != std::string::npos);
  }
  // 64 states with one observed are well inside.
  CHECK_NOTHROW(derive_filter(model_with_drift(linear, 1), FilterKind::Optimal));
  // The derivation benchmark's largest model (dense cubic drift, 20 states) passes both limits.
  const Model dense = pfgen_test::dense_cubic_model(20);
  std::vector<Polynomial> f;
  std::vector<std::vector<Polynomial>> J(20, std::vector<Polynomial>(20));
  for (std::size_t i = 0; i < 20; ++i) f.push_back(Polynomial::from_ex(dense.drift[i], dense.states));
  for (std::size_t i = 0; i < 20; ++i)
    for (std::size_t k = 0; k < 20; ++k) J[i][k] = f[i].derivative(static_cast<std::uint32_t>(k));
  std::vector<Polynomial> G_upper;
  for (std::size_t i = 0; i < 20; ++i)
    for (std::size_t j = i; j < 20; ++j) G_upper.push_back(Polynomial::from_ex(dense.diffusion.G[i][j], dense.states));
  CHECK_NOTHROW(check_derivation_budget(dense, DerivationInputs{true, f, J, G_upper, "diffusion", 20}));
}

namespace {

// Two states x1, x2 observed through polynomial rows `h` (noise B), or sampled through `c`.
Model observed_through(const std::vector<std::string>& rows, bool sampled, const std::string& B = "") {
  std::string list;
  for (const auto& row : rows) list += (list.empty() ? "\"" : ", \"") + row + "\"";
  std::string noise = B;
  if (noise.empty()) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      noise += r ? ", [" : "[";
      for (std::size_t s = 0; s < rows.size(); ++s) noise += std::string(s ? ", " : "") + (r == s ? "\"1\"" : "\"0\"");
      noise += "]";
    }
  }
  const std::string observation =
      sampled ? "observation:\n  sampled: {period: 0.1, c: [" + list + "], Uv: [" + noise + "]}\n"
              : "observation:\n  h: [" + list + "]\n  B: [" + noise + "]\n";
  return load_model_text("name: obs\nstates: [x1, x2]\ndrift: [\"-x1\", \"-x2\"]\n"
                         "diffusion: [[\"1\", \"0\"], [\"0\", \"1\"]]\n" + observation, "obs.yaml");
}

// The field and the start of the message of what derive_filter refuses, or "derived".
std::string refusal(const Model& model, FilterKind kind) {
  try {
    derive_filter(model, kind);
    return "derived";
  } catch (const ModelError& e) {
    return e.field() + ": " + e.message();
  }
}

}  // namespace

TEST_CASE("the derivation budget counts a polynomial h and a sampled c as it counts the drift",
          "[derivation_budget][integration]") {
  // h = x1^20 x2^20 derived for more than 30 s; its correction's products are counted first.
  const Model h20 = observed_through({"x1^20*x2^20"}, false);
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ukf})
    CHECK(refusal(h20, kind).rfind("observation.h: with 2 states, the filter's gain and correction would take up to "
                                   "8176740 products of terms, above the limit of 4000000", 0) == 0);
  CHECK(refusal(h20, FilterKind::Ekf) == "derived");  // at m: J(m) has one term a row
  // x1^50 x2^50 died with bad_alloc, x1^300 x2^300 reached 2.6 GB first: every filter's frame takes
  // E[h], the extended kind's too.
  CHECK(refusal(observed_through({"x1^50*x2^50"}, false), FilterKind::Optimal)
            .rfind("observation.h: the Gaussian expectations of the observation up to this row", 0) == 0);
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf, FilterKind::Ukf}) {
    INFO(filter_kind_name(kind));
    CHECK(refusal(observed_through({"x1", "x1^300*x2^300"}, false), kind)
              .rfind("observation.h: the Gaussian expectations of the observation up to this row", 0) == 0);
  }
  try {
    derive_filter(observed_through({"x1", "x1^300*x2^300"}, false), FilterKind::Ekf);
    FAIL("x1^300 x2^300 was derived");
  } catch (const ModelError& e) {
    CHECK(e.row() == 2);
    CHECK(e.file() == "obs.yaml");
  }
  // A sampled c: its update takes E[c_a c_b] at every kind.
  for (FilterKind kind : {FilterKind::CdOptimal, FilterKind::CdEkf})
    CHECK(refusal(observed_through({"x1^50*x2^50"}, true), kind)
              .rfind("observation.sampled.c: the Gaussian expectations of the observation", 0) == 0);
  CHECK(refusal(observed_through({"x1^30*x2^30"}, true), FilterKind::CdOptimal)
            .rfind("observation.sampled.c: with 2 states, the filter's update would take up to", 0) == 0);
  // Inside: the examples' degrees and well beyond.
  CHECK(refusal(observed_through({"x1^6*x2^6", "x1^2 + x2^2"}, false), FilterKind::Optimal) == "derived");
  CHECK(refusal(observed_through({"x1^6*x2^6"}, true), FilterKind::CdOptimal) == "derived");

  // The gain's R^-1 couples rows only where B B^T does: two rows of degree 14 pass with
  // independent noises and are refused when one noise drives both.
  const std::vector<std::string> two = {"x1^14*x2^14", "x1^14*x2^14 + x1"};
  auto budget = [&](const std::string& B) {
    const Model model = observed_through(two, false, B);
    check_observation_budget(model,
                             ObservationPolynomials{model.observation.rate().polynomials(model.states), "observation.h",
                                                    false, model.observation.rate().noise()},
                             true);
  };
  CHECK_NOTHROW(budget("[\"1\", \"0\"], [\"0\", \"1\"]"));
  CHECK_THROWS_WITH(budget("[\"1\", \"0\"], [\"1\", \"1\"]"), Catch::Contains("above the limit of 4000000"));
}

namespace {

// Every g with |g| <= most over n states, by dense exponent vectors.
std::vector<std::vector<std::uint32_t>> exponent_vectors(std::size_t n, std::uint32_t most) {
  std::vector<std::vector<std::uint32_t>> out{{}};
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::vector<std::uint32_t>> next;
    for (const auto& g : out) {
      std::uint32_t size = 0;
      for (std::uint32_t e : g) size += e;
      for (std::uint32_t e = 0; size + e <= most; ++e) {
        next.push_back(g);
        next.back().push_back(e);
      }
    }
    out = std::move(next);
  }
  return out;
}

// All terms of a moment filter's equations.
double equation_terms(const FilterEquations& eq) {
  double terms = 0;
  auto add = [&](const std::vector<Polynomial>& list) {
    for (const auto& p : list) terms += static_cast<double>(p.terms().size());
  };
  add(eq.m_drift);
  add(eq.P_moment);
  add(eq.P_diffusion);
  add(eq.P_correction);
  add(eq.higher_drift);
  for (const auto* rows : {&eq.gain, &eq.P_gain, &eq.higher_gain})
    for (const auto& row : *rows) add(row);
  return terms;
}

ClosureInputs closure_inputs(const Model& model, FilterKind kind) {
  std::vector<Polynomial> f, h = model.observation.rate().polynomials(model.states);
  for (const auto& e : model.drift) f.push_back(Polynomial::from_ex(e, model.states));
  return ClosureInputs{filter_kind_info(kind).closure_order, filter_kind_name(kind), f, h,
                       model.observation.rate().noise(), "diffusion", "observation.h"};
}

}  // namespace

TEST_CASE("closed_moment_terms counts the terms of the closed law's central moments", "[derivation_budget][unit]") {
  // At order 3 the count is exact; at order 4 the M4's cumulant M4 - 3 P^2 cancels some of the P terms
  // (E[e^8] of one state: 35 M4^2 + 280 M3^2 P - 210 P^4, its M4 P^2 terms cancel), so it is at most
  // 20 % above.
  for (unsigned order : {3u, 4u}) {
    const FilterVariables vars(3, false, order);
    ClosedExpectation E(vars);
    double counted = 0, terms = 0;
    for (const auto& g : exponent_vectors(3, 9)) {
      INFO("order " << order << ", e^(" << g[0] << ", " << g[1] << ", " << g[2] << ")");
      const double real = static_cast<double>(E.central(g).terms().size());
      if (order == 3) CHECK(closed_moment_terms(g, order) == real);
      CHECK(closed_moment_terms(g, order) >= real);
      counted += closed_moment_terms(g, order);
      terms += real;
    }
    CHECK(counted <= 1.2 * terms);
  }
  // By hand: E[e^6] of one state at order 4 is 15 M4 P - 30 P^3 + 10 M3^2 (15 kappa4 kappa2 + 10 kappa3^2
  // + 15 kappa2^3, kappa4 = M4 - 3 P^2); of six distinct states, one term per split into blocks of
  // 2..4: 15 into pairs, 10 into two triples, 15 into a block of four and a pair.
  CHECK(closed_moment_terms({6}, 4) == 3);
  CHECK(closed_moment_terms({1, 1, 1, 1, 1, 1}, 4) == 40);
  CHECK(closed_moment_terms({1, 1, 1, 1, 1, 1}, 3) == 25);
  // The carried moments are their own variables; one factor has mean zero.
  CHECK(closed_moment_terms({2, 1, 1}, 4) == 1);
  CHECK(closed_moment_terms({0, 1}, 3) == 0);
  CHECK(closed_moment_terms({}, 3) == 1);
  // Beyond the stopping point only "more than" is promised, cheaply: 30 distinct states.
  CHECK(closed_moment_terms(std::vector<std::uint32_t>(30, 1), 4, 1e6) > 1e6);
}

TEST_CASE("the moment filters' count bounds the terms of their equations", "[derivation_budget][integration]") {
  // The dense cubic models (cubic drift, linear multiplicative noise, every state observed) and a polynomial
  // observation: the count is at least the equations' terms, and within a small factor of them.
  std::vector<Model> models = {pfgen_test::dense_cubic_model(2), pfgen_test::dense_cubic_model(3)};
  models.push_back(load_model_text("name: obs\nstates: [x1, x2]\ndrift: [\"-x1 + x2^2\", \"-x2^3\"]\n"
                                   "diffusion: [[\"1\", \"0\"], [\"x1\", \"1\"]]\n"
                                   "observation:\n  h: [\"x1^2 + x2\", \"x1*x2^2\"]\n  B: [[\"1\", \"0\"], [\"1\", \"1\"]]\n",
                                   "obs.yaml"));
  for (const Model& model : models)
    for (FilterKind kind : {FilterKind::Closure3, FilterKind::Closure4}) {
      INFO(model.name << " " << filter_kind_name(kind));
      const double terms = equation_terms(derive_filter(model, kind));
      const double counted = closure_derivation_work(model, closure_inputs(model, kind)).total();
      CHECK(counted >= terms);
      CHECK(counted <= 30 * terms);
    }
}

TEST_CASE("the moment filters' budget refuses what would run away and passes the dense models it can derive",
          "[derivation_budget][integration]") {
  // closure4 of 9 dense cubic states took 11.6 s and 1.3 GB; of 10, 30 s and 2.7 GB.
  try {
    derive_filter(pfgen_test::dense_cubic_model(9), FilterKind::Closure4);
    FAIL("closure4 of 9 dense cubic states was derived");
  } catch (const ModelError& e) {
    CHECK(e.field() == "drift");
    CHECK(e.message().rfind("filter closure4 of a 9-state model with a drift of degree 3 would take up to ", 0) == 0);
    CHECK(e.message().find(" products of terms (limit 10000000): its 714 equations (m and the central moments of "
                           "orders 2 to 4) read the closed law's moments up to order 6; use closure3, fewer states "
                           "or lower degrees") != std::string::npos);
  }
  // What passes derives: 4 states at once, 8 states (closure4, 5 s) and 12 (closure3, 6 s) pass the count.
  const FilterEquations four = derive_filter(pfgen_test::dense_cubic_model(4), FilterKind::Closure4);
  CHECK(four.higher_drift.size() == 20 + 35);
  for (auto [n, kind] : {std::pair{8, FilterKind::Closure4}, std::pair{12, FilterKind::Closure3}}) {
    const Model model = pfgen_test::dense_cubic_model(static_cast<std::size_t>(n));
    CHECK_NOTHROW(check_closure_budget(model, closure_inputs(model, kind)));
  }
  const Model thirteen = pfgen_test::dense_cubic_model(13);
  CHECK_THROWS_WITH(check_closure_budget(thirteen, closure_inputs(thirteen, FilterKind::Closure3)),
                    Catch::Contains("filter closure3 of a 13-state model") && Catch::Contains("use fewer states"));

  // A polynomial observation's products: h of degree 3 in all of 4 states (closure3: 3.6 s).
  const Model observed = load_model_text(
      "name: obs\nstates: [x1, x2, x3, x4]\ndrift: [\"-x1\", \"-x2\", \"-x3\", \"-x4\"]\n"
      "diffusion: [[\"1\", \"0\", \"0\", \"0\"], [\"0\", \"1\", \"0\", \"0\"], [\"0\", \"0\", \"1\", \"0\"], "
      "[\"0\", \"0\", \"0\", \"1\"]]\nobservation:\n  h: [\"(x1 + x2 + x3 + x4 + 1)^3\"]\n  B: [[\"1\"]]\n",
      "obs.yaml");
  CHECK_NOTHROW(check_closure_budget(observed, closure_inputs(observed, FilterKind::Closure3)));
  try {
    derive_filter(observed, FilterKind::Closure4);
    FAIL("closure4 of a cubic h in 4 states was derived");
  } catch (const ModelError& e) {
    CHECK(e.field() == "observation.h");
    CHECK(e.file() == "obs.yaml");
    CHECK(e.message().rfind("filter closure4 of a 4-state model with a drift of degree 1 would take up to ", 0) == 0);
  }
  // Many states with a linear drift: the equations themselves, C(n + 4, 4) - 1 of them.
  std::vector<std::string> linear;
  for (int i = 1; i <= 64; ++i) linear.push_back("-x" + std::to_string(i));
  CHECK(refusal(model_with_drift(linear, 1), FilterKind::Closure4)
            .rfind("states: filter closure4 of a 64-state model with a drift of degree 1 would take more than "
                   "40000000 products of terms (limit 10000000): its 814384 equations",
                   0) == 0);
}
