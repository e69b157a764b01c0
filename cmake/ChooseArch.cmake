# QVERIFY_ARCH=auto: which -march the build takes (included from the top-level CMakeLists.txt).
# Sets QVERIFY_MARCH (empty: the compiler's default, the x86-64 baseline), QVERIFY_DOUBLE_MARCH,
# QVERIFY_INTERVAL_MARCH and QVERIFY_DIGIT_MARCH (the -march of a second copy of the double batch
# kernel, of the interval batch kernel and of the exact digit blocks, run where the processor has
# it; empty when the build's own is the faster) and QVERIFY_ARCH_NOTE (how the choices were made,
# for the configure message).
#
# The build takes x86-64-v3 (AVX2, FMA) wherever the machine runs it, also on a machine with
# AVX-512: valgrind, which cannot execute AVX-512, then runs the release build itself, and
# ./run-tests needs no second tree for it (a release tree of AVX-512 made it build the CLI once
# more, 4 1/2 minutes of a 20-minute suite). Where the vector width pays is the three batch kernels,
# and each of them runs on the faster of the two levels where the processor has both: when this
# machine runs x86-64-v4 (AVX-512 F/BW/CD/DQ/VL) too, each kernel is measured with both -march
# values and, when x86-64-v4 is more than 10% faster, the exact library carries a second copy of it
# compiled for x86-64-v4, which its dispatcher (exact/double_batch.hpp, interval_batch.hpp,
# digit_batch.hpp) runs when the processor has it (asked at run time: never under valgrind).
#
# The widest instruction set is not always the fastest, hence the measurement: on AMD Zen 4 (one of this
# project's machines) the AVX-512 double batch kernel measured 2-3x slower than the AVX2 one before
# the store order of batch/batch.hpp was fixed (README, "bench"), and 30% faster after its stores
# became whole vectors; on AMD Zen 5 (family 26) the AVX-512 interval kernel and digit blocks took
# about 2/3 of the AVX2 ones' time while the double kernel was 5-10% faster with AVX2. The probe is
# cmake/arch_probe.cpp, which times the direct shadow batch in double and in certified intervals,
# and the exact digit blocks, built with each -march; the probes run in turn, seven times each
# (best of each; a run takes 0.1-0.3 s).
# The margin is the noise of the probe on a shared 2-core machine: at parity (AMD Zen 4 after the
# store-order fix) best-of-three with a 5% margin chose v4 at one configure and v3 at the next.
# The decisions and the timings are cached (QVERIFY_ARCH_MEASURED, internal) for this compiler,
# these sources of the kernels and this file, so a reconfigure does not measure again;
# `cmake -U QVERIFY_ARCH_MEASURED <build>` measures again.
# When the probe cannot be built or run (cross build, a compiler without the -march, no CPU
# support), the build is x86-64-v3 without second kernels (a probe that failed is remembered the
# same way, and not tried again at every configure).

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
set(QVERIFY_DOUBLE_MARCH "")
set(QVERIFY_INTERVAL_MARCH "")
set(QVERIFY_DIGIT_MARCH "")
set(QVERIFY_ARCH_NOTE "")
if(QVERIFY_HOST_HAS_X86_64_V3 AND QVERIFY_HOST_HAS_AVX512 AND QVERIFY_AVX512)
  # Both run here: measure (or take the cached measurement of the same compiler and kernels).
  set(_qv_probe_sources ${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp ${CMAKE_CURRENT_LIST_DIR}/arch_probe_project/CMakeLists.txt
      ${PROJECT_SOURCE_DIR}/batch/include/qverify/batch/batch.hpp ${PROJECT_SOURCE_DIR}/batch/include/qverify/batch/pack.hpp
      ${PROJECT_SOURCE_DIR}/exact/include/qverify/exact/interval_pack.hpp
      ${PROJECT_SOURCE_DIR}/exact/include/qverify/exact/digit_pack.hpp ${PROJECT_SOURCE_DIR}/exact/src/digit_batch_impl.hpp
      ${CMAKE_CURRENT_LIST_FILE})
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
    # the interval probe needs CGAL's headers and, through qverify's scalar headers, GMP and MPFR;
    # without them only the double kernel is measured (and no second interval kernel is built)
    find_path(_qv_cgal_include CGAL/Interval_nt.h)
    find_library(_qv_gmp gmp)
    find_library(_qv_mpfr mpfr)
    set(_qv_probe_kernels double)
    set(_qv_probe_includes "${PROJECT_SOURCE_DIR}/core/include;${PROJECT_SOURCE_DIR}/batch/include")
    set(_qv_probe_definitions "")
    set(_qv_probe_libraries Eigen3::Eigen)
    if(_qv_cgal_include AND _qv_gmp AND _qv_mpfr)
      list(APPEND _qv_probe_kernels interval)
      list(APPEND _qv_probe_kernels exact)
      string(APPEND _qv_probe_includes ";${PROJECT_SOURCE_DIR}/exact/include;${PROJECT_SOURCE_DIR}/exact/src;${_qv_cgal_include}")
      set(_qv_probe_definitions -DQVERIFY_PROBE_INTERVAL=1)
      list(APPEND _qv_probe_libraries ${_qv_mpfr} ${_qv_gmp})
    endif()
    unset(_qv_cgal_include CACHE)
    unset(_qv_gmp CACHE)
    unset(_qv_mpfr CACHE)
    if(TARGET Eigen3::Eigen)
      message(STATUS "qverify: timing the batch kernels with -march=x86-64-v3 and x86-64-v4 (QVERIFY_ARCH=auto)")
      set(_qv_ok TRUE)
      # Eigen is an imported target here: the probe project takes its include directories
      get_target_property(_qv_eigen_include Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
      list(REMOVE_ITEM _qv_probe_libraries Eigen3::Eigen)
      set(_qv_probe_dir ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe)
      # (lists cross to the project with | for ;, which would split the -D arguments)
      string(REPLACE ";" "|" _qv_includes_arg "${_qv_probe_includes};${_qv_eigen_include}")
      string(REPLACE ";" "|" _qv_libraries_arg "${_qv_probe_libraries}")
      try_compile(_qv_compiled ${_qv_probe_dir}/build ${CMAKE_CURRENT_LIST_DIR}/arch_probe_project qverify_arch_probe
                  CMAKE_FLAGS "-DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}"
                              "-DPROBE_SOURCE=${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp"
                              "-DPROBE_INCLUDES=${_qv_includes_arg}"
                              "-DPROBE_DEFINITIONS=${_qv_probe_definitions}"
                              "-DPROBE_LIBRARIES=${_qv_libraries_arg}"
                              "-DPROBE_OUTPUT=${_qv_probe_dir}"
                  OUTPUT_VARIABLE _qv_log)
      if(NOT _qv_compiled OR NOT EXISTS ${_qv_probe_dir}/arch_probe_v3 OR NOT EXISTS ${_qv_probe_dir}/arch_probe_v4)
        set(_qv_ok FALSE)
        file(WRITE ${_qv_probe_dir}/build.log "${_qv_log}")
        message(STATUS "qverify: the arch probes did not build (CMakeFiles/qverify_arch_probe/build.log)")
      endif()
      # Seven runs of each kernel and level, in turn (a shared machine's speed drifts; each run is
      # itself the best of eight passes over 2^19 items, of five over 2^17 for the slower intervals,
      # whose batches take twice the memory), and the best of each. A run's time is mostly touching
      # its memory the first time (2^20 items took 1.2 s a run, of which 0.08 s in the kernel):
      # half the items, still five times the largest cache, halved the configure's 29 s of probing.
      foreach(_qv_kernel double interval exact)
        foreach(_qv_level 3 4)
          set(_qv_best_${_qv_kernel}_${_qv_level} "")
          set(_qv_text_${_qv_kernel}_${_qv_level} failed)
        endforeach()
      endforeach()
      set(_qv_interval_ok FALSE)
      set(_qv_exact_ok FALSE)
      if("interval" IN_LIST _qv_probe_kernels)
        set(_qv_interval_ok TRUE)
        set(_qv_exact_ok TRUE)
      endif()
      if(_qv_ok)
        foreach(_qv_round 1 2 3 4 5 6 7)
          foreach(_qv_kernel double interval exact)
            if(_qv_kernel STREQUAL "double")
              set(_qv_items 524288)  # 150 MB of doubles
              set(_qv_passes 8)
            elseif(_qv_kernel STREQUAL "interval" AND _qv_interval_ok)
              set(_qv_items 131072)  # 80 MB of intervals, still far beyond the caches
              set(_qv_passes 5)
            elseif(_qv_kernel STREQUAL "exact" AND _qv_exact_ok)
              set(_qv_items 16384)  # bound by arithmetic: about 5 ms a pass
              set(_qv_passes 3)
            else()
              continue()
            endif()
            foreach(_qv_level 3 4)
              execute_process(COMMAND ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe/arch_probe_v${_qv_level}
                                      ${_qv_kernel} ${_qv_items} ${_qv_passes}
                              RESULT_VARIABLE _qv_rc OUTPUT_VARIABLE _qv_out ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE
                              TIMEOUT 60)
              if(NOT _qv_rc STREQUAL "0" OR NOT _qv_out MATCHES "^[0-9]+\\.[0-9]+$")
                message(STATUS "qverify: the ${_qv_kernel} arch probe built with -march=x86-64-v${_qv_level} did not run (${_qv_rc})")
                # a double probe that fails spoils the measurement; another one only its second kernel
                if(_qv_kernel STREQUAL "double")
                  set(_qv_ok FALSE)
                else()
                  set(_qv_${_qv_kernel}_ok FALSE)
                endif()
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
        # A second kernel for each of the three: only when its x86-64-v4 copy is more than 10% faster
        # than the build's x86-64-v3 one (v4 * 100 < v3 * 90), each measured on its own.
        foreach(_qv_kernel double interval exact)
          set(_qv_second_${_qv_kernel} none)
          if(_qv_kernel STREQUAL "double" OR _qv_${_qv_kernel}_ok)
            math(EXPR _qv_v4_scaled "${_qv_best_${_qv_kernel}_4} * 100")
            math(EXPR _qv_v3_scaled "${_qv_best_${_qv_kernel}_3} * 90")
            if(_qv_v4_scaled LESS _qv_v3_scaled)
              set(_qv_second_${_qv_kernel} x86-64-v4)
            endif()
          else()
            set(_qv_text_${_qv_kernel}_3 failed)
            set(_qv_text_${_qv_kernel}_4 failed)
          endif()
        endforeach()
        set(_qv_measured "${_qv_key};${_qv_second_double};${_qv_text_double_3};${_qv_text_double_4};${_qv_second_interval};${_qv_text_interval_3};${_qv_text_interval_4};${_qv_second_exact};${_qv_text_exact_3};${_qv_text_exact_4}")
        set(_qv_how "measured now")
      else()
        # remembered too, so that every reconfigure does not try again (-U QVERIFY_ARCH_MEASURED does)
        set(_qv_measured "${_qv_key};none;failed;failed;none;failed;failed;none;failed;failed")
      endif()
      set(QVERIFY_ARCH_MEASURED "${_qv_measured}" CACHE INTERNAL
          "QVERIFY_ARCH=auto: key (compiler, kernel sources); the -march of a second double kernel (none); ns/item of the double kernel with x86-64-v3 and x86-64-v4; the -march of a second interval kernel (none); ns/item of the interval kernel with x86-64-v3 and x86-64-v4; the same for the exact digit kernel")
    endif()
  endif()
  set(QVERIFY_MARCH x86-64-v3)
  if(_qv_measured)
    list(GET _qv_measured 1 _qv_second_double)
    list(GET _qv_measured 2 _qv_v3_ns)
    list(GET _qv_measured 3 _qv_v4_ns)
    list(GET _qv_measured 4 _qv_second)
    list(GET _qv_measured 5 _qv_interval_v3_ns)
    list(GET _qv_measured 6 _qv_interval_v4_ns)
    list(GET _qv_measured 7 _qv_second_exact)
    list(GET _qv_measured 8 _qv_exact_v3_ns)
    list(GET _qv_measured 9 _qv_exact_v4_ns)
  endif()
  if(_qv_measured AND NOT _qv_v3_ns STREQUAL "failed")
    set(QVERIFY_ARCH_NOTE "measured: double v3 ${_qv_v3_ns} ns/item, v4 ${_qv_v4_ns}; interval v3 ${_qv_interval_v3_ns}, v4 ${_qv_interval_v4_ns}; exact v3 ${_qv_exact_v3_ns}, v4 ${_qv_exact_v4_ns}; one thread; ${_qv_how}")
    foreach(_qv_pair "double;_qv_second_double;double batches" "INTERVAL;_qv_second;interval batches" "DIGIT;_qv_second_exact;exact digit blocks")
      list(GET _qv_pair 0 _qv_name)
      list(GET _qv_pair 1 _qv_var)
      list(GET _qv_pair 2 _qv_what)
      if(NOT ${_qv_var} STREQUAL "none")
        string(TOUPPER ${_qv_name} _qv_name)
        set(QVERIFY_${_qv_name}_MARCH ${${_qv_var}})
        string(APPEND QVERIFY_ARCH_NOTE "; ${_qv_what}: a second kernel for ${${_qv_var}}, run where the processor has it")
      endif()
    endforeach()
  else()
    set(QVERIFY_ARCH_NOTE "not measured, the probe did not build or run: no second kernels")
  endif()
elseif(QVERIFY_HOST_HAS_X86_64_V3)
  set(QVERIFY_MARCH x86-64-v3)
endif()
