# Build-time step of bench_handwritten for one size n (run with cmake -P):
#   PFGEN  the built pfgen;  WRITER  the built dense_linear_yaml;  N  the size;  OUT  the output directory.
# Writes OUT/models/dense_linear_N.yaml (tests/support/dense_linear_system.hpp's system), its optimal
# filter twice, OUT/double/dense_linear_N/optimal.hpp (namespace bench_hw_double, --scalar double)
# and OUT/float/dense_linear_N/optimal.hpp (bench_hw_float, --scalar float), and
# OUT/stats/dense_linear_N.hpp with the CSE op counts of the three generated functions that `step`
# calls, from `pfgen codegen --stats`. Each file is replaced only when its contents change, so a
# rebuilt pfgen that generates the same code does not recompile the generated headers.
foreach(variable PFGEN WRITER N OUT)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "handwritten_case.cmake: -D${variable}=... is required")
  endif()
endforeach()
set(NAME dense_linear_${N})
set(TMP ${OUT}/tmp-${NAME})
file(REMOVE_RECURSE ${TMP})
file(MAKE_DIRECTORY ${TMP})

execute_process(COMMAND ${WRITER} ${N} ${TMP}/${NAME}.yaml RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "dense_linear_yaml ${N} failed (${result})")
endif()
foreach(scalar double float)
  execute_process(
    COMMAND ${PFGEN} codegen ${TMP}/${NAME}.yaml --filter optimal --scalar ${scalar} --namespace bench_hw_${scalar}
            -o ${TMP}/${scalar} --stats
    OUTPUT_VARIABLE stats_json
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "pfgen codegen ${TMP}/${NAME}.yaml --scalar ${scalar} failed (${result})")
  endif()
endforeach()

# The CSE totals of derivatives, gain and predicted_observation (the same for both scalars).
# pfgen prints counts in shortest %g spelling (2e+01 is 20), hence double constants.
set(stats "")
string(JSON function_count LENGTH "${stats_json}" functions)
math(EXPR last "${function_count} - 1")
foreach(k RANGE ${last})
  string(JSON function GET "${stats_json}" functions ${k} function)
  string(JSON total GET "${stats_json}" functions ${k} cse total)
  string(APPEND stats "inline constexpr double ops_${function} = ${total};\n")
endforeach()
file(WRITE ${TMP}/stats.hpp
  "// Written by benchmarks/handwritten_case.cmake from `pfgen codegen --stats`; do not edit.\n"
  "#pragma once\n"
  "namespace pfgen_bench::hw_stats::${NAME} {\n"
  "${stats}"
  "}  // namespace pfgen_bench::hw_stats::${NAME}\n")

file(MAKE_DIRECTORY ${OUT}/models ${OUT}/double/${NAME} ${OUT}/float/${NAME} ${OUT}/stats)
file(COPY_FILE ${TMP}/${NAME}.yaml ${OUT}/models/${NAME}.yaml ONLY_IF_DIFFERENT)
foreach(scalar double float)
  file(COPY_FILE ${TMP}/${scalar}/${NAME}/optimal.hpp ${OUT}/${scalar}/${NAME}/optimal.hpp ONLY_IF_DIFFERENT)
endforeach()
file(COPY_FILE ${TMP}/stats.hpp ${OUT}/stats/${NAME}.hpp ONLY_IF_DIFFERENT)
file(REMOVE_RECURSE ${TMP})
