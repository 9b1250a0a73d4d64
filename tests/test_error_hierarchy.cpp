// One error type (pfgen_support/error.hpp): every error pfgen reports derives from
// pfgen_support::Error, carries its place where it has one, and says its own one line, which the
// command line prints after "pfgen: " from a single catch.
#include <catch2/catch.hpp>

#include <type_traits>

#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen/toolchain/process.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"
#include "pfgen_support/atomic_file.hpp"
#include "pfgen_support/error.hpp"
#include "pfgen_support/process.hpp"

using pfgen_support::Error;

TEST_CASE("errors: every error pfgen reports is a pfgen_support::Error", "[unit][errors]") {
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen::ModelError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen::EvaluationError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen::codegen::CodegenError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen::toolchain::ToolchainError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen::toolchain::PluginCompileError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen_runtime::PluginLoadError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen_support::ProcessError>);
  STATIC_REQUIRE(std::is_base_of_v<Error, pfgen_support::AtomicWriteError>);
}

TEST_CASE("errors: a model error carries its place and spells its own line", "[unit][errors]") {
  pfgen::ModelError error("diffusion", "'sin(x)' is not polynomial in the states", 1, 2);
  error.set_file("bad.yaml");
  error.set_location({4, 15});
  CHECK(error.report() ==
        "bad.yaml:4:15: error: field 'diffusion', row 1, column 2: 'sin(x)' is not polynomial in the states");
  CHECK(error.report() == error.what());
  const pfgen_support::ErrorPlace& place = error.place();
  CHECK(place.file == "bad.yaml");
  CHECK(place.line == 4);
  CHECK(place.column == 15);
  CHECK(place.field == "diffusion");
  CHECK(place.row == 1);
  CHECK(place.entry == 2);

  // The others say "error: " and their message; a file they could not write is their place.
  CHECK(pfgen::EvaluationError("division by zero at the point").report() == "error: division by zero at the point");
  const pfgen_support::AtomicWriteError write(pfgen_support::AtomicWriteError::Stage::not_a_file, "out.csv", "", 0);
  CHECK(write.report() == std::string("error: ") + write.what());
  CHECK(write.place().file == "out.csv");
}
