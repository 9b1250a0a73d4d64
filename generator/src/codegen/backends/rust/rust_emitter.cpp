#include "pfgen/codegen/backends/rust/rust_emitter.hpp"

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/kinds/model_functions.hpp"

namespace pfgen::codegen {

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

namespace {

// The bodies declare the module's alias `Scalar`, defined as rust_scalar(mode), which refuses
// a mode Rust has no type for.
std::string scalar_alias(ScalarMode mode) {
  RustEmitter::rust_scalar(mode);
  return "Scalar";
}

}  // namespace

RustEmitter::RustEmitter(ScalarMode mode, std::string temporary_prefix, std::string params_type)
    : CFamilyEmitter(mode, scalar_alias(mode), std::move(temporary_prefix)),
      params_type_(std::move(params_type)) {}

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
  return text + "    }\n}\n";
}

std::string RustEmitter::declaration(const std::string& name, const std::string& value) const {
  return "let " + name + ": " + scalar_type_ + " = " + value + ";";
}

// A straight-line body too large for one function, in parts, as C's split body (c_split_body.cpp
// says why): each part a private function <function>_part<k> taking the function's arguments as
// slices and, when parts pass values on, the local array through which they do. Every operation is
// computed once, in the same order and with the same temporaries as the unsplit body.
FunctionBody RustEmitter::split_body(const ExpressionGraph& graph, const std::vector<std::size_t>& outputs,
                                     const FunctionSignature& signature, const std::vector<std::size_t>& order) const {
  const SplitPlan plan = split_plan(graph, outputs);
  const std::vector<std::string> destinations = indexed(signature.target, outputs.size());
  auto spell = [&](std::size_t id) {
    return graph.is_leaf(id) ? expression(graph.node(id), {}) : temporary(plan.number.at(id));
  };
  const bool passes = plan.slots != 0;
  const std::string& s = scalar_type_;
  std::string parameters = signature.time + ": " + s;
  std::string arguments = signature.time;
  for (const std::string& array : signature.arrays) {
    parameters += ", " + array + ": &[" + s + "]";
    arguments += ", " + array;
  }
  parameters += ", " + signature.params + ": &" + params_type_ + ", " + signature.target + ": &mut [" + s + "]";
  arguments += ", " + signature.params + ", " + signature.target;
  if (passes) {
    parameters += ", " + shared_array_ + ": &mut [" + s + "]";
    arguments += ", &mut " + shared_array_;
  }

  FunctionBody body;
  // Statements in the C family's two-space indentation, as the unsplit body's (rust_indent doubles it).
  body.statements = "  // " + std::to_string(plan.operations.size()) + " operations in " +
                    std::to_string(plan.parts) + " parts of at most " + std::to_string(max_ops_) +
                    ", each its own function: one function this large takes a compiler long.\n";
  if (passes)
    body.statements += "  let mut " + shared_array_ + ": [" + s + "; " + std::to_string(plan.slots) + "] = [" +
                       constant(GiNaC::numeric(0)) + "; " + std::to_string(plan.slots) + "];\n";
  std::size_t next = 0;
  for (std::size_t p = 0; p < plan.parts; ++p) {
    const std::string part = signature.function + "_part" + std::to_string(p);
    std::string reads, arithmetic, stores, writes;
    std::set<std::size_t> inputs;
    auto note_input = [&](std::size_t id) {
      if (graph.node(id).kind == OpKind::Input) inputs.insert(id);
    };
    for (std::size_t id : plan.reads[p])
      reads += "    " + declaration(spell(id), shared_array_ + "[" + std::to_string(plan.slot.at(id)) + "]") + "\n";
    for (; next < plan.operations.size() && plan.part.at(plan.operations[next]) == p; ++next) {
      const std::size_t id = plan.operations[next];
      std::vector<std::string> operands;
      for (std::size_t arg : graph.node(id).args) {
        note_input(arg);
        operands.push_back(spell(arg));
      }
      arithmetic += "    " + declaration(spell(id), expression(graph.node(id), operands)) + "\n";
      if (plan.slot[id] != SplitPlan::kNone)
        stores += "    " + shared_array_ + "[" + std::to_string(plan.slot[id]) + "] = " + spell(id) + ";\n";
    }
    for (std::size_t k = 0; k < outputs.size(); ++k)
      if (plan.writer(graph, outputs[k]) == p) {
        note_input(outputs[k]);
        writes += "    " + destinations.at(k) + " = " + spell(outputs[k]) + ";\n";
      }
    std::string top = rust_indent(unused_arguments_of(graph, inputs, signature));
    if (writes.empty()) top += "    " + ignored(signature.target) + "\n";
    if (passes && reads.empty() && stores.empty()) top += "    " + ignored(shared_array_) + "\n";
    body.helpers += "fn " + part + "(" + parameters + ") {\n" + top + rust_indent(declarations_of(graph, inputs, order)) +
                    reads + arithmetic + stores + writes + "}\n\n";
    body.statements += "  " + part + "(" + arguments + ");\n";
  }
  return body;
}

}  // namespace pfgen::codegen
