# qverify_add_room(NAME SOURCES src... LINKS target... [PRECOMPILE header...])
# The library of the room NAME/ (one job, one folder): the static library qverify_NAME, alias
# qverify::NAME, exported as NAME; its headers are NAME/include/qverify/NAME/*.hpp, installed;
# it links publicly the rooms before it in the flow (scene -> eval -> verify -> studies -> report)
# and compiles with the precompiled headers below (PRECOMPILE: headers of its own added to them).
function(qverify_add_room name)
  cmake_parse_arguments(PARSE_ARGV 1 ROOM "" "" "SOURCES;LINKS;PRECOMPILE")
  add_library(qverify_${name} STATIC ${ROOM_SOURCES})
  add_library(qverify::${name} ALIAS qverify_${name})
  set_target_properties(qverify_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(qverify_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(qverify_${name} PUBLIC ${ROOM_LINKS})
  target_compile_options(qverify_${name} PRIVATE -Wall -Wextra)
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  qverify_precompile(qverify_${name} ${ROOM_PRECOMPILE})
endfunction()

# Precompiled headers. The third-party headers behind every room (Eigen, Boost.Multiprecision,
# CGAL's number types, parts of the standard library) took about half of each library file's
# compile time: `-fsyntax-only` of eval.hpp alone is 7.6 s. qverify_exact parses them once; the
# rooms with the same compile flags and definitions reuse its parse (REUSE_FROM), and a room
# that adds headers of its own (report: JSON and fmt) precompiles the list and those.
# Only third-party headers are listed: a file that misses an include of qverify's own still
# fails to compile here.
set(QVERIFY_PRECOMPILED_HEADERS
  <Eigen/Core> <Eigen/LU> <Eigen/Geometry>
  <boost/multiprecision/gmp.hpp> <boost/multiprecision/mpfr.hpp> <boost/multiprecision/mpfi.hpp>
  <boost/multiprecision/float128.hpp>
  <CGAL/Gmpq.h> <CGAL/Interval_nt.h> <CGAL/Sqrt_extension.h>
  <algorithm> <array> <cmath> <functional> <limits> <map> <optional> <sstream> <stdexcept> <string>
  <vector>)

# qverify_precompile(TARGET [HEADER...]): TARGET compiles with the precompiled headers above,
# its own set when HEADERs are given, else qverify_exact's.
function(qverify_precompile target)
  if(ARGN)
    target_precompile_headers(${target} PRIVATE ${QVERIFY_PRECOMPILED_HEADERS} ${ARGN})
  elseif(NOT target STREQUAL "qverify_exact")
    target_precompile_headers(${target} REUSE_FROM qverify_exact)
  else()
    target_precompile_headers(${target} PRIVATE ${QVERIFY_PRECOMPILED_HEADERS})
  endif()
endfunction()
