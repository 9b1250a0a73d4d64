# Fails when a Catch2 test case of TESTS has no class tag among CLASSES, or more than one
# (tests/CMakeLists.txt registers one ctest label per class).
set(none "")
set(pairs "")
foreach(class IN LISTS CLASSES)
  string(APPEND none "~[${class}]")
  foreach(other IN LISTS CLASSES)
    if(class STRLESS other)
      list(APPEND pairs "[${class}][${other}]")
    endif()
  endforeach()
endforeach()
list(JOIN pairs "," two)
foreach(spec IN ITEMS "${none}" "${two}")
  execute_process(COMMAND ${TESTS} --list-test-names-only "${spec}"
                  OUTPUT_VARIABLE listed ERROR_VARIABLE errors)
  string(STRIP "${listed}" listed)
  if(NOT listed STREQUAL "")
    message(FATAL_ERROR "test cases with no class tag or with two (spec ${spec}):\n${listed}\n"
                        "Give each exactly one of: ${CLASSES}")
  endif()
endforeach()
message(STATUS "every test case has exactly one class tag")
