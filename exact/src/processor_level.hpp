#pragma once
// Does this processor run x86-64 level 3 (AVX2, FMA, BMI2) or level 4 (those and AVX-512
// F/BW/CD/DQ/VL)? Asked at run time by the dispatchers of the second kernels (double_batch.cpp,
// interval_batch.cpp, digit_batch.cpp). The features one by one: clang 14 knows no level names in
// __builtin_cpu_supports, nor "f16c" and "movbe" (every processor with these three has both).

namespace qverify {

inline bool processor_runs_level(int level) {
#if defined(__x86_64__)
  __builtin_cpu_init();
  const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
  if (level <= 3) return v3;
  return v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
#else
  (void)level;
  return false;
#endif
}

/// Does a second kernel built for `level` (0: the build has none) run on this processor? The
/// processor is asked once per process.
inline bool second_kernel_runs(int level) {
  static const bool v3 = processor_runs_level(3), v4 = processor_runs_level(4);
  return level == 0 ? false : level <= 3 ? v3 : v4;
}

}  // namespace qverify
