// The filter parts the observation modules describe: the sampled prediction's statements
// (sampled_predict.hpp) as each backend's emitter writes them, the same nodes giving C++'s, C's and
// Rust's text, with the local-array nodes (ir::local_arrays, ir::local_array) spelled as each
// language declares and passes an array; the delayed history's ring parts, built for the delay's
// case (delayed_history.hpp), as C and Rust write them; the Heun step's statements
// (codegen/heun_step.hpp) and the continuous, polynomial and delayed files' steps composed of them;
// and the layouts of a loop's or a conditional's block.
#include <catch2/catch.hpp>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/rust/rust_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/heun_step.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/observations/delayed/delayed_history.hpp"
#include "pfgen/observations/sampled/sampled_predict.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

TEST_CASE("local arrays: declared together and passed whole, as each language does", "[unit][codegen]") {
  const CppEmitter cpp(ScalarMode::Double);
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Float, "tmp", "Params");
  const ir::Block block = {
      ir::local_arrays({"a", "b"}, ir::Type::Scalar, ir::sub(ir::name("N"), ir::name("M"))),
      ir::call_statement("f", {ir::local_array("a", false), ir::local_array("b", true)}),
  };
  CHECK(cpp.block(block) == "  std::array<Scalar, N - M> a{}, b{};\n  f(a.data(), b.data());\n");
  CHECK(c.block(block) == "  float a[N - M], b[N - M];\n  f(a, b);\n");
  CHECK(rust.block(block, "    ") ==
        "    let mut a: [Scalar; N - M] = [0.0; N - M];\n    let mut b: [Scalar; N - M] = [0.0; N - M];\n    f(&a, &mut b);\n");
}

TEST_CASE("sampled predict: Heun's and cd-euler's sub-step as statements for every language", "[unit][codegen]") {
  const CEmitter c(ScalarMode::Double, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Double, "tmp", "Params");
  CHECK(c.block(predict_statements(false)) ==
        "  double first[ns_m_f_state_size], predicted[ns_m_f_state_size], second[ns_m_f_state_size];\n"
        "  ns_m_f_derivatives(t, state, params, first);\n"
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) predicted[i] = state[i] + first[i] * dt;\n"
        "  ns_m_f_derivatives(t + dt, predicted, params, second);\n"
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) state[i] += (first[i] + second[i]) * dt / 2.0;\n");
  CHECK(c.block(predict_statements(true)) ==
        "  double rates[ns_m_f_state_size];\n"
        "  double square[ns_m_f_state_size - ns_m_f_n];\n"
        "  ns_m_f_derivatives(t, state, params, rates);\n"
        "  ns_m_f_euler_square(t, state, params, square);\n"
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) state[i] += rates[i] * dt;\n"
        "  for (size_t i = ns_m_f_n; i < ns_m_f_state_size; ++i) state[i] += square[i - ns_m_f_n] * dt * dt;\n");
  CHECK(rust_indent(rust.block(predict_statements(true))) ==
        "    let mut rates: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
        "    let mut square: [Scalar; STATE_SIZE - STATES] = [0.0; STATE_SIZE - STATES];\n"
        "    derivatives(t, state, params, &mut rates);\n"
        "    euler_square(t, state, params, &mut square);\n"
        "    for i in 0..STATE_SIZE {\n"
        "        state[i] += rates[i] * dt;\n"
        "    }\n"
        "    for i in STATES..STATE_SIZE {\n"
        "        state[i] += square[i - STATES] * dt * dt;\n"
        "    }\n");
}

