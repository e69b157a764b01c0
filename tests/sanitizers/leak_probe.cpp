// GMP's limb arrays go through gmp_block_cache.cpp in the sanitizer build; one that the program loses
// must still be reported by LeakSanitizer (CTest "sanitizers: a lost exact number is still reported as a
// leak", sanitizer builds only: the test passes when the report is printed).
#include <gmp.h>

#include <cstdio>

namespace {

/// Exact arithmetic whose blocks (of several size classes, growing with the denominator) are taken
/// from the cache and given back to it many times.
void traffic() {
  mpq_t sum, term;
  mpq_inits(sum, term, nullptr);
  for (unsigned long i = 1; i < 3000; ++i) {
    mpq_set_ui(term, 1, i);
    mpq_add(sum, sum, term);
  }
  std::printf("H(2999) has a denominator of %zu bits\n", mpz_sizeinbase(mpq_denref(sum), 2));
  mpq_clears(sum, term, nullptr);
}

/// A number never cleared: when this frame is gone nothing points to its limbs.
__attribute__((noinline)) void lose_a_number() {
  mpz_t z;
  mpz_init_set_str(z, "123456789012345678901234567890123456789012345678901234567890", 10);
  mpz_mul(z, z, z);
  std::printf("the lost number has %zu bits\n", mpz_sizeinbase(z, 2));
}

}  // namespace

int main() {
  traffic();
  lose_a_number();
  traffic();
  return 0;
}
