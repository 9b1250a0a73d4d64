#include "pfgen/codegen/filter_functions.hpp"

#include <functional>
#include <memory>
#include <optional>

#include "pfgen/codegen/correction_factor.hpp"
#include "pfgen/codegen/expanded_counts.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/codegen/moment_form.hpp"
#include "pfgen/codegen/p_drift_loops.hpp"
#include "pfgen/codegen/local_names.hpp"
#include "pfgen/derivation/closed_expectation.hpp"

namespace pfgen::codegen {
namespace {

// Where each filter variable is read from: array[index], named as the equations name it. An
// undelayed filter reads its count() variables from the state; a delayed one also reads x* from
// the state (after m and P) and m(t - h), Phi* from the `delayed` argument (docs/theory.md §2.6).
struct InputLayout {
  std::vector<std::string> names, arrays;
  std::vector<std::size_t> indices;
  std::vector<std::string> array_arguments;  // the functions' array arguments, in signature order
};

InputLayout input_layout(const FilterVariables& vars, const FunctionNames& names) {
  InputLayout layout;
  layout.array_arguments = {names.state};
  const std::size_t count = vars.count(), n = vars.n();
  auto add = [&](std::uint32_t v, const std::string& array, std::size_t index) {
    layout.names.push_back(vars.text_name(v));
    layout.arrays.push_back(array);
    layout.indices.push_back(index);
  };
  for (std::size_t v = 0; v < count; ++v) add(static_cast<std::uint32_t>(v), names.state, v);
  if (!vars.delayed()) return layout;
  layout.array_arguments.push_back(names.delayed);
  for (std::size_t i = 0; i < n; ++i) add(vars.m_delayed(i), names.delayed, i);
  for (std::size_t i = 0; i < n; ++i) add(vars.phi(i), names.delayed, n + i);
  for (std::size_t i = 0; i < n; ++i) add(vars.x_star(i), names.state, count + i);
  return layout;
}

GraphBuilder graph_builder(ExpressionGraph& graph, const Model& model, const InputLayout& layout,
                           const FunctionNames& names) {
  return GraphBuilder(graph, model, layout.names, layout.arrays, layout.indices, names.params);
}

FunctionSignature signature(const std::string& function, const FunctionNames& names, const InputLayout& layout,
                            const std::string& target) {
  return {function, names.time, layout.array_arguments, names.params, target};
}

// A function's graph, built and counted but not yet written: derivatives() builds two and writes
// only the one it keeps, which for a large model is far the smaller (the expanded dense cubic
// n = 20 P drift is millions of operations, its structured form a few hundred thousand).
struct BuiltFunction {
  std::string function;
  ExpressionGraph graph;
  InputLayout layout;
  std::vector<std::size_t> roots;
  std::vector<std::size_t> declaration_order;
  FunctionStats stats;
  // derivatives() in loops: the roots fill the work array, and the loops write the outputs.
  std::optional<PDriftLoops> loops;
};

// Builds the outputs of one function into a graph: their roots in order, in `roots`. The builder
// reads the filter's variables and definitions; the graph takes operations the builder does not make.
using OutputBuilder = std::function<void(GraphBuilder&, ExpressionGraph&, std::vector<std::size_t>& roots)>;
// The same for derivatives() in loops, which also says what the loops compute.
using LoopBuilder = std::function<PDriftLoops(GraphBuilder&, ExpressionGraph&, std::vector<std::size_t>& roots)>;

// The graph of the outputs `add_outputs` builds, read through the filter's definitions, which are
// computed first.
std::unique_ptr<BuiltFunction> built_function(const std::string& function, const Model& model,
                                              const FilterEquations& eq, const FunctionNames& names,
                                              const OutputBuilder& add_outputs) {
  auto built = std::make_unique<BuiltFunction>();
  built->function = function;
  built->layout = input_layout(eq.variables, names);
  GraphBuilder builder = graph_builder(built->graph, model, built->layout, names);
  builder.define(eq.definitions, eq.variables.symbols());
  add_outputs(builder, built->graph, built->roots);
  built->declaration_order = builder.declaration_order();
  built->stats =
      FunctionStats{function, built->graph.tree_counts(built->roots), built->graph.shared_counts(built->roots)};
  return built;
}

std::unique_ptr<BuiltFunction> built_loops(const Model& model, const FilterEquations& eq, const FunctionNames& names,
                                           const LoopBuilder& add_outputs) {
  PDriftLoops loops;
  auto built = built_function("derivatives", model, eq, names,
                              [&](GraphBuilder& builder, ExpressionGraph& graph, std::vector<std::size_t>& roots) {
                                loops = add_outputs(builder, graph, roots);
                              });
  built->stats.cse += loops.counts();
  built->loops = loops;
  return built;
}

PDriftLoopNames loop_names(const FunctionNames& names) {
  return {names.work, names.state, names.out, names.full_P, names.JP, names.gain_T, names.H,
          names.sum, names.i, names.j, names.u, names.JP_T};
}

FunctionCode written(const BuiltFunction& built, const std::string& target, const FunctionNames& names,
                     const StatementEmitter& emitter, bool shared) {
  FunctionCode code;
  code.stats = built.stats;
  if (!built.loops) {
    code.body = emitter.function_body(built.graph, built.roots, signature(built.function, names, built.layout, target),
                                      built.declaration_order, shared);
    return code;
  }
  // The graph fills the work array; the loops write `target`.
  code.body = emitter.function_body(built.graph, built.roots,
                                    signature(built.function, names, built.layout, names.work),
                                    built.declaration_order, shared);
  const PDriftLoopNames loop = loop_names(names);
  code.body.statements = emitter.block(full_P_statements(*built.loops, loop)) +
                         emitter.block({ir::declare_array(names.work, ir::Type::Scalar, built.loops->work_size)}) +
                         code.body.statements + emitter.block(p_drift_statements(*built.loops, loop));
  return code;
}

// E[f], E[J] and E[g g^T], as the structured forms read them: the derivation's expanded polynomials,
// or (`moments`, for the Gaussian-closure kinds) sums over shared moments (moment_form.hpp). Each
// call builds its node; asking twice shares it, as the graph shares everything.
class Expectations {
 public:
  Expectations(const FilterEquations& eq, bool moments, GraphBuilder& builder)
      : eq_(eq), builder_(builder), sources_(moments ? &*eq.expectation_sources : nullptr) {
    if (moments) form_.emplace(builder, eq.variables);
  }
  std::size_t drift(std::size_t j) {
    return form_ ? form_->expectation(sources_->drift[j]) : builder_.polynomial(eq_.m_drift[j]);
  }
  std::size_t jacobian(std::size_t j, std::size_t k) {
    return form_ ? form_->expectation(sources_->jacobian(j, k)) : builder_.polynomial(eq_.jacobian_term[j][k]);
  }
  // E[g g^T] at upper entry u.
  std::size_t diffusion(std::size_t u) {
    return form_ ? form_->expectation(sources_->diffusion_upper[u]) : builder_.polynomial(eq_.P_diffusion[u]);
  }

