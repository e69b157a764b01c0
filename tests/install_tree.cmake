# Installs the build tree BUILD into PREFIX, afresh (the CTest fixture `installed_tree`: the
# example projects are configured against this prefix, never against the build tree).
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${PREFIX}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}):\n${out}\n${err}")
endif()
foreach(f lib/cmake/qverify/qverifyConfig.cmake lib/cmake/qverify/qverifyTargets.cmake include/qverify/core/core.hpp
         include/qverify/batch/batch.hpp include/qverify/eval/eval_report.hpp include/qverify/report/eval_document.hpp)
  if(NOT EXISTS "${PREFIX}/${f}")
    message(FATAL_ERROR "the installed tree lacks ${f}")
  endif()
endforeach()
message(STATUS "installed into ${PREFIX}")
