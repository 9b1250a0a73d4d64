# Build-time step of bench_codegen for one model (run with cmake -P):
#   PFGEN  the built pfgen;  MODEL_TO_CPP  the built model_to_cpp;  MODEL  the model file;
#   NAME  its `name:`;  OUT  the output directory.
# Writes the optimal filter twice, OUT/cse/NAME/optimal.hpp (namespace bench_cse) and
# OUT/nocse/NAME/optimal.hpp (namespace bench_nocse, --no-cse), both with --scalar double,
# OUT/stats/NAME.hpp holding derivatives()'s op counts from `pfgen codegen --stats`, and
# OUT/typed/NAME.hpp, the model's f and g as plain C++ for the quadrature baseline.
# Each file is replaced only when its contents change, so that a rebuilt pfgen that
# generates the same code does not recompile the (large) generated headers.
foreach(variable PFGEN MODEL_TO_CPP MODEL NAME OUT)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "codegen_case.cmake: -D${variable}=... is required")
  endif()
endforeach()

execute_process(
  COMMAND ${PFGEN} codegen ${MODEL} --filter optimal --scalar double --namespace bench_cse -o ${OUT}/tmp-${NAME}/cse --stats
  OUTPUT_VARIABLE stats_json
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "pfgen codegen ${MODEL} failed (${result})")
endif()
execute_process(
  COMMAND ${PFGEN} codegen ${MODEL} --filter optimal --scalar double --namespace bench_nocse -o ${OUT}/tmp-${NAME}/nocse --no-cse
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "pfgen codegen --no-cse ${MODEL} failed (${result})")
endif()

file(MAKE_DIRECTORY ${OUT}/tmp-${NAME})
execute_process(
  COMMAND ${MODEL_TO_CPP} ${MODEL}
  OUTPUT_FILE ${OUT}/tmp-${NAME}/typed.hpp
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "model_to_cpp ${MODEL} failed (${result})")
endif()

# The derivatives() entry of the one JSON line (one filter kind was asked for).
string(JSON function_count LENGTH "${stats_json}" functions)
math(EXPR last "${function_count} - 1")
set(found FALSE)
foreach(k RANGE ${last})
  string(JSON function GET "${stats_json}" functions ${k} function)
  if(function STREQUAL "derivatives")
    string(JSON ops_naive GET "${stats_json}" functions ${k} naive total)
    string(JSON ops_cse GET "${stats_json}" functions ${k} cse total)
    string(JSON muls_naive GET "${stats_json}" functions ${k} naive muls)
    string(JSON muls_cse GET "${stats_json}" functions ${k} cse muls)
    set(found TRUE)
  endif()
endforeach()
if(NOT found)
  message(FATAL_ERROR "pfgen codegen --stats ${MODEL}: no derivatives entry in: ${stats_json}")
endif()

file(WRITE ${OUT}/tmp-${NAME}/stats.hpp
  "// Written by benchmarks/codegen_case.cmake from `pfgen codegen --stats`; do not edit.\n"
  "#pragma once\n"
  "#include <cstddef>\n"
  "namespace pfgen_bench::stats::${NAME} {\n"
  "inline constexpr std::size_t ops_naive = ${ops_naive};\n"
  "inline constexpr std::size_t ops_cse = ${ops_cse};\n"
  "inline constexpr std::size_t muls_naive = ${muls_naive};\n"
  "inline constexpr std::size_t muls_cse = ${muls_cse};\n"
  "}  // namespace pfgen_bench::stats::${NAME}\n")
file(MAKE_DIRECTORY ${OUT}/cse/${NAME} ${OUT}/nocse/${NAME} ${OUT}/stats ${OUT}/typed)
file(COPY_FILE ${OUT}/tmp-${NAME}/cse/${NAME}/optimal.hpp ${OUT}/cse/${NAME}/optimal.hpp ONLY_IF_DIFFERENT)
file(COPY_FILE ${OUT}/tmp-${NAME}/nocse/${NAME}/optimal.hpp ${OUT}/nocse/${NAME}/optimal.hpp ONLY_IF_DIFFERENT)
file(COPY_FILE ${OUT}/tmp-${NAME}/stats.hpp ${OUT}/stats/${NAME}.hpp ONLY_IF_DIFFERENT)
file(COPY_FILE ${OUT}/tmp-${NAME}/typed.hpp ${OUT}/typed/${NAME}.hpp ONLY_IF_DIFFERENT)
file(REMOVE_RECURSE ${OUT}/tmp-${NAME})