 private:
  const FilterEquations& eq_;
  GraphBuilder& builder_;
  const ExpectationSources* sources_;
  std::optional<MomentForm> form_;
};

// The number or parameter expression an entry of E[J] is, where it is one (its only monomial is 1).
const GiNaC::ex* constant_entry(const Polynomial& entry) {
  if (entry.terms().size() != 1 || !entry.terms().begin()->first.is_one()) return nullptr;
  return &entry.terms().begin()->second;
}

// How build_structured writes P's drift besides the form of its expectations.
struct StructuredOptions {
  bool moments = false;  // E[f], E[J] and E[g g^T] over shared moments (moment_form.hpp)
  // The products of P with the entries of E[J] that are numbers or parameters (sigma, -1) are
  // terms of a polynomial in P, summed with E[g g^T] as one expanded polynomial, so that equal
  // monomials merge: on the Lorenz model's diagonal -2 sigma P11 and s^2 P11 are one product.
  bool collect_constant_jacobian = false;
};

// derivatives() in the derivation's structure (see derivatives_code): E[f], E[J] and E[g g^T] as
// Expectations gives them; P's moment terms as P E[J]^T + E[J] P; the correction as K (A P) where
// correction_factor() finds it equal.
void build_structured(const FilterEquations& eq, const StructuredOptions& options, GraphBuilder& builder,
                      ExpressionGraph& graph, std::vector<std::size_t>& roots) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  Expectations expectations(eq, options.moments, builder);
  for (std::size_t j = 0; j < n; ++j) roots.push_back(expectations.drift(j));
  auto collected = [&](std::size_t j, std::size_t k) -> const GiNaC::ex* {
    return options.collect_constant_jacobian ? constant_entry(eq.jacobian_term[j][k]) : nullptr;
  };
  std::vector<std::vector<std::size_t>> J(n, std::vector<std::size_t>(n));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
      if (!eq.jacobian_term[j][k].is_zero() && !collected(j, k)) J[j][k] = expectations.jacobian(j, k);
  // The correction's factors: K (n x p) and H = A P (p x n), each entry built once.
  const auto H = correction_factor(eq);
  std::vector<std::vector<std::size_t>> K_node, H_node;
  if (H) {
    K_node.assign(n, std::vector<std::size_t>(eq.p));
    H_node.assign(eq.p, std::vector<std::size_t>(n));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t r = 0; r < eq.p; ++r)
        if (!eq.gain[i][r].is_zero()) K_node[i][r] = builder.polynomial(eq.gain[i][r]);
    for (std::size_t r = 0; r < eq.p; ++r)
      for (std::size_t j = 0; j < n; ++j)
        if (!(*H)[r][j].is_zero()) H_node[r][j] = builder.polynomial((*H)[r][j]);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      const std::size_t u = vars.upper_index(i, j);
      // P_ik times an entry of E[J], a negated entry (-m1, -10) as its positive, the product
      // subtracted: no negation, no multiplication by -1. The products first, then their sum.
      std::vector<std::pair<std::size_t, bool>> products;
      auto add_product = [&](std::uint32_t p, std::size_t factor) {
        const Node& node = graph.node(factor);
        const bool negated = node.kind == OpKind::Neg;
        products.emplace_back(graph.mul(builder.variable(p), negated ? node.args[0] : factor), negated);
      };
      // The collected products and E[g g^T], one polynomial in m and P.
      Polynomial rest;
      auto collect = [&](std::uint32_t p, const GiNaC::ex& c) { rest.add_term(Monomial::variable(p), c); };
      // On the diagonal the two products are one, (P E[J]^T)_ii = (E[J] P)_ii: their sum is
      // doubled once instead of adding each product twice.
      for (std::size_t k = 0; k < n; ++k) {
        if (!eq.jacobian_term[j][k].is_zero()) {
          if (const GiNaC::ex* c = collected(j, k)) {
            collect(vars.P(i, k), i == j ? 2 * *c : *c);
          } else {
            add_product(vars.P(i, k), J[j][k]);
          }
        }
        if (i != j && !eq.jacobian_term[i][k].is_zero()) {
          if (const GiNaC::ex* c = collected(i, k)) {
            collect(vars.P(k, j), *c);
          } else {
            add_product(vars.P(k, j), J[i][k]);
          }
        }
      }
      SignedSum sum(graph);
      for (const auto& [product, negative] : products) sum.add(product, negative);
      if (i == j) sum.double_it();
      if (options.collect_constant_jacobian) {
        rest += eq.P_diffusion[u];
        if (!rest.is_zero()) sum.add(builder.polynomial(rest));
      } else if (!eq.P_diffusion[u].is_zero()) {
        sum.add(expectations.diffusion(u));
      }
      if (eq.P_correction[u].is_zero()) {
      } else if (H) {
        std::vector<std::size_t> gain_products;
        for (std::size_t r = 0; r < eq.p; ++r)
          if (!eq.gain[i][r].is_zero() && !(*H)[r][j].is_zero())
            gain_products.push_back(graph.mul(K_node[i][r], H_node[r][j]));
        std::size_t correction = gain_products[0];  // not empty: the correction is not zero
        for (std::size_t k = 1; k < gain_products.size(); ++k) correction = graph.add(correction, gain_products[k]);
        sum.add(correction, true);
      } else {
        sum.add(builder.polynomial(eq.P_correction[u]), true);
      }
      roots.push_back(sum.result());
    }
  for (const auto& p : eq.x_star_drift) roots.push_back(builder.polynomial(p));
}

