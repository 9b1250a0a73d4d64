#include "pfgen/codegen/heun_step.hpp"

namespace pfgen::codegen {
namespace {

using ir::Expr;

Expr at(const std::string& array, const Expr& index) { return ir::element(array, index); }

}  // namespace

HeunStepLoops::HeunStepLoops(std::size_t n, std::size_t p, std::size_t state_size, bool written_out)
    : n_(n), p_(p), state_size_(state_size), written_out_(written_out) {}

void HeunStepLoops::each(ir::Block& block, const std::string& index, const Expr& count_size, std::size_t count,
                         const std::function<ir::Statement(const Expr&)>& body) const {
  if (!written_out_) {
    block.push_back(ir::loop(index, ir::Type::Size, ir::integer(0), count_size, {body(ir::name(index))}));
    return;
  }
  for (std::size_t k = 0; k < count; ++k) block.push_back(body(ir::integer(k)));
}

void HeunStepLoops::innovation(ir::Block& block, const std::string& observation, const Expr& dt) const {
  each(block, "r", ir::dimension("p"), p_, [&](const Expr& r) {
    return ir::assign(at("innovation", r), ir::sub(at("dy", r), ir::mul(at(observation, r), dt)));
  });
}

void HeunStepLoops::scaled_rates(ir::Block& block, const Entry& rate, const Expr& dt) const {
  each(block, "i", ir::dimension("state_size"), state_size_,
       [&](const Expr& i) { return ir::assign(at("delta", i), ir::mul(rate(i), dt)); });
}

void HeunStepLoops::state_gain(ir::Block& block, const std::string& gain, const Entry& innovation) const {
  gain_times_innovation(block, "i", 0, n_, ir::dimension("n"), gain, innovation);
}

void HeunStepLoops::covariance_gain(ir::Block& block, const std::string& gain, const Entry& innovation) const {
  gain_times_innovation(block, "u", n_, state_size_ - n_, ir::sub(ir::dimension("state_size"), ir::dimension("n")),
                        gain, innovation);
}

void HeunStepLoops::gain_times_innovation(ir::Block& block, const std::string& index, std::size_t first_row,
                                          std::size_t rows, const Expr& rows_size, const std::string& gain,
                                          const Entry& innovation) const {
  auto statement = [&](const Expr& target, const Expr& gain_entry, const Expr& r) {
    return ir::accumulate(at("delta", target), ir::mul(at(gain, gain_entry), innovation(r)));
  };
  if (!written_out_) {
    const Expr row = ir::name(index), r = ir::name("r"), p_size = ir::dimension("p");
    const Expr target = first_row == 0 ? row : ir::add(ir::dimension("n"), row);
    block.push_back(ir::loop(index, ir::Type::Size, ir::integer(0), rows_size,
                             {ir::loop("r", ir::Type::Size, ir::integer(0), p_size,
                                       {statement(target, ir::add(ir::mul(row, p_size), r), r)})}));
    return;
  }
  for (std::size_t row = 0; row < rows; ++row)
    for (std::size_t r = 0; r < p_; ++r)
      block.push_back(statement(ir::integer(first_row + row), ir::integer(row * p_ + r), ir::integer(r)));
}

ir::Block HeunStepLoops::predicted() const {
  ir::Block block;
  each(block, "i", ir::dimension("state_size"), state_size_,
       [](const Expr& i) { return ir::assign(at("predicted", i), ir::add(at("state", i), at("first", i))); });
  return block;
}

ir::Block HeunStepLoops::predictor_corrector(const Increment& increment, bool written_first) const {
  ir::Block block = {ir::local_arrays({"first", "predicted", "second"}, ir::Type::Scalar, ir::dimension("state_size"),
                                      written_first)};
  auto append = [&block](ir::Block part) {
    for (ir::Statement& s : part) block.push_back(std::move(s));
  };
  append(increment(false, ir::name("state"), ir::local_array("first", true)));
  append(predicted());
  append(increment(true, ir::local_array("predicted", false), ir::local_array("second", true)));
  return block;
}

ir::Block HeunStepLoops::average() const {
  ir::Block block;
  each(block, "i", ir::dimension("state_size"), state_size_, [](const Expr& i) {
    return ir::accumulate(at("state", i),
                          ir::div(ir::grouped(ir::add(at("first", i), at("second", i))), ir::whole_scalar(2)));
  });
  return block;
}

}  // namespace pfgen::codegen
