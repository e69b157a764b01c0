# The libraries of qverify's compiled targets that come without a CMake package, as imported
# targets (included by the build's CMakeLists.txt and by the installed qverifyConfig.cmake):
#
#   qverify::gmp, qverify::mpfr, qverify::mpfi   header and library (exact rationals, MPFR, MPFI)
#   qverify::quadmath   libquadmath (Float128). Located by asking the C++ compiler
#                       (-print-file-name), so whatever GCC installation it uses is the one taken.
#                       With clang also GCC's quadmath.h: it lives in GCC's private include
#                       directory, next to GCC-only intrinsics headers that clang must not see, so
#                       that one header is copied into a directory of its own, which the target
#                       carries as a system include directory.
#   qverify::cgal       CGAL's headers (header-only use: Sqrt_extension, Interval_nt, Gmpq)
#
# Sets QVERIFY_MISSING_DEPENDENCIES to what could not be found (empty when all were).

set(QVERIFY_MISSING_DEPENDENCIES "")

function(_qverify_import_library name library header)
  if(TARGET qverify::${name})
    return()
  endif()
  string(TOUPPER "${name}" up)
  find_library(QVERIFY_${up}_LIBRARY ${library})
  find_path(QVERIFY_${up}_INCLUDE_DIR ${header})
  if(NOT QVERIFY_${up}_LIBRARY OR NOT QVERIFY_${up}_INCLUDE_DIR)
    set(QVERIFY_MISSING_DEPENDENCIES ${QVERIFY_MISSING_DEPENDENCIES} "${name} (lib${library}, ${header})" PARENT_SCOPE)
    return()
  endif()
  add_library(qverify::${name} UNKNOWN IMPORTED)
  set_target_properties(qverify::${name} PROPERTIES
    IMPORTED_LOCATION "${QVERIFY_${up}_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${QVERIFY_${up}_INCLUDE_DIR}")
endfunction()

_qverify_import_library(gmp gmp gmp.h)
_qverify_import_library(mpfr mpfr mpfr.h)
_qverify_import_library(mpfi mpfi mpfi.h)
if(TARGET qverify::mpfi AND TARGET qverify::mpfr AND TARGET qverify::gmp)
  set_property(TARGET qverify::mpfi PROPERTY INTERFACE_LINK_LIBRARIES qverify::mpfr qverify::gmp)
  set_property(TARGET qverify::mpfr PROPERTY INTERFACE_LINK_LIBRARIES qverify::gmp)
endif()

if(NOT TARGET qverify::cgal)
  find_path(QVERIFY_CGAL_INCLUDE_DIR CGAL/Sqrt_extension.h)
  if(QVERIFY_CGAL_INCLUDE_DIR)
    add_library(qverify::cgal INTERFACE IMPORTED)
    set_target_properties(qverify::cgal PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${QVERIFY_CGAL_INCLUDE_DIR}")
  else()
    list(APPEND QVERIFY_MISSING_DEPENDENCIES "cgal (CGAL/Sqrt_extension.h)")
  endif()
endif()

if(NOT TARGET qverify::quadmath)
  # Ask the compiler which libquadmath it links (an absolute path when it knows one).
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libquadmath.so
                  OUTPUT_VARIABLE _qverify_qm OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(IS_ABSOLUTE "${_qverify_qm}" AND EXISTS "${_qverify_qm}")
    cmake_path(NORMAL_PATH _qverify_qm)  # /usr/bin/../lib/gcc/... -> /usr/lib/gcc/... (symbolic links kept)
    set(QVERIFY_QUADMATH_LIBRARY "${_qverify_qm}" CACHE FILEPATH "libquadmath (from ${CMAKE_CXX_COMPILER} -print-file-name)")
  else()
    find_library(QVERIFY_QUADMATH_LIBRARY quadmath)
  endif()
  set(_qverify_qm_include "")
  set(_qverify_qm_ok TRUE)
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=include/quadmath.h
                    OUTPUT_VARIABLE _qverify_qm_h OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(IS_ABSOLUTE "${_qverify_qm_h}" AND EXISTS "${_qverify_qm_h}")
      cmake_path(NORMAL_PATH _qverify_qm_h)
      set(_qverify_qm_include "${CMAKE_BINARY_DIR}/qverify-quadmath-include")
      file(COPY "${_qverify_qm_h}" DESTINATION "${_qverify_qm_include}")
    else()
      set(_qverify_qm_ok FALSE)  # the header is required with clang
    endif()
  endif()
  if(QVERIFY_QUADMATH_LIBRARY AND _qverify_qm_ok)
    add_library(qverify::quadmath UNKNOWN IMPORTED)
    set_target_properties(qverify::quadmath PROPERTIES IMPORTED_LOCATION "${QVERIFY_QUADMATH_LIBRARY}")
    if(_qverify_qm_include)
      set_target_properties(qverify::quadmath PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_qverify_qm_include}")
    endif()
  else()
    list(APPEND QVERIFY_MISSING_DEPENDENCIES "quadmath (libquadmath.so, with clang also quadmath.h: ask ${CMAKE_CXX_COMPILER} -print-file-name)")
  endif()
  unset(_qverify_qm)
  unset(_qverify_qm_h)
  unset(_qverify_qm_include)
  unset(_qverify_qm_ok)
endif()