// derivatives() with P's drift in loops (p_drift_loops.hpp): the graph computes into the work array
// m's drift, E[J] (every entry, 0 where it is zero), the correction's blocks that the loops do not
// multiply out, and the rest of P's drift per upper entry; the loops do the products. `moments`:
// E[f], E[J] and E[g g^T] over shared moments, as in build_structured.
PDriftLoops build_loops(const FilterEquations& eq, bool moments, GraphBuilder& builder, ExpressionGraph& graph,
                        std::vector<std::size_t>& roots) {
  using Kind = PDriftLoops::WeightEntry::Kind;
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  Expectations expectations(eq, moments, builder);
  // A number is written as it is (a negative one too): an entry of a block costs no operation.
  auto entry = [&](const GiNaC::ex& e) {
    return GiNaC::is_exactly_a<GiNaC::numeric>(e) ? graph.constant(GiNaC::ex_to<GiNaC::numeric>(e))
                                                   : builder.expression(e);
  };
  // A block's entry q: 0, a number, or built (by `build`, the polynomial itself by default).
  auto polynomial_entry = [&](const Polynomial& q, auto build) {
    if (q.is_zero()) return graph.constant(0);
    if (q.terms().size() == 1 && q.terms().begin()->first.is_one()) return entry(q.terms().begin()->second);
    return build();
  };
  auto polynomial = [&](const Polynomial& q) { return polynomial_entry(q, [&] { return builder.polynomial(q); }); };
  auto dense = [](const std::vector<std::vector<GiNaC::ex>>& block) {
    for (const auto& row : block)
      for (const GiNaC::ex& e : row)
        if (e.is_zero()) return false;
    return true;
  };

  PDriftLoops loops;
  loops.n = n;
  for (std::size_t j = 0; j < n; ++j) roots.push_back(expectations.drift(j));
  loops.jacobian_offset = roots.size();
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
      roots.push_back(polynomial_entry(eq.jacobian_term[j][k], [&] { return expectations.jacobian(j, k); }));

  // The correction K (A P): H = A P and K^T = M H in the loops where A (and M) allow, else from the graph.
  const auto H = correction_factor(eq);
  loops.factored = H.has_value();
  if (loops.factored) {
    loops.p = eq.p;
    const auto A = observation_matrix(eq);
    const auto Gt = gain_factor(eq);
    const auto M = A && Gt ? gain_weight(*Gt, *A) : std::nullopt;
    loops.H_in_loops = A && dense(*A);
    if (loops.H_in_loops) {
      loops.observation_offset = roots.size();
      for (const auto& row : *A)
        for (const GiNaC::ex& e : row) roots.push_back(entry(e));
    } else {
      loops.H_offset = roots.size();
      for (const auto& row : *H)
        for (const Polynomial& q : row) roots.push_back(polynomial(q));
    }
    loops.weighted = M.has_value();
    if (loops.weighted) {
      loops.weight.assign(eq.p, std::vector<PDriftLoops::WeightEntry>(eq.p));
      for (std::size_t r = 0; r < eq.p; ++r)
        for (std::size_t s = 0; s < eq.p; ++s) {
          const GiNaC::ex& m = (*M)[r][s];
          if (m.is_zero()) continue;
          if (m == 1) {
            loops.weight[r][s].kind = Kind::One;
            continue;
          }
          loops.weight[r][s] = {Kind::Value, roots.size()};
          roots.push_back(entry(m));
        }
    } else {
      loops.gain_offset = roots.size();
      for (std::size_t r = 0; r < eq.p; ++r)
        for (std::size_t i = 0; i < n; ++i) roots.push_back(polynomial(eq.gain[i][r]));
    }
  }
  loops.rest_offset = roots.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      const std::size_t u = vars.upper_index(i, j);
      // E[g g^T], less the correction where the loops do not compute it.
      const bool corrected = !loops.factored && !eq.P_correction[u].is_zero();
      const Polynomial rest = corrected ? eq.P_diffusion[u] - eq.P_correction[u] : eq.P_diffusion[u];
      loops.rest = loops.rest || !rest.is_zero();
      roots.push_back(corrected ? polynomial(rest)
                                : polynomial_entry(rest, [&] { return expectations.diffusion(u); }));
    }
  return loops;
}

}  // namespace

