// The registry of output languages (codegen/backend.hpp): one backend per kinds/output_languages row,
// by the same name, and everything the command line says of a language read from it.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "pfgen/codegen/backend.hpp"
#include "pfgen/kinds/output_languages.hpp"
#include "support/process.hpp"

using namespace pfgen;

TEST_CASE("every output language has one backend of its name, and every backend a language row", "[unit][codegen]") {
  std::set<std::string> facts, backends;
  for (const auto& language : output_languages()) facts.insert(language.name);
  for (const codegen::Backend* backend : codegen::backends()) {
    CHECK(backends.insert(backend->name()).second);
    CHECK(&codegen::backend(backend->name()) == backend);
    CHECK(backend->facts().name == backend->name());
    CHECK_FALSE(backend->summary().empty());
  }
  CHECK(facts == backends);
  CHECK(codegen::backends().front()->name() == codegen::CodegenOptions{}.language);  // the default first
  CHECK_THROWS_AS(codegen::backend("fortran"), std::logic_error);
}

TEST_CASE("codegen's --language help and check list every backend", "[integration][cli]") {
  const auto result = pfgen_test::run_program({PFGEN_EXECUTABLE, "codegen", "--help"});
  REQUIRE(result.exit_code == 0);
  std::string names;
  for (const codegen::Backend* backend : codegen::backends()) {
    CHECK(result.out.find(backend->summary()) != std::string::npos);
    names += (names.empty() ? "" : ",") + backend->name();
  }
  CHECK(result.out.find("--language TEXT:{" + names + "}") != std::string::npos);
}
