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

// Every slot holds the pre-history: the initial state's m (and x*).
ir::Block initial_history(std::size_t delay_steps) {
  if (delay_steps == 0) return {ir::unused("state"), ir::unused("history")};
  ir::Statement fill = ir::laid_out(
      over_history_width(ir::assign(
          ir::element("history", ir::add(ir::mul(ir::name("slot"), dim("history_width")), i())), slot_entry())),
      ir::Layout::NextLine);
  return {ir::loop("slot", ir::Type::Size, ir::integer(0), dim("delay_steps"), {std::move(fill)})};
}

// The start state enters slot k mod delay_steps.
ir::Block history_store(std::size_t delay_steps) {
  if (delay_steps == 0) return {ir::unused("history")};
  Expr offset = ir::mul(ir::grouped(ir::rem(ir::name("k"), dim("delay_steps"))), dim("history_width"));
  return {ir::scope({ir::view("slot", "history", std::move(offset), dim("history_width"), true),
                     over_history_width(ir::assign(ir::element("slot", i()), slot_entry()))})};
}

ir::Statement over_n(Expr target_offset, Expr value) {
  Expr target = target_offset.kind == Expr::Kind::Integer ? i() : ir::add(std::move(target_offset), i());
  return ir::loop("i", ir::Type::Size, ir::integer(0), dim("n"), {ir::assign(ir::element("delayed", std::move(target)),
                                                                             std::move(value))});
}

// Phi*_ii = x*_i(t - h) / x*_i(t), 0 where x*_i(t) = 0 and over every step that starts before h.
ir::Statement phi_star() {
  ir::Statement ratio = ir::conditional(
      ir::logical_or(ir::less(ir::name("k"), dim("delay_steps")),
                     ir::equal(ir::element("x_star_now", i()), ir::number(0))),
      {ir::assign(ir::element("delayed", ir::add(dim("n"), i())), ir::number(0))},
      {ir::assign(ir::element("delayed", ir::add(dim("n"), i())),
                  ir::div(ir::element("x_star_past", i()), ir::element("x_star_now", i())))});
  return ir::scope(
      {ir::view("x_star_now", "now", ir::grouped(ir::sub(dim("state_size"), dim("n"))), dim("n"), false),
       ir::laid_out(ir::loop("i", ir::Type::Size, ir::integer(0), dim("n"), {std::move(ratio)}), ir::Layout::Braced)});
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
                                  ir::slice("start", ir::grouped(ir::sub(dim("state_size"), dim("n"))), dim("n"))));
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

}  // namespace

std::map<std::string, ir::Block> history_statements(std::size_t delay_steps, bool x_star) {
  return {{"initial_history_body", initial_history(delay_steps)},
          {"delayed_inputs_body", delayed_inputs(delay_steps, x_star)},
          {"history_store", history_store(delay_steps)}};
}

}  // namespace pfgen::codegen
