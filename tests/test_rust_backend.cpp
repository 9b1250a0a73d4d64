// The Rust backend against the C backend: for every example model (examples/**/*.yaml, and a dense
// model whose P drift is written in loops) and every
// filter it has (the opt-in ukf included), in f32 and in f64, each Rust module is compiled by
// rustc as its own `#![no_std]` crate (edition 2021, warnings denied), and a Rust driver and a C
// driver put both through the same inputs (the initial state nudged off the prior, then
// continuous steps, sampled advances and predictions, or delayed steps with their history, then
// every function the filter has at the state reached) and print each number's bits. The C side
// is compiled with -ffp-contract=off, and rustc never contracts a multiply and an add, so both
// compute the same operations in the same order: every number must be bit-identical. The inputs
// are small integers times powers of two, exact in both scalar types, so that the two drivers
// start from the same bits.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "pfgen/codegen/backends/c/c_backend.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/process.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

// What one filter's drivers call, by its observation: the functions beyond the common ones.
enum class Shape { Rate, Polynomial, Sampled, SampledEuler, Delayed };

Shape shape_of(const FilterEquations& eq, const std::string& c_source) {
  switch (eq.observation) {
    case ObservationKind::Delayed: return Shape::Delayed;
    case ObservationKind::Sampled:
      return c_source.find("_euler_square(") != std::string::npos ? Shape::SampledEuler : Shape::Sampled;
    default: return c_source.find("_covariance_gain(") != std::string::npos ? Shape::Polynomial : Shape::Rate;
  }
}

