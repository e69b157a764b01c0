#include <qverify/verify/adaptive.hpp>
#include <qverify/verify/verifier.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <functional>
#include <map>
#include <optional>
#include <limits>
#include <qverify/exact/mpfi.hpp>

namespace qverify {

using Q = Rational;

namespace {

/// Bits of the MPFR-interval stage.
constexpr unsigned kMpfiBits = 256;

using IntervalMatrix = Eigen::Matrix<Interval, Eigen::Dynamic, Eigen::Dynamic>;
using MpfiMatrix = Eigen::Matrix<Mpfi, Eigen::Dynamic, Eigen::Dynamic>;
using ExactMatrix = Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic>;

/// A certified enclosure [lo_i, hi_i] of every entry of an exact result, as rationals.
struct EntryEnclosure {
  std::vector<Q> lo, hi;
};

EntryEnclosure enclosure(const IntervalMatrix& m) {
  EntryEnclosure e;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    e.lo.push_back(to_rational(m(i).inf()));
    e.hi.push_back(to_rational(m(i).sup()));
  }
  return e;
}

EntryEnclosure enclosure(const MpfiMatrix& m) {
  EntryEnclosure e;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    e.lo.push_back(to_rational(mpfi_lower(m(i))));
    e.hi.push_back(to_rational(mpfi_upper(m(i))));
  }
  return e;
}

EntryEnclosure enclosure(const ExactMatrix& m) {
  EntryEnclosure e;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    e.lo.push_back(m(i));
    e.hi.push_back(m(i));
  }
  return e;
}

/// A lower bound of the largest |entry| of the exact result.
Q scale_lower_bound(const EntryEnclosure& e) {
  Q s = 0;
  for (std::size_t i = 0; i < e.lo.size(); ++i) {
    if (e.lo[i] > 0) s = std::max(s, e.lo[i]);
    else if (e.hi[i] < 0) s = std::max(s, Q(-e.hi[i]));
  }
  return s;
}

/// A certified bound of max_i |x_i - exact_i| / max_i |exact_i| (infinite when unknown).
double certified_error(const Eigen::MatrixXd& x, const EntryEnclosure& e) {
  Q worst = 0;
  for (std::size_t i = 0; i < e.lo.size(); ++i) {
    const double v = x(static_cast<Eigen::Index>(i));
    if (!std::isfinite(v)) return std::numeric_limits<double>::infinity();
    const Q q = to_rational(v);
    worst = std::max({worst, Q(abs(q - e.lo[i])), Q(abs(e.hi[i] - q))});
  }
  if (worst == 0) return 0;
  const Q s = scale_lower_bound(e);
  if (s == 0) return std::numeric_limits<double>::infinity();
  RoundingReport rep;
  const double b = round_rational<double>(Q(worst / s), rep);
  return rep.inexact ? std::nextafter(b, std::numeric_limits<double>::infinity()) : b;  // rounded up
}

template <class D> Eigen::MatrixXd midpoints(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const Interval& x) { return (x.inf() + x.sup()) / 2; }).eval();
}

Eigen::MatrixXd midpoints(const MpfiMatrix& m) {
  Eigen::MatrixXd r(m.rows(), m.cols());
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const mpfi_srcptr x = m(i).backend().data();
    mpfr_t mid;
    mpfr_init2(mid, mpfi_get_prec(x));
    mpfi_mid(mid, x);
    r(i) = mpfr_get_d(mid, MPFR_RNDN);
    mpfr_clear(mid);
  }
  return r;
}

Eigen::MatrixXd rounded(const ExactMatrix& m) {
  return m.unaryExpr([](const Q& x) {
             RoundingReport rep;
             return round_rational<double>(x, rep);
           })
      .eval();
}

/// One output of an item (a 4x4 matrix or a plane) at every stage of the ladder.
struct Part {
  const char* key;
  Eigen::MatrixXd dbl;
  IntervalMatrix enc;
  std::function<MpfiMatrix()> mpfi;    ///< evaluated only when the item reaches the MPFR stage
  std::function<ExactMatrix()> exact;  ///< evaluated only when the item reaches the exact stage
};

/// Certifies one item within tol: at each stage a double candidate for every part and a certified
/// enclosure of the exact result; the stage certifies when every candidate entry is within
/// tol x (largest |exact entry|) of every point of the enclosure. Stages: the double result
/// (enclosure: interval), the interval midpoints, the MPFI midpoints (256 bits), the exact result
/// rounded. Writes the parts' values into the item's results and into `chosen`, and the stage and
/// its bound into `certified`.
void certify(EvalItem& item, const std::vector<Part>& parts, double tol, std::vector<Eigen::MatrixXd>& chosen) {
  using Candidate = std::function<std::pair<Eigen::MatrixXd, EntryEnclosure>(const Part&)>;
  const std::vector<std::pair<std::string, Candidate>> stages = {
      {"double", [](const Part& p) { return std::make_pair(p.dbl, enclosure(p.enc)); }},
      {"interval", [](const Part& p) { return std::make_pair(midpoints(p.enc), enclosure(p.enc)); }},
      {"mpfr", [](const Part& p) {
         const MpfiMatrix m = p.mpfi();
         return std::make_pair(midpoints(m), enclosure(m));
       }},
      {"exact", [](const Part& p) {
         const ExactMatrix e = p.exact();
         return std::make_pair(rounded(e), enclosure(e));
       }}};
  for (const auto& [name, candidate] : stages) {
    double bound = 0;
    std::vector<Eigen::MatrixXd> values;
    for (const Part& p : parts) {
      auto [x, enc] = candidate(p);
      bound = std::max(bound, certified_error(x, enc));
      values.push_back(std::move(x));
    }
    if (bound <= tol || name == "exact") {
      for (std::size_t k = 0; k < parts.size(); ++k)
        for (auto& [key, m] : item.results)
          if (key == parts[k].key) m = numbers_of(values[k]);
      item.certified = StageCertificate{name, bound};
      chosen = std::move(values);
      return;
    }
  }
}

