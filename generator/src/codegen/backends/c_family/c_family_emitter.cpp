#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/notation/number_format.hpp"

namespace pfgen::codegen {
namespace {

std::string with_point(std::string text) {
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

std::string shortest_float(float value) {
  char buffer[40];
  for (int precision = 1; precision <= 9; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, static_cast<double>(value));
    if (std::strtof(buffer, nullptr) == value) break;
  }
  return buffer;
}

}  // namespace

std::string scalar_mode_name(ScalarMode mode) {
  switch (mode) {
    case ScalarMode::Template: return "template";
    case ScalarMode::Float: return "float";
    case ScalarMode::Double: return "double";
  }
  return "?";
}

std::string CFamilyEmitter::literal(const GiNaC::numeric& value) const {
  const double d = value.to_double();
  // A constant beyond the scalar's range would print as `inf`, which is no literal.
  if (!std::isfinite(d))
    throw CodegenError("the constant, about " + approximate_text(value) +
                       ", is beyond the largest double (about 1.8e308 in magnitude); a lower degree keeps the "
                       "equations' numbers in range");
  if (mode_ == ScalarMode::Float && !std::isfinite(static_cast<float>(d)))
    throw CodegenError("the constant " + shortest_double(d) +
                       " is out of the range of float (above 3.4e38 in magnitude); use --scalar double");
  // Nor may a nonzero constant become 0 unnoticed: below float's (or double's) range it would,
  // which changes the equations rather than rounding them. GiNaC gives no subnormal doubles
  // (1e-310 becomes 0), so double's limit is the smallest normal one.
  if (!value.is_zero() && d == 0)
    throw CodegenError("the constant, about " + approximate_text(value) +
                       ", is below the smallest normal double (about 2.2e-308 in magnitude) and would be 0");
  if (mode_ == ScalarMode::Float && d != 0 && static_cast<float>(d) == 0.0f)
    throw CodegenError("the constant " + shortest_double(d) +
                       " is below the smallest positive float (1.4e-45 in magnitude) and would be 0; use --scalar "
                       "double");
  std::string text;
  switch (mode_) {
    case ScalarMode::Float: text = with_point(shortest_float(static_cast<float>(d))) + "f"; break;
    case ScalarMode::Double: text = with_point(shortest_double(d)); break;
    case ScalarMode::Template:
      text = value.is_integer() && GiNaC::abs(value) < 1000000 ? "Scalar(" + shortest_double(d) + ")"
                                                              : "Scalar(" + with_point(shortest_double(d)) + ")";
      break;
  }
  return d < 0 ? "(" + text + ")" : text;
}

std::string CFamilyEmitter::zero_where_zero(const std::string& guard, const std::string& value) const {
  const std::string zero = literal(GiNaC::numeric(0));
  return "(" + guard + " == " + zero + " ? " + zero + " : " + value + ")";
}

std::string CFamilyEmitter::type(ir::Type t) const {
  switch (t) {
    case ir::Type::Scalar: return scalar_type_;
    case ir::Type::Size: return size_type();
    case ir::Type::Int: return "int";
    case ir::Type::Bool: return truth_type();
  }
  return "?";
}

std::string CFamilyEmitter::declaration(const ir::Declaration& node, const std::string&) const {
  if (node.size) return type(node.type) + " " + node.name + "[" + std::to_string(*node.size) + "];";
  std::string text = node.variable ? "" : "const ";
  text += type(node.type);
  text += ' ';
  text += node.name;
  text += " = ";
  text += expression(*node.value);
  text += ';';
  return text;
}

std::string CFamilyEmitter::arrays(const ir::LocalArrays& node, const std::string& indent) const {
  const std::string length = expression(node.length);
  std::string text = type(node.type) + " ";
  for (std::size_t k = 0; k < node.names.size(); ++k) {
    if (k) text += node.apart ? ";\n" + indent + type(node.type) + " " : ", ";
    text += node.names[k] + "[" + length + "]";
  }
  return text + ";";
}

std::string CFamilyEmitter::view(const ir::View& node, const std::string&) const {
  std::string text = std::string(node.writable ? "" : "const ") + scalar_type_ + "* " + node.name + " = " +
                     (node.local ? local_array(node.array, node.writable) : node.array);
  // A view of the whole array, or from its start, is the array itself.
  if (!node.whole && !(node.offset.kind == ir::Expr::Kind::Integer && node.offset.integer == 0))
    text += " + " + expression(node.offset);
  return text + ";" + (node.comment.empty() ? "" : trailing_comment(node.comment));
}

std::string CFamilyEmitter::assignment(const ir::Assignment& node, const std::string& indent) const {
  if (node.symmetric && !chains_symmetric_store()) {
    const std::string upper = expression(node.targets.at(0));
    return upper + " = " + expression(node.value) + ";\n" + indent + expression(node.targets.at(1)) + " = " + upper + ";";
  }
  std::string text;
  const char* op = !node.accumulate ? " = " : node.subtract ? " -= " : " += ";
  for (const ir::Expr& target : node.targets) text += expression(target) + op;
  return text + expression(node.value) + ";";
}

std::string CFamilyEmitter::slice(const ir::Expr& node) const {
  if (node.operands.empty()) return node.name;
  return node.name + " + " + expression(node.operands.at(0));
}

std::string CFamilyEmitter::scope(const ir::Scope& node, const std::string& indent) const {
  return "{\n" + block(node.body, indent + "  ") + indent + "}";
}

std::string CFamilyEmitter::with_block(const std::string& header, const ir::Block& body, const std::string& indent,
                                       ir::Layout layout) const {
  const std::string inner = indent + "  ";
  // A symmetric store written as two statements is braced like two.
  const bool one = body.size() == 1 && !(body[0].kind == ir::Statement::Kind::Assignment &&
                                         body[0].assignment().symmetric && !chains_symmetric_store());
  if (layout != ir::Layout::Braced && one &&
      (layout == ir::Layout::NextLine || body[0].kind == ir::Statement::Kind::Loop))
    return header + "\n" + inner + statement(body[0], inner);
  if (layout == ir::Layout::Fit && one) {
    const std::string text = statement(body[0], indent);
    if (indent.size() + header.size() + 1 + text.size() <= 100) return header + " " + text;
    return header + "\n" + inner + statement(body[0], inner);
  }
  if (layout != ir::Layout::Braced && one) return header + " " + statement(body[0], indent);
  return header + " {\n" + block(body, inner) + indent + "}";
}

std::string CFamilyEmitter::loop(const ir::Loop& node, const std::string& indent) const {
  std::string header = "for (" + type(node.counter) + " " + node.index + " = " + expression(node.begin);
  if (node.declares) header += ", " + node.declares->name + " = " + expression(node.declares->start);
  header += "; " + node.index + " < " + expression(node.end) + "; ++" + node.index;
  if (!node.steps.empty()) header += ", ++" + node.steps;
  return with_block(header + ")", node.body, indent, node.layout);
}

std::string CFamilyEmitter::call_statement(const ir::CallStatement& node, const std::string&) const {
  return call_text(callee(node), node.arguments) + ";";
}

std::string CFamilyEmitter::conditional(const ir::Conditional& node, const std::string& indent) const {
  const std::string header = (node.compile_time ? compile_time_if() : "if") + " (" + expression(node.condition) + ")";
  if (node.otherwise.empty()) return with_block(header, node.then, indent, node.layout);
  // With an else: each branch of one statement on its own line, else both in braces; an else of
  // one conditional continues the chain on the else's line (`else if`).
  const std::string inner = indent + "  ";
  const bool chain = node.otherwise.size() == 1 && node.otherwise[0].kind == ir::Statement::Kind::Conditional;
  if (node.then.size() == 1 && node.otherwise.size() == 1)
    return header + "\n" + inner + statement(node.then[0], inner) + "\n" + indent +
           (chain ? "else " + statement(node.otherwise[0], indent) : "else\n" + inner + statement(node.otherwise[0], inner));
  return header + " {\n" + block(node.then, inner) + indent +
         (chain ? "} else " + statement(node.otherwise[0], indent) : "} else {\n" + block(node.otherwise, inner) + indent + "}");
}

std::string CFamilyEmitter::return_statement(const ir::Return& node, const std::string&) const {
  return node.value ? "return " + expression(*node.value) + ";" : "return;";
}

std::string CFamilyEmitter::comment(const ir::Comment& node, const std::string&) const { return "// " + node.text; }

std::string CFamilyEmitter::unused(const ir::Unused& node, const std::string&) const {
  return "(void)" + node.name + ";";
}

}  // namespace pfgen::codegen