// The Rust driver's block for one filter (module F, crate `krate`).
std::string rust_block(const std::string& krate, const std::string& label, Shape shape) {
  std::string s = "    {\n        use " + krate + " as F;\n        let name = \"" + label + "\";\n";
  if (shape == Shape::Delayed) {
    s += "        let mut b = F::Filter::new();\n        put(&mut o, name, \"initial\", &b.state);\n"
         "        for k in 0..2 * F::DELAY_STEPS + 7 {\n"
         "            let mut dy = [0.0 as S; F::OBSERVATIONS];\n"
         "            for r in 0..F::OBSERVATIONS {\n"
         "                dy[r] = ((k * 7 + r * 3) % 11) as S * 0.00390625 - 0.01953125;\n            }\n"
         "            b.step(&dy);\n            put(&mut o, name, \"step\", &b.state);\n        }\n"
         "        put(&mut o, name, \"history\", &b.history);\n"
         "        let mut delayed = [0.0 as S; F::DELAYED_SIZE];\n"
         "        for i in 0..F::DELAYED_SIZE {\n            delayed[i] = if i < F::STATES { b.state[i] } else { 0.5 };\n        }\n"
         "        let t = b.time();\n"
         "        let mut d = [0.0 as S; F::STATE_SIZE];\n"
         "        F::derivatives(t, &b.state, &delayed, &b.params, &mut d);\n        put(&mut o, name, \"derivatives\", &d);\n"
         "        let mut g = [0.0 as S; F::STATES * F::OBSERVATIONS];\n"
         "        F::gain(t, &b.state, &delayed, &b.params, &mut g);\n        put(&mut o, name, \"gain\", &g);\n"
         "        let mut h = [0.0 as S; F::OBSERVATIONS];\n"
         "        F::predicted_observation(t, &b.state, &delayed, &b.params, &mut h);\n"
         "        put(&mut o, name, \"predicted_observation\", &h);\n    }\n";
    return s;
  }
  s += "        let mut a = [0.0 as S; F::STATE_SIZE];\n        F::initial_state(&mut a);\n"
       "        put(&mut o, name, \"initial\", &a);\n"
       "        let mut k = F::STATES;\n"
       "        for i in 0..F::STATES {\n            a[i] += (i + 1) as S * 0.125;\n"
       "            for j in i..F::STATES {\n                if i == j {\n                    a[k] += 0.5;\n                }\n"
       "                k += 1;\n            }\n        }\n"
       "        let p = F::default_params();\n        let mut t: S = 0.0;\n";
  if (shape == Shape::Sampled || shape == Shape::SampledEuler) {
    s += "        for k in 0..12 {\n"
         "            let mut y = [0.0 as S; F::OBSERVATIONS];\n"
         "            for r in 0..F::OBSERVATIONS {\n"
         "                y[r] = ((k * 5 + r * 3) % 7) as S * 0.0625 - 0.1875;\n            }\n"
         "            let flag = F::advance(&mut a, t, &y, &p);\n"
         "            put(&mut o, name, \"updated\", &[if flag { 1.0 } else { 0.0 }]);\n"
         "            put(&mut o, name, \"advance\", &a);\n"
         "            F::predict(&mut a, t, F::period() / 3.0, &p);\n"
         "            put(&mut o, name, \"predict\", &a);\n"
         "            t += F::period();\n        }\n"
         "        let mut d = [0.0 as S; F::STATE_SIZE];\n"
         "        F::derivatives(t, &a, &p, &mut d);\n        put(&mut o, name, \"derivatives\", &d);\n"
         "        let mut u = [0.0 as S; F::STATES * F::OBSERVATIONS + F::OBSERVATIONS * (F::OBSERVATIONS + 1) / 2];\n"
         "        F::innovation_terms(t, &a, &p, &mut u);\n        put(&mut o, name, \"innovation_terms\", &u);\n"
         "        F::observation_matrices(t, &a, &p, &mut u);\n        put(&mut o, name, \"observation_matrices\", &u);\n"
         "        let mut h = [0.0 as S; F::OBSERVATIONS];\n"
         "        F::predicted_observation(t, &a, &p, &mut h);\n        put(&mut o, name, \"predicted_observation\", &h);\n";
    if (shape == Shape::SampledEuler)
      s += "        let mut e = [0.0 as S; F::STATE_SIZE - F::STATES];\n"
           "        F::euler_square(t, &a, &p, &mut e);\n        put(&mut o, name, \"euler_square\", &e);\n";
    return s + "    }\n";
  }
  s += "        let dt: S = 0.0078125;\n        for k in 0..60 {\n"
       "            let mut dy = [0.0 as S; F::OBSERVATIONS];\n"
       "            for r in 0..F::OBSERVATIONS {\n"
       "                dy[r] = ((k * 7 + r * 3) % 11) as S * 0.00390625 - 0.01953125;\n            }\n"
       "            F::step(&mut a, t, dt, &dy, &p);\n            put(&mut o, name, \"step\", &a);\n"
       "            t += dt;\n        }\n"
       "        let mut d = [0.0 as S; F::STATE_SIZE];\n"
       "        F::derivatives(t, &a, &p, &mut d);\n        put(&mut o, name, \"derivatives\", &d);\n"
       "        let mut g = [0.0 as S; F::STATES * F::OBSERVATIONS];\n"
       "        F::gain(t, &a, &p, &mut g);\n        put(&mut o, name, \"gain\", &g);\n"
       "        let mut h = [0.0 as S; F::OBSERVATIONS];\n"
       "        F::predicted_observation(t, &a, &p, &mut h);\n        put(&mut o, name, \"predicted_observation\", &h);\n";
  if (shape == Shape::Polynomial)
    s += "        let mut l = [0.0 as S; (F::STATE_SIZE - F::STATES) * F::OBSERVATIONS];\n"
         "        F::covariance_gain(t, &a, &p, &mut l);\n        put(&mut o, name, \"covariance_gain\", &l);\n"
         "        F::stratonovich_correction(t, &a, &p, &mut d);\n        put(&mut o, name, \"stratonovich_correction\", &d);\n";
  return s + "    }\n";
}

