// LocalNames (codegen/local_names.hpp): the generated code's own names keep clear of the model's.
// The usual spelling when it is free, then with `_`, `_2`, `_3`, ... (never `__`, which C++
// reserves); temporaries `tmp<N>` move to `tmp_<N>`, `tmp_2_<N>`, ... while a model name has that form. Compiling such code is
// test_codegen_names.cpp's part.
#include <catch2/catch.hpp>

#include "pfgen/codegen/local_names.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

using pfgen::codegen::LocalNames;

TEST_CASE("local names: the usual spellings when the model leaves them free", "[unit][codegen]") {
  LocalNames names({"m1", "P11", "a", "t", "temp", "tmp", "tmpx", "tmp1x", "x"});
  CHECK(names.temporary_prefix() == "tmp");  // tmp, tmpx and tmp1x are no tmp<digits>
  CHECK(names.take("state") == "state");
  CHECK(names.take("params") == "params");
  CHECK(names.take("out") == "out");
  CHECK(names.take("x") == "x_");
}

TEST_CASE("local names: a taken name gets `_`, then `_2`, `_3`, ..., and each name is given once",
          "[unit][codegen]") {
  LocalNames names({"state", "state_", "K", "shared", "shared_", "shared_2"});
  CHECK(names.take("state") == "state_2");  // was state__, reserved in C++
  CHECK(names.take("shared") == "shared_3");
  CHECK(names.take("K") == "K_");
  CHECK(names.take("K") == "K_2");  // K_ is given out now
  CHECK(names.take("h") == "h");
  CHECK(names.take("h") == "h_");
}

TEST_CASE("local names: temporaries move away from model names of their form", "[unit][codegen]") {
  CHECK(LocalNames({"tmp0"}).temporary_prefix() == "tmp_");
  CHECK(LocalNames({"tmp12", "tmp_3"}).temporary_prefix() == "tmp_2_");  // was tmp__, reserved in C++
  CHECK(LocalNames({"tmp12", "tmp_3", "tmp_2_0"}).temporary_prefix() == "tmp_3_");
  CHECK(LocalNames({"tmp_3"}).temporary_prefix() == "tmp");  // tmp_3 is not tmp<digits>
  // An argument never takes the temporaries' form.
  LocalNames names({"tmp0"});
  CHECK(names.take("tmp_7") == "tmp_7_");
  CHECK(names.take("tmp7") == "tmp7");
}

TEST_CASE("local names: the inputs of a filter and of the truth", "[unit][codegen]") {
  const pfgen::Model model = pfgen::load_model_text(R"model(name: unit
states: [x, y]
time: s
parameters: {a: 1}
drift: ["-a*x", "-y"]
diffusion: [["1", "0"], ["0", "1"]]
observation: {A: [["1", "0"]], B: [["1"]]}
)model",
                                                    "unit.yaml");
  CHECK(pfgen::codegen::filter_input_names(model) ==
        std::set<std::string>{"m1", "m2", "P11", "P12", "P22", "a", "s"});
  CHECK(pfgen::codegen::truth_input_names(model) == std::set<std::string>{"x", "y", "a", "s"});
}
