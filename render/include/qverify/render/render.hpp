#pragma once
/// \file render.hpp
/// `qverify render`: an ID-buffer ray caster of a scene's quadrics and plane
/// mirrors, seen through the scene's `camera`, by two methods (trace.hpp):
/// `transforms` (shadow volumes P / polar planes and mirror images B, primary
/// rays only: the paper's section 4) and `raytrace` (Whitted shadow and
/// reflection rays). Both use the same camera rays, the same visibility code
/// and the same shading, so their ID buffers can be compared pixel by pixel;
/// disagreeing pixels are re-traced with certified intervals (`certify`).
///
/// What is drawn:
///  - every quadric, clipped to the render box unless it is bounded (an
///    ellipsoid: its 3x3 block is definite), which keeps its own extent. The
///    box is the axis-aligned cube centred at `look_at` with half side
///    `box_half` (default: |eye - look_at|_oo / 2, so the eye is outside);
///  - every mirror, an infinite two-sided plane, showing the quadrics the
///    scene requests reflections of for it (one bounce); 40% of a mirror is
///    diffuse silver, so shadows fall on it;
///  - shadows of the requested (quadric, light) pairs whose shadow exists
///    (status not degenerate-quadric or light-on-surface); the other pairs are
///    listed in `left_out`.
/// Shading is Lambert (ambient 0.25, lights share the rest), two-sided.

#include <qverify/exact/mpfi.hpp>
#include <qverify/render/trace.hpp>
#include <qverify/scene/scene.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <string>
#include <vector>

namespace qverify::render {

struct RenderOptions {
  std::optional<Rational> box_half;  ///< half side of the clipping cube (exact); default in the file comment
  int threads = 0;    ///< 0: all hardware threads
  /// Work in the camera frame (origin at look_at, moved exactly before the one
  /// rounding to double) rather than in the world frame as written.
  bool camera_frame = true;
};

/// A pinhole camera, in double: pixel (px, py) looks along
/// forward + u right + v up (u, v at the pixel's centre). This double ray is
/// *the* ray of the pixel, for both methods and for the certified check.
struct Camera {
  Vec3<double> eye, forward, right, up;
  int width = 0, height = 0;
  Vec3<double> direction(int px, int py) const;
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< row-major, 3 bytes a pixel
  std::vector<PixelId> ids;
  double seconds = 0;  ///< wall time of the render (for transforms: including P, pi, B)
};

/// The certified verdict on one pixel.
struct Certified {
  bool decided = false;
  unsigned bits = 0;         ///< Mpfi precision that decided it
  PixelId truth;             ///< the raytrace decision procedure, certified
  bool methods_agree = true; ///< the transforms procedure, certified, gives the same id
};

class Renderer {
 public:
  /// Throws InputError (file, JSON path) when the scene has no camera, is too
  /// large to render, or a number does not fit a double.
  Renderer(const Scene& scene, const RenderOptions& opts);
  ~Renderer();

  Image render(RenderMethod method) const;
  /// Re-traces pixel (px, py) in certified interval arithmetic (Mpfi at 128,
  /// 512 and 2048 bits) from the exact scene and the pixel's double ray.
  Certified certify(int px, int py) const;

  const Camera& camera() const { return cam_; }
  /// Human-readable lines: what the render leaves out and why.
  const std::vector<std::string>& left_out() const { return left_out_; }
  int threads() const { return threads_; }
  /// Colour of a pixel id in the ID image (background black).
  static std::array<std::uint8_t, 3> id_colour(const PixelId& id);
  /// "ball (shadowed: lamp)", "ball in floor", "background".
  std::string describe(const PixelId& id) const;