// The C driver's block for the same filter (names prefixed `c`).
std::string c_block(const std::string& c, const std::string& label, Shape shape) {
  std::string s = "  {\n    const char* name = \"" + label + "\";\n";
  if (shape == Shape::Delayed) {
    s += "    static " + c + "_filter b;\n    " + c + "_filter_init(&b);\n    put(name, \"initial\", b.state, " + c +
         "_state_size);\n"
         "    for (size_t k = 0; k < 2 * " + c + "_delay_steps + 7; ++k) {\n"
         "      S dy[" + c + "_p];\n"
         "      for (size_t r = 0; r < " + c + "_p; ++r) dy[r] = (S)((k * 7 + r * 3) % 11) * (S)0.00390625 - (S)0.01953125;\n"
         "      " + c + "_filter_step(&b, dy);\n      put(name, \"step\", b.state, " + c + "_state_size);\n    }\n"
         "    put(name, \"history\", b.history, " + c + "_history_size);\n"
         "    {\n      S delayed[" + c + "_delayed_size], d[" + c + "_state_size], g[" + c + "_n * " + c + "_p], h[" + c +
         "_p];\n"
         "      const S t = " + c + "_filter_time(&b);\n"
         "      for (size_t i = 0; i < " + c + "_delayed_size; ++i) delayed[i] = i < " + c +
         "_n ? b.state[i] : (S)0.5;\n"
         "      " + c + "_derivatives(t, b.state, delayed, &b.params, d);\n      put(name, \"derivatives\", d, " + c +
         "_state_size);\n"
         "      " + c + "_gain(t, b.state, delayed, &b.params, g);\n      put(name, \"gain\", g, " + c + "_n * " + c +
         "_p);\n"
         "      " + c + "_predicted_observation(t, b.state, delayed, &b.params, h);\n"
         "      put(name, \"predicted_observation\", h, " + c + "_p);\n    }\n  }\n";
    return s;
  }
  s += "    S a[" + c + "_state_size];\n    " + c + "_params p;\n    S t = 0;\n    size_t k = " + c + "_n;\n    " + c +
       "_initial_state(a);\n    put(name, \"initial\", a, " + c + "_state_size);\n"
       "    for (size_t i = 0; i < " + c + "_n; ++i) {\n      a[i] += (S)(i + 1) * (S)0.125;\n"
       "      for (size_t j = i; j < " + c + "_n; ++j, ++k)\n        if (i == j) a[k] += (S)0.5;\n    }\n"
       "    " + c + "_default_params(&p);\n";
  const std::string size = c + "_state_size", np = c + "_n * " + c + "_p";
  if (shape == Shape::Sampled || shape == Shape::SampledEuler) {
    s += "    for (size_t k = 0; k < 12; ++k) {\n      S y[" + c + "_p];\n      S flag;\n"
         "      for (size_t r = 0; r < " + c + "_p; ++r) y[r] = (S)((k * 5 + r * 3) % 7) * (S)0.0625 - (S)0.1875;\n"
         "      flag = " + c + "_advance(a, t, y, &p) ? (S)1 : (S)0;\n"
         "      put(name, \"updated\", &flag, 1);\n      put(name, \"advance\", a, " + size + ");\n"
         "      " + c + "_predict(a, t, " + c + "_period() / (S)3, &p);\n      put(name, \"predict\", a, " + size + ");\n"
         "      t += " + c + "_period();\n    }\n"
         "    {\n      S d[" + size + "], u[" + np + " + " + c + "_p * (" + c + "_p + 1) / 2], h[" + c + "_p];\n"
         "      " + c + "_derivatives(t, a, &p, d);\n      put(name, \"derivatives\", d, " + size + ");\n"
         "      " + c + "_innovation_terms(t, a, &p, u);\n      put(name, \"innovation_terms\", u, " + np + " + " + c +
         "_p * (" + c + "_p + 1) / 2);\n"
         "      " + c + "_observation_matrices(t, a, &p, u);\n      put(name, \"observation_matrices\", u, " + np +
         " + " + c + "_p * (" + c + "_p + 1) / 2);\n"
         "      " + c + "_predicted_observation(t, a, &p, h);\n      put(name, \"predicted_observation\", h, " + c +
         "_p);\n";
    if (shape == Shape::SampledEuler)
      s += "      {\n        S e[" + size + " - " + c + "_n];\n        " + c + "_euler_square(t, a, &p, e);\n"
           "        put(name, \"euler_square\", e, " + size + " - " + c + "_n);\n      }\n";
    return s + "    }\n  }\n";
  }
  s += "    for (size_t k = 0; k < 60; ++k) {\n      S dy[" + c + "_p];\n"
       "      for (size_t r = 0; r < " + c + "_p; ++r) dy[r] = (S)((k * 7 + r * 3) % 11) * (S)0.00390625 - (S)0.01953125;\n"
       "      " + c + "_step(a, t, (S)0.0078125, dy, &p);\n      put(name, \"step\", a, " + size + ");\n"
       "      t += (S)0.0078125;\n    }\n"
       "    {\n      S d[" + size + "], g[" + np + "], h[" + c + "_p];\n"
       "      " + c + "_derivatives(t, a, &p, d);\n      put(name, \"derivatives\", d, " + size + ");\n"
       "      " + c + "_gain(t, a, &p, g);\n      put(name, \"gain\", g, " + np + ");\n"
       "      " + c + "_predicted_observation(t, a, &p, h);\n      put(name, \"predicted_observation\", h, " + c +
       "_p);\n";
  if (shape == Shape::Polynomial)
    s += "      {\n        S l[(" + size + " - " + c + "_n) * " + c + "_p];\n"
         "        " + c + "_covariance_gain(t, a, &p, l);\n        put(name, \"covariance_gain\", l, (" + size + " - " + c +
         "_n) * " + c + "_p);\n"
         "        " + c + "_stratonovich_correction(t, a, &p, d);\n        put(name, \"stratonovich_correction\", d, " +
         size + ");\n      }\n";
  return s + "    }\n  }\n";
}

