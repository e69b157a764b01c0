# QVERIFY_ARCH=auto: which -march the build takes (included from the top-level CMakeLists.txt).
# Sets QVERIFY_MARCH (empty: the compiler's default, the x86-64 baseline), QVERIFY_DOUBLE_MARCH,
# QVERIFY_INTERVAL_MARCH and QVERIFY_DIGIT_MARCH (the -march of a second copy of the double batch
# kernel, of the interval batch kernel and of the exact digit blocks, run where the processor has
# it; empty when the build's own is the faster), QVERIFY_DOUBLE_COMPILER (the compiler of the second
# double kernel when it is not the build's: clang++) and QVERIFY_ARCH_NOTE (how the choices were
# made, for the configure message).
#
# The build takes x86-64-v3 (AVX2, FMA) wherever the machine runs it, also on a machine with
# AVX-512: valgrind, which cannot execute AVX-512, then runs the release build itself, and
# ./run-tests needs no second tree for it (a release tree of AVX-512 made it build the CLI once
# more, 4 1/2 minutes of a 20-minute suite). Where the code generation pays is the three batch
# kernels, and each of them runs the fastest of its measured variants: the build's compiler with
# x86-64-v3 (the build's own kernel) and, where this machine runs AVX-512 (F/BW/CD/DQ/VL), with
# x86-64-v4; for the double kernel also clang++ with each level, where the build's compiler is GCC
# and clang++ is installed. When the fastest variant is more than 10% faster than the build's own,
# the exact library carries a second copy of the kernel compiled that way, which its dispatcher
# (exact/double_batch.hpp, interval_batch.hpp, digit_batch.hpp) runs when the processor has the
# level (asked at run time: never an AVX-512 copy under valgrind).
#
# Neither the widest instruction set nor one compiler is always the fastest, hence the measurement:
# on AMD Zen 4 (one of this project's machines) the AVX-512 double batch kernel measured 2-3x slower
# than the AVX2 one before the store order of batch/batch.hpp was fixed (README, "bench"); on AMD
# Zen 5 (family 26) it measured 30% faster than AVX2 once its stores became whole vectors, and level
# with it on other days (9.50 against 9.73 ns per item, 2026-12-03); there the AVX-512 interval
# kernel and digit blocks take about 2/3 of the AVX2 ones' time, and clang 14 compiles the double
# kernel's AVX2 form in 70% of GCC 12's time (GCC keeps the 4x4 matrices of packs on the stack: about
# three times clang's stack accesses; README, "bench"), while clang's interval kernel, faster than
# GCC's AVX2 one, is no faster than GCC's AVX-512 one. The probe is cmake/arch_probe.cpp, which times the direct shadow
# batch in double and in certified intervals, and the exact digit blocks, built each way; the
# probes run in turn, seven times each (best of each; a run takes 0.1-0.3 s).
# The margin is the noise of the probe on a shared 2-core machine: at parity (AMD Zen 4 after the
# store-order fix) best-of-three with a 5% margin chose v4 at one configure and v3 at the next.
# The decisions and the timings are cached (QVERIFY_ARCH_MEASURED, internal) for these compilers,
# these sources of the kernels and this file, so a reconfigure does not measure again;
# `cmake -U QVERIFY_ARCH_MEASURED <build>` measures again.
# A cross build gets the baseline (the host checks below fail). When the probe cannot be built or
# run (a compiler without the -march, no CPU support), the build is x86-64-v3 without second kernels (a probe that failed is remembered the
# same way, and not tried again at every configure); a clang probe that fails only leaves clang out.

include(CheckCXXSourceRuns)

# Does this machine run x86-64-v3 / x86-64-v4? (the CPU, asked at run time; false when cross-building)
check_cxx_source_runs([=[
  int main() {
    __builtin_cpu_init();
    // (not "f16c" and "movbe", which clang 14 does not know: every processor with these three has both)
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2") ? 0 : 1;
  }]=] QVERIFY_HOST_HAS_X86_64_V3)