 private:
  const Scene& scene_;
  Camera cam_;
  RenderData<double> dbl_;
  std::function<RenderData<Rational>()> make_exact_;
  mutable std::optional<RenderData<Rational>> exact_;
  double prep_seconds_ = 0;
  int threads_ = 1;
  std::vector<std::array<double, 3>> colours_;
  std::vector<std::string> left_out_;
  mutable std::map<unsigned, std::shared_ptr<RenderData<Mpfi>>> certified_cache_;
  double lambert(const Vec3<double>& x, Vec3<double> n, const Vec3<double>& ray, std::uint64_t shadowed) const;
  void shade(const Traced<double>& t, const Vec3<double>& primary, std::uint8_t* px) const;
};

/// Pixel-by-pixel comparison of the two methods.
struct Comparison {
  long pixels = 0, disagreeing = 0;
  double agreement = 1;
  double seconds_transforms = 0, seconds_raytrace = 0;
  struct Pixel {
    int x = 0, y = 0;
    PixelId transforms, raytrace;
    Certified certified;
  };
  std::vector<Pixel> checked;  ///< the disagreeing pixels that were certified
  long transforms_right = 0, raytrace_right = 0, neither = 0, undecided = 0, unchecked = 0;
  long methods_differ_exactly = 0;
  Image transforms_image, raytrace_image;
  std::vector<std::uint8_t> diff_rgb;  ///< agreeing pixels dimmed, disagreeing ones red
};

/// Renders with both methods (`repeat` times each, keeping the fastest, in
/// alternation), compares the ID buffers and certifies up to `max_checked`
/// disagreeing pixels.
Comparison compare_methods(const Renderer& r, int repeat = 3, long max_checked = 2000);

/// What `qverify render` says of one image: the typed report that
/// report/render_document.hpp writes as the `qverify-render/1` document and
/// as text.
struct RenderReport {
  std::string out;  ///< the PNG written
  RenderMethod method = RenderMethod::transforms;
  int width = 0, height = 0, threads = 0;
  long pixels = 0;
  double seconds = 0;
  std::vector<std::string> left_out;  ///< requests the renderer cannot draw, in words
};

RenderReport render_report(const Renderer& r, const Image& img, RenderMethod method, const std::string& out);

/// One pixel's reading by one procedure: its id and what it means in words (Renderer::describe).
struct PixelReading {
  PixelId id;
  std::string reads;
};

/// A disagreeing pixel, read by both methods and (when decided) certified.
struct DisagreeingPixel {
  int x = 0, y = 0;
  PixelReading transforms, raytrace;
  std::optional<PixelReading> certified;  ///< the certified reading, when decided
  unsigned bits = 0;                      ///< the precision that decided it
  std::string right;                      ///< "transforms", "raytrace" or "neither" (when decided)
};

/// How many disagreeing pixels read as what, by each method and certified ("undecided" when not).
struct DisagreementKind {
  long pixels = 0;
  std::string transforms, raytrace, certified;
};

/// What `qverify render --compare` says: the comparison's counts, the kinds of
/// disagreement (most frequent first), the first disagreeing pixels read in
/// words, and the verdict against the agreement asked for.
struct CompareReport {
  std::string scene_file;
  int width = 0, height = 0, threads = 0, repeat = 1;
  long pixels = 0, disagreeing = 0;
  double agreement = 1, min_agreement = 1;
  double seconds_transforms = 0, seconds_raytrace = 0;
  long checked = 0, transforms_right = 0, raytrace_right = 0, neither = 0, undecided = 0, unchecked = 0;
  long methods_differ_exactly = 0;
  std::vector<DisagreementKind> kinds;
  std::vector<DisagreeingPixel> disagreements;  ///< at most kListedDisagreements
  std::vector<std::string> left_out;
  bool pass() const { return agreement >= min_agreement; }
};

/// The disagreeing pixels a CompareReport lists one by one.
inline constexpr std::size_t kListedDisagreements = 50;

CompareReport compare_report(const Scene& sc, const Renderer& r, const Comparison& c, int repeat, double min_agreement);

/// The ID buffer as an RGB image (Renderer::id_colour).
std::vector<std::uint8_t> id_image(const Image& img);

/// Writes an 8-bit RGB PNG (libpng), through the checked write of
/// qverify/scene/files.hpp: throws FileWriteError naming the file and the
/// reason when it cannot be written (std::runtime_error on a size mismatch).
void write_png(const std::string& file, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace qverify::render
