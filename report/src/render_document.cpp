#include <qverify/report/render_document.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace qverify {
namespace {

using json = nlohmann::ordered_json;

json reading_json(const render::PixelReading& p) {
  return {{"surface", p.id.surface}, {"mirror", p.id.mirror}, {"shadowed", p.id.shadowed}, {"reads", p.reads}};
}

double speedup(const render::CompareReport& c) {
  return c.seconds_transforms > 0 ? c.seconds_raytrace / c.seconds_transforms : 0.0;
}

}  // namespace

json render_json(const render::RenderReport& r) {
  return {{"format", "qverify-render/1"}, {"method", render::method_word(r.method)},
          {"width", r.width},            {"height", r.height},
          {"pixels", r.pixels},          {"seconds", {{render::method_word(r.method), r.seconds}}},
          {"threads", r.threads},        {"left_out", r.left_out}};
}

std::string render_text(const render::RenderReport& r) {
  std::string out = fmt::format("rendered {} ({}x{}) by {} in {:.3f} s on {} threads\n", r.out, r.width, r.height,
                                render::method_word(r.method), r.seconds, r.threads);
  for (const auto& l : r.left_out) out += fmt::format("left out: {}\n", l);
  return out;
}

json compare_json(const render::CompareReport& c) {
  json kinds = json::array();
  for (const auto& k : c.kinds)
    kinds.push_back({{"pixels", k.pixels}, {"transforms", k.transforms}, {"raytrace", k.raytrace}, {"certified", k.certified}});
  json px = json::array();
  for (const auto& p : c.disagreements) {
    json e{{"x", p.x}, {"y", p.y}, {"transforms", reading_json(p.transforms)}, {"raytrace", reading_json(p.raytrace)}};
    if (p.certified) e["certified"] = {{"id", reading_json(*p.certified)}, {"bits", p.bits}, {"right", p.right}};
    else e["certified"] = nullptr;
    px.push_back(e);
  }
  return {{"format", "qverify-render/1"},
          {"pixels", c.pixels},
          {"agreement", c.agreement},
          {"disagreeing", c.disagreeing},
          {"seconds", {{"transforms", c.seconds_transforms}, {"raytrace", c.seconds_raytrace}}},
          {"speedup", speedup(c)},
          {"width", c.width},
          {"height", c.height},
          {"threads", c.threads},
          {"certified", {{"checked", c.checked}, {"transforms_right", c.transforms_right},
                         {"raytrace_right", c.raytrace_right}, {"neither", c.neither}, {"undecided", c.undecided},
                         {"unchecked", c.unchecked}, {"methods_differ_exactly", c.methods_differ_exactly}}},
          {"kinds", kinds},
          {"disagreements", px},
          {"left_out", c.left_out}};
}

std::string compare_text(const render::CompareReport& c) {
  std::string out = fmt::format("scene        {} ({}x{}, {} threads)\n", c.scene_file, c.width, c.height, c.threads);
  out += fmt::format("agreement    {:.6f}% of {} pixels ({} disagree)\n", 100 * c.agreement, c.pixels, c.disagreeing);
  out += fmt::format("seconds      transforms {:.4f}   raytrace {:.4f}   raytrace/transforms {:.2f}x (fastest of {})\n",
                     c.seconds_transforms, c.seconds_raytrace, speedup(c), c.repeat);
  out += fmt::format("certified    {} checked: transforms right {}, raytrace right {}, neither {}, undecided {}{}\n",
                     c.checked, c.transforms_right, c.raytrace_right, c.neither, c.undecided,
                     c.unchecked ? fmt::format(", {} not checked", c.unchecked) : std::string());
  if (c.methods_differ_exactly)
    out += fmt::format("WARNING      {} pixels differ between the methods even in certified arithmetic\n",
                       c.methods_differ_exactly);
  for (std::size_t i = 0; i < c.kinds.size() && i < 12; ++i) {
    const auto& k = c.kinds[i];
    out += fmt::format("  {:>6} px  transforms: {}; raytrace: {}; certified: {}\n", k.pixels, k.transforms, k.raytrace,
                       k.certified);
  }
  for (const auto& l : c.left_out) out += fmt::format("left out: {}\n", l);
  if (!c.pass()) out += fmt::format("FAIL: agreement below {}\n", c.min_agreement);
  return out;
}

}  // namespace qverify
