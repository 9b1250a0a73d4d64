#include "pfgen/codegen/emitter.hpp"

namespace pfgen::codegen {

std::string Emitter::expression(const Node& node, const std::vector<std::string>& a) const {
  switch (node.kind) {
    case OpKind::Input: return input(node);
    case OpKind::Constant: return constant(node.value());
    case OpKind::Add: return add(a.at(0), a.at(1));
    case OpKind::Sub: return sub(a.at(0), a.at(1));
    case OpKind::Mul: return mul(a.at(0), a.at(1));
    case OpKind::Div: return div(a.at(0), a.at(1));
    case OpKind::Neg: return neg(a.at(0));
    case OpKind::Call: return call(node.function, a);
    case OpKind::ZeroWhereZero: return zero_where_zero(a.at(0), a.at(1));
  }
  return "?";
}

}  // namespace pfgen::codegen
