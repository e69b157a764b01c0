# QVERIFY_ARCH=auto: which -march the build takes (included from the top-level CMakeLists.txt).
# Sets QVERIFY_MARCH (empty: the compiler's default, the x86-64 baseline), QVERIFY_INTERVAL_MARCH
# (the -march of a second copy of the interval batch kernel, run where the processor has it; empty
# when the build's own is the faster) and QVERIFY_ARCH_NOTE (how the choices were made, for the
# configure message).
#
# The widest instruction set is not always the fastest: on AMD Zen 4 (this project's machine) the
# AVX-512 build of the batch kernel measured 2-3x slower than the AVX2 one before the store order
# of batch/batch.hpp was fixed (README, "bench"). So when this machine runs both x86-64-v4 (AVX-512)
# and x86-64-v3 (AVX2), the choice is made by measurement: cmake/arch_probe.cpp, which times the
# direct shadow batch in double and in certified intervals, is built with each -march and the
# probes are run in turn, seven times each (best of each; a run takes 0.1-0.3 s); x86-64-v4 is taken
# for the build only when its double kernel is more than 10% faster. The interval kernel is
# measured on its own: it is bound by arithmetic and registers, not by memory, and on AMD Zen 4
# and 5 the AVX-512 one takes 2/3 of the AVX2 one's time while the double kernel is 5-10% faster
# with AVX2. When the build takes x86-64-v3 and the interval kernel is more than 10% faster with
# x86-64-v4, the exact library carries a second copy of it compiled for x86-64-v4, which the batch
# functions of exact/interval_batch.hpp run when the processor has AVX-512 (asked at run time).
# The margin is the noise of the probe on a shared 2-core machine: after the store-order fix the two
# are at parity on AMD Zen 4, and best-of-three with a 5% margin chose v4 at one configure and v3
# at the next. Ties go to the narrower set: valgrind then runs the release CLI, and ./run-tests
# needs no second build without AVX-512. The decision and both timings are
# cached (QVERIFY_ARCH_MEASURED, internal) for this compiler and these sources of the kernel, so a
# reconfigure does not measure again; `cmake -U QVERIFY_ARCH_MEASURED <build>` measures again.
# When the probe cannot be built or run (cross build, a compiler without the -march, no CPU
# support), the rule is the widest level this machine runs, as before the measurement (a probe
# that failed is remembered the same way, and not tried again at every configure).

include(CheckCXXSourceRuns)

# Does this machine run x86-64-v3 / x86-64-v4? (the CPU, asked at run time; false when cross-building)
check_cxx_source_runs([=[
  int main() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2") &&
           __builtin_cpu_supports("f16c") && __builtin_cpu_supports("movbe") ? 0 : 1;
  }]=] QVERIFY_HOST_HAS_X86_64_V3)
check_cxx_source_runs([=[
  int main() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl") ? 0 : 1;
  }]=] QVERIFY_HOST_HAS_AVX512)

