#include "pfgen/observations/continuous/heun_step.hpp"

#include <functional>

namespace pfgen::codegen {
namespace {

using ir::Expr;

Expr at(const std::string& array, const Expr& index) { return ir::element(array, index); }

// for index < count: body(index), or below kStepWrittenOutBelow states the statements body(0),
// body(1), ... one per line.
class StepLoops {
 public:
  explicit StepLoops(bool written_out) : written_out_(written_out) {}

  void loop(ir::Block& block, const std::string& index, const Expr& count_name, std::size_t count,
            const std::function<ir::Statement(const Expr&)>& body) const {
    if (!written_out_) {
      block.push_back(ir::loop(index, ir::Type::Size, ir::integer(0), count_name, {body(ir::name(index))}));
      return;
    }
    for (std::size_t k = 0; k < count; ++k) block.push_back(body(ir::integer(k)));
  }

  // delta[i] += K[i p + r] innovation[r] for each i < n and r < p.
  void correction(ir::Block& block, std::size_t n, std::size_t p) const {
    auto statement = [](const Expr& i, const Expr& gain_entry, const Expr& r) {
      return ir::accumulate(at("delta", i), ir::mul(at("K", gain_entry), at("innovation", r)));
    };
    if (!written_out_) {
      const Expr i = ir::name("i"), r = ir::name("r");
      const Expr n_size = ir::dimension("n"), p_size = ir::dimension("p");
      block.push_back(ir::loop("i", ir::Type::Size, ir::integer(0), n_size,
                               {ir::loop("r", ir::Type::Size, ir::integer(0), p_size,
                                         {statement(i, ir::add(ir::mul(i, p_size), r), r)})}));
      return;
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t r = 0; r < p; ++r)
        block.push_back(statement(ir::integer(i), ir::integer(i * p + r), ir::integer(r)));
  }

 private:
  bool written_out_;
};

}  // namespace

HeunStepLoops heun_step_loops(std::size_t n, std::size_t p, std::size_t state_size) {
  const StepLoops loops(n < kStepWrittenOutBelow);
  const Expr p_size = ir::dimension("p"), state = ir::dimension("state_size"), two = ir::whole_scalar(2);
  HeunStepLoops step;
  loops.loop(step.increment, "r", p_size, p, [](const Expr& r) {
    return ir::assign(at("innovation", r), ir::sub(at("dy", r), ir::mul(at("innovation", r), ir::name("dt"))));
  });
  loops.loop(step.increment, "i", state, state_size,
             [](const Expr& i) { return ir::assign(at("delta", i), ir::mul(at("all", i), ir::name("dt"))); });
  loops.correction(step.increment, n, p);
  loops.loop(step.predicted, "i", state, state_size,
             [](const Expr& i) { return ir::assign(at("predicted", i), ir::add(at("state", i), at("first", i))); });
  loops.loop(step.average, "i", state, state_size, [&](const Expr& i) {
    return ir::accumulate(at("state", i), ir::div(ir::grouped(ir::add(at("first", i), at("second", i))), two));
  });
  return step;
}

}  // namespace pfgen::codegen
