#pragma once
// The second kernels (exact/double_batch.hpp, interval_batch.hpp, digit_batch.hpp) run wherever
// the build has one and the processor its instruction set. A dispatch that silently fell back to
// the build's own kernel would pass every comparison of results: this checks the choice itself,
// asking the processor again.
#include <catch2/catch.hpp>

#include <string>

namespace qverify::test {

/// Does this processor run x86-64 level 3 (AVX2, FMA, BMI2) / level 4 (and AVX-512 F/BW/CD/DQ/VL)?
inline bool processor_runs_v3() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
}
inline bool processor_runs_v4() {
  return processor_runs_v3() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
}

/// `second`: the -march of the build's second kernel ("" for none); `dispatched`, `kernel`: what
/// the dispatcher says it runs.
inline void check_dispatch(const std::string& second, bool dispatched, const std::string& kernel) {
  if (second == "x86-64-v4") CHECK(dispatched == processor_runs_v4());
  else if (second == "x86-64-v3") CHECK(dispatched == processor_runs_v3());
  else CHECK(!dispatched);
  CHECK((kernel.find("(run-time dispatch)") != std::string::npos) == dispatched);
}

}  // namespace qverify::test