TEST_CASE("delayed history: the ring's parts for each delay's case are statements every backend holding the ring writes",
          "[unit][codegen]") {
  // C and Rust write the ring for the case (no history, a one-step history whose end is the start
  // state, a ring), with and without x*; C++'s template places the form for any delay (next case),
  // so it has no key for these blocks.
  const CEmitter c(ScalarMode::Double, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Double, "tmp", "Params");
  std::set<std::string> texts;
  for (std::size_t steps : {0, 1, 50})
    for (bool x_star : {false, true}) {
      const auto blocks = history_statements(steps, x_star);
      CHECK(blocks.size() == 3);
      for (const auto& [key, block] : blocks) {
        INFO(key);
        CHECK_FALSE(block.empty());
        CHECK(values_in_template("c/delayed_filter.c.tmpl", {{key, ""}}).count(key) == 1);
        CHECK(values_in_template("rust/delayed_filter.rs.tmpl", {{key, ""}}).count(key) == 1);
        CHECK(values_in_template("cpp/delayed_filter.hpp.tmpl", {{key, ""}}).empty());
        texts.insert(key + ":" + c.block(block));
      }
    }
  // Each case its own read; the empty history's initial and store parts apart from the ring's.
  CHECK(texts.size() == 10);

  // C's text is the ring as the C backend has always written it.
  const auto ring = history_statements(50, true);
  CHECK(c.block(ring.at("initial_history_body")) ==
        "  for (size_t slot = 0; slot < ns_m_f_delay_steps; ++slot)\n"
        "    for (size_t i = 0; i < ns_m_f_history_width; ++i)\n"
        "      history[slot * ns_m_f_history_width + i] = i < ns_m_f_n ? state[i] : state[ns_m_f_state_size - "
        "ns_m_f_n + (i - ns_m_f_n)];\n");
  CHECK(c.block(ring.at("history_store")) ==
        "  {\n"
        "    double* slot = history + (k % ns_m_f_delay_steps) * ns_m_f_history_width;\n"
        "    for (size_t i = 0; i < ns_m_f_history_width; ++i) slot[i] = i < ns_m_f_n ? state[i] : "
        "state[ns_m_f_state_size - ns_m_f_n + (i - ns_m_f_n)];\n"
        "  }\n");
  CHECK(c.block(ring.at("delayed_inputs_body")) ==
        "  const double* m_past = history + ((k + offset) % ns_m_f_delay_steps) * ns_m_f_history_width;\n"
        "  const double* x_star_past = m_past + ns_m_f_n;\n"
        "  (void)start;\n"
        "  for (size_t i = 0; i < ns_m_f_n; ++i) delayed[i] = m_past[i];\n"
        "  {\n"
        "    const double* x_star_now = now + (ns_m_f_state_size - ns_m_f_n);\n"
        "    for (size_t i = 0; i < ns_m_f_n; ++i) {\n"
        "      if (k < ns_m_f_delay_steps || x_star_now[i] == 0.0)\n"
        "        delayed[ns_m_f_n + i] = 0.0;\n"
        "      else\n"
        "        delayed[ns_m_f_n + i] = x_star_past[i] / x_star_now[i];\n"
        "    }\n"
        "  }\n");
  CHECK(c.block(history_statements(1, false).at("delayed_inputs_body")) ==
        "  const double* m_past = history + ((k + offset) % ns_m_f_delay_steps) * ns_m_f_history_width;\n"
        "  if (offset == 1) {\n"
        "    m_past = start;\n"
        "  }\n"
        "  for (size_t i = 0; i < ns_m_f_n; ++i) delayed[i] = m_past[i];\n"
        "  (void)now;\n");
  CHECK(c.block(history_statements(0, true).at("delayed_inputs_body")) ==
        "  (void)history;\n  (void)start;\n  (void)k;\n  (void)offset;\n"
        "  for (size_t i = 0; i < ns_m_f_n; ++i) delayed[i] = now[i];\n"
        "  for (size_t i = 0; i < ns_m_f_n; ++i) delayed[ns_m_f_n + i] = 1.0;\n");
  CHECK(c.block(history_statements(0, false).at("history_store")) == "  (void)history;\n");

  // Rust's: the same statements; the views rebound at the end of a one-step history are `let mut`
  // slices, the others immutable (rustc denies an unused `mut`).
  CHECK(rust_indent(rust.block(history_statements(1, true).at("delayed_inputs_body"))) ==
        "    let mut m_past: &[Scalar] = &history[((k + offset) % DELAY_STEPS) * HISTORY_WIDTH..((k + offset) % "
        "DELAY_STEPS) * HISTORY_WIDTH + HISTORY_WIDTH];\n"
        "    let mut x_star_past: &[Scalar] = &m_past[STATES..STATES + STATES];\n"
        "    if offset == 1 {\n"
        "        m_past = &start[..];\n"
        "        x_star_past = &start[STATE_SIZE - STATES..STATE_SIZE - STATES + STATES];\n"
        "    }\n"
        "    for i in 0..STATES {\n"
        "        delayed[i] = m_past[i];\n"
        "    }\n"
        "    {\n"
        "        let x_star_now = &now[STATE_SIZE - STATES..STATE_SIZE - STATES + STATES];\n"
        "        for i in 0..STATES {\n"
        "            if k < DELAY_STEPS || x_star_now[i] == 0.0 {\n"
        "                delayed[STATES + i] = 0.0;\n"
        "            } else {\n"
        "                delayed[STATES + i] = x_star_past[i] / x_star_now[i];\n"
        "            }\n"
        "        }\n"
        "    }\n");
  CHECK(rust_indent(rust.block(ring.at("history_store"))) ==
        "    {\n"
        "        let slot = &mut history[(k % DELAY_STEPS) * HISTORY_WIDTH..(k % DELAY_STEPS) * HISTORY_WIDTH + "
        "HISTORY_WIDTH];\n"
        "        for i in 0..HISTORY_WIDTH {\n"
        "            slot[i] = if i < STATES { state[i] } else { state[STATE_SIZE - STATES + (i - STATES)] };\n"
        "        }\n"
        "    }\n");
}

