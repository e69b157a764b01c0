#include <qverify/exact/root_enclosure.hpp>

#include <map>
#include <memory>

namespace qverify {

RootEnclosure::RootEnclosure(mpfr_prec_t bits) {
  for (mpfr_ptr x : {&sdlo_[0], &sdhi_[0], &alo_[0], &ahi_[0], &blo_[0], &bhi_[0], &t0_[0], &t1_[0], &sqlo_[0], &sqhi_[0]})
    mpfr_init2(x, bits);
}

RootEnclosure::~RootEnclosure() {
  for (mpfr_ptr x : {&sdlo_[0], &sdhi_[0], &alo_[0], &ahi_[0], &blo_[0], &bhi_[0], &t0_[0], &t1_[0], &sqlo_[0], &sqhi_[0]})
    mpfr_clear(x);
}

void enclose_sqrt(mpfr_ptr lo, mpfr_ptr hi, const BigInt& n) {
  mpfr_set_z(lo, mpz(n), MPFR_RNDD);
  mpfr_sqrt(lo, lo, MPFR_RNDD);
  mpfr_set_z(hi, mpz(n), MPFR_RNDU);
  mpfr_sqrt(hi, hi, MPFR_RNDU);
}

void RootEnclosure::set_radicand(const BigInt& d) {
  d_ = &d;
  enclose_sqrt(sdlo_, sdhi_, d);
}

void RootEnclosure::add_square(mpfr_ptr lo, mpfr_ptr hi, const BigInt& u, const BigInt& v, bool root) {
  enclose(sqlo_, sqhi_, u, v, root);
  mpfr_sqr(sqlo_, sqlo_, MPFR_RNDD);
  mpfr_add(lo, lo, sqlo_, MPFR_RNDD);
  mpfr_sqr(sqhi_, sqhi_, MPFR_RNDU);
  mpfr_add(hi, hi, sqhi_, MPFR_RNDU);
}

void RootEnclosure::enclose(mpfr_ptr lo, mpfr_ptr hi, const BigInt& u, const BigInt& v, bool root) {
  const int su = mpz_sgn(mpz(u)), sv = root && mpz_sgn(mpz(*d_)) != 0 ? mpz_sgn(mpz(v)) : 0;
  mpz_abs(mpz(abs_), mpz(u));
  mpfr_set_z(alo_, mpz(abs_), MPFR_RNDD);  // |u|
  mpfr_set_z(ahi_, mpz(abs_), MPFR_RNDU);
  if (sv == 0) {
    mpfr_set(lo, alo_, MPFR_RNDD);
    mpfr_set(hi, ahi_, MPFR_RNDU);
    return;
  }
  mpz_abs(mpz(abs_), mpz(v));
  mpfr_set_z(blo_, mpz(abs_), MPFR_RNDD);  // |v| sqrt(d)
  mpfr_mul(blo_, blo_, sdlo_, MPFR_RNDD);
  mpfr_set_z(bhi_, mpz(abs_), MPFR_RNDU);
  mpfr_mul(bhi_, bhi_, sdhi_, MPFR_RNDU);
  if (su == 0 || su == sv) {
    mpfr_add(lo, alo_, blo_, MPFR_RNDD);
    mpfr_add(hi, ahi_, bhi_, MPFR_RNDU);
    return;
  }
  // Opposite signs: | |u| - |v| sqrt(d) | directly, when the two are told apart well enough.
  const bool u_larger = mpfr_greater_p(alo_, bhi_), v_larger = mpfr_greater_p(blo_, ahi_);
  if (u_larger || v_larger) {
    if (u_larger) {
      mpfr_sub(t0_, alo_, bhi_, MPFR_RNDD);
      mpfr_sub(t1_, ahi_, blo_, MPFR_RNDU);
    } else {
      mpfr_sub(t0_, blo_, ahi_, MPFR_RNDD);
      mpfr_sub(t1_, bhi_, alo_, MPFR_RNDU);
    }
    // width t1 - t0 against t0 2^-kTightBits (both rounded against acceptance)
    mpfr_sub(hi, t1_, t0_, MPFR_RNDU);
    mpfr_mul_2si(lo, t0_, -kTightBits, MPFR_RNDD);
    if (mpfr_lessequal_p(hi, lo)) {
      mpfr_set(lo, t0_, MPFR_RNDD);
      mpfr_set(hi, t1_, MPFR_RNDU);
      return;
    }
  }
  // The norm: |u^2 - v^2 d| / (|u| + |v| sqrt(d)), exact over a sum without cancellation.
  root_norm(conj_, u, v, *d_, t_);
  mpz_abs(mpz(conj_), mpz(conj_));
  mpfr_add(t0_, alo_, blo_, MPFR_RNDD);  // the sum, down (for the upper bound)
  mpfr_add(t1_, ahi_, bhi_, MPFR_RNDU);  // and up (for the lower bound)
  mpfr_set_z(lo, mpz(conj_), MPFR_RNDD);
  mpfr_div(lo, lo, t1_, MPFR_RNDD);
  mpfr_set_z(hi, mpz(conj_), MPFR_RNDU);
  mpfr_div(hi, hi, t0_, MPFR_RNDU);
}

RootEnclosure& thread_root_enclosure(mpfr_prec_t bits) {
  thread_local std::map<mpfr_prec_t, std::unique_ptr<RootEnclosure>> per_precision;
  auto& e = per_precision[bits];
  if (!e) e = std::make_unique<RootEnclosure>(bits);
  return *e;
}

}  // namespace qverify
