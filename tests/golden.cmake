# One golden test: runs the CLI QV with ARGS (a ;-list) in the source tree SRC and compares its
# stdout byte for byte with GOLDEN (tests/golden/NAME.json, written by scripts/update-golden).
# {work} in ARGS is a scratch directory of the build tree (the --out of a study).
string(REPLACE "{work}" "${WORK}" ARGS "${ARGS}")
execute_process(COMMAND ${QV} ${ARGS} WORKING_DIRECTORY ${SRC} RESULT_VARIABLE rc OUTPUT_FILE ${OUT} ERROR_VARIABLE err)
if(NOT (rc EQUAL 0 OR rc EQUAL 1))
  message(FATAL_ERROR "qverify ${ARGS}: exit ${rc}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${GOLDEN} RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  execute_process(COMMAND diff -u ${GOLDEN} ${OUT} OUTPUT_VARIABLE d)
  string(SUBSTRING "${d}" 0 4000 d)
  message(FATAL_ERROR "qverify ${ARGS}: the output differs from ${GOLDEN} (scripts/update-golden writes it, "
                      "when the change is meant):\n${d}")
endif()