set(QVERIFY_MARCH "")
set(QVERIFY_INTERVAL_MARCH "")
set(QVERIFY_ARCH_NOTE "")
if(QVERIFY_HOST_HAS_X86_64_V3 AND QVERIFY_HOST_HAS_AVX512 AND QVERIFY_AVX512)
  # Both run here: measure (or take the cached measurement of the same compiler and kernels).
  set(_qv_probe_sources ${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp
      ${PROJECT_SOURCE_DIR}/batch/include/qverify/batch/batch.hpp ${PROJECT_SOURCE_DIR}/batch/include/qverify/batch/pack.hpp
      ${PROJECT_SOURCE_DIR}/exact/include/qverify/exact/interval_pack.hpp)
  set(_qv_key "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION} ${CMAKE_CXX_COMPILER}")
  foreach(_qv_file IN LISTS _qv_probe_sources)
    file(SHA256 ${_qv_file} _qv_hash)
    string(APPEND _qv_key " ${_qv_hash}")
  endforeach()
  string(SHA256 _qv_key "${_qv_key}")
  set(_qv_measured "")
  if(DEFINED QVERIFY_ARCH_MEASURED)
    list(GET QVERIFY_ARCH_MEASURED 0 _qv_cached_key)
    if(_qv_cached_key STREQUAL _qv_key)
      set(_qv_measured ${QVERIFY_ARCH_MEASURED})
      set(_qv_how "measured at an earlier configure")
    endif()
  endif()
  if(NOT _qv_measured AND NOT CMAKE_CROSSCOMPILING)
    find_package(Eigen3 3.4 QUIET NO_MODULE)
    find_path(_qv_cgal_include CGAL/Interval_nt.h)
    find_library(_qv_gmp gmp)
    find_library(_qv_mpfr mpfr)
    if(TARGET Eigen3::Eigen AND _qv_cgal_include AND _qv_gmp AND _qv_mpfr)
      message(STATUS "qverify: timing the batch kernels with -march=x86-64-v3 and x86-64-v4 (QVERIFY_ARCH=auto)")
      set(_qv_ok TRUE)
      set(_qv_saved_config "${CMAKE_TRY_COMPILE_CONFIGURATION}")
      set(CMAKE_TRY_COMPILE_CONFIGURATION Release)
      foreach(_qv_level 3 4)
        set(_qv_exe ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe/arch_probe_v${_qv_level})
        try_compile(_qv_compiled ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe/v${_qv_level}
                    SOURCES ${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp
                    CMAKE_FLAGS "-DINCLUDE_DIRECTORIES=${PROJECT_SOURCE_DIR}/core/include;${PROJECT_SOURCE_DIR}/batch/include;${PROJECT_SOURCE_DIR}/exact/include;${_qv_cgal_include}"
                    COMPILE_DEFINITIONS -O3 -DNDEBUG -march=x86-64-v${_qv_level} -ffp-contract=off
                    LINK_LIBRARIES Eigen3::Eigen ${_qv_mpfr} ${_qv_gmp}
                    CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON
                    OUTPUT_VARIABLE _qv_log
                    COPY_FILE ${_qv_exe})
        if(NOT _qv_compiled)
          set(_qv_ok FALSE)
          file(WRITE ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe/v${_qv_level}.log "${_qv_log}")
          message(STATUS "qverify: the arch probe did not build with -march=x86-64-v${_qv_level} "
                         "(CMakeFiles/qverify_arch_probe/v${_qv_level}.log)")
          break()
        endif()
      endforeach()
      set(CMAKE_TRY_COMPILE_CONFIGURATION "${_qv_saved_config}")
      # Seven runs of each kernel and level, in turn (a shared machine's speed drifts; each run is
      # itself the best of five passes over 2^20 items, three for the slower intervals), and the best
      # of each.
      foreach(_qv_kernel double interval)
        foreach(_qv_level 3 4)
          set(_qv_best_${_qv_kernel}_${_qv_level} "")
        endforeach()
      endforeach()
      if(_qv_ok)
        foreach(_qv_round 1 2 3 4 5 6 7)
          foreach(_qv_kernel double interval)
            if(_qv_kernel STREQUAL "double")
              set(_qv_passes 5)
            else()
              set(_qv_passes 3)
            endif()
            foreach(_qv_level 3 4)
              execute_process(COMMAND ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe/arch_probe_v${_qv_level}
                                      ${_qv_kernel} 1048576 ${_qv_passes}
                              RESULT_VARIABLE _qv_rc OUTPUT_VARIABLE _qv_out ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE
                              TIMEOUT 60)
              if(NOT _qv_rc STREQUAL "0" OR NOT _qv_out MATCHES "^[0-9]+\\.[0-9]+$")
                set(_qv_ok FALSE)
                message(STATUS "qverify: the ${_qv_kernel} arch probe built with -march=x86-64-v${_qv_level} did not run (${_qv_rc})")
                break()
              endif()
              # CMake compares only integers: hundredths of a ns
              string(REPLACE "." "" _qv_centi "${_qv_out}")
              math(EXPR _qv_centi "${_qv_centi} + 0")
              if(_qv_best_${_qv_kernel}_${_qv_level} STREQUAL "" OR _qv_centi LESS _qv_best_${_qv_kernel}_${_qv_level})
                set(_qv_best_${_qv_kernel}_${_qv_level} ${_qv_centi})
                set(_qv_text_${_qv_kernel}_${_qv_level} ${_qv_out})
              endif()
            endforeach()
            if(NOT _qv_ok)
              break()
            endif()
          endforeach()
          if(NOT _qv_ok)
            break()
          endif()
        endforeach()
      endif()
      if(_qv_ok)
        # x86-64-v4 only when more than 10% faster: v4 * 100 < v3 * 90
        foreach(_qv_kernel double interval)
          math(EXPR _qv_v4_scaled "${_qv_best_${_qv_kernel}_4} * 100")
          math(EXPR _qv_v3_scaled "${_qv_best_${_qv_kernel}_3} * 90")
          if(_qv_v4_scaled LESS _qv_v3_scaled)
            set(_qv_choice_${_qv_kernel} x86-64-v4)
          else()
            set(_qv_choice_${_qv_kernel} x86-64-v3)
          endif()
        endforeach()
        set(_qv_measured "${_qv_key};${_qv_choice_double};${_qv_text_double_3};${_qv_text_double_4};${_qv_choice_interval};${_qv_text_interval_3};${_qv_text_interval_4}")
        set(_qv_how "measured now")
      else()
        # remembered too, so that every reconfigure does not try again (-U QVERIFY_ARCH_MEASURED does)
        set(_qv_measured "${_qv_key};x86-64-v4;failed;failed;x86-64-v4;failed;failed")
      endif()
      set(QVERIFY_ARCH_MEASURED "${_qv_measured}" CACHE INTERNAL
          "QVERIFY_ARCH=auto: key (compiler, kernel sources); choice, ns/item with x86-64-v3 and with x86-64-v4 of the double kernel; the same of the interval kernel")
    endif()
  endif()
  if(_qv_measured)
    list(GET _qv_measured 1 QVERIFY_MARCH)
    list(GET _qv_measured 2 _qv_v3_ns)
    list(GET _qv_measured 3 _qv_v4_ns)
    list(GET _qv_measured 4 _qv_interval_choice)
    list(GET _qv_measured 5 _qv_interval_v3_ns)
    list(GET _qv_measured 6 _qv_interval_v4_ns)
  endif()
  if(_qv_measured AND NOT _qv_v3_ns STREQUAL "failed")
    set(QVERIFY_ARCH_NOTE "measured: double v3 ${_qv_v3_ns} ns/item, v4 ${_qv_v4_ns}; interval v3 ${_qv_interval_v3_ns}, v4 ${_qv_interval_v4_ns}; one thread; ${_qv_how}")
    if(NOT _qv_interval_choice STREQUAL QVERIFY_MARCH)
      set(QVERIFY_INTERVAL_MARCH ${_qv_interval_choice})
      string(APPEND QVERIFY_ARCH_NOTE "; interval batches: a second kernel for ${_qv_interval_choice}, run where the processor has it")
    endif()
  else()
    set(QVERIFY_MARCH x86-64-v4)
    set(QVERIFY_ARCH_NOTE "not measured, the probe did not build or run: the widest level this machine runs")
  endif()
elseif(QVERIFY_HOST_HAS_X86_64_V3)
  set(QVERIFY_MARCH x86-64-v3)
endif()
