// pfgen::api::ModelBuilder: the model builder behind the model file, for models made in code.
#include "api_impl.hpp"
#include "pfgen/model/model_builder.hpp"

namespace pfgen::api {
namespace {

// A C++ double as the exact rational of its shortest decimal, as in expressions (0.1 -> 1/10).
GiNaC::numeric exact(double value) { return GiNaC::ex_to<GiNaC::numeric>(exact_rationals(GiNaC::numeric(value))); }

std::vector<GiNaC::numeric> exact(const Vector& values) {
  std::vector<GiNaC::numeric> out;
  for (double value : values) out.push_back(exact(value));
  return out;
}

// The API's substeps 0: not given, each filter chooses (observations/sampled/substep_choice.hpp).
std::optional<std::size_t> given_substeps(std::size_t substeps) {
  return substeps == 0 ? std::nullopt : std::optional<std::size_t>(substeps);
}

}  // namespace

struct ModelBuilder::Impl {
  explicit Impl(const std::string& name) : builder(name) {}
  pfgen::ModelBuilder builder;
};

ModelBuilder::ModelBuilder(const std::string& name) : impl_(guarded([&] { return std::make_unique<Impl>(name); })) {}

ModelBuilder::~ModelBuilder() {
  if (impl_) destroy_locked(impl_.release());
}

ModelBuilder::ModelBuilder(ModelBuilder&&) noexcept = default;

ModelBuilder& ModelBuilder::operator=(ModelBuilder&& other) noexcept {
  if (impl_) destroy_locked(impl_.release());
  impl_ = std::move(other.impl_);
  return *this;
}

GiNaC::symbol ModelBuilder::state(const std::string& name) {
  return guarded([&] { return impl_->builder.state(name); });
}

GiNaC::symbol ModelBuilder::parameter(const std::string& name, double default_value) {
  return guarded([&] { return impl_->builder.parameter(name, exact(default_value)); });
}

GiNaC::symbol ModelBuilder::time() const {
  return guarded([&] { return impl_->builder.time(); });
}

ModelBuilder& ModelBuilder::drift(const Exprs& f) {
  guarded([&] { impl_->builder.drift(f); });
  return *this;
}

ModelBuilder& ModelBuilder::diffusion(const ExprMatrix& g) {
  guarded([&] { impl_->builder.diffusion(g); });
  return *this;
}

ModelBuilder& ModelBuilder::diffusion_covariance(const ExprMatrix& G) {
  guarded([&] { impl_->builder.diffusion_covariance(G); });
  return *this;
}

ModelBuilder& ModelBuilder::additive_diffusion(const ExprMatrix& g) {
  guarded([&] { impl_->builder.additive_diffusion(g); });
  return *this;
}

ModelBuilder& ModelBuilder::additive_diffusion_covariance(const ExprMatrix& G) {
  guarded([&] { impl_->builder.additive_diffusion_covariance(G); });
  return *this;
}

ModelBuilder& ModelBuilder::observation(const Exprs& A0, const ExprMatrix& A, const ExprMatrix& B) {
  guarded([&] { impl_->builder.observation(A0, A, B); });
  return *this;
}

ModelBuilder& ModelBuilder::delayed_observation(double delay, const Exprs& A0, const ExprMatrix& A,
                                                const ExprMatrix& B) {
  guarded([&] { impl_->builder.delayed_observation(exact(delay), A0, A, B); });
  return *this;
}

ModelBuilder& ModelBuilder::sampled_observation(double period, const Exprs& C0, const ExprMatrix& C,
                                                const ExprMatrix& Uv, std::size_t substeps) {
  guarded([&] { impl_->builder.sampled_observation(exact(period), C0, C, Uv, given_substeps(substeps)); });
  return *this;
}

ModelBuilder& ModelBuilder::sampled_polynomial_observation(double period, const Exprs& c, const ExprMatrix& Uv,
                                                          std::size_t substeps) {
  guarded([&] { impl_->builder.sampled_polynomial_observation(exact(period), c, Uv, given_substeps(substeps)); });
  return *this;
}

ModelBuilder& ModelBuilder::polynomial_observation(const Exprs& h, const ExprMatrix& B) {
  guarded([&] { impl_->builder.polynomial_observation(h, B); });
  return *this;
}

ModelBuilder& ModelBuilder::initial(const Vector& m0, const Matrix& P0, const Vector& x0) {
  guarded([&] {
    InitialConditions initial;
    initial.m0 = exact(m0);
    for (const Vector& row : P0) initial.P0.push_back(exact(row));
    initial.x0 = exact(x0);
    initial.x0_from_prior = x0.empty();
    impl_->builder.initial(initial);
  });
  return *this;
}

ModelBuilder& ModelBuilder::stratonovich() {
  guarded([&] { impl_->builder.noise(NoiseCalculus::Stratonovich); });
  return *this;
}

Model ModelBuilder::build() const {
  return guarded([&] { return Model(locked_shared(Model::Impl{impl_->builder.build(), "", ""})); });
}

}  // namespace pfgen::api
