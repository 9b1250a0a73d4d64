#include "pfgen/codegen/backends/rust/rust_emitter.hpp"

#include <cctype>

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/kinds/model_functions.hpp"

namespace pfgen::codegen {
namespace {

// The bodies declare the module's alias `Scalar`, defined as rust_scalar(mode), which refuses a
// mode Rust has no type for.
std::string scalar_alias(ScalarMode mode) {
  RustEmitter::rust_scalar(mode);
  return "Scalar";
}

// `{` ... `}` around a block, each statement on its own line one level in.
std::string braced(const std::string& header, const std::string& body, const std::string& indent) {
  return header + " {\n" + body + indent + "}";
}

}  // namespace

std::string rust_indent(const std::string& text) {
  std::string out;
  bool start = true;
  std::size_t spaces = 0;
  for (char c : text) {
    if (start && c == ' ') {
      ++spaces;
      continue;
    }
    if (start) {
      out.append(2 * spaces, ' ');
      start = false;
      spaces = 0;
    }
    out += c;
    if (c == '\n') start = true;
  }
  return out;
}

RustEmitter::RustEmitter(ScalarMode mode, std::string temporary_prefix, std::string params_type)
    : CFamilyEmitter(mode, scalar_alias(mode), std::move(temporary_prefix)), params_type_(std::move(params_type)) {}

std::string RustEmitter::rust_scalar(ScalarMode mode) {
  switch (mode) {
    case ScalarMode::Float: return "f32";
    case ScalarMode::Double: return "f64";
    case ScalarMode::Template: break;
  }
  throw CodegenError("Rust has no templates here: its scalar is float (f32) or double (f64)");
}

std::string RustEmitter::constant(const GiNaC::numeric& value) const {
  std::string text = literal(value);  // C's digits, range checked: `0.5f`, `(-0.5)`
  if (text.front() == '(') text = text.substr(1, text.size() - 2);
  if (mode_ == ScalarMode::Float && text.back() == 'f') text.pop_back();
  return text;
}

std::string RustEmitter::dimension(const std::string& name) const {
  if (name == "n") return "STATES";
  if (name == "p") return "OBSERVATIONS";
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return upper;
}

std::string RustEmitter::function_spelling(Function function) const {
  const ModelFunction* model = model_function(function_name(function));
  const std::string name = model ? model->c_name : function_name(function);
  return mode_ == ScalarMode::Float ? name + "f" : name;
}

std::string RustEmitter::call(Function function, const std::vector<std::string>& args) const {
  called_.insert(function);
  std::string out = "unsafe { c_math::" + function_spelling(function) + "(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + ") }";
}

std::string RustEmitter::zero_where_zero(const std::string& guard, const std::string& value) const {
  const std::string zero = constant(GiNaC::numeric(0));
  return "if " + guard + " == " + zero + " { " + zero + " } else { " + value + " }";
}

std::string RustEmitter::math_declarations() const {
  if (called_.empty()) return "";
  const std::string s = rust_scalar(mode_);
  std::string text =
      "// The C library's <math.h> functions the bodies call (libm; newlib on a microcontroller): core\n"
      "// has none without std, and these give the C backend's numbers bit for bit.\n"
      "mod c_math {\n    extern \"C\" {\n";
  std::set<std::string> declared;  // sorted by spelling, each once
  for (Function function : called_) {
    const ModelFunction* model = model_function(function_name(function));
    const std::size_t arity = model ? model->arity : (function == Function::Pow ? 2 : 1);
    std::string line = "        pub fn " + function_spelling(function) + "(";
    for (std::size_t k = 0; k < arity; ++k) line += std::string(k ? ", " : "") + (k ? "y" : "x") + ": " + s;
    declared.insert(line + ") -> " + s + ";\n");
  }
  for (const std::string& line : declared) text += line;
  return text + "    }\n}\n\n";
}

std::string RustEmitter::declaration(const ir::Declaration& node, const std::string&) const {
  const std::string t = node.type == ir::Type::Int ? "usize" : type(node.type);  // Rust indexes with usize
  if (node.size) {
    const std::string zero = node.type == ir::Type::Scalar ? constant(GiNaC::numeric(0)) : "0";
    const std::string size = std::to_string(*node.size);
    return "let mut " + node.name + ": [" + t + "; " + size + "] = [" + zero + "; " + size + "];";
  }
  return (node.variable ? "let mut " : "let ") + node.name + ": " + t + " = " + expression(*node.value) + ";";
}

std::string RustEmitter::arrays(const ir::LocalArrays& node, const std::string& indent) const {
  const std::string zero = node.type == ir::Type::Scalar ? constant(GiNaC::numeric(0)) : "0";
  const std::string t = node.type == ir::Type::Int ? "usize" : type(node.type);
  const std::string length = expression(node.length);
  std::string text;
  for (std::size_t k = 0; k < node.names.size(); ++k)
    text += (k ? "\n" + indent : "") + "let mut " + node.names[k] + ": [" + t + "; " + length + "] = [" + zero + "; " +
            length + "];";
  return text;
}

namespace {
// A range's bound needs no parentheses (`..` binds loosest), and rustc would lint them.
ir::Expr ungrouped(ir::Expr e) {
  e.grouped = false;
  return e;
}
}  // namespace

std::string RustEmitter::slice(const ir::Expr& node) const {
  if (node.operands.empty()) return "&" + node.name + "[..]";
  const std::string offset = expression(ungrouped(node.operands.at(0)));
  return "&" + node.name + "[" + offset + ".." + offset + " + " + expression(node.operands.at(1)) + "]";
}