/// The item's error_bound (its geometric error on exact points, eval's rule) and `inaccurate` flag.
void accuracy_of(EvalItem& item, const ItemAccuracy& acc) {
  if (acc.inaccurate) item.flags.emplace_back("inaccurate");
  item.accuracy = acc;
}

Mat4<Q> exact4(const Eigen::MatrixXd& m) { return exact_matrix(Mat4<double>(m)); }

/// Are the chosen values finite (a value beyond double's range is an infinity: nothing to measure)?
bool finite_values(const std::vector<Eigen::MatrixXd>& v) {
  for (const Eigen::MatrixXd& m : v)
    if (!m.allFinite()) return false;
  return true;
}

/// The item's `non-finite` flag, of the values it gives (a later stage's, not double's).
void non_finite_of(EvalItem& item, const std::vector<Eigen::MatrixXd>& v) {
  item.flags.erase(std::remove(item.flags.begin(), item.flags.end(), "non-finite"), item.flags.end());
  if (!finite_values(v)) item.flags.emplace_back("non-finite");
}

}  // namespace

EvalReport adaptive_eval_report(const Scene& sc, Method method, double tol, const AccuracyOptions& accuracy) {
  if (!(tol >= std::ldexp(1.0, -53))) throw std::invalid_argument("adaptive tolerance below 2^-53 cannot be certified in double");
  // Every stage in world coordinates and without rescaling, so that the stages are comparable.
  Evaluation<double> d = evaluate<double>(sc, method, Frame::world);
  const TypedScene<Q> exs = typed_scene<Q>(sc);
  decide_statuses(exs, method, d);  // statuses and their flags: predicates of the exact inputs, as eval's
  const Evaluation<Interval> iv = evaluate<Interval>(sc, method, Frame::world);
  std::optional<Evaluation<Q>> ex;  // only when some item needs it
  auto exact = [&]() -> const Evaluation<Q>& {
    if (!ex) ex = evaluate<Q>(sc, method, Frame::world);
    return *ex;
  };
  std::optional<Evaluation<Mpfi>> mp;  // likewise
  auto mpfi = [&]() -> const Evaluation<Mpfi>& {
    if (!mp) {
      set_mpfi_bits(kMpfiBits);
      mp = evaluate<Mpfi>(sc, method, Frame::world);
    }
    return *mp;
  };
  EvalReport rep;
  rep.scene = sc.name;
  rep.precision = Precision{Precision::Kind::f64};
  rep.method = method;
  rep.frame = Frame::world;
  rep.adaptive = AdaptiveFacts{tol, {}};
  rep.accuracy = accuracy;
  for (std::size_t k = 0; k < sc.shadows.size(); ++k) {
    const ShadowItem<double>& dd = d.shadows[k];
    const ShadowResult<Interval>& ii = iv.shadows[k].result;
    EvalItem item = shadow_item(sc, dd);
    std::vector<Eigen::MatrixXd> v;
    certify(item,
            {{"P", dd.result.P, ii.P, [&] { return MpfiMatrix(mpfi().shadows[k].result.P); },
              [&] { return ExactMatrix(exact().shadows[k].result.P); }},
             {"polar_plane", dd.result.polar_plane, ii.polar_plane,
              [&] { return MpfiMatrix(mpfi().shadows[k].result.polar_plane); },
              [&] { return ExactMatrix(exact().shadows[k].result.polar_plane); }},
             {"R", dd.result.R, ii.R, [&] { return MpfiMatrix(mpfi().shadows[k].result.R); },
              [&] { return ExactMatrix(exact().shadows[k].result.R); }}},
            tol, v);
    ++rep.adaptive->items_by_stage[item.certified->by];
    non_finite_of(item, v);
    ShadowMeter meter(exs.A[dd.pair.quadric], exs.L[dd.pair.other], accuracy);
    accuracy_of(item, finite_values(v) ? meter(std::nullopt, exact4(v[0]), exact_matrix(Vec4<double>(v[1])), exact4(v[2]))
                                       : non_finite_accuracy());
    rep.shadows.push_back(std::move(item));
  }
  for (std::size_t k = 0; k < sc.reflections.size(); ++k) {
    const ReflectionItem<double>& dd = d.reflections[k];
    const ReflectionItem<Interval>& ii = iv.reflections[k];
    EvalItem item = reflection_item(sc, dd);
    std::vector<Eigen::MatrixXd> v;
    certify(item,
            {{"M", dd.M, ii.M, [&] { return MpfiMatrix(mpfi().reflections[k].M); },
              [&] { return ExactMatrix(exact().reflections[k].M); }},
             {"B", dd.result.B, ii.result.B, [&] { return MpfiMatrix(mpfi().reflections[k].result.B); },
              [&] { return ExactMatrix(exact().reflections[k].result.B); }}},
            tol, v);
    ++rep.adaptive->items_by_stage[item.certified->by];
    non_finite_of(item, v);
    ReflectionMeter meter(exs.A[dd.pair.quadric], exs.planes[dd.pair.other], accuracy);
    const Mat4<Rational> M = finite_values(v) ? exact4(v[0]) : Mat4<Rational>(Mat4<Rational>::Zero());
    accuracy_of(item, finite_values(v) ? meter(std::nullopt, exact4(v[1]), &M) : non_finite_accuracy());
    rep.reflections.push_back(std::move(item));
  }
  rep.skipped = skipped_pairs(sc);
  return rep;
}

}  // namespace qverify
