// The C99 backend against the C++ backend: for every example model and every filter it has (the
// opt-in ukf included), in float and in double, the C code and the C++ code are compiled with the
// same optimisation flags and driven through the same inputs (the initial state nudged off the
// prior, then continuous steps, sampled predictions and updates, or delayed steps with their
// history), and every number they produce must be bit-identical: the two backends write the same
// operations in the same order, with the same operation counts. The C side is compiled by gcc and
// clang with -std=c99 -Wall -Wextra -Wpedantic -Werror, and may call no library function but
// sqrt/sqrtf and the model's own functions (scripts/embedded-check.sh compiles it for the
// Cortex-M4F).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "pfgen/codegen/backends/c/c_backend.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/process.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

struct Driven {
  std::string includes, body;
};

// The C++ statements that drive one filter through both backends and compare what they give.
std::string drive(const Model& model, const FilterEquations& eq, const std::string& scalar) {
  const std::string id = filter_identifier(eq.name);
  const std::string ns = "cpp_side::" + model.name + "::" + id;
  const std::string c = codegen::c_symbol_prefix("c_side", model.name, eq.name);
  std::string s = "  {\n    namespace F = " + ns + ";\n    using S = " + scalar + ";\n    const char* name = \"" +
                  model.name + "/" + eq.name + "\";\n";
  if (eq.observation == pfgen::ObservationKind::Delayed) {
    s += "    F::Filter a;\n    " + c + "_filter b;\n    " + c + "_filter_init(&b);\n";
    s += "    same(name, \"initial\", a.state.data(), b.state, F::state_size);\n";
    s += "    for (std::size_t k = 0; k < 3 * F::delay_steps + 7; ++k) {\n"
         "      S dy[F::p];\n"
         "      for (std::size_t r = 0; r < F::p; ++r) dy[r] = S(0.05) * std::sin(S(k + 2 * r + 1));\n"
         "      a.step(dy);\n      " + c + "_filter_step(&b, dy);\n"
         "      same(name, \"step\", a.state.data(), b.state, F::state_size);\n"
         "      same(name, \"history\", a.history.data(), b.history, F::history_size);\n    }\n  }\n";
    return s;
  }
  s += "    std::array<S, F::state_size> a{}, b{};\n    F::initial_state(a.data());\n    " + c +
       "_initial_state(b.data());\n    same(name, \"initial\", a.data(), b.data(), F::state_size);\n";
  // Off the prior: m moved, P's diagonal raised, so that every term has a nonzero share.
  s += "    for (std::size_t i = 0, k = F::n; i < F::n; ++i) {\n"
       "      a[i] += S(0.1) * S(i + 1);\n"
       "      for (std::size_t j = i; j < F::n; ++j, ++k)\n"
       "        if (i == j) a[k] += S(0.5);\n"
       "    }\n    b = a;\n";
  s += "    const F::Params<S> pa{};\n    " + c + "_params pb;\n    " + c + "_default_params(&pb);\n";
  if (eq.observation == pfgen::ObservationKind::Sampled) {
    s += "    S t = 0;\n    for (int k = 0; k < 12; ++k) {\n"
         "      S y[F::p];\n"
         "      for (std::size_t r = 0; r < F::p; ++r) y[r] = S(0.3) * std::sin(S(k + 3 * r + 1));\n"
         "      const int ua = F::advance(a.data(), t, y, pa) ? 1 : 0;\n"
         "      const int ub = " + c + "_advance(b.data(), t, y, &pb);\n"
         "      same_flag(name, ua, ub);\n"
         "      same(name, \"advance\", a.data(), b.data(), F::state_size);\n"
         "      F::predict(a.data(), t, F::period() / S(3), pa);\n      " + c +
         "_predict(b.data(), t, " + c + "_period() / S(3), &pb);\n"
         "      same(name, \"predict\", a.data(), b.data(), F::state_size);\n"
         "      t += F::period();\n    }\n  }\n";
    return s;
  }
  s += "    S t = 0;\n    const S dt = S(0.01);\n    for (int k = 0; k < 60; ++k) {\n"
       "      S dy[F::p];\n"
       "      for (std::size_t r = 0; r < F::p; ++r) dy[r] = S(0.02) * std::sin(S(k + 2 * r + 1));\n"
       "      F::step(a.data(), t, dt, dy, pa);\n      " + c + "_step(b.data(), t, dt, dy, &pb);\n"
       "      same(name, \"step\", a.data(), b.data(), F::state_size);\n      t += dt;\n    }\n"
       "    std::array<S, F::state_size> da{}, db{};\n    std::array<S, F::n * F::p> Ka{}, Kb{};\n"
       "    std::array<S, F::p> ha{}, hb{};\n"
       "    F::derivatives(t, a.data(), pa, da.data());\n    " + c + "_derivatives(t, b.data(), &pb, db.data());\n"
       "    F::gain(t, a.data(), pa, Ka.data());\n    " + c + "_gain(t, b.data(), &pb, Kb.data());\n"
       "    F::predicted_observation(t, a.data(), pa, ha.data());\n    " + c +
       "_predicted_observation(t, b.data(), &pb, hb.data());\n"
       "    same(name, \"derivatives\", da.data(), db.data(), F::state_size);\n"
       "    same(name, \"gain\", Ka.data(), Kb.data(), F::n * F::p);\n"
       "    same(name, \"predicted_observation\", ha.data(), hb.data(), F::p);\n  }\n";
  return s;
}

std::string run(const std::string& command) {
  const auto result = pfgen_test::run_process(command);
  INFO(command << "\n" << result.err.substr(0, 3000));
  REQUIRE(result.exit_code == 0);
  return result.out;
}

}  // namespace

