// The delayed filter's history ring as statements (delayed_history.hpp).
#include "pfgen/observations/delayed/delayed_history.hpp"

#include <utility>

namespace pfgen::codegen {
namespace {

using ir::Expr;

Expr dim(const char* name) { return ir::dimension(name); }
Expr i() { return ir::name("i"); }

// Entry i of a history slot from the state: m's entries, then x*'s (the state's last n).
Expr slot_entry() {
  return ir::select(ir::less(i(), dim("n")), ir::element("state", i()),
                    ir::element("state", ir::add(ir::sub(dim("state_size"), dim("n")),
                                                 ir::grouped(ir::sub(i(), dim("n"))))));
}

ir::Statement over_history_width(ir::Statement body) {
  return ir::loop("i", ir::Type::Size, ir::integer(0), dim("history_width"), {std::move(body)});
}

Expr state_x_star_offset() { return ir::grouped(ir::sub(dim("state_size"), dim("n"))); }

// Every slot holds the pre-history: the initial state's m (and x*). No slot, no pass.
ir::Statement fill_every_slot() {
  ir::Statement fill = ir::laid_out(
      over_history_width(ir::assign(
          ir::element("history", ir::add(ir::mul(ir::name("slot"), dim("history_width")), i())), slot_entry())),
      ir::Layout::NextLine);
  return ir::loop("slot", ir::Type::Size, ir::integer(0), dim("delay_steps"), {std::move(fill)});
}

ir::Block initial_history(std::size_t delay_steps) {
  if (delay_steps == 0) return {ir::unused("state"), ir::unused("history")};
  return {fill_every_slot()};
}

// The start state enters slot k mod `slots`.
ir::Block store_in_slot(Expr slots) {
  Expr offset = ir::mul(ir::grouped(ir::rem(ir::name("k"), std::move(slots))), dim("history_width"));
  return {ir::view("slot", "history", std::move(offset), dim("history_width"), true),
          over_history_width(ir::assign(ir::element("slot", i()), slot_entry()))};
}

ir::Block history_store(std::size_t delay_steps) {
  if (delay_steps == 0) return {ir::unused("history")};
  return {ir::scope(store_in_slot(dim("delay_steps")))};
}

ir::Statement over_n(Expr target_offset, Expr value) {
  Expr target = target_offset.kind == Expr::Kind::Integer ? i() : ir::add(std::move(target_offset), i());
  return ir::loop("i", ir::Type::Size, ir::integer(0), dim("n"), {ir::assign(ir::element("delayed", std::move(target)),
                                                                             std::move(value))});
}

// Phi*_ii (delayed[n + i]) = x*_i(t - h) / x*_i(t), 0 where x*_i(t) = 0 and over every step that
// starts before h (`before_h`); `zero`: 0 as the form writes it.
ir::Statement phi_ratio(Expr before_h, Expr zero) {
  auto phi = [] { return ir::element("delayed", ir::add(dim("n"), i())); };
  return ir::conditional(
      ir::logical_or(std::move(before_h), ir::equal(ir::element("x_star_now", i()), zero)), {ir::assign(phi(), zero)},
      {ir::assign(phi(), ir::div(ir::element("x_star_past", i()), ir::element("x_star_now", i())))});
}

// x*(t) viewed in `now`, and Phi*'s diagonal entry by entry.
ir::Block phi_star_over_n(ir::Statement entry) {
  return {ir::view("x_star_now", "now", state_x_star_offset(), dim("n"), false),
          ir::laid_out(ir::loop("i", ir::Type::Size, ir::integer(0), dim("n"), {std::move(entry)}), ir::Layout::Braced)};
}

ir::Statement phi_star() {
  return ir::scope(phi_star_over_n(phi_ratio(ir::less(ir::name("k"), dim("delay_steps")), ir::number(0))));
}

// m(t - h) (and Phi*) at grid index k - delay_steps + offset: `now` itself without a history; else
// the ring's slot, or with a one-step history at the step's end (offset 1), the start state.
ir::Block delayed_inputs(std::size_t delay_steps, bool x_star) {
  if (delay_steps == 0) {
    ir::Block body = {ir::unused("history"), ir::unused("start"), ir::unused("k"), ir::unused("offset"),
                      over_n(ir::integer(0), ir::element("now", i()))};
    if (x_star) body.push_back(over_n(dim("n"), ir::number(1)));
    return body;
  }
  const bool one = delay_steps == 1;
  Expr slot = ir::mul(ir::grouped(ir::rem(ir::grouped(ir::add(ir::name("k"), ir::name("offset"))), dim("delay_steps"))),
                      dim("history_width"));
  ir::Block body;
  body.push_back(one ? ir::rebound_view("m_past", "history", std::move(slot), dim("history_width"))
                     : ir::view("m_past", "history", std::move(slot), dim("history_width"), false));
  if (x_star)
    body.push_back(one ? ir::rebound_view("x_star_past", "m_past", dim("n"), dim("n"))
                       : ir::view("x_star_past", "m_past", dim("n"), dim("n"), false));
  if (one) {
    ir::Block at_end = {ir::assign(ir::name("m_past"), ir::slice("start"))};
    if (x_star)
      at_end.push_back(ir::assign(ir::name("x_star_past"),
                                  ir::slice("start", state_x_star_offset(), dim("n"))));
    body.push_back(ir::laid_out(ir::conditional(ir::equal(ir::name("offset"), ir::integer(1)), std::move(at_end)),
                                ir::Layout::Braced));
  } else {
    body.push_back(ir::unused("start"));
  }
  body.push_back(over_n(ir::integer(0), ir::element("m_past", i())));
  if (x_star)
    body.push_back(phi_star());
  else
    body.push_back(ir::unused("now"));
  return body;
}

// The parts for any delay: the history's delay_steps slots may be none, and the sizes choose when
// the code runs (or a compiler folds them); the modulus is never 0. x*'s part is under a
// compile-time conditional: without x* the state has none to view.
Expr slots_or_one() {
  return ir::grouped(ir::select(ir::greater(dim("delay_steps"), ir::integer(0)), dim("delay_steps"), ir::integer(1)));
}

Expr has_history() { return ir::greater(dim("delay_steps"), ir::integer(0)); }

ir::Block any_delay_store() {
  return {ir::laid_out(ir::conditional(has_history(), store_in_slot(slots_or_one())), ir::Layout::Braced)};
}

// Phi*_ii: 1 without a delay; else as phi_star(), the step's start before h already known.
ir::Statement any_delay_phi_star() {
  ir::Statement entry = ir::conditional(
      ir::equal(dim("delay_steps"), ir::integer(0)),
      {ir::assign(ir::element("delayed", ir::add(dim("n"), i())), ir::whole_scalar(1))},
      {phi_ratio(ir::name("step_starts_before_h"), ir::whole_scalar(0))});
  return ir::compile_time_conditional(dim("uses_x_star"), phi_star_over_n(std::move(entry)),
                                      {ir::unused("x_star_past"), ir::unused("step_starts_before_h")});
}

// m(t - h) (and Phi*): `now` itself without a history; else the start state at the end of a one-step
// history, the ring's slot otherwise.
ir::Block any_delay_inputs() {
  ir::Block at_end = {ir::assign(ir::name("m_past"), ir::slice("start")),
                      ir::assign(ir::name("x_star_past"), ir::slice("start", state_x_star_offset(), dim("n")))};
  ir::Block in_ring = {
      ir::declare("slot", ir::Type::Size, ir::rem(ir::grouped(ir::add(ir::name("k"), ir::name("offset"))), slots_or_one())),
      ir::assign(ir::name("m_past"),
                 ir::slice("history", ir::mul(ir::name("slot"), dim("history_width")), dim("history_width"))),
      ir::assign(ir::name("x_star_past"), ir::slice("m_past", dim("n"), dim("n")))};
  ir::Block read = {
      ir::assign(ir::name("step_starts_before_h"), ir::less(ir::name("k"), dim("delay_steps"))),
      ir::conditional(ir::logical_and(ir::equal(ir::name("offset"), ir::integer(1)),
                                      ir::equal(dim("delay_steps"), ir::integer(1))),
                      std::move(at_end), std::move(in_ring))};
  return {ir::rebound_view("m_past", "now"),
          ir::rebound_view("x_star_past", "now", state_x_star_offset(), dim("n")),
          ir::declare_variable("step_starts_before_h", ir::Type::Bool, ir::boolean(false)),
          ir::laid_out(ir::conditional(has_history(), std::move(read)), ir::Layout::Braced),
          over_n(ir::integer(0), ir::element("m_past", i())),
          any_delay_phi_star()};
}

}  // namespace

std::map<std::string, ir::Block> any_delay_history_statements() {
  return {{"any_delay_initial_history_body", {fill_every_slot()}},
          {"any_delay_delayed_inputs_body", any_delay_inputs()},
          {"any_delay_history_store", any_delay_store()}};
}

std::map<std::string, ir::Block> history_statements(std::size_t delay_steps, bool x_star) {
  return {{"initial_history_body", initial_history(delay_steps)},
          {"delayed_inputs_body", delayed_inputs(delay_steps, x_star)},
          {"history_store", history_store(delay_steps)}};
}

}  // namespace pfgen::codegen
