#include "pfgen/observations/sampled/cholesky_solve.hpp"

namespace pfgen::codegen {
namespace {

std::string L(std::size_t a, std::size_t b) { return "L" + std::to_string(a) + "_" + std::to_string(b); }

std::string packed(std::size_t a, std::size_t b, std::size_t r) {
  return std::to_string(a * r - a * (a + 1) / 2 + b);  // a <= b
}

}  // namespace

std::string cholesky_gain_body(std::size_t r, const CFamilyEmitter& emitter, const CholeskySpelling& spelling) {
  const std::string& scalar = emitter.scalar_type();
  std::string body;
  // S = L L^T, column by column: L_jj = sqrt(S_jj - sum_k L_jk^2), L_ij = (S_ji - sum_k L_ik L_jk) / L_jj.
  for (std::size_t j = 0; j < r; ++j) {
    std::string pivot = "S[" + packed(j, j, r) + "]";
    for (std::size_t k = 0; k < j; ++k) pivot += " - " + L(j, k) + " * " + L(j, k);
    const std::string d = "d" + std::to_string(j);
    body += "  const " + scalar + " " + d + " = " + pivot + ";\n";
    body += "  if (!(" + d + " > " + spelling.zero + ")) return " + spelling.failure + ";\n";
    body += "  const " + scalar + " " + L(j, j) + " = " + emitter.call(Function::Sqrt, {d}) + ";\n";
    for (std::size_t i = j + 1; i < r; ++i) {
      std::string entry = "S[" + packed(j, i, r) + "]";
      for (std::size_t k = 0; k < j; ++k) entry += " - " + L(i, k) + " * " + L(j, k);
      body += "  const " + scalar + " " + L(i, j) + " = (" + entry + ") / " + L(j, j) + ";\n";
    }
  }
  // Each row k of K solves S k = b (b the row of PCt): L z = b, then L^T k = z.
  body += "  for (" + spelling.size_type + " i = 0; i < " + spelling.n + "; ++i) {\n";
  body += "    const " + scalar + "* b = PCt + i * " + spelling.p + ";\n";
  body += "    " + scalar + "* k = K + i * " + spelling.p + ";\n";
  for (std::size_t a = 0; a < r; ++a) {
    std::string z = "b[" + std::to_string(a) + "]";
    for (std::size_t c = 0; c < a; ++c) z += " - " + L(a, c) + " * z" + std::to_string(c);
    body += "    const " + scalar + " z" + std::to_string(a) + " = (" + z + ") / " + L(a, a) + ";\n";
  }
  for (std::size_t a = r; a-- > 0;) {
    std::string x = "z" + std::to_string(a);
    for (std::size_t c = a + 1; c < r; ++c) x += " - " + L(c, a) + " * k[" + std::to_string(c) + "]";
    body += "    k[" + std::to_string(a) + "] = (" + x + ") / " + L(a, a) + ";\n";
  }
  body += "  }\n  return " + spelling.success + ";\n";
  return body;
}

}  // namespace pfgen::codegen
