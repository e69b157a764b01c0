#pragma once
/// \file root_enclosure.hpp
/// Outward-rounded enclosures of |u + v sqrt(d)| for exact integers u, v and
/// d >= 0 (the values of an IntegerPoint: integer_point.hpp), in MPFR at a
/// small fixed precision. The second stage of the verifier's filters: between
/// a double interval of the point, which loses about as much as a double
/// result's whole residual, and the 80-digit rounding of root_magnitude.
///
/// Where u and v sqrt(d) have the same sign nothing cancels: |u| + |v| sqrt(d)
/// rounded down and up. Where the signs differ the difference is first taken
/// at the working precision; when it cancels too much to be useful (not away
/// from 0, or wider than 2^-kTightBits of itself) the exact norm is used,
///   |u + v sqrt(d)| = |u^2 - v^2 d| / (|u| + |v| sqrt(d)),
/// an integer over a sum: no cancellation left. The enclosure always holds;
/// the precision only decides how often the norm (two big products) is needed.

#include <qverify/exact/integer_point.hpp>

#include <mpfr.h>

namespace qverify {

class RootEnclosure {
 public:
  /// A difference narrower than 2^-kTightBits of itself is kept without the norm.
  static constexpr int kTightBits = 32;

  explicit RootEnclosure(mpfr_prec_t bits);
  ~RootEnclosure();
  RootEnclosure(const RootEnclosure&) = delete;
  RootEnclosure& operator=(const RootEnclosure&) = delete;

  /// The radicand of the values that follow (sqrt(d) is enclosed once here).
  /// Kept by reference: d must outlive those calls.
  void set_radicand(const BigInt& d);
  /// [lo, hi] contains |u + v sqrt(d)|, lo >= 0 (d from set_radicand; `root`
  /// false: the point is rational and v is ignored). lo and hi may have any precision.
  void enclose(mpfr_ptr lo, mpfr_ptr hi, const BigInt& u, const BigInt& v, bool root);
  /// [lo, hi] += |u + v sqrt(d)|^2, rounded outwards (a sum of squares: a gradient's norm).
  void add_square(mpfr_ptr lo, mpfr_ptr hi, const BigInt& u, const BigInt& v, bool root);

 private:
  const BigInt* d_ = nullptr;
  mpfr_t sdlo_, sdhi_, alo_, ahi_, blo_, bhi_, t0_, t1_, sqlo_, sqhi_;
  BigInt abs_, conj_, t_;
};

/// [lo, hi] = sqrt(n) of an integer n >= 0, rounded outwards at lo's and hi's precision.
void enclose_sqrt(mpfr_ptr lo, mpfr_ptr hi, const BigInt& n);

/// One RootEnclosure per thread at `bits` (the filters' scratch: no allocation per value once grown).
RootEnclosure& thread_root_enclosure(mpfr_prec_t bits);

}  // namespace qverify