TEST_CASE("the C backend's results are bit-identical to the C++ backend's on every example and kind",
          "[codegen][c][compiler]") {
  std::vector<std::string> examples;
  for (const auto& entry : std::filesystem::directory_iterator(pfgen_test::source_dir() + "/examples"))
    if (entry.path().extension() == ".yaml") examples.push_back(entry.path().string());
  std::sort(examples.begin(), examples.end());
  REQUIRE(examples.size() >= 8);

  for (const std::string scalar : {"double", "float"}) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pfgen-test-c-backend-" + scalar);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::string includes, body;
    std::vector<std::string> c_files;
    std::size_t filters = 0;
    for (const std::string& path : examples) {
      const Model model = load_model_file(path);
      for (const std::string& name : available_filter_names(model)) {
        // The moment filters' state grows as C(n + k, k): their files for the larger examples (ins16: 4844
        // variables at order 4) would take minutes to compile; they are checked here on the examples of up to
        // three states.
        if (const auto kind = parse_filter_kind(name); kind && uses_cumulant_closure(*kind) && model.n() > 3) continue;
        const FilterEquations eq = derive_named_filter(model, name);
        codegen::CodegenOptions options;
        options.scalar = scalar == "float" ? codegen::ScalarMode::Float : codegen::ScalarMode::Double;
        options.grid_step = model.simulation.dt;  // a delayed filter's grid, as `pfgen codegen` takes it
        std::vector<std::pair<std::size_t, std::size_t>> cpp_counts;
        for (const std::string language : {"cpp", "c"}) {
          options.language = language;
          const bool c = language == "c";
          options.name_space = c ? "c_side" : "cpp_side";
          const codegen::GeneratedFilter code = codegen::generate_filter_code(model, eq, options);
          // The same graphs: the same operation counts, function by function.
          if (c) {
            REQUIRE(code.functions.size() == cpp_counts.size());
            for (std::size_t k = 0; k < cpp_counts.size(); ++k) {
              INFO(name << " " << code.functions[k].function);
              CHECK(code.functions[k].naive.total() == cpp_counts[k].first);
              CHECK(code.functions[k].cse.total() == cpp_counts[k].second);
            }
          } else {
            cpp_counts.clear();
            for (const auto& f : code.functions) cpp_counts.emplace_back(f.naive.total(), f.cse.total());
          }
          for (const auto& file : code.files) {
            const std::filesystem::path out = dir / options.name_space / file.relative_path;
            std::filesystem::create_directories(out.parent_path());
            std::ofstream(out) << file.contents;
            if (out.extension() == ".c") c_files.push_back(out.string());
          }
          includes += "#include \"" + options.name_space + "/" + code.files.at(0).relative_path + "\"\n";
        }
        body += drive(model, eq, scalar);
        ++filters;
      }
    }
    const std::string program =
        "#include <array>\n#include <cmath>\n#include <cstdint>\n#include <cstdio>\n#include <cstring>\n" + includes +
        "\nstatic long compared = 0, differing = 0;\n"
        "template <class S>\nvoid same(const char* filter, const char* what, const S* a, const S* b, std::size_t count) {\n"
        "  for (std::size_t k = 0; k < count; ++k, ++compared)\n"
        "    if (std::memcmp(&a[k], &b[k], sizeof(S)) != 0 && ++differing <= 20)\n"
        "      std::printf(\"%s %s[%zu]: C++ %.17g, C %.17g\\n\", filter, what, k, double(a[k]), double(b[k]));\n"
        "}\n"
        "void same_flag(const char* filter, int a, int b) {\n"
        "  ++compared;\n  if (a != b && ++differing <= 20) std::printf(\"%s update: C++ %d, C %d\\n\", filter, a, b);\n}\n"
        "int main() {\n" + body + "  std::printf(\"compared %ld differing %ld\\n\", compared, differing);\n  return 0;\n}\n";
    std::ofstream(dir / "main.cpp") << program;

    // The C side: strict C99, warnings as errors, then its undefined symbols.
    std::string objects;
    std::set<std::string> undefined;
    for (std::size_t k = 0; k < c_files.size(); ++k) {
      const std::string object = (dir / ("c" + std::to_string(k) + ".o")).string();
      run("cc -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -c " + pfgen_test::shell_quote(c_files[k]) + " -o " +
          pfgen_test::shell_quote(object));
      run("clang -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -c " + pfgen_test::shell_quote(c_files[k]) +
          " -o /dev/null");
      std::istringstream symbols(run("nm -u " + pfgen_test::shell_quote(object)));
      std::string kind, symbol;
      while (symbols >> kind >> symbol) undefined.insert(symbol);
      objects += " " + pfgen_test::shell_quote(object);
    }
    // sqrt for the sampled filters' Cholesky solve and the ukf's sigma points; the examples' own
    // functions of t (paper 002's tracking model: none; ins16: none) would add theirs.
    for (const std::string& symbol : undefined) {
      INFO(scalar << ": the C code calls " << symbol);
      CHECK((symbol == "sqrt" || symbol == "sqrtf"));
    }
    const std::string binary = (dir / "compare").string();
    run("c++ -std=c++17 -O2 -I " + pfgen_test::shell_quote(dir.string()) + " " +
        pfgen_test::shell_quote((dir / "main.cpp").string()) + objects + " -lm -o " + pfgen_test::shell_quote(binary));
    const std::string out = run(pfgen_test::shell_quote(binary));
    INFO(scalar << ", " << filters << " filters:\n" << out);
    std::smatch counts;
    REQUIRE(std::regex_search(out, counts, std::regex("compared ([0-9]+) differing ([0-9]+)")));
    CHECK(std::stol(counts[1]) > 10000);
    CHECK(counts[2] == "0");
    CHECK(filters >= 30);  // 31 on the examples of today
  }
}