check_cxx_source_runs([=[
  int main() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl") ? 0 : 1;
  }]=] QVERIFY_HOST_HAS_AVX512)

# The variants measured: g3 and g4, the build's compiler with -march=x86-64-v3 / x86-64-v4 (g4 where
# the machine runs AVX-512 and QVERIFY_AVX512 is on); with GCC as the build's compiler and clang++
# installed, also c3 and c4, the double kernel compiled by clang (double only: see above), and c4n,
# clang's x86-64-v4 kernel with 256-bit packs (QVERIFY_PACK_BITS, pack.hpp): AVX-512's 32 vector
# registers hold the 4x4 matrices of packs that spill with 16 (on AMD Zen 5, in the caches, 4.4
# against c3's 5.0 ns per item for shadows, 6.7 against 7.6 for reflections, 2026-12-02). The
# clang probe and the clang kernel (exact/CMakeLists.txt) take the same flags and include paths
# (QVERIFY_KERNEL_CLANG_FLAGS, qverify_kernel_clang_includes), so that what is measured is what is
# built: -O3 whatever the build type, and the build's -ffp-contract=off.
set(QVERIFY_KERNEL_CLANG_VERSION "")
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND QVERIFY_HOST_HAS_X86_64_V3)
  find_program(QVERIFY_KERNEL_CLANG NAMES clang++ clang++-14 clang++-15 clang++-16
               DOC "clang++ for a measured second double batch kernel (QVERIFY_ARCH=auto)")
  if(QVERIFY_KERNEL_CLANG)
    execute_process(COMMAND ${QVERIFY_KERNEL_CLANG} -dumpversion OUTPUT_VARIABLE QVERIFY_KERNEL_CLANG_VERSION
                    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  endif()
endif()
set(QVERIFY_KERNEL_CLANG_FLAGS -O3 -DNDEBUG -std=gnu++17 -ffp-contract=off)
function(qverify_kernel_clang_includes out_var eigen_include)
  set(r "")
  foreach(dir IN ITEMS core/include batch/include exact/include)
    list(APPEND r -I${PROJECT_SOURCE_DIR}/${dir})
  endforeach()
  foreach(dir IN LISTS eigen_include)  # a third party's headers: not our warnings
    list(APPEND r -isystem ${dir})
  endforeach()
  set(${out_var} ${r} PARENT_SCOPE)
endfunction()
set(QVERIFY_MARCH "")
set(QVERIFY_DOUBLE_MARCH "")
set(QVERIFY_DOUBLE_COMPILER "")  # empty: the build's compiler
set(QVERIFY_DOUBLE_PACK_BITS "")  # empty: the -march's native pack width (pack.hpp)
set(QVERIFY_INTERVAL_MARCH "")
set(QVERIFY_DIGIT_MARCH "")
set(QVERIFY_ARCH_NOTE "")
if(QVERIFY_HOST_HAS_X86_64_V3)
  set(QVERIFY_MARCH x86-64-v3)
  set(_qv_variants g3)
  if(QVERIFY_HOST_HAS_AVX512 AND QVERIFY_AVX512)
    list(APPEND _qv_variants g4)
  endif()
  if(QVERIFY_KERNEL_CLANG_VERSION)
    list(APPEND _qv_variants c3)
    if("g4" IN_LIST _qv_variants)
      list(APPEND _qv_variants c4 c4n)
    endif()
  endif()
  # Measure (or take the cached measurement of the same compilers, variants and kernels).
  set(_qv_probe_sources ${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp ${CMAKE_CURRENT_LIST_DIR}/arch_probe_project/CMakeLists.txt
      ${PROJECT_SOURCE_DIR}/batch/include/qverify/batch/batch.hpp ${PROJECT_SOURCE_DIR}/batch/include/qverify/batch/pack.hpp
      ${PROJECT_SOURCE_DIR}/exact/include/qverify/exact/interval_pack.hpp
      ${PROJECT_SOURCE_DIR}/exact/include/qverify/exact/digit_pack.hpp ${PROJECT_SOURCE_DIR}/exact/src/digit_batch_impl.hpp
      ${CMAKE_CURRENT_LIST_FILE})
  set(_qv_key "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION} ${CMAKE_CXX_COMPILER} ${_qv_variants} clang ${QVERIFY_KERNEL_CLANG} ${QVERIFY_KERNEL_CLANG_VERSION}")
  foreach(_qv_file IN LISTS _qv_probe_sources)
    file(SHA256 ${_qv_file} _qv_hash)
    string(APPEND _qv_key " ${_qv_hash}")
  endforeach()
  string(SHA256 _qv_key "${_qv_key}")
  set(_qv_measured "")
  if(DEFINED QVERIFY_ARCH_MEASURED)
    list(GET QVERIFY_ARCH_MEASURED 0 _qv_cached_key)
    list(LENGTH QVERIFY_ARCH_MEASURED _qv_cached_fields)
    if(_qv_cached_key STREQUAL _qv_key AND _qv_cached_fields EQUAL 13)
      set(_qv_measured ${QVERIFY_ARCH_MEASURED})
      set(_qv_how "measured at an earlier configure")
    endif()
  endif()
  if(NOT _qv_measured AND NOT CMAKE_CROSSCOMPILING AND NOT _qv_variants STREQUAL "g3")
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
    if(_qv_cgal_include AND _qv_gmp AND _qv_mpfr AND "g4" IN_LIST _qv_variants)  # (else nothing to choose for them)
      list(APPEND _qv_probe_kernels interval exact)
      string(APPEND _qv_probe_includes ";${PROJECT_SOURCE_DIR}/exact/include;${PROJECT_SOURCE_DIR}/exact/src;${_qv_cgal_include}")
      set(_qv_probe_definitions -DQVERIFY_PROBE_INTERVAL=1)
      list(APPEND _qv_probe_libraries ${_qv_mpfr} ${_qv_gmp})
    endif()
    unset(_qv_cgal_include CACHE)
    unset(_qv_gmp CACHE)
    unset(_qv_mpfr CACHE)
    if(TARGET Eigen3::Eigen)
      message(STATUS "qverify: timing the batch kernels (${_qv_variants}; QVERIFY_ARCH=auto)")
      set(_qv_ok TRUE)
      # Eigen is an imported target here: the probe project takes its include directories
      get_target_property(_qv_eigen_include Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
      list(REMOVE_ITEM _qv_probe_libraries Eigen3::Eigen)
      set(_qv_probe_dir ${CMAKE_BINARY_DIR}/CMakeFiles/qverify_arch_probe)
      # (lists cross to the project with | for ;, which would split the -D arguments)
      string(REPLACE ";" "|" _qv_includes_arg "${_qv_probe_includes};${_qv_eigen_include}")
      string(REPLACE ";" "|" _qv_libraries_arg "${_qv_probe_libraries}")
      # (One difference remains between a probe and the library: the probes for x86-64-v4 allocate
      # their batches 64-byte aligned, as Eigen does there, and the library, built for x86-64-v3, 32-byte
      # aligned, so its AVX-512 kernels store each 64-byte vector as two halves (pack.hpp,
      # pack_aligned). Capping the probes' alignment at 32 (EIGEN_MAX_ALIGN_BYTES) does not compile
      # the kernels of 512-bit packs with clang, and without the 32-byte halves the library's
      # AVX-512 kernels fell back to 16-byte stores that no probe timed.)
      # Built afresh at every measurement: in the build tree a try_compile project kept, ninja's log
      # recorded no header dependencies (`ninja -t deps`: 0), so a change of batch.hpp or pack.hpp
      # alone (which changes the key above, hence a new measurement) timed the old probes.
      file(REMOVE_RECURSE ${_qv_probe_dir})
      try_compile(_qv_compiled ${_qv_probe_dir}/build ${CMAKE_CURRENT_LIST_DIR}/arch_probe_project qverify_arch_probe
                  CMAKE_FLAGS "-DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}"
                              "-DPROBE_SOURCE=${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp"
                              "-DPROBE_INCLUDES=${_qv_includes_arg}"
                              "-DPROBE_DEFINITIONS=${_qv_probe_definitions}"
                              "-DPROBE_LIBRARIES=${_qv_libraries_arg}"
                              "-DPROBE_OUTPUT=${_qv_probe_dir}"
                  OUTPUT_VARIABLE _qv_log)
      if(NOT _qv_compiled OR NOT EXISTS ${_qv_probe_dir}/arch_probe_v3
         OR ("g4" IN_LIST _qv_variants AND NOT EXISTS ${_qv_probe_dir}/arch_probe_v4))
        set(_qv_ok FALSE)
        file(WRITE ${_qv_probe_dir}/build.log "${_qv_log}")
        message(STATUS "qverify: the arch probes did not build (CMakeFiles/qverify_arch_probe/build.log)")
      endif()
      set(_qv_exe_g3 ${_qv_probe_dir}/arch_probe_v3)
      set(_qv_exe_g4 ${_qv_probe_dir}/arch_probe_v4)
      # The clang probes: the double kernel alone (no CGAL, GMP, MPFR), 3 s each to compile; c4n
      # with 256-bit packs (pack.hpp, QVERIFY_PACK_BITS).
      foreach(_qv_variant c3 c4 c4n)
        if(_qv_variant IN_LIST _qv_variants AND _qv_ok)
          string(SUBSTRING ${_qv_variant} 1 1 _qv_level)
          set(_qv_pack_flags "")
          if(_qv_variant STREQUAL "c4n")
            set(_qv_pack_flags -DQVERIFY_PACK_BITS=256)
          endif()
          set(_qv_exe_${_qv_variant} ${_qv_probe_dir}/arch_probe_clang_${_qv_variant})
          qverify_kernel_clang_includes(_qv_clang_includes "${_qv_eigen_include}")
          execute_process(COMMAND ${QVERIFY_KERNEL_CLANG} ${QVERIFY_KERNEL_CLANG_FLAGS} -march=x86-64-v${_qv_level}
                                  ${_qv_pack_flags} ${_qv_clang_includes} ${CMAKE_CURRENT_LIST_DIR}/arch_probe.cpp
                                  -o ${_qv_exe_${_qv_variant}}
                          RESULT_VARIABLE _qv_rc OUTPUT_VARIABLE _qv_log ERROR_VARIABLE _qv_log TIMEOUT 120)
          if(NOT _qv_rc STREQUAL "0")
            file(WRITE ${_qv_probe_dir}/clang_${_qv_variant}.log "${_qv_log}")
            message(STATUS "qverify: the clang arch probe did not build (CMakeFiles/qverify_arch_probe/clang_${_qv_variant}.log)")
            list(REMOVE_ITEM _qv_variants ${_qv_variant})
          endif()
        endif()
      endforeach()
      # Seven runs of each kernel and variant, in turn (a shared machine's speed drifts; each run is
      # itself the best of eight passes over 2^19 items, of five over 2^17 for the slower intervals,
      # whose batches take twice the memory), and the best of each. A run's time is mostly touching
      # its memory the first time (2^20 items took 1.2 s a run, of which 0.08 s in the kernel):
      # half the items, still five times the largest cache, halved the configure's 29 s of probing.
      foreach(_qv_kernel double interval exact)
        foreach(_qv_variant g3 g4 c3 c4 c4n)
          set(_qv_best_${_qv_kernel}_${_qv_variant} "")
          set(_qv_text_${_qv_kernel}_${_qv_variant} -)  # not measured
        endforeach()
      endforeach()
      set(_qv_double_ok TRUE)
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
            foreach(_qv_variant IN LISTS _qv_variants)
              if(NOT _qv_kernel STREQUAL "double" AND _qv_variant MATCHES "^c")
                continue()
              endif()
              if(_qv_text_${_qv_kernel}_${_qv_variant} STREQUAL "failed")
                continue()
              endif()
              execute_process(COMMAND ${_qv_exe_${_qv_variant}} ${_qv_kernel} ${_qv_items} ${_qv_passes}
                              RESULT_VARIABLE _qv_rc OUTPUT_VARIABLE _qv_out ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE
                              TIMEOUT 60)
              if(NOT _qv_rc STREQUAL "0" OR NOT _qv_out MATCHES "^[0-9]+\\.[0-9]+$")
                message(STATUS "qverify: the ${_qv_kernel} arch probe ${_qv_variant} did not run (${_qv_rc})")
                # the build's own double probe failing spoils the measurement; another one only its variant
                if(_qv_variant STREQUAL "g3")
                  set(_qv_${_qv_kernel}_ok FALSE)
                endif()
                set(_qv_text_${_qv_kernel}_${_qv_variant} failed)
                set(_qv_best_${_qv_kernel}_${_qv_variant} "")
                continue()
              endif()
              # CMake compares only integers: hundredths of a ns
              string(REPLACE "." "" _qv_centi "${_qv_out}")
              math(EXPR _qv_centi "${_qv_centi} + 0")
              if(_qv_best_${_qv_kernel}_${_qv_variant} STREQUAL "" OR _qv_centi LESS _qv_best_${_qv_kernel}_${_qv_variant})
                set(_qv_best_${_qv_kernel}_${_qv_variant} ${_qv_centi})
                set(_qv_text_${_qv_kernel}_${_qv_variant} ${_qv_out})
              endif()
            endforeach()
          endforeach()
          if(NOT _qv_double_ok)
            break()
          endif()
        endforeach()
      endif()
      if(_qv_ok AND _qv_double_ok)
        # A second kernel for each of the three: the fastest other variant, when it is more than 10%
        # faster than the build's own (g3): best * 100 < g3 * 90; each kernel measured on its own.
        foreach(_qv_kernel double interval exact)
          set(_qv_second_${_qv_kernel} none)
          if(NOT _qv_${_qv_kernel}_ok)
            continue()
          endif()
          set(_qv_fastest "")
          foreach(_qv_variant IN LISTS _qv_variants)
            if(_qv_variant STREQUAL "g3" OR _qv_best_${_qv_kernel}_${_qv_variant} STREQUAL "")
              continue()
            endif()
            if(NOT _qv_fastest OR _qv_best_${_qv_kernel}_${_qv_variant} LESS _qv_best_${_qv_kernel}_${_qv_fastest})
              set(_qv_fastest ${_qv_variant})
            endif()
          endforeach()
          if(_qv_fastest)
            math(EXPR _qv_other_scaled "${_qv_best_${_qv_kernel}_${_qv_fastest}} * 100")
            math(EXPR _qv_own_scaled "${_qv_best_${_qv_kernel}_g3} * 90")
            if(_qv_other_scaled LESS _qv_own_scaled)
              set(_qv_second_${_qv_kernel} ${_qv_fastest})
            endif()
          endif()
        endforeach()
        set(_qv_measured "${_qv_key};${_qv_second_double};${_qv_text_double_g3};${_qv_text_double_g4};${_qv_second_interval};${_qv_text_interval_g3};${_qv_text_interval_g4};${_qv_second_exact};${_qv_text_exact_g3};${_qv_text_exact_g4};${_qv_text_double_c3};${_qv_text_double_c4};${_qv_text_double_c4n}")
        set(_qv_how "measured now")
      else()
        # remembered too, so that every reconfigure does not try again (-U QVERIFY_ARCH_MEASURED does)
        set(_qv_measured "${_qv_key};none;failed;failed;none;failed;failed;none;failed;failed;failed;failed;failed")
      endif()
      set(QVERIFY_ARCH_MEASURED "${_qv_measured}" CACHE INTERNAL
          "QVERIFY_ARCH=auto: key (compilers, variants, kernel sources); the variant of a second double kernel (none, g4, c3, c4, c4n); ns/item of the double kernel g3, g4; the same for the interval kernel and the exact digit kernel; ns/item of the double kernel c3, c4, c4n (-: not measured)")
    endif()
  endif()
  if(_qv_measured)
    list(GET _qv_measured 1 _qv_second_double)
    list(GET _qv_measured 2 _qv_g3_ns)
    list(GET _qv_measured 3 _qv_g4_ns)
    list(GET _qv_measured 4 _qv_second_interval)
    list(GET _qv_measured 5 _qv_interval_g3_ns)
    list(GET _qv_measured 6 _qv_interval_g4_ns)
    list(GET _qv_measured 7 _qv_second_exact)
    list(GET _qv_measured 8 _qv_exact_g3_ns)
    list(GET _qv_measured 9 _qv_exact_g4_ns)
    list(GET _qv_measured 10 _qv_c3_ns)
    list(GET _qv_measured 11 _qv_c4_ns)
    list(GET _qv_measured 12 _qv_c4n_ns)
  endif()
  if(_qv_measured AND NOT _qv_g3_ns STREQUAL "failed")
    set(QVERIFY_ARCH_NOTE "measured: double v3 ${_qv_g3_ns} ns/item, v4 ${_qv_g4_ns}")
    if(QVERIFY_KERNEL_CLANG_VERSION)
      string(APPEND QVERIFY_ARCH_NOTE ", clang ${QVERIFY_KERNEL_CLANG_VERSION} v3 ${_qv_c3_ns}, v4 ${_qv_c4_ns}, v4 with 256-bit packs ${_qv_c4n_ns}")
    endif()
    string(APPEND QVERIFY_ARCH_NOTE "; interval v3 ${_qv_interval_g3_ns}, v4 ${_qv_interval_g4_ns}; exact v3 ${_qv_exact_g3_ns}, v4 ${_qv_exact_g4_ns}; one thread; ${_qv_how}")
    foreach(_qv_pair "DOUBLE;_qv_second_double;double batches" "INTERVAL;_qv_second_interval;interval batches" "DIGIT;_qv_second_exact;exact digit blocks")
      list(GET _qv_pair 0 _qv_name)
      list(GET _qv_pair 1 _qv_var)
      list(GET _qv_pair 2 _qv_what)
      set(_qv_variant ${${_qv_var}})
      if(_qv_variant MATCHES "^([gc])([34])(n?)$")
        set(QVERIFY_${_qv_name}_MARCH x86-64-v${CMAKE_MATCH_2})
        set(_qv_packs "")
        if(CMAKE_MATCH_3 STREQUAL "n")  # (c4n: the double kernel only)
          set(QVERIFY_${_qv_name}_PACK_BITS 256)
          set(_qv_packs " with 256-bit packs")
        endif()
        if(CMAKE_MATCH_1 STREQUAL "c")
          set(QVERIFY_${_qv_name}_COMPILER ${QVERIFY_KERNEL_CLANG})
          string(APPEND QVERIFY_ARCH_NOTE "; ${_qv_what}: a second kernel compiled by clang ${QVERIFY_KERNEL_CLANG_VERSION} for x86-64-v${CMAKE_MATCH_2}${_qv_packs}, run where the processor has it")
        else()
          string(APPEND QVERIFY_ARCH_NOTE "; ${_qv_what}: a second kernel for x86-64-v${CMAKE_MATCH_2}, run where the processor has it")
        endif()
      endif()
    endforeach()
  elseif(NOT _qv_variants STREQUAL "g3")
    set(QVERIFY_ARCH_NOTE "not measured, the probe did not build or run: no second kernels")
  endif()
endif()
