# pfgen_add_filter(TARGET <target> MODEL <file.yaml>
#                  [FILTERS <kind>...] [SCALAR float|double|template] [NAMESPACE <ns>]
#                  [EIGEN] [OUTPUT_DIR <dir>])
#
# Runs `pfgen codegen` on MODEL at build time into OUTPUT_DIR (default
# ${CMAKE_CURRENT_BINARY_DIR}/pfgen_generated), again whenever the model file or
# the pfgen program changes, and adds OUTPUT_DIR to TARGET's include path, so that
# TARGET's sources `#include "<model name>/<kind>.hpp"`. FILTERS defaults to every
# kind the model supports, SCALAR to template, NAMESPACE to pfgen_models; EIGEN
# also writes <kind>_eigen.hpp (TARGET then needs Eigen). Call it in the directory
# that defines TARGET. The file names depend on the model's `name` and kinds, so
# pfgen is asked for them at configure time, and CMake configures again when the
# model changes.
include_guard(GLOBAL)

# The path of the imported pfgen::pfgen program, for use at configure time.
function(_pfgen_program_location out)
  if(NOT TARGET pfgen::pfgen)
    message(FATAL_ERROR "pfgen: no target pfgen::pfgen; use find_package(pfgen)")
  endif()
  get_target_property(location pfgen::pfgen IMPORTED_LOCATION)
  if(NOT location)
    get_target_property(configurations pfgen::pfgen IMPORTED_CONFIGURATIONS)
    foreach(configuration IN LISTS configurations)
      get_target_property(location pfgen::pfgen IMPORTED_LOCATION_${configuration})
      if(location)
        break()
      endif()
    endforeach()
  endif()
  if(NOT location)
    message(FATAL_ERROR "pfgen: pfgen::pfgen has no imported location")
  endif()
  set(${out} "${location}" PARENT_SCOPE)
endfunction()

function(pfgen_add_filter)
  cmake_parse_arguments(PARSE_ARGV 0 arg "EIGEN" "TARGET;MODEL;SCALAR;NAMESPACE;OUTPUT_DIR" "FILTERS")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "pfgen_add_filter: unexpected arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_TARGET OR NOT TARGET "${arg_TARGET}")
    message(FATAL_ERROR "pfgen_add_filter: TARGET '${arg_TARGET}' is not a target")
  endif()
  get_target_property(target_type "${arg_TARGET}" TYPE)
  get_target_property(target_dir "${arg_TARGET}" SOURCE_DIR)
  if(target_type STREQUAL "INTERFACE_LIBRARY" OR target_type STREQUAL "UTILITY")
    message(FATAL_ERROR "pfgen_add_filter: TARGET '${arg_TARGET}' must be an executable or a compiled library")
  endif()
  if(NOT target_dir STREQUAL CMAKE_CURRENT_SOURCE_DIR)
    message(FATAL_ERROR "pfgen_add_filter: call it in the directory that defines '${arg_TARGET}' (${target_dir})")
  endif()
  if(NOT arg_MODEL)
    message(FATAL_ERROR "pfgen_add_filter: MODEL is required")
  endif()
  cmake_path(ABSOLUTE_PATH arg_MODEL BASE_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" NORMALIZE OUTPUT_VARIABLE model)
  if(NOT EXISTS "${model}")
    message(FATAL_ERROR "pfgen_add_filter: model file '${model}' does not exist")
  endif()
  if(NOT arg_OUTPUT_DIR)
    set(arg_OUTPUT_DIR pfgen_generated)
  endif()
  cmake_path(ABSOLUTE_PATH arg_OUTPUT_DIR BASE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}" NORMALIZE
             OUTPUT_VARIABLE output_dir)

  set(options "")
  if(arg_FILTERS)
    list(JOIN arg_FILTERS "," filters)
    list(APPEND options --filter "${filters}")
  endif()
  if(arg_SCALAR)
    list(APPEND options --scalar "${arg_SCALAR}")
  endif()
  if(arg_NAMESPACE)
    list(APPEND options --namespace "${arg_NAMESPACE}")
  endif()
  if(arg_EIGEN)
    list(APPEND options --eigen)
  endif()

  # Ask pfgen which files it will write (this also checks the model and the options now).
  _pfgen_program_location(pfgen)
  execute_process(COMMAND "${pfgen}" codegen "${model}" --stats ${options}
                  OUTPUT_VARIABLE stats ERROR_VARIABLE error RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    string(STRIP "${error}" error)
    message(FATAL_ERROR "pfgen_add_filter: ${error}")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${model}")
  string(REGEX MATCHALL "\"model\": \"[A-Za-z0-9_]+\", \"filter\": \"[A-Za-z0-9_-]+\"" files "${stats}")
  if(NOT files)
    message(FATAL_ERROR "pfgen_add_filter: pfgen codegen --stats printed no filter: ${stats}")
  endif()
  set(outputs "")
  foreach(file IN LISTS files)
    string(REGEX REPLACE "\"model\": \"([A-Za-z0-9_]+)\", \"filter\": \"([A-Za-z0-9_-]+)\"" "\\1;\\2" pair "${file}")
    list(GET pair 0 model_name)
    list(GET pair 1 kind)
    string(REPLACE "-" "_" kind "${kind}")
    list(APPEND outputs "${output_dir}/${model_name}/${kind}.hpp")
    if(arg_EIGEN)
      list(APPEND outputs "${output_dir}/${model_name}/${kind}_eigen.hpp")
    endif()
  endforeach()

  # One rule, driven by one custom target, per set of outputs: several targets may share a model's
  # headers, as long as they ask for the same code.
  string(MD5 rule_key "${outputs}")
  string(SUBSTRING "${rule_key}" 0 12 rule_key)
  set(generate_target "pfgen_generate_${model_name}_${rule_key}")
  get_property(rule DIRECTORY PROPERTY _pfgen_rule_${rule_key})
  set(this_rule "${model};${options}")
  if("${rule}" STREQUAL "")
    set_property(DIRECTORY PROPERTY _pfgen_rule_${rule_key} "${this_rule}")
    add_custom_command(
      OUTPUT ${outputs}
      COMMAND pfgen::pfgen codegen "${model}" -o "${output_dir}" ${options}
      DEPENDS "${model}" "$<TARGET_FILE:pfgen::pfgen>"
      COMMENT "pfgen: generating ${model_name} filter code from ${arg_MODEL}"
      VERBATIM)
    add_custom_target(${generate_target} DEPENDS ${outputs})
  elseif(NOT "${rule}" STREQUAL "${this_rule}")
    message(FATAL_ERROR "pfgen_add_filter: ${output_dir} already gets ${model_name} with other options; "
                        "give this call its own OUTPUT_DIR")
  endif()
  add_dependencies("${arg_TARGET}" ${generate_target})
  target_sources("${arg_TARGET}" PRIVATE ${outputs})
  target_include_directories("${arg_TARGET}" PUBLIC "${output_dir}")
endfunction()