FunctionCode function_code(const std::string& function, const std::vector<Polynomial>& outputs,
                           const std::string& target, const Model& model, const FilterEquations& eq,
                           const CodegenOptions& options, const FunctionNames& names, const StatementEmitter& emitter) {
  const auto built = built_function(function, model, eq, names,
                                    [&](GraphBuilder& builder, ExpressionGraph&, std::vector<std::size_t>& roots) {
                                      for (const Polynomial& p : outputs) roots.push_back(builder.polynomial(p));
                                    });
  return written(*built, target, names, emitter, options.eliminate_common_subexpressions);
}

// derivatives() may also be built from the derivation's structure: the P
// moment terms are sum_k P_ik J_jk + J_ik P_kj, so each entry of J (E[d_k f_j]
// or its EKF stand-in) is computed once and shared by every P equation,
// instead of being expanded into each. The naive count stays that of the
// expanded equations; the emitted graph is whichever of the two forms needs
// fewer operations after sharing. A user filter has no Jacobian term (its P
// drift is given whole), so it always takes the expanded form. The structured
// form also writes the correction P A^T R^-1 A P as K (A P), K the gain, where
// correction_factor() has checked that this is the same polynomial. For the Gaussian-closure
// kinds a third form writes E[f], E[J] and E[g g^T] over shared moments (moment_form.hpp).
namespace {

// Whether every entry of E[J] (or its EKF stand-in) is nonzero.
bool dense_jacobian(const FilterEquations& eq) {
  for (const auto& row : eq.jacobian_term)
    for (const Polynomial& entry : row)
      if (entry.is_zero()) return false;
  return !eq.jacobian_term.empty();
}

// Whether an entry of E[J] is a number or a parameter expression, which the Collected forms
// collect (none in a dense cubic model: the forms are not built there).
bool constant_jacobian_entry(const FilterEquations& eq) {
  for (const auto& row : eq.jacobian_term)
    for (const Polynomial& entry : row)
      if (constant_entry(entry)) return true;
  return false;
}

// The outputs rates() writes after derivatives' own: the gain (n x p, row-major), then the
// predicted observation.
struct ExtraOutputs {
  const FilterEquations* eq = nullptr;  // null: none
  void append(GraphBuilder& builder, std::vector<std::size_t>& roots, bool gain) const {
    if (!eq) return;
    if (gain)
      for (const auto& row : eq->gain)
        for (const Polynomial& q : row) roots.push_back(builder.polynomial(q));
    for (const Polynomial& q : eq->predicted_observation) roots.push_back(builder.polynomial(q));
  }
};

std::unique_ptr<BuiltFunction> built_form(DerivativesForm form, const std::string& function, const Model& model,
                                          const FilterEquations& eq, const FunctionNames& names,
                                          const ExtraOutputs& extras) {
  switch (form) {
    case DerivativesForm::Expanded:
      // P's drift (upper triangle) is summed one entry at a time, as the graph takes it.
      return built_function(function, model, eq, names,
                            [&](GraphBuilder& builder, ExpressionGraph&, std::vector<std::size_t>& roots) {
                              for_each_expanded_output(
                                  eq, [&](const Polynomial& p) { roots.push_back(builder.polynomial(p)); });
                              extras.append(builder, roots, true);
                            });
    case DerivativesForm::Structured:
    case DerivativesForm::Moments:
    case DerivativesForm::CollectedStructured:
    case DerivativesForm::CollectedMoments:
      return built_function(function, model, eq, names,
                            [&](GraphBuilder& builder, ExpressionGraph& graph, std::vector<std::size_t>& roots) {
                              const StructuredOptions options{
                                  form == DerivativesForm::Moments || form == DerivativesForm::CollectedMoments,
                                  form == DerivativesForm::CollectedStructured ||
                                      form == DerivativesForm::CollectedMoments};
                              build_structured(eq, options, builder, graph, roots);
                              extras.append(builder, roots, true);
                            });
    case DerivativesForm::Loops:
    case DerivativesForm::MomentLoops: {
      auto built = built_loops(model, eq, names, [&](GraphBuilder& builder, ExpressionGraph& graph,
                                                     std::vector<std::size_t>& roots) {
        PDriftLoops loops = build_loops(eq, form == DerivativesForm::MomentLoops, builder, graph, roots);
        // rates(): the gain comes from K^T where the correction is factored, else from the graph;
        // what the graph computes follows the rest in the work array and is copied into place.
        loops.tail_offset = roots.size();
        if (extras.eq) {
          loops.gain_out = loops.factored;
          extras.append(builder, roots, !loops.factored);
          loops.tail = roots.size() - loops.tail_offset;
        }
        loops.work_size = roots.size();
        return loops;
      });
      built->function = function;
      built->stats.function = function;
      return built;
    }
  }
  return nullptr;
}

}  // namespace

