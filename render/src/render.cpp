#include <qverify/render/render.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <thread>
#include <tuple>

namespace qverify::render {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Which pairs take part, decided once, exactly.
struct Plan {
  std::vector<char> clipped;
  struct Shadow {
    std::size_t quadric, light;
    int side;
  };
  std::vector<Shadow> shadows;
  std::vector<Pair> reflections;
};

/// The scene's data for both methods in scalar S, by the core's generic
/// formulas: P and pi (eqs. 3, 6, direct route), M and B (eqs. 9, 11).
template <class S>
RenderData<S> build(const TypedScene<S>& ts, const Plan& plan, const Vec3<S>& box_centre, const S& half) {
  RenderData<S> rd;
  rd.A = ts.A;
  rd.clipped = plan.clipped;
  rd.box_lo = box_centre - Vec3<S>::Constant(half);
  rd.box_hi = box_centre + Vec3<S>::Constant(half);
  for (const Vec4<S>& L : ts.L) rd.lights.push_back(LightData<S>{L, {}});
  for (const Plan::Shadow& s : plan.shadows) {
    const Mat4<S>& A = ts.A[s.quadric];
    const Vec4<S>& L = ts.L[s.light];
    const Vec4<S> pi = polar_plane<S>(A, L);
    rd.lights[s.light].occluders.push_back(
        Occluder<S>{static_cast<int>(s.quadric), tangent_cone_from_polar<S>(A, L, pi), pi, s.side});
  }
  for (const Vec4<S>& pl : ts.planes) rd.mirrors.push_back(MirrorData<S>{pl, mirror_matrix<S>(pl), {}});
  for (const Pair& p : plan.reflections) {
    MirrorData<S>& md = rd.mirrors[p.other];
    md.images.push_back(MirrorImage<S>{static_cast<int>(p.quadric), mirror_image<S>(ts.A[p.quadric], md.M),
                                        EyeForm<S>{Vec3<S>::Zero(), S(0)}});
  }
  return rd;
}

/// Precomputes what every primary ray from `eye` shares (EyeForm).
template <class S> void attach_eye(RenderData<S>& rd, const Vec3<S>& eye) {
  rd.eye = eye;
  rd.A_eye.clear();
  for (const Mat4<S>& A : rd.A) rd.A_eye.push_back(eye_form<S>(A, eye));
  for (auto& m : rd.mirrors)
    for (auto& im : m.images) im.B_eye = eye_form<S>(im.B, eye);
}

/// Entry by entry conversion (Rational -> Mpfi enclosures).
template <class T, class S, class F> RenderData<T> convert(const RenderData<S>& in, F&& f) {
  auto eye = [&](const EyeForm<S>& e) { return EyeForm<T>{e.q.unaryExpr(f), f(e.c)}; };
  RenderData<T> out;
  out.eye = in.eye.unaryExpr(f);
  for (const auto& A : in.A) out.A.push_back(A.unaryExpr(f));
  for (const auto& e : in.A_eye) out.A_eye.push_back(eye(e));
  out.clipped = in.clipped;
  out.box_lo = in.box_lo.unaryExpr(f);
  out.box_hi = in.box_hi.unaryExpr(f);
  for (const auto& l : in.lights) {
    LightData<T> ld{l.L.unaryExpr(f), {}};
    for (const auto& o : l.occluders) ld.occluders.push_back(Occluder<T>{o.quadric, o.P.unaryExpr(f), o.pi.unaryExpr(f), o.side});
    out.lights.push_back(std::move(ld));
  }
  for (const auto& m : in.mirrors) {
    MirrorData<T> md{m.plane.unaryExpr(f), m.M.unaryExpr(f), {}};
    for (const auto& im : m.images) md.images.push_back(MirrorImage<T>{im.quadric, im.B.unaryExpr(f), eye(im.B_eye)});
    out.mirrors.push_back(std::move(md));
  }
  return out;
}

Vec3<double> normalized(const Vec3<double>& v) { return v / v.norm(); }

std::uint64_t mix64(std::uint64_t z) {  // splitmix64 finaliser
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

Vec3<double> Camera::direction(int px, int py) const {
  const double u = (2 * (px + 0.5) / width - 1), v = (1 - 2 * (py + 0.5) / height);
  return forward + u * right + v * up;
}

Renderer::Renderer(const Scene& sc, const RenderOptions& opts) : scene_(sc) {
  if (!sc.has_camera) throw InputError(sc.file, "camera", "the scene has no camera; render needs one (scene-format.md, CAMERA)");
  const CameraSpec& c = sc.camera;
  if (c.width * c.height > 4096L * 4096L)
    throw InputError(sc.file, "camera.width", "render supports at most 4096 x 4096 pixels");
  if (sc.lights.size() > 63)
    throw InputError(sc.file, "lights", "render supports at most 63 lights (one ID bit each)");

  // ---- exact decisions: what takes part
  TypedScene<Rational> tq = typed_scene<Rational>(sc);
  Plan plan;
  for (const Mat4<Rational>& A : tq.A)
    plan.clipped.push_back(conic_definite<Rational>(Mat3<Rational>(A.topLeftCorner<3, 3>())) != Truth::yes);
  for (const Pair& p : sc.shadows) {
    const unsigned flags = shadow_flags<Rational>(tq.A[p.quadric], tq.L[p.other]);
    const auto bad = flags & (static_cast<unsigned>(ShadowFlag::degenerate_quadric) |
                              static_cast<unsigned>(ShadowFlag::light_on_surface));
    if (bad) {
      ShadowResult<Rational> st;
      st.flags = flags;
      left_out_.push_back("shadow of " + sc.quadrics[p.quadric].id + " from " + sc.lights[p.other].id + ": " + st.status());
      continue;
    }
    const Rational s = tq.L[p.other].dot(tq.A[p.quadric] * tq.L[p.other]);
    plan.shadows.push_back({p.quadric, p.other, s > 0 ? 1 : -1});
  }
  plan.reflections = sc.reflections;
  for (const Pair& p : sc.skipped_shadows())
    left_out_.push_back("shadow of " + sc.quadrics[p.quadric].id + " from " + sc.lights[p.other].id + ": not requested");
  for (const Pair& p : sc.skipped_reflections())
    left_out_.push_back("image of " + sc.quadrics[p.quadric].id + " in " + sc.mirrors[p.other].id + ": not requested");

  Vec3<Rational> eye, look, up;
  for (int i = 0; i < 3; ++i) {
    eye(i) = c.eye[static_cast<std::size_t>(i)].value;
    look(i) = c.look_at[static_cast<std::size_t>(i)].value;
    up(i) = c.up[static_cast<std::size_t>(i)].value;
  }
  Rational half = 0;
  if (opts.box_half) {
    half = *opts.box_half;
  } else {
    for (int i = 0; i < 3; ++i) half = std::max(half, Rational(abs(eye(i) - look(i))));
    half /= 2;  // the eye stays outside the box
  }
  // The camera frame: the scene moved, exactly, so that look_at is the origin
  // (x = x' + look_at: A' = T^T A T, L' = T^-1 L, planes n.x' + (d + n.look_at)).
  // Rounded once from there, small scenes far from the world origin keep their digits.
  TypedScene<Rational>& tl = tq;
  Vec3<Rational> shift = Vec3<Rational>::Zero();
  if (opts.camera_frame) {
    shift = look;
    Mat4<Rational> T = Mat4<Rational>::Identity();
    T.topRightCorner<3, 1>() = look;
    for (auto& A : tl.A) A = T.transpose() * A * T;
    for (auto& L : tl.L) L.head<3>() -= L(3) * look;
    for (auto& pl : tl.planes) pl(3) += pl.head<3>().dot(look);
  }

  // ---- double: the scene rounded once, then the core's formulas in double
  const auto t0 = Clock::now();
  TypedScene<double> td;
  auto dbl = [&](const Rational& q, const std::string& path) {
    RoundingReport rep;
    const double v = round_rational<double>(q, rep);
    if (rep.overflow) throw InputError(sc.file, path, "a value does not fit a double; render works in double");
    return v;
  };
  for (std::size_t k = 0; k < tl.A.size(); ++k)
    td.A.push_back(tl.A[k].unaryExpr([&](const Rational& q) { return dbl(q, sc.quadrics[k].path); }));
  for (std::size_t k = 0; k < tl.L.size(); ++k)
    td.L.push_back(tl.L[k].unaryExpr([&](const Rational& q) { return dbl(q, sc.lights[k].path); }));
  for (std::size_t k = 0; k < tl.planes.size(); ++k)
    td.planes.push_back(tl.planes[k].unaryExpr([&](const Rational& q) { return dbl(q, sc.mirrors[k].path); }));
  Vec3<double> eye_d, look_d, up_d;
  for (int i = 0; i < 3; ++i) {
    eye_d(i) = dbl(eye(i) - shift(i), "camera.eye");
    look_d(i) = dbl(look(i) - shift(i), "camera.look_at");
    up_d(i) = dbl(up(i), "camera.up");
  }
  dbl_ = build<double>(td, plan, look_d, dbl(half, "camera"));
  attach_eye<double>(dbl_, eye_d);
  prep_seconds_ = seconds_since(t0);
  // The certified twin, built when a pixel is first certified. It traces the same
  // double rays: its eye is eye_d, exactly.
  make_exact_ = [tl = std::move(tl), plan, centre = Vec3<Rational>(look - shift), half,
                 eye_q = Vec3<Rational>(Rational(eye_d(0)), Rational(eye_d(1)), Rational(eye_d(2)))] {
    RenderData<Rational> rd = build<Rational>(tl, plan, centre, half);
    attach_eye<Rational>(rd, eye_q);
    return rd;
  };

  cam_.width = static_cast<int>(c.width);
  cam_.height = static_cast<int>(c.height);
  cam_.eye = eye_d;
  const double tan_half = std::tan(c.fov_y_deg.value.convert_to<double>() * M_PI / 360);
  const Vec3<double> f = normalized(look_d - eye_d);
  const Vec3<double> r = normalized(f.cross(up_d));
  cam_.forward = f;
  cam_.right = r * (tan_half * cam_.width / cam_.height);
  cam_.up = r.cross(f) * tan_half;

  threads_ = opts.threads > 0 ? opts.threads : std::max(1u, std::thread::hardware_concurrency());
  static const double palette[][3] = {{0.90, 0.45, 0.30}, {0.35, 0.65, 0.90}, {0.55, 0.80, 0.40}, {0.85, 0.75, 0.35},
                                      {0.70, 0.50, 0.85}, {0.40, 0.80, 0.75}, {0.90, 0.55, 0.65}, {0.75, 0.75, 0.75}};
  for (std::size_t q = 0; q < sc.quadrics.size(); ++q) {
    const double* p = palette[q % 8];
    colours_.push_back({p[0], p[1], p[2]});
  }
}

Renderer::~Renderer() = default;

/// Lambert shading of a point with normal n (two-sided: turned against the
/// ray), lit by every light whose bit is clear in `shadowed`.
double Renderer::lambert(const Vec3<double>& x, Vec3<double> n, const Vec3<double>& ray, std::uint64_t shadowed) const {
  if (n.dot(ray) > 0) n = -n;
  n = normalized(n);
  double lum = 0.25;
  const double share = 0.75 / static_cast<double>(std::max<std::size_t>(1, dbl_.lights.size()));
  for (std::size_t l = 0; l < dbl_.lights.size(); ++l) {
    if (shadowed & (std::uint64_t(1) << std::min<std::size_t>(l, 63))) continue;
    const Vec4<double>& L = dbl_.lights[l].L;
    const Vec3<double> to = L(3) != 0 ? Vec3<double>(L.head<3>() / L(3) - x) : Vec3<double>(L.head<3>());
    lum += share * std::max(0.0, n.dot(normalized(to)));
  }
  return lum;
}

void Renderer::shade(const Traced<double>& t, const Vec3<double>& primary, std::uint8_t* px) const {
  std::array<double, 3> rgb;
  if (t.id.surface < 0) {  // sky: a vertical gradient by the ray's direction
    const Vec3<double> d = normalized(t.ray);
    const double k = 0.5 * (1 + (std::isfinite(d(2)) ? d(2) : 0));
    rgb = {0.75 - 0.35 * k, 0.80 - 0.25 * k, 0.90 - 0.05 * k};
  } else {
    const Mat4<double>& A = dbl_.A[static_cast<std::size_t>(t.id.surface)];
    const double lum = lambert(t.x, A.topLeftCorner<3, 3>() * t.x + A.topRightCorner<3, 1>(), t.ray, t.id.shadowed);
    const auto& c = colours_[static_cast<std::size_t>(t.id.surface)];
    rgb = {c[0] * lum, c[1] * lum, c[2] * lum};
  }
  if (t.id.mirror >= 0) {  // 60% reflection, 40% a diffuse silver that takes shadows
    const Vec4<double>& pl = dbl_.mirrors[static_cast<std::size_t>(t.id.mirror)].plane;
    const double g = 0.8 * lambert(t.p, pl.head<3>(), primary, t.id.mirror_shadowed);
    rgb = {0.6 * rgb[0] + 0.4 * g, 0.6 * rgb[1] + 0.4 * g, 0.6 * rgb[2] + 0.4 * g};
  }
  for (int i = 0; i < 3; ++i) {
    const double v = std::isfinite(rgb[static_cast<std::size_t>(i)]) ? rgb[static_cast<std::size_t>(i)] : 0;
    px[i] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  }
}

Image Renderer::render(RenderMethod method) const {
  Image img;
  img.width = cam_.width;
  img.height = cam_.height;
  const std::size_t n = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height);
  img.rgb.assign(3 * n, 0);
  img.ids.assign(n, PixelId{});
  const auto t0 = Clock::now();
  std::atomic<int> next_row{0};
  auto work = [&] {
    for (int y; (y = next_row.fetch_add(1)) < img.height;) {
      for (int x = 0; x < img.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(x);
        const Vec3<double> d = cam_.direction(x, y);
        const Traced<double> t = trace<double>(dbl_, method, d);
        img.ids[i] = t.id;
        shade(t, d, &img.rgb[3 * i]);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < threads_; ++k) pool.emplace_back(work);
  work();
  for (auto& th : pool) th.join();
  img.seconds = seconds_since(t0) + (method == RenderMethod::transforms ? prep_seconds_ : 0);
  return img;
}

Certified Renderer::certify(int px, int py) const {
  Certified c;
  const Vec3<double> dd = cam_.direction(px, py);
  for (unsigned bits : {128u, 512u, 2048u}) {
    const unsigned used = set_mpfi_bits(bits);
    auto& slot = certified_cache_[used];
    if (!slot) {
      if (!exact_) exact_ = make_exact_();
      slot = std::make_shared<RenderData<Mpfi>>(convert<Mpfi>(*exact_, [](const Rational& q) { return enclose_mpfi(q); }));
    }
    const Vec3<Mpfi> d(Mpfi(dd(0)), Mpfi(dd(1)), Mpfi(dd(2)));
    try {
      c.truth = trace<Mpfi>(*slot, RenderMethod::raytrace, d).id;
      c.methods_agree = trace<Mpfi>(*slot, RenderMethod::transforms, d).id == c.truth;
      c.decided = true;
      c.bits = used;
      return c;
    } catch (const Undecided&) {
    }
  }
  return c;
}

std::array<std::uint8_t, 3> Renderer::id_colour(const PixelId& id) {
  if (id.surface < 0 && id.mirror < 0) return {0, 0, 0};
  const std::uint64_t h = mix64((std::uint64_t(std::uint32_t(id.surface + 1)) << 40) ^
                                (std::uint64_t(std::uint32_t(id.mirror + 1)) << 20) ^ mix64(id.shadowed) ^
                                mix64(~id.mirror_shadowed));
  // keep the channels away from black so no id looks like the background
  return {static_cast<std::uint8_t>(40 + (h & 0xff) % 216), static_cast<std::uint8_t>(40 + ((h >> 8) & 0xff) % 216),
          static_cast<std::uint8_t>(40 + ((h >> 16) & 0xff) % 216)};
}

std::string Renderer::describe(const PixelId& id) const {
  auto lights = [&](std::uint64_t mask) {
    std::string out;
    for (std::size_t l = 0; l < scene_.lights.size(); ++l)
      if (mask & (std::uint64_t(1) << std::min<std::size_t>(l, 63))) out += (out.empty() ? "" : ", ") + scene_.lights[l].id;
    return out.empty() ? out : " (shadowed from " + out + ")";
  };
  std::string s = id.surface < 0 ? "background" : scene_.quadrics[static_cast<std::size_t>(id.surface)].id;
  s += lights(id.shadowed);
  if (id.mirror >= 0) s += " in " + scene_.mirrors[static_cast<std::size_t>(id.mirror)].id + lights(id.mirror_shadowed);
  return s;
}

std::vector<std::uint8_t> id_image(const Image& img) {
  std::vector<std::uint8_t> out(3 * img.ids.size());
  for (std::size_t i = 0; i < img.ids.size(); ++i) {
    const auto c = Renderer::id_colour(img.ids[i]);
    std::copy(c.begin(), c.end(), out.begin() + static_cast<std::ptrdiff_t>(3 * i));
  }
  return out;
}

Comparison compare_methods(const Renderer& r, int repeat, long max_checked) {
  Comparison cmp;
  repeat = std::max(1, repeat);
  for (int k = 0; k < repeat; ++k) {
    Image t = r.render(RenderMethod::transforms);
    Image w = r.render(RenderMethod::raytrace);
    if (k == 0 || t.seconds < cmp.transforms_image.seconds) cmp.transforms_image = std::move(t);
    if (k == 0 || w.seconds < cmp.raytrace_image.seconds) cmp.raytrace_image = std::move(w);
  }
  const Image& a = cmp.transforms_image;
  const Image& b = cmp.raytrace_image;
  cmp.seconds_transforms = a.seconds;
  cmp.seconds_raytrace = b.seconds;
  cmp.pixels = static_cast<long>(a.ids.size());
  cmp.diff_rgb.assign(a.rgb.size(), 0);
  for (std::size_t i = 0; i < a.ids.size(); ++i) {
    std::uint8_t* d = &cmp.diff_rgb[3 * i];
    if (a.ids[i] == b.ids[i]) {
      const int g = (a.rgb[3 * i] + a.rgb[3 * i + 1] + a.rgb[3 * i + 2]) / 9;
      d[0] = d[1] = d[2] = static_cast<std::uint8_t>(g);
      continue;
    }
    d[0] = 255;
    ++cmp.disagreeing;
    if (static_cast<long>(cmp.checked.size()) >= max_checked) {
      ++cmp.unchecked;
      continue;
    }
    Comparison::Pixel p;
    p.x = static_cast<int>(i % static_cast<std::size_t>(a.width));
    p.y = static_cast<int>(i / static_cast<std::size_t>(a.width));
    p.transforms = a.ids[i];
    p.raytrace = b.ids[i];
    p.certified = r.certify(p.x, p.y);
    if (!p.certified.decided) ++cmp.undecided;
    else if (p.certified.truth == p.transforms) ++cmp.transforms_right;
    else if (p.certified.truth == p.raytrace) ++cmp.raytrace_right;
    else ++cmp.neither;
    if (p.certified.decided && !p.certified.methods_agree) ++cmp.methods_differ_exactly;
    cmp.checked.push_back(p);
  }
  cmp.agreement = cmp.pixels ? 1.0 - static_cast<double>(cmp.disagreeing) / static_cast<double>(cmp.pixels) : 1.0;
  return cmp;
}

RenderReport render_report(const Renderer& r, const Image& img, RenderMethod method, const std::string& out) {
  const auto& cam = r.camera();
  return {out, method, cam.width, cam.height, r.threads(), static_cast<long>(img.ids.size()), img.seconds, r.left_out()};
}

CompareReport compare_report(const Scene& sc, const Renderer& r, const Comparison& c, int repeat, double min_agreement) {
  const auto& cam = r.camera();
  CompareReport rep;
  rep.scene_file = sc.file;
  rep.width = cam.width;
  rep.height = cam.height;
  rep.threads = r.threads();
  rep.repeat = std::max(1, repeat);
  rep.pixels = c.pixels;
  rep.disagreeing = c.disagreeing;
  rep.agreement = c.agreement;
  rep.min_agreement = min_agreement;
  rep.seconds_transforms = c.seconds_transforms;
  rep.seconds_raytrace = c.seconds_raytrace;
  rep.checked = static_cast<long>(c.checked.size());
  rep.transforms_right = c.transforms_right;
  rep.raytrace_right = c.raytrace_right;
  rep.neither = c.neither;
  rep.undecided = c.undecided;
  rep.unchecked = c.unchecked;
  rep.methods_differ_exactly = c.methods_differ_exactly;
  // the disagreements grouped by what each method drew and what is certified true, most frequent first
  std::map<std::tuple<std::string, std::string, std::string>, long> kinds;
  for (const auto& p : c.checked)
    ++kinds[{r.describe(p.transforms), r.describe(p.raytrace),
             p.certified.decided ? r.describe(p.certified.truth) : std::string("undecided")}];
  for (const auto& [k, n] : kinds) rep.kinds.push_back({n, std::get<0>(k), std::get<1>(k), std::get<2>(k)});
  std::stable_sort(rep.kinds.begin(), rep.kinds.end(),
                   [](const DisagreementKind& x, const DisagreementKind& y) { return x.pixels > y.pixels; });
  for (const auto& p : c.checked) {
    if (rep.disagreements.size() >= kListedDisagreements) break;
    DisagreeingPixel d{p.x, p.y, {p.transforms, r.describe(p.transforms)}, {p.raytrace, r.describe(p.raytrace)}, {}, 0, {}};
    if (p.certified.decided) {
      d.certified = PixelReading{p.certified.truth, r.describe(p.certified.truth)};
      d.bits = p.certified.bits;
      d.right = p.certified.truth == p.transforms ? "transforms" : p.certified.truth == p.raytrace ? "raytrace" : "neither";
    }
    rep.disagreements.push_back(std::move(d));
  }
  rep.left_out = r.left_out();
  return rep;
}

}  // namespace qverify::render
