# cmake -DLINKER=ld -DOBJCOPY=objcopy -DNM=nm -DKEEP=prefix -DOUTPUT=out.o -DINPUTS="a.o;b.o" -P LocalizeObject.cmake
#
# Links INPUTS into one relocatable object OUTPUT in which every defined symbol is local except
# those whose (mangled) names start with KEEP, then checks that it is so. For the second batch
# kernels (exact/CMakeLists.txt; one call per compiler and -march): an object compiled with another
# -march or compiler defines its own copies of
# every inline function it uses (Eigen's, CGAL's, the standard library's) as weak symbols in
# COMDAT groups, and the final link keeps one copy of each group for the whole program, possibly
# the AVX-512 one for code that must run without AVX-512. `ld -r --force-group-allocation` takes
# the copies out of their groups and objcopy makes them local: each object then calls its own.
foreach(v LINKER OBJCOPY NM KEEP OUTPUT INPUTS)
  if(NOT DEFINED ${v} OR "${${v}}" STREQUAL "")
    message(FATAL_ERROR "LocalizeObject.cmake: ${v} is not set")
  endif()
endforeach()
execute_process(COMMAND ${LINKER} -r --force-group-allocation -o ${OUTPUT}.linked.o ${INPUTS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "LocalizeObject.cmake: ${LINKER} -r failed (${rc})")
endif()
execute_process(COMMAND ${OBJCOPY} --wildcard "--keep-global-symbol=${KEEP}*" ${OUTPUT}.linked.o ${OUTPUT}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "LocalizeObject.cmake: ${OBJCOPY} failed (${rc})")
endif()
file(REMOVE ${OUTPUT}.linked.o)
# Every global symbol it still defines must be an entry point, a strong definition (a weak one, an
# inline function, would be merged with the rest of the program's copies); and there must be some.
execute_process(COMMAND ${NM} -g --defined-only ${OUTPUT} OUTPUT_VARIABLE defined RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "LocalizeObject.cmake: ${NM} failed (${rc})")
endif()
string(REPLACE "\n" ";" defined "${defined}")
set(entries 0)
foreach(line IN LISTS defined)
  if(line STREQUAL "")
    continue()
  endif()
  string(REGEX REPLACE "^[0-9a-fA-F]* *([A-Za-z]) .*$" "\\1" kind "${line}")
  string(REGEX REPLACE "^[0-9a-fA-F]* *[A-Za-z] " "" name "${line}")
  string(FIND "${name}" "${KEEP}" at)
  if(NOT at EQUAL 0 OR NOT kind STREQUAL "T")
    file(REMOVE ${OUTPUT})
    message(FATAL_ERROR "LocalizeObject.cmake: ${OUTPUT} still defines the global symbol ${name} (${kind})")
  endif()
  math(EXPR entries "${entries} + 1")
endforeach()
if(entries EQUAL 0)
  file(REMOVE ${OUTPUT})
  message(FATAL_ERROR "LocalizeObject.cmake: ${OUTPUT} defines no entry point ${KEEP}*")
endif()