FunctionCode derivatives_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                              const FunctionNames& names, const StatementEmitter& emitter, DerivativesForm* rates_form) {
  const std::size_t n = eq.n();
  DerivativesForm form = DerivativesForm::Expanded;
  if (!options.eliminate_common_subexpressions || eq.jacobian_term.empty()) {
    if (rates_form) *rates_form = form;
    auto flat = built_form(DerivativesForm::Expanded, "derivatives", model, eq, names, {});
    return written(*flat, names.out, names, emitter, options.eliminate_common_subexpressions);
  }
  // The form with the fewest operations after sharing, the expanded first on a tie, then the
  // others in the order below. The structured forms are built first: where the expanded one's count
  // after sharing is bound to exceed theirs, its graph is never built (expanded_counts.hpp).
  std::unique_ptr<BuiltFunction> kept;
  const bool moments = eq.expectation_sources && eq.expectation_sources->drift.size() == n;
  for (DerivativesForm candidate_form : {DerivativesForm::Structured, DerivativesForm::Moments,
                                         DerivativesForm::CollectedStructured, DerivativesForm::CollectedMoments}) {
    const bool collected =
        candidate_form == DerivativesForm::CollectedStructured || candidate_form == DerivativesForm::CollectedMoments;
    if ((candidate_form == DerivativesForm::Moments || candidate_form == DerivativesForm::CollectedMoments) &&
        !moments)
      continue;
    if (collected && !constant_jacobian_entry(eq)) continue;
    auto candidate = built_form(candidate_form, "derivatives", model, eq, names, {});
    if (!kept || candidate->stats.cse.total() < kept->stats.cse.total()) {
      kept = std::move(candidate);
      form = candidate_form;
    }
  }
  const std::optional<ExpandedCounts> counted = expanded_counts(eq);
  OpCounts naive;  // the count of the expanded equations, whichever form is written
  if (counted && counted->shared_lower_bound > kept->stats.cse.total()) {
    naive = counted->naive;
  } else {
    auto flat = built_form(DerivativesForm::Expanded, "derivatives", model, eq, names, {});
    naive = flat->stats.naive;
    if (flat->stats.cse.total() <= kept->stats.cse.total()) {
      kept = std::move(flat);
      form = DerivativesForm::Expanded;
    }
  }
  if (rates_form) *rates_form = form;
  // P's drift in loops over dense blocks (p_drift_loops.hpp), over the same expectations as the
  // kept form: where E[J] is dense, or where the loops need no more operations. For a dense E[J]
  // the loops do the straight-line form's products, and code that is loops is what compilers
  // vectorise and what fits an instruction cache; the straight-line form may still count fewer
  // operations where coefficients happen to be equal (graph sharing multiplies P_ik by 0.3 once
  // for every entry of E[J] that is 0.3), which depends on the model's numbers, not its structure.
  // rates() takes them from kMinLoopDimension on, derivatives() alone from kMinLoopDimensionAlone.
  // A delayed filter's x* drift follows P's in `out`, which the loops do not write.
  if (n >= kMinLoopDimension && eq.x_star_drift.empty()) {
    const DerivativesForm loop_form =
        form == DerivativesForm::Moments || form == DerivativesForm::CollectedMoments ? DerivativesForm::MomentLoops
                                                                                      : DerivativesForm::Loops;
    auto candidate = built_form(loop_form, "derivatives", model, eq, names, {});
    if (dense_jacobian(eq) || candidate->stats.cse.total() <= kept->stats.cse.total()) {
      if (rates_form) *rates_form = loop_form;
      if (n >= kMinLoopDimensionAlone) kept = std::move(candidate);
    }
  }
  kept->stats.naive = naive;
  return written(*kept, names.out, names, emitter, true);
}