TEST_CASE("delayed history for any delay: one form of every ring part, chosen by the file's constants, that C++ writes",
          "[unit][codegen]") {
  // C++'s template places this form (its constexpr constants fold the tests), the others the case's.
  const auto blocks = any_delay_history_statements();
  CHECK(blocks.size() == 3);
  for (const auto& [key, block] : blocks) {
    INFO(key);
    CHECK(values_in_template("cpp/delayed_filter.hpp.tmpl", {{key, ""}}).count(key) == 1);
    CHECK(values_in_template("c/delayed_filter.c.tmpl", {{key, ""}}).empty());
    CHECK(values_in_template("rust/delayed_filter.rs.tmpl", {{key, ""}}).empty());
  }
  // The text C++'s delayed filters have always had, in every scalar mode (Scalar is the alias or
  // the template parameter; its whole numbers are Scalar(k) in each).
  for (ScalarMode mode : {ScalarMode::Template, ScalarMode::Float, ScalarMode::Double}) {
    const CppEmitter cpp(mode);
    INFO(scalar_mode_name(mode));
    CHECK(cpp.block(blocks.at("any_delay_initial_history_body")) ==
          "  for (std::size_t slot = 0; slot < delay_steps; ++slot)\n"
          "    for (std::size_t i = 0; i < history_width; ++i)\n"
          "      history[slot * history_width + i] = i < n ? state[i] : state[state_size - n + (i - n)];\n");
    CHECK(cpp.block(blocks.at("any_delay_delayed_inputs_body")) ==
          "  const Scalar* m_past = now;\n"
          "  const Scalar* x_star_past = now + (state_size - n);\n"
          "  bool step_starts_before_h = false;\n"
          "  if (delay_steps > 0) {\n"
          "    step_starts_before_h = k < delay_steps;\n"
          "    if (offset == 1 && delay_steps == 1) {\n"
          "      m_past = start;\n"
          "      x_star_past = start + (state_size - n);\n"
          "    } else {\n"
          "      const std::size_t slot = (k + offset) % (delay_steps > 0 ? delay_steps : 1);\n"
          "      m_past = history + slot * history_width;\n"
          "      x_star_past = m_past + n;\n"
          "    }\n"
          "  }\n"
          "  for (std::size_t i = 0; i < n; ++i) delayed[i] = m_past[i];\n"
          "  if constexpr (uses_x_star) {\n"
          "    const Scalar* x_star_now = now + (state_size - n);\n"
          "    for (std::size_t i = 0; i < n; ++i) {\n"
          "      if (delay_steps == 0)\n"
          "        delayed[n + i] = Scalar(1);\n"
          "      else if (step_starts_before_h || x_star_now[i] == Scalar(0))\n"
          "        delayed[n + i] = Scalar(0);\n"
          "      else\n"
          "        delayed[n + i] = x_star_past[i] / x_star_now[i];\n"
          "    }\n"
          "  } else {\n"
          "    (void)x_star_past;\n"
          "    (void)step_starts_before_h;\n"
          "  }\n");
    CHECK(cpp.block(blocks.at("any_delay_history_store")) ==
          "  if (delay_steps > 0) {\n"
          "    Scalar* slot = history + (k % (delay_steps > 0 ? delay_steps : 1)) * history_width;\n"
          "    for (std::size_t i = 0; i < history_width; ++i) slot[i] = i < n ? state[i] : state[state_size - n + (i - "
          "n)];\n"
          "  }\n");
  }
}

