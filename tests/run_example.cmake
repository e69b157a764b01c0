# Configures, builds and tests examples/renderer-ctest against the qverify just built.
foreach(step
    "${CMAKE_COMMAND};-S;${SRC};-B;${BIN};-DQVERIFY_EXECUTABLE=${QV}"
    "${CMAKE_COMMAND};--build;${BIN}"
    "${CMAKE_CTEST_COMMAND};--test-dir;${BIN};--output-on-failure")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "example project: configured, built, its CTest suite passed")
