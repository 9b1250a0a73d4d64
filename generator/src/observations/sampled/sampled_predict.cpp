#include "pfgen/observations/sampled/sampled_predict.hpp"

#include <utility>

#include "pfgen/codegen/filter_file.hpp"

namespace pfgen::codegen {
namespace {

using ir::Expr;

Expr at(const std::string& array) { return ir::element(array, ir::name("i")); }

// for i in [begin, state_size): body.
ir::Statement over_state(Expr begin, ir::Statement body) {
  return ir::loop("i", ir::Type::Size, std::move(begin), ir::dimension("state_size"), {std::move(body)});
}

}  // namespace

ir::Block predict_statements(bool euler) {
  const Expr n = ir::dimension("n"), state_size = ir::dimension("state_size");
  const Expr t = ir::name("t"), dt = ir::name("dt"), state = ir::name("state");
  if (euler)
    return {
        ir::local_arrays({"rates"}, ir::Type::Scalar, state_size),
        ir::local_arrays({"square"}, ir::Type::Scalar, ir::sub(state_size, n)),
        state_function_call("derivatives", t, state, "rates"),
        state_function_call("euler_square", t, state, "square"),
        over_state(ir::integer(0), ir::accumulate(at("state"), ir::mul(at("rates"), dt))),
        over_state(n,
                   ir::accumulate(at("state"), ir::mul(ir::mul(ir::element("square", ir::sub(ir::name("i"), n)), dt), dt))),
    };
  return {
      ir::local_arrays({"first", "predicted", "second"}, ir::Type::Scalar, state_size),
      state_function_call("derivatives", t, state, "first"),
      over_state(ir::integer(0), ir::assign(at("predicted"), ir::add(at("state"), ir::mul(at("first"), dt)))),
      state_function_call("derivatives", ir::add(t, dt), ir::local_array("predicted", false), "second"),
      over_state(ir::integer(0),
                 ir::accumulate(at("state"), ir::div(ir::mul(ir::grouped(ir::add(at("first"), at("second"))), dt), ir::whole_scalar(2)))),
  };
}

ir::Block advance_statements() {
  const Expr t = ir::name("t"), dt = ir::name("dt"), state = ir::name("state"), params = ir::name("params");
  const Expr period = ir::file_scalar("period");
  return {
      ir::declare("dt", ir::Type::Scalar, ir::div(period, ir::to_scalar(ir::dimension("substeps")))),
      ir::loop("s", ir::Type::Size, ir::integer(0), ir::dimension("substeps"),
               {ir::call_file_function("predict", {state, ir::add(t, ir::mul(ir::to_scalar(ir::name("s")), dt)), dt, params})}),
      ir::return_value(ir::file_call("update", {state, ir::add(t, period), ir::name("y"), params})),
  };
}

}  // namespace pfgen::codegen