TEST_CASE("statement layouts: a C-family block on the header's line, the next line or in braces; Rust always braces",
          "[unit][codegen]") {
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Float, "tmp", "Params");
  const auto one = [] { return ir::Block{ir::assign(ir::element("a", ir::name("i")), ir::number(0))}; };
  const ir::Statement loop = ir::loop("i", ir::Type::Size, ir::integer(0), ir::name("N"), one());
  CHECK(c.block({loop}) == "  for (size_t i = 0; i < N; ++i) a[i] = 0.0f;\n");
  CHECK(c.block({ir::laid_out(loop, ir::Layout::NextLine)}) == "  for (size_t i = 0; i < N; ++i)\n    a[i] = 0.0f;\n");
  CHECK(c.block({ir::laid_out(loop, ir::Layout::Braced)}) == "  for (size_t i = 0; i < N; ++i) {\n    a[i] = 0.0f;\n  }\n");
  CHECK(rust.block({ir::laid_out(loop, ir::Layout::NextLine)}) == rust.block({loop}));
  const ir::Statement choice = ir::conditional(ir::less(ir::name("i"), ir::name("N")), one(), one());
  CHECK(c.block({choice}) == "  if (i < N)\n    a[i] = 0.0f;\n  else\n    a[i] = 0.0f;\n");
  CHECK(rust.block({choice}) == "  if i < N {\n    a[i] = 0.0;\n  } else {\n    a[i] = 0.0;\n  }\n");
  const ir::Expr pick = ir::select(ir::logical_or(ir::equal(ir::name("k"), ir::integer(1)), ir::name("b")),
                                   ir::rem(ir::name("k"), ir::name("N")), ir::integer(0));
  CHECK(c.expression(pick) == "k == 1 || b ? k % N : 0");
  CHECK(rust.expression(pick) == "if k == 1 || b { k % N } else { 0 }");
  // An else of one conditional continues the chain.
  const ir::Statement chain = ir::conditional(ir::equal(ir::name("k"), ir::integer(0)), one(), {choice});
  CHECK(c.block({chain}) == "  if (k == 0)\n    a[i] = 0.0f;\n  else if (i < N)\n    a[i] = 0.0f;\n  else\n    a[i] = 0.0f;\n");
  CHECK(rust.block({chain}) ==
        "  if k == 0 {\n    a[i] = 0.0;\n  } else if i < N {\n    a[i] = 0.0;\n  } else {\n    a[i] = 0.0;\n  }\n");
  const ir::Statement braced_chain = ir::conditional(ir::name("b"), {one()[0], one()[0]}, {choice});
  CHECK(c.block({braced_chain}) ==
        "  if (b) {\n    a[i] = 0.0f;\n    a[i] = 0.0f;\n  } else if (i < N)\n    a[i] = 0.0f;\n  else\n    a[i] = 0.0f;\n");
  // A conditional on the file's constants: C++ folds it (if constexpr), C and Rust test it.
  const ir::Statement constant_choice =
      ir::compile_time_conditional(ir::dimension("uses_x_star"), one(), {ir::unused("x")});
  CHECK(CppEmitter(ScalarMode::Float).block({constant_choice}) ==
        "  if constexpr (uses_x_star)\n    a[i] = 0.0f;\n  else\n    (void)x;\n");
  CHECK(c.block({constant_choice}) == "  if (ns_m_f_uses_x_star)\n    a[i] = 0.0f;\n  else\n    (void)x;\n");
  CHECK(rust.block({constant_choice}) == "  if USES_X_STAR {\n    a[i] = 0.0;\n  } else {\n    let _ = x;\n  }\n");
  // A variable (assigned again), a truth value, `and`, a view of a whole array.
  const ir::Block locals = {ir::declare_variable("b", ir::Type::Bool, ir::boolean(false)),
                            ir::assign(ir::name("b"), ir::logical_and(ir::name("c"), ir::name("d"))),
                            ir::rebound_view("v", "a"), ir::view("w", "a", ir::integer(1), ir::integer(2), false)};
  CHECK(c.block(locals) ==
        "  int b = 0;\n  b = c && d;\n  const float* v = a;\n  const float* w = a + 1;\n");
  CHECK(rust.block(locals) ==
        "  let mut b: bool = false;\n  b = c && d;\n  let mut v: &[Scalar] = &a[..];\n  let w = &a[1..1 + 2];\n");
  CHECK(c.expression(ir::slice("a")) == "a");
  CHECK(rust.expression(ir::slice("a", ir::grouped(ir::sub(ir::name("N"), ir::name("M"))), ir::name("M"))) ==
        "&a[N - M..N - M + M]");
}