std::string RustEmitter::view(const ir::View& node, const std::string& indent) const {
  if (!node.comment.empty()) {
    ir::View bare = node;
    bare.comment.clear();
    return view(bare, indent) + trailing_comment(node.comment);
  }
  // A writable view of a local array while the array is read: the borrow checker allows the two
  // only as the array split in two, the array's name shadowed by the part before the view.
  if (node.local && node.writable)
    return "let (" + node.array + ", " + node.name + ") = " + node.array + ".split_at_mut(" +
           expression(ungrouped(node.offset)) + ");";
  const std::string head = (node.rebound ? "let mut " + node.name + ": &[" + scalar_type() + "] = &" : "let " + node.name + " = &") +
                           (node.writable ? "mut " : "") + node.array + "[";
  if (node.whole) return head + "..];";
  // A view from the start: up to its size.
  if (node.offset.kind == ir::Expr::Kind::Integer && node.offset.integer == 0)
    return head + ".." + expression(node.size) + "];";
  const std::string offset = expression(ungrouped(node.offset));
  return head + offset + ".." + offset + " + " + expression(node.size) + "];";
}

std::string RustEmitter::assignment(const ir::Assignment& node, const std::string& indent) const {
  // Rust has no chained assignment: the last target takes the value, each one before it the next's.
  const std::string op = !node.accumulate ? " = " : node.subtract ? " -= " : " += ";
  std::string text = expression(node.targets.back()) + op + expression(node.value) + ";";
  for (std::size_t k = node.targets.size() - 1; k-- > 0;)
    text += "\n" + indent + expression(node.targets[k]) + " = " + expression(node.targets[k + 1]) + ";";
  return text;
}

std::string RustEmitter::loop(const ir::Loop& node, const std::string& indent) const {
  const std::string inner = indent + "  ";
  std::string body = block(node.body, inner);
  if (!node.steps.empty()) body += inner + node.steps + " += 1;\n";
  std::string text = braced("for " + node.index + " in " + expression(node.begin) + ".." + expression(node.end), body,
                            indent);
  // A counter that runs over the whole nest: declared before the loop whose iterations start it.
  if (node.declares)
    text = "let mut " + node.declares->name + ": usize = " + expression(node.declares->start) + ";\n" + indent + text;
  return text;
}

std::string RustEmitter::conditional(const ir::Conditional& node, const std::string& indent) const {
  std::string text = braced("if " + expression(node.condition), block(node.then, indent + "  "), indent);
  // An else of one conditional continues the chain (`else if`).
  if (node.otherwise.size() == 1 && node.otherwise[0].kind == ir::Statement::Kind::Conditional)
    text += " else " + statement(node.otherwise[0], indent);
  else if (!node.otherwise.empty())
    text += braced(" else", block(node.otherwise, indent + "  "), indent);
  return text;
}

std::string RustEmitter::unused(const ir::Unused& node, const std::string&) const { return "let _ = " + node.name + ";"; }

// A straight-line body too large for one function, in parts (ir::split_statements), as C's split
// body (c_split_body.cpp says why): each part a private function <function>_part<k> taking the
// function's arguments as slices and, when parts pass values on, the local array through which
// they do. Every operation is computed once, in the same order and with the same temporaries as
// the unsplit body.
FunctionBody RustEmitter::split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                     const FunctionSignature& signature, const std::vector<std::size_t>& order) const {
  const ir::SplitBody split = ir::split_statements(graph, outputs, ir::indexed(signature.target, outputs.size()),
                                                   temporary_prefix_, max_ops_, shared_array_);
  const bool passes = split.plan.slots != 0;
  std::string parameters = signature.time + ": " + scalar_type_;
  std::string arguments = signature.time;
  // Each array passed as a whole slice: an argument (a reference to an array) or a local array
  // (derivatives()' work array when P's drift is in loops) alike.
  for (const std::string& array : signature.arrays) {
    parameters += ", " + array + ": &[" + scalar_type_ + "]";
    arguments += ", &" + array + "[..]";
  }
  parameters += ", " + signature.params + ": &" + params_type_ + ", " + signature.target + ": &mut [" + scalar_type_ + "]";
  arguments += ", " + signature.params + ", &mut " + signature.target + "[..]";
  if (passes) {
    parameters += ", " + shared_array_ + ": &mut [" + scalar_type_ + "]";
    arguments += ", &mut " + shared_array_;
  }
  ir::Block top = {ir::comment(std::to_string(split.plan.operations.size()) + " operations in " +
                               std::to_string(split.plan.parts) + " parts of at most " + std::to_string(max_ops_) +
                               ", each its own function: one function this large takes a compiler long.")};
  if (passes) top.push_back(ir::declare_array(shared_array_, ir::Type::Scalar, split.plan.slots));
  FunctionBody body;
  body.statements = block(top);
  for (std::size_t p = 0; p < split.parts.size(); ++p) {
    const ir::SplitPart& part = split.parts[p];
    const std::string name = signature.function + "_part" + std::to_string(p);
    ir::Block head = ir::unused_arguments(graph, part.inputs, signature);
    if (part.writes.empty()) head.push_back(ir::unused(signature.target));
    if (passes && part.reads.empty() && part.stores.empty()) head.push_back(ir::unused(shared_array_));
    for (ir::Statement& s : ir::input_declarations(graph, part.inputs, order)) head.push_back(std::move(s));
    body.helpers += "fn " + name + "(" + parameters + ") {\n" + block(head, "    ");
    for (const ir::Block* statements : {&part.reads, &part.arithmetic, &part.stores, &part.writes})
      body.helpers += block(*statements, "    ");
    body.helpers += "}\n\n";
    body.statements += "  " + name + "(" + arguments + ");\n";
  }
  return body;
}

}  // namespace pfgen::codegen
