#include "pfgen/observations/continuous/heun_step_text.hpp"

#include <functional>

namespace pfgen::codegen {
namespace {

// `for (index_type i = 0; i < count_name; ++i) body(i);`, or below kStepWrittenOutBelow states the
// statements body(0), body(1), ... one per line.
class StepLoops {
 public:
  StepLoops(const HeunStepSpelling& spelling, bool written_out) : spelling_(spelling), written_out_(written_out) {}

  std::string loop(const std::string& index, const std::string& count_name, std::size_t count,
                   const std::function<std::string(const std::string&)>& body) const {
    if (!written_out_) return "  " + header(index, count_name) + " " + body(index) + "\n";
    std::string text;
    for (std::size_t k = 0; k < count; ++k) text += "  " + body(std::to_string(k)) + "\n";
    return text;
  }

  // delta[i] += K[i p + r] innovation[r] for each i < n and r < p.
  std::string correction(std::size_t n, std::size_t p) const {
    auto statement = [](const std::string& i, const std::string& gain_entry, const std::string& r) {
      return "delta[" + i + "] += K[" + gain_entry + "] * innovation[" + r + "];";
    };
    if (!written_out_)
      return "  " + header("i", spelling_.n) + "\n    " + header("r", spelling_.p) + " " +
             statement("i", "i * " + spelling_.p + " + r", "r") + "\n";
    std::string text;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t r = 0; r < p; ++r)
        text += "  " + statement(std::to_string(i), std::to_string(i * p + r), std::to_string(r)) + "\n";
    return text;
  }

 private:
  std::string header(const std::string& index, const std::string& count_name) const {
    return "for (" + spelling_.index_type + " " + index + " = 0; " + index + " < " + count_name + "; ++" + index + ")";
  }

  const HeunStepSpelling& spelling_;
  bool written_out_;
};

}  // namespace

void add_heun_step_loops(std::map<std::string, std::string>& values, const HeunStepSpelling& spelling, std::size_t n,
                         std::size_t p, std::size_t state_size) {
  const StepLoops loops(spelling, n < kStepWrittenOutBelow);
  const std::string& size = spelling.state_size;
  values.emplace("increment_loops",
                 loops.loop("r", spelling.p, p,
                            [](const std::string& r) {
                              return "innovation[" + r + "] = dy[" + r + "] - innovation[" + r + "] * dt;";
                            }) +
                     loops.loop("i", size, state_size,
                                [](const std::string& i) { return "delta[" + i + "] = all[" + i + "] * dt;"; }) +
                     loops.correction(n, p));
  values.emplace("predicted_loop", loops.loop("i", size, state_size, [](const std::string& i) {
                   return "predicted[" + i + "] = state[" + i + "] + first[" + i + "];";
                 }));
  values.emplace("average_loop", loops.loop("i", size, state_size, [&](const std::string& i) {
                   return "state[" + i + "] += (first[" + i + "] + second[" + i + "]) / " + spelling.two + ";";
                 }));
}

}  // namespace pfgen::codegen