TEST_CASE("Heun step loops: an increment's parts and the step's loops, as loops or written out, in every language",
          "[unit][codegen]") {
  const CppEmitter cpp(ScalarMode::Template);
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Double, "tmp", "Params");
  auto innovation = [](const ir::Expr& r) { return ir::element("innovation", r); };
  auto rates = [](const ir::Expr& i) { return ir::element("rates", i); };
  const ir::Expr dt = ir::name("dt");
  {
    const HeunStepLoops loops(2, 1, 5, false);
    ir::Block increment;
    loops.innovation(increment, "yhat", dt);
    loops.scaled_rates(increment, rates, dt);
    loops.state_gain(increment, "K", innovation);
    loops.covariance_gain(increment, "L", innovation);
    CHECK(c.block(increment) ==
          "  for (size_t r = 0; r < ns_m_f_p; ++r) innovation[r] = dy[r] - yhat[r] * dt;\n"
          "  for (size_t i = 0; i < ns_m_f_state_size; ++i) delta[i] = rates[i] * dt;\n"
          "  for (size_t i = 0; i < ns_m_f_n; ++i)\n"
          "    for (size_t r = 0; r < ns_m_f_p; ++r) delta[i] += K[i * ns_m_f_p + r] * innovation[r];\n"
          "  for (size_t u = 0; u < ns_m_f_state_size - ns_m_f_n; ++u)\n"
          "    for (size_t r = 0; r < ns_m_f_p; ++r) delta[ns_m_f_n + u] += L[u * ns_m_f_p + r] * innovation[r];\n");
    CHECK(cpp.block(loops.predicted()) ==
          "  for (std::size_t i = 0; i < state_size; ++i) predicted[i] = state[i] + first[i];\n");
    CHECK(cpp.block(loops.average()) ==
          "  for (std::size_t i = 0; i < state_size; ++i) state[i] += (first[i] + second[i]) / Scalar(2);\n");
    CHECK(c.block(loops.average()) ==
          "  for (size_t i = 0; i < ns_m_f_state_size; ++i) state[i] += (first[i] + second[i]) / 2.0f;\n");
    ir::Block covariance;
    loops.covariance_gain(covariance, "L", innovation);
    CHECK(rust_indent(rust.block(covariance)) ==
          "    for u in 0..STATE_SIZE - STATES {\n"
          "        for r in 0..OBSERVATIONS {\n"
          "            delta[STATES + u] += L[u * OBSERVATIONS + r] * innovation[r];\n"
          "        }\n"
          "    }\n");
    CHECK(rust_indent(rust.block(loops.average())) ==
          "    for i in 0..STATE_SIZE {\n"
          "        state[i] += (first[i] + second[i]) / 2.0;\n"
          "    }\n");
    // step()'s predictor and corrector around the module's increment, a call of the file's internal
    // function: C's prefixed, C++'s in namespace detail, Rust's by its name.
    const ir::Block step = loops.predictor_corrector([&](bool end, const ir::Expr& state, const ir::Expr& delta) {
      return ir::Block{ir::call_internal_function(
          "increment", {end ? ir::add(ir::name("t"), dt) : ir::name("t"), state, dt, ir::name("dy"), delta})};
    });
    CHECK(cpp.block(step) ==
          "  std::array<Scalar, state_size> first{}, predicted{}, second{};\n"
          "  detail::increment(t, state, dt, dy, first.data());\n"
          "  for (std::size_t i = 0; i < state_size; ++i) predicted[i] = state[i] + first[i];\n"
          "  detail::increment(t + dt, predicted.data(), dt, dy, second.data());\n");
    CHECK(c.block(step) ==
          "  float first[ns_m_f_state_size], predicted[ns_m_f_state_size], second[ns_m_f_state_size];\n"
          "  ns_m_f_increment(t, state, dt, dy, first);\n"
          "  for (size_t i = 0; i < ns_m_f_state_size; ++i) predicted[i] = state[i] + first[i];\n"
          "  ns_m_f_increment(t + dt, predicted, dt, dy, second);\n");
    CHECK(rust_indent(rust.block(step)) ==
          "    let mut first: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
          "    let mut predicted: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
          "    let mut second: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
          "    increment(t, state, dt, dy, &mut first);\n"
          "    for i in 0..STATE_SIZE {\n"
          "        predicted[i] = state[i] + first[i];\n"
          "    }\n"
          "    increment(t + dt, &predicted, dt, dy, &mut second);\n");
    // Arrays written before they are read: C++ leaves them unfilled, C and Rust as before.
    auto none = [](bool, const ir::Expr&, const ir::Expr&) { return ir::Block{}; };
    const ir::Block unfilled = {loops.predictor_corrector(none, true).front()};
    CHECK(cpp.block(unfilled) ==
          "  std::array<Scalar, state_size> first, predicted, second;  // written before they are read\n");
    CHECK(c.block(unfilled) ==
          "  float first[ns_m_f_state_size], predicted[ns_m_f_state_size], second[ns_m_f_state_size];\n");
  }
  {
    // Written out: one statement per entry, the loops' order, the indices as numbers.
    const HeunStepLoops loops(1, 2, 2, true);
    ir::Block increment;
    loops.state_gain(increment, "K", innovation);
    loops.covariance_gain(increment, "L", innovation);
    CHECK(c.block(increment) ==
          "  delta[0] += K[0] * innovation[0];\n"
          "  delta[0] += K[1] * innovation[1];\n"
          "  delta[1] += L[0] * innovation[0];\n"
          "  delta[1] += L[1] * innovation[1];\n");
    CHECK(c.block(loops.predicted()) ==
          "  predicted[0] = state[0] + first[0];\n"
          "  predicted[1] = state[1] + first[1];\n");
  }
}