std::string run(const std::string& command) {
  const auto result = pfgen_test::run_process(command);
  INFO(command << "\n" << result.err.substr(0, 3000));
  REQUIRE(result.exit_code == 0);
  return result.out;
}

std::string q(const std::filesystem::path& path) { return pfgen_test::shell_quote(path.string()); }

// A number's value from its bits as the drivers print them (8 hex digits for f32, 16 for f64).
double value_of(const std::string& hex) {
  const std::uint64_t bits = std::stoull(hex, nullptr, 16);
  if (hex.size() == 8) {
    const auto narrow = static_cast<std::uint32_t>(bits);
    float f;
    std::memcpy(&f, &narrow, sizeof f);
    return f;
  }
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

}  // namespace

TEST_CASE("the Rust backend's modules compile with warnings denied and equal the C backend's results bit for bit",
          "[codegen][rust][compiler]") {
  const std::string rustc = PFGEN_RUSTC;
  std::vector<std::string> examples;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(pfgen_test::source_dir() + "/examples"))
    if (entry.path().extension() == ".yaml") examples.push_back(entry.path().string());
  std::sort(examples.begin(), examples.end());
  REQUIRE(examples.size() >= 20);
  // And a dense model whose rates() keep P's drift in loops (p_drift_loops.hpp, from n = 4), which
  // no example's filters do.
  examples.push_back(pfgen_test::source_dir() + "/benchmarks/models/dense_cubic_4.yaml");
  // Each filter derived once, for both scalar types.
  std::vector<Model> models;
  for (const std::string& path : examples) models.push_back(load_model_file(path));
  std::vector<std::pair<const Model*, FilterEquations>> derived;
  for (const Model& model : models)
    for (const std::string& name : available_filter_names(model)) {
      // The moment filters on the examples of up to three states (their state grows as C(n + k, k); as the C test).
      if (const auto kind = parse_filter_kind(name); kind && uses_cumulant_closure(*kind) && model.n() > 3) continue;
      derived.emplace_back(&model, derive_named_filter(model, name));
    }

  for (const std::string scalar : {"f64", "f32"}) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pfgen-test-rust-backend-" + scalar);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::string rust_body, c_includes, c_body, makefile = "all:", rules;
    std::vector<std::string> c_sources;
    std::string externs;
    std::size_t filters = 0;
    for (const auto& [model_pointer, eq] : derived) {
      const Model& model = *model_pointer;
      const std::string& name = eq.name;
      {
        codegen::CodegenOptions options;
        options.scalar = scalar == "f32" ? codegen::ScalarMode::Float : codegen::ScalarMode::Double;
        options.grid_step = model.simulation.dt;  // a delayed filter's grid, as `pfgen codegen` takes it
        // A short prefix for the C functions the comparison program calls (c_block below).
        options.name_space = "cs";
        options.language = "c";
        const codegen::GeneratedFilter c = codegen::generate_filter_code(model, eq, options);
        options.language = "rust";
        const codegen::GeneratedFilter rust = codegen::generate_filter_code(model, eq, options);
        // The same graphs: the same operation counts, function by function.
        REQUIRE(rust.functions.size() == c.functions.size());
        for (std::size_t k = 0; k < c.functions.size(); ++k) {
          INFO(model.name << "/" << name << " " << c.functions[k].function);
          CHECK(rust.functions[k].naive.total() == c.functions[k].naive.total());
          CHECK(rust.functions[k].cse.total() == c.functions[k].cse.total());
        }
        for (const auto& file : c.files) {
          const std::filesystem::path out = dir / "c" / file.relative_path;
          std::filesystem::create_directories(out.parent_path());
          std::ofstream(out) << file.contents;
          if (out.extension() == ".c") c_sources.push_back(out.string());
        }
        REQUIRE(rust.files.size() == 1);
        const std::filesystem::path module = dir / "rust" / rust.files[0].relative_path;
        std::filesystem::create_directories(module.parent_path());
        std::ofstream(module) << rust.files[0].contents;

        const std::string krate = "filter" + std::to_string(filters);
        const std::filesystem::path rlib = dir / ("lib" + krate + ".rlib");
        makefile += " " + rlib.string();
        // MAKEFLAGS and MFLAGS unset: rustc would try make's jobserver, whose descriptors are not passed on.
        rules += rlib.string() + ": " + module.string() + "\n\tenv -u MAKEFLAGS -u MFLAGS " + rustc +
                 " --edition 2021 -D warnings --crate-type lib --crate-name " + krate + " " + q(module) + " -o " +
                 q(rlib) + "\n";
        externs += " --extern " + krate + "=" + q(rlib);
        const std::string label = model.name + "/" + name;
        const Shape shape = shape_of(eq, c.files.at(1).contents);
        rust_body += rust_block(krate, label, shape);
        c_includes += "#include \"c/" + c.files.at(0).relative_path + "\"\n";
        c_body += c_block(codegen::c_symbol_prefix("cs", model.name, eq.name), label, shape);
        ++filters;
      }
    }
    CHECK(filters >= 90);  // 103 today, the opt-in ukf included

    // Each module its own crate, compiled once, two at a time.
    std::ofstream(dir / "Makefile") << makefile << "\n" << rules;
    run("make -s -j2 -f " + q(dir / "Makefile"));

    const std::string bits = scalar == "f32" ? "{:08x}" : "{:016x}";
    std::ofstream(dir / "driver.rs")
        << "use std::fmt::Write;\n\ntype S = " << scalar << ";\n\n"
        << "fn put(o: &mut String, name: &str, what: &str, values: &[S]) {\n"
        << "    for (i, v) in values.iter().enumerate() {\n"
        << "        writeln!(o, \"{} {} {} " << bits << "\", name, what, i, v.to_bits()).unwrap();\n    }\n}\n\n"
        << "fn main() {\n    let mut o = String::new();\n" << rust_body << "    print!(\"{}\", o);\n}\n";
    run(rustc + " --edition 2021 -D warnings -l m " + q(dir / "driver.rs") + " -o " + q(dir / "rust_driver") + externs +
        " -L " + q(dir));

    const std::string c_type = scalar == "f32" ? "float" : "double";
    const std::string c_bits = scalar == "f32" ? "uint32_t" : "uint64_t";
    const std::string c_format = scalar == "f32" ? "%08llx" : "%016llx";
    std::ofstream(dir / "driver.c")
        << "#include <stdint.h>\n#include <stdio.h>\n#include <string.h>\n" << c_includes << "\ntypedef " << c_type
        << " S;\n\nstatic void put(const char* name, const char* what, const S* values, size_t count) {\n"
        << "  for (size_t i = 0; i < count; ++i) {\n    " << c_bits << " b;\n    memcpy(&b, &values[i], sizeof b);\n"
        << "    printf(\"%s %s %zu " << c_format << "\\n\", name, what, i, (unsigned long long)b);\n  }\n}\n\n"
        << "int main(void) {\n" << c_body << "  return 0;\n}\n";
    std::string sources;
    for (const std::string& source : c_sources) sources += " " + pfgen_test::shell_quote(source);
    run("cc -std=c99 -O1 -ffp-contract=off -I " + q(dir) + " " + q(dir / "driver.c") + sources + " -lm -o " +
        q(dir / "c_driver"));

    // Line by line: the same label, then the same bits. A NaN is a NaN whatever its sign bit (the
    // ukf of paper 002's reactor reaches NaN in both; x86's sqrtsd and the C library's sqrt give
    // it different signs).
    std::istringstream rust_out(run(q(dir / "rust_driver"))), c_out(run(q(dir / "c_driver")));
    std::string rust_line, c_line, first_difference;
    std::size_t compared = 0, differing = 0, nans = 0, misaligned = 0;
    double largest = 0;
    while (std::getline(c_out, c_line)) {
      if (!std::getline(rust_out, rust_line)) {
        ++misaligned;
        break;
      }
      const std::size_t c_cut = c_line.rfind(' '), r_cut = rust_line.rfind(' ');
      if (c_line.compare(0, c_cut, rust_line, 0, r_cut) != 0) {
        ++misaligned;
        break;
      }
      ++compared;
      const std::string c_hex = c_line.substr(c_cut + 1), r_hex = rust_line.substr(r_cut + 1);
      if (c_hex == r_hex) continue;
      const double a = value_of(c_hex), b = value_of(r_hex);
      if (std::isnan(a) && std::isnan(b)) {
        ++nans;
        continue;
      }
      if (++differing == 1) first_difference = "C " + c_line + ", Rust " + rust_line;
      largest = std::max(largest, std::abs(a - b) / std::max(std::abs(a), std::abs(b)));
    }
    if (std::getline(rust_out, rust_line)) ++misaligned;
    INFO(scalar << ": " << filters << " filters, " << compared << " numbers compared, " << differing
                << " differing (largest relative difference " << largest << "), " << nans
                << " NaN in both with another sign bit; first difference: " << first_difference);
    CHECK(misaligned == 0);
    CHECK(compared > 50000);
    CHECK(differing == 0);
  }
}