FunctionCode rates_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                        const FunctionNames& names, const StatementEmitter& emitter, DerivativesForm form,
                        const OpCounts& naive) {
  auto built = built_form(form, "rates", model, eq, names, ExtraOutputs{&eq});
  built->stats.naive = naive;
  built->stats.in_totals = false;
  return written(*built, names.out, names, emitter, options.eliminate_common_subexpressions);
}

std::string counts_text(const OpCounts& c) {
  return std::to_string(c.total()) + " (" + std::to_string(c.adds) + " add, " + std::to_string(c.muls) + " mul, " +
         std::to_string(c.divs) + " div, " + std::to_string(c.calls) + " call)";
}

std::string ops_comment(const FunctionStats& s) {
  return "Ops: " + counts_text(s.naive) + " without CSE, " + counts_text(s.cse) + " with CSE.";
}

FunctionNames function_names(const Model& model) {
  LocalNames names(filter_input_names(model));
  FunctionNames f;
  f.time = model.time.get_name();
  f.state = names.take("state");
  f.params = names.take("params");
  f.out = names.take("out");
  f.K = names.take("K");
  f.h = names.take("h");
  // Taken last, so that the names above are spelled as before for every model.
  f.delayed = names.take("delayed");
  f.shared = names.take("shared");  // the local array of a function written in parts (split_body)
  f.L = names.take("L");
  f.c = names.take("c");
  // The loops of P's drift (p_drift_loops.hpp), taken after the others for the same reason.
  f.work = names.take("w");
  f.full_P = names.take("P_full");
  f.JP = names.take("JP");
  f.gain_T = names.take("K_T");
  f.H = names.take("H");
  f.sum = names.take("S");
  f.i = names.take("i");
  f.j = names.take("j");
  f.u = names.take("u");
  f.JP_T = names.take("JP_T");  // after the others, for the same reason
  f.temporary_prefix = names.temporary_prefix();
  return f;
}

std::vector<GiNaC::numeric> initial_values(const Model& model, const FilterVariables& vars, bool x_star) {
  std::vector<GiNaC::numeric> values(vars.count() + (x_star ? vars.n() : 0), 0);
  if (model.initial) {
    for (std::size_t i = 0; i < vars.n(); ++i) {
      values[vars.m(i)] = model.initial->m0[i];
      for (std::size_t j = i; j < vars.n(); ++j) values[vars.P(i, j)] = model.initial->P0[i][j];
      if (x_star) values[vars.count() + i] = model.initial->m0[i];
    }
    // A moment filter starts from the Gaussian prior's moments.
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q)
      values[vars.first_higher_moment() + q] = gaussian_central_moment(vars.higher_moments()[q], model.initial->P0);
  }
  return values;
}

ir::Block initial_state_statements(const std::vector<GiNaC::numeric>& values) {
  ir::Block body;
  for (std::size_t v = 0; v < values.size(); ++v) body.push_back(ir::assign(ir::element("state", v), ir::number(values[v])));
  return body;
}

}  // namespace pfgen::codegen