namespace {

// The generated file of `model_file`'s filter `filter` in `language` whose path ends with `suffix`
// (names under the default namespace, pfgen_models).
std::string filter_text(const std::string& model_file, const std::string& filter, const std::string& language,
                        const std::string& suffix) {
  const Model model = load_model_file(pfgen_test::source_dir() + "/examples/" + model_file);
  codegen::CodegenOptions options;
  options.language = language;
  options.scalar = language == "cpp" ? ScalarMode::Template : ScalarMode::Double;
  options.grid_step = model.simulation.dt;
  for (const auto& file : codegen::generate_filter_code(model, derive_named_filter(model, filter), options).files)
    if (file.relative_path.size() >= suffix.size() &&
        file.relative_path.compare(file.relative_path.size() - suffix.size(), suffix.size(), suffix) == 0)
      return file.contents;
  return "";
}

// Whether `text` holds `part`, each `$` in it standing for the C file's prefix `prefix`.
bool contains(const std::string& text, std::string part, const std::string& prefix = "") {
  for (std::size_t at = part.find('$'); at != std::string::npos; at = part.find('$', at + prefix.size()))
    part.replace(at, 1, prefix);
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("continuous, polynomial and delayed steps: the increment's and the step's loops are the module's statements "
          "in every language",
          "[unit][codegen]") {
  // Each file's template places the blocks the module built (a template's placeholder without its
  // block fails to fill); the text is the loops the templates held before they were statements.
  const std::string poly_c = filter_text("polynomial/cubic_sensor.yaml", "optimal", "c", ".c");
  const std::string poly_prefix = "pfgen_models_cubic_sensor_optimal";
  // increment()'s arrays and calls: C one array a line, C++ those of one length together.
  CHECK(contains(poly_c,
                 "                      const $_params* params, double* delta) {\n"
                 "  double rates[$_state_size];\n"
                 "  double correction[$_state_size];\n"
                 "  double K[$_n * $_p];\n"
                 "  double L[($_state_size - $_n) * $_p];\n"
                 "  double yhat[$_p];\n"
                 "  double innovation[$_p];\n"
                 "  $_derivatives(t, state, params, rates);\n"
                 "  $_gain(t, state, params, K);\n"
                 "  $_covariance_gain(t, state, params, L);\n"
                 "  $_predicted_observation(t, state, params, yhat);\n"
                 "  $_stratonovich_correction(t, state, params, correction);\n"
                 "  for (size_t r = 0; r < $_p; ++r) innovation[r] = dy[r] - yhat[r] * dt;\n",
                 poly_prefix));
  CHECK(contains(poly_c,
                 "  $_stratonovich_correction(t, state, params, correction);\n"
                 "  for (size_t r = 0; r < $_p; ++r) innovation[r] = dy[r] - yhat[r] * dt;\n"
                 "  for (size_t i = 0; i < $_state_size; ++i) delta[i] = (rates[i] - correction[i]) * dt;\n"
                 "  for (size_t i = 0; i < $_n; ++i)\n"
                 "    for (size_t r = 0; r < $_p; ++r) delta[i] += K[i * $_p + r] * innovation[r];\n"
                 "  for (size_t u = 0; u < $_state_size - $_n; ++u)\n"
                 "    for (size_t r = 0; r < $_p; ++r) delta[$_n + u] += L[u * $_p + r] * innovation[r];\n"
                 "}\n",
                 poly_prefix));
  CHECK(contains(poly_c,
                 "  $_increment(t, state, dt, dy, params, first);\n"
                 "  for (size_t i = 0; i < $_state_size; ++i) predicted[i] = state[i] + first[i];\n"
                 "  $_increment(t + dt, predicted, dt, dy, params, second);\n"
                 "  for (size_t i = 0; i < $_state_size; ++i) state[i] += (first[i] + second[i]) / 2.0;\n"
                 "}\n",
                 poly_prefix));
  const std::string poly_cpp = filter_text("polynomial/cubic_sensor.yaml", "optimal", "cpp", ".hpp");
  CHECK(contains(poly_cpp,
                 "                      Scalar* delta) {\n"
                 "  std::array<Scalar, state_size> rates{}, correction{};\n"
                 "  std::array<Scalar, n * p> K{};\n"
                 "  std::array<Scalar, (state_size - n) * p> L{};\n"
                 "  std::array<Scalar, p> yhat{}, innovation{};\n"
                 "  derivatives(t, state, params, rates.data());\n"
                 "  gain(t, state, params, K.data());\n"
                 "  covariance_gain(t, state, params, L.data());\n"
                 "  predicted_observation(t, state, params, yhat.data());\n"
                 "  stratonovich_correction(t, state, params, correction.data());\n"
                 "  for (std::size_t r = 0; r < p; ++r) innovation[r] = dy[r] - yhat[r] * dt;\n"));
  CHECK(contains(poly_cpp,
                 "  for (std::size_t u = 0; u < state_size - n; ++u)\n"
                 "    for (std::size_t r = 0; r < p; ++r) delta[n + u] += L[u * p + r] * innovation[r];\n"
                 "}\n"));
  CHECK(contains(poly_cpp,
                 "  for (std::size_t i = 0; i < state_size; ++i) state[i] += (first[i] + second[i]) / Scalar(2);\n"
                 "}\n"));
  const std::string poly_rust = filter_text("polynomial/cubic_sensor.yaml", "optimal", "rust", ".rs");
  CHECK(contains(poly_rust,
                 "             delta: &mut [Scalar; STATE_SIZE]) {\n"
                 "    let mut rates: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
                 "    let mut correction: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
                 "    let mut K: [Scalar; STATES * OBSERVATIONS] = [0.0; STATES * OBSERVATIONS];\n"
                 "    let mut L: [Scalar; (STATE_SIZE - STATES) * OBSERVATIONS] = [0.0; (STATE_SIZE - STATES) * OBSERVATIONS];\n"
                 "    let mut yhat: [Scalar; OBSERVATIONS] = [0.0; OBSERVATIONS];\n"
                 "    let mut innovation: [Scalar; OBSERVATIONS] = [0.0; OBSERVATIONS];\n"
                 "    derivatives(t, state, params, &mut rates);\n"));
  CHECK(contains(poly_rust,
                 "    stratonovich_correction(t, state, params, &mut correction);\n"
                 "    for r in 0..OBSERVATIONS {\n"
                 "        innovation[r] = dy[r] - yhat[r] * dt;\n"
                 "    }\n"
                 "    for i in 0..STATE_SIZE {\n"
                 "        delta[i] = (rates[i] - correction[i]) * dt;\n"
                 "    }\n"));

  // The continuous file's step: its arrays written first, its loops written out below 8 states.
  CHECK(contains(filter_text("van_der_pol.yaml", "optimal", "cpp", "optimal.hpp"),
                 "  std::array<Scalar, state_size> first, predicted, second;  // written before they are read\n"
                 "  detail::increment(t, state, dt, dy, params, first.data());\n"
                 "  predicted[0] = state[0] + first[0];\n"));

  const std::string delayed_c = filter_text("delay_linear.yaml", "delay-optimal", "c", ".c");
  const std::string delayed_prefix = "pfgen_models_delay_linear_delay_optimal";
  CHECK(contains(delayed_c,
                 "                      const $_params* params, double* delta) {\n"
                 "  double rates[$_state_size];\n"
                 "  double K[$_n * $_p];\n"
                 "  double h[$_p];\n"
                 "  const double step = $_dt();\n"
                 "  $_derivatives(t, state, delayed, params, rates);\n"
                 "  $_gain(t, state, delayed, params, K);\n"
                 "  $_predicted_observation(t, state, delayed, params, h);\n"
                 "  for (size_t i = 0; i < $_state_size; ++i) delta[i] = rates[i] * step;\n",
                 delayed_prefix));
  CHECK(contains(delayed_c,
                 "const $_params* params) {\n"
                 "  const double t = (double)k * $_dt();\n"
                 "  const double t_end = (double)(k + 1) * $_dt();\n"
                 "  double delayed[$_delayed_size];\n",
                 delayed_prefix));
  CHECK(contains(delayed_c,
                 "  for (size_t i = 0; i < $_state_size; ++i) delta[i] = rates[i] * step;\n"
                 "  for (size_t i = 0; i < $_n; ++i)\n"
                 "    for (size_t r = 0; r < $_p; ++r) delta[i] += K[i * $_p + r] * (dy[r] - h[r] * step);\n"
                 "}\n",
                 delayed_prefix));
  CHECK(contains(delayed_c,
                 "  for (size_t i = 0; i < $_state_size; ++i) predicted[i] = state[i] + first[i];\n"
                 "  $_delayed_inputs(history, state, predicted, k, 1, delayed);\n",
                 delayed_prefix));
  const std::string delayed_cpp = filter_text("delay_linear.yaml", "delay-optimal", "cpp", ".hpp");
  CHECK(contains(delayed_cpp,
                 "                      const Params<Scalar>& params, Scalar* delta) {\n"
                 "  std::array<Scalar, state_size> rates{};\n"
                 "  std::array<Scalar, n * p> K{};\n"
                 "  std::array<Scalar, p> h{};\n"
                 "  const Scalar step = dt<Scalar>();\n"
                 "  derivatives(t, state, delayed, params, rates.data());\n"
                 "  gain(t, state, delayed, params, K.data());\n"
                 "  predicted_observation(t, state, delayed, params, h.data());\n"
                 "  for (std::size_t i = 0; i < state_size; ++i) delta[i] = rates[i] * step;\n"));
  CHECK(contains(delayed_cpp,
                 "const Params<Scalar>& params) {\n"
                 "  const Scalar t = static_cast<Scalar>(k) * dt<Scalar>();\n"
                 "  const Scalar t_end = static_cast<Scalar>(k + 1) * dt<Scalar>();\n"
                 "  std::array<Scalar, delayed_size> delayed{};\n"));
  CHECK(contains(delayed_cpp,
                 "  std::array<Scalar, delayed_size> delayed{};\n"
                 "  std::array<Scalar, state_size> first{}, predicted{}, second{};\n"
                 "  detail::delayed_inputs(history, state, state, k, 0, delayed.data());\n"
                 "  detail::increment(t, state, delayed.data(), dy, params, first.data());\n"
                 "  for (std::size_t i = 0; i < state_size; ++i) predicted[i] = state[i] + first[i];\n"
                 "  detail::delayed_inputs(history, state, predicted.data(), k, 1, delayed.data());\n"
                 "  detail::increment(t_end, predicted.data(), delayed.data(), dy, params, second.data());\n"));
  CHECK(contains(delayed_cpp, "  }\n  for (std::size_t i = 0; i < state_size; ++i) state[i] += (first[i] + second[i]) "
                              "/ Scalar(2);\n}\n"));
  const std::string delayed_rust = filter_text("delay_linear.yaml", "delay-optimal", "rust", ".rs");
  CHECK(contains(delayed_rust,
                 "            params: &Params) {\n"
                 "    let t: Scalar = k as Scalar * dt();\n"
                 "    let t_end: Scalar = (k + 1) as Scalar * dt();\n"
                 "    let mut delayed: [Scalar; DELAYED_SIZE] = [0.0; DELAYED_SIZE];\n"));
  CHECK(contains(delayed_rust,
                 "             params: &Params, delta: &mut [Scalar; STATE_SIZE]) {\n"
                 "    let mut rates: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
                 "    let mut K: [Scalar; STATES * OBSERVATIONS] = [0.0; STATES * OBSERVATIONS];\n"
                 "    let mut h: [Scalar; OBSERVATIONS] = [0.0; OBSERVATIONS];\n"
                 "    let step: Scalar = dt();\n"
                 "    derivatives(t, state, delayed, params, &mut rates);\n"
                 "    gain(t, state, delayed, params, &mut K);\n"
                 "    predicted_observation(t, state, delayed, params, &mut h);\n"
                 "    for i in 0..STATE_SIZE {\n"
                 "        delta[i] = rates[i] * step;\n"
                 "    }\n"
                 "    for i in 0..STATES {\n"
                 "        for r in 0..OBSERVATIONS {\n"
                 "            delta[i] += K[i * OBSERVATIONS + r] * (dy[r] - h[r] * step);\n"
                 "        }\n"
                 "    }\n"
                 "}\n"));
}

TEST_CASE("Heun-step templates: increment()'s and step()'s bodies are the module's blocks alone, in every language",
          "[unit][codegen]") {
  // Each body is placeholders only, up to its closing brace: the statements are the module's.
  const std::regex blocks_only(R"(^(\{\{[a-z_]+\}\})+\}\n)");
  struct Frame {
    std::string language, suffix, increment, step;
  };
  const std::vector<Frame> frames = {{"cpp", ".hpp.tmpl", "inline void increment(", "inline void step("},
                                     {"c", ".c.tmpl", "_increment({{scalar}} t", "_step({{scalar}}* state"},
                                     {"rust", ".rs.tmpl", "fn increment(", "pub fn step("}};
  for (const Frame& frame : frames)
    for (const std::string layout : {"filter", "polynomial_filter", "delayed_filter"}) {
      const std::string name = frame.language + "/" + layout + frame.suffix;
      const std::string text = expanded_template(name);
      for (const std::string& header : {frame.increment, frame.step}) {
        INFO(name << ": " << header);
        const std::size_t at = text.find(header);
        REQUIRE(at != std::string::npos);
        const std::size_t body = text.find(") {\n", at);
        REQUIRE(body != std::string::npos);
        CHECK(std::regex_search(text.substr(body + 4), blocks_only));
      }
    }
}
