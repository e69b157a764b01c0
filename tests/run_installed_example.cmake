# Configures and builds the example project SRC in BIN against the installed qverify in PREFIX
# (CMAKE_PREFIX_PATH; compiler CXX, the one qverify was built with). Then runs PROGRAM (relative
# to BIN) with the argument ARG, which must exit 0 and, with EXPECT, print output matching that
# regular expression; without PROGRAM, the project's own CTest suite runs instead.
# Used with the CTest fixture `installed_tree` (tests/install_tree.cmake).
file(REMOVE_RECURSE "${BIN}")
if(PROGRAM)
  set(last "${BIN}/${PROGRAM};${ARG}")
else()
  set(last "${CMAKE_CTEST_COMMAND};--test-dir;${BIN};--output-on-failure")
endif()
# Without optimization (no build type): what is tested is that a user's project finds, builds and
# links against the installed tree and gets the right answers; at -O3 the Catch2 example took 47 s
# to build and run against 25 s (the GoogleTest one 21 s against 15), in a suite that has 20 minutes.
foreach(step
    "${CMAKE_COMMAND};-S;${SRC};-B;${BIN};-DCMAKE_PREFIX_PATH=${PREFIX};-DCMAKE_CXX_COMPILER=${CXX}"
    "${CMAKE_COMMAND};--build;${BIN}"
    "${last}")
  execute_process(COMMAND ${step} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${step}\n${out}\n${err}")
  endif()
endforeach()
if(EXPECT AND NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "the output does not match \"${EXPECT}\":\n${out}")
endif()
message(STATUS "${out}")
message(STATUS "${SRC}: configured and built against the installed tree ${PREFIX}; it ran and passed")
