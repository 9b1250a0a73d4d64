#include "support/dense_cubic_model.hpp"

#include <string>
#include <vector>

#include "pfgen/model/model_builder.hpp"
#include "support/dense_cubic_system.hpp"

namespace pfgen_test {

pfgen::Model dense_cubic_model(std::size_t n) {
  const DenseCubicSystem system = dense_cubic_system(n);
  pfgen::ModelBuilder b("dense_cubic_" + std::to_string(n));
  std::vector<GiNaC::symbol> x;
  for (std::size_t i = 0; i < n; ++i) x.push_back(b.state("x" + std::to_string(i + 1)));
  std::vector<GiNaC::ex> monomials;
  for (const auto& indices : system.monomials) {
    GiNaC::ex monomial = 1;
    for (std::size_t k : indices) monomial *= x[k];
    monomials.push_back(monomial);
  }
  pfgen::ExVector f;
  pfgen::ExMatrix g(n, pfgen::ExVector(n, 0)), A(n, pfgen::ExVector(n, 0)), B(n, pfgen::ExVector(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    GiNaC::ex fi = 0;
    for (std::size_t t = 0; t < monomials.size(); ++t) fi += GiNaC::numeric(system.drift_tenths[i][t], 10) * monomials[t];
    f.push_back(fi);
    GiNaC::ex gi = GiNaC::numeric(system.diffusion_tenths[i][0], 10);
    for (std::size_t k = 0; k < n; ++k) gi += GiNaC::numeric(system.diffusion_tenths[i][k + 1], 10) * x[k];
    g[i][i] = gi;
    A[i][i] = 1;
    B[i][i] = 1;
  }
  b.drift(f).diffusion(g).observation(pfgen::ExVector(n, 0), A, B);
  return b.build();
}

}  // namespace pfgen_test
