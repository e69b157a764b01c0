// qverify command line. The contract: README ("Command line"), docs/json-documents.md (documents,
// exit status) and docs/scene-format.md (input).
#include <qverify/exact/number_text.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/eval/eval.hpp>
#include <qverify/verify/adaptive.hpp>
#include <qverify/verify/candidate_run.hpp>
#include <qverify/verify/verifier.hpp>
#include <qverify/studies/audit.hpp>
#include <qverify/studies/bench.hpp>
#include <qverify/studies/paper_audit.hpp>
#include <qverify/studies/stress.hpp>
#include <qverify/report/report.hpp>
#include <qverify/report/verify_document.hpp>
#include <qverify/render/render.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <fstream>
#include <vector>
#include <functional>
#include <iostream>
#include <sstream>
#include <map>
#include <tuple>

namespace {

using json = nlohmann::ordered_json;
using namespace qverify;

constexpr int kOk = 0, kUsage = 2, kInternal = 3;

/// Usage errors (bad flag values): exit 2 with a message.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Precision precision_of(const std::string& text) {
  const auto p = parse_precision(text);
  if (!p)
    throw UsageError("--precision: unknown precision \"" + text +
                     "\" (expected float, double, long-double, float128, mpfr:BITS with 16 <= BITS <= 65536, interval, exact)");
  return *p;
}

std::optional<Frame> frame_of(const std::string& text) {
  if (text.empty()) return std::nullopt;
  if (text == "local") return Frame::local;
  if (text == "world") return Frame::world;
  throw UsageError("--frame: unknown frame \"" + text + "\" (expected local or world)");
}

Method method_of(const std::string& text) {
  if (text == "direct") return Method::direct;
  if (text == "paper") return Method::paper;
  throw UsageError("--method: unknown method \"" + text + "\" (expected direct or paper)");
}

/// Human-readable number: JSON strings unquoted.
std::string cell(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

void print_matrix(const char* name, const json& m) {
  if (m.empty() || !m[0].is_array()) {
    std::string row;
    for (const auto& x : m) row += fmt::format(" {:>14}", cell(x));
    fmt::print("    {:<12}[{} ]\n", name, row);
    return;
  }
  for (std::size_t i = 0; i < m.size(); ++i) {
    std::string row;
    for (const auto& x : m[i]) row += fmt::format(" {:>14}", cell(x));
    fmt::print("    {:<12}[{} ]\n", i == 0 ? name : "", row);
  }
}

/// The item's error bound, and in words whether it may miss the accuracy target.
void print_accuracy(const json& item, const json& doc) {
  if (!item.contains("error_bound")) return;
  const double T = doc["accuracy"].get<double>();
  const bool inaccurate = std::find(item["flags"].begin(), item["flags"].end(), "inaccurate") != item["flags"].end();
  if (item["error_bound"].is_null())
    fmt::print("    error bound: none ({}){}\n", item.contains("reason") ? item["reason"].get<std::string>() : "",
               inaccurate ? "; INACCURATE: the result may be off by more than the accuracy target" : "");
  else if (inaccurate)
    fmt::print("    INACCURATE: error bound {:.3g} of the object size exceeds the accuracy target {:.3g}\n",
               item["error_bound"].get<double>(), T);
  else
    fmt::print("    accurate: error bound {:.3g} of the object size (target {:.3g})\n", item["error_bound"].get<double>(), T);
}

void print_eval(const json& doc) {
  fmt::print("scene      {}\nprecision  {}   method {}\n", doc["scene"].get<std::string>(),
             doc["precision"].get<std::string>(), doc["method"].get<std::string>());
  for (const auto& s : doc["shadows"]) {
    fmt::print("\nshadow  {} lit by {}: {}\n", s["quadric"].get<std::string>(), s["light"].get<std::string>(),
               s["status"].get<std::string>());
    print_matrix("P", s["P"]);
    print_matrix("polar_plane", s["polar_plane"]);
    print_matrix("R", s["R"]);
    print_accuracy(s, doc);
  }
  for (const auto& r : doc["reflections"]) {
    fmt::print("\nreflection  {} in {}: {}\n", r["quadric"].get<std::string>(), r["mirror"].get<std::string>(),
               r["status"].get<std::string>());
    print_matrix("M", r["M"]);
    print_matrix("B", r["B"]);
    print_accuracy(r, doc);
  }
  if (!doc["skipped"].empty()) {
    fmt::print("\nleft out ({}):\n", doc["skipped"].size());
    for (const auto& k : doc["skipped"])
      fmt::print("    {} / {}: {}\n", k["quadric"].get<std::string>(),
                 k.contains("light") ? k["light"].get<std::string>() : k["mirror"].get<std::string>(),
                 k["reason"].get<std::string>());
  }
  if (!doc["inputs_rounded"].empty())
    fmt::print("\n{} input number(s) are not exactly representable in {} and were rounded once to nearest.\n",
               doc["inputs_rounded"].size(), doc["precision"].get<std::string>());
}

void print_verify(const json& doc) {
  fmt::print("scene      {}\nprecision  {}   method {}   source {}\nsamples    {} per item, seed {}   accuracy target {}\n\n",
             doc["scene"].get<std::string>(), doc["precision"].get<std::string>(), doc["method"].get<std::string>(),
             doc["source"].get<std::string>(), doc["samples"].get<int>(), doc["seed"].get<std::uint64_t>(),
             doc["accuracy"].get<double>() == 0 ? std::string("0 (exact proof)") : fmt::format("{:.3g}", doc["accuracy"].get<double>()));
  fmt::print("{:<11} {:<10} {:<10} {:<8} {:>6} {:>11} {:>11} {:>11} {:>9}\n", "kind", "quadric", "with", "status",
             "points", "geo. error", "obj. size", "proved", "rounding");
  auto num = [](const json& c, const char* k) {
    return !c.contains(k) ? std::string("-") : c[k].is_null() ? std::string("inf") : fmt::format("{:.2e}", c[k].get<double>());
  };
  for (const auto& c : doc["checks"]) {
    const std::string other = c.contains("light") ? c["light"].get<std::string>() : c["mirror"].get<std::string>();
    fmt::print("{:<11} {:<10} {:<10} {:<8} {:>6} {:>11} {:>11} {:>11} {:>9}\n", c["kind"].get<std::string>(),
               c["quadric"].get<std::string>(), other, c["status"].get<std::string>(),
               c.contains("points") ? c["points"].get<int>() : 0, num(c, "geometric_error"), num(c, "object_size"),
               c.contains("proved_exactly") ? std::to_string(c["proved_exactly"].get<int>()) : "-",
               !c.contains("consistent_with_precision") ? "-" : c["consistent_with_precision"].get<bool>() ? "as good" : "worse");
    if (c.contains("reason")) fmt::print("            {}\n", c["reason"].get<std::string>());
  }
  fmt::print("\npass = geometric error <= accuracy target{}; 'rounding' says whether the residuals are as small as "
             "this precision can make them (information only)\n",
             doc["accuracy"].get<double>() == 0 ? " (exact: every residual exactly zero)" : "");
  fmt::print("\n{} passed, {} failed, {} skipped\n", doc["passed"].get<int>(), doc["failed"].get<int>(),
             doc["skipped"].get<int>());
}

void print_audit(const json& doc, const std::string& dir) {
  fmt::print("precision audit of {} (reference: exact)\n\n", doc["scene"].get<std::string>());
  fmt::print("{:<12} {:<9} {:>12} {:>14} {:>14} {:>8} {:>11}  {}\n", "precision", "method", "ns/item", "max rel.err", "median",
             "bits", "inaccurate", "pareto");
  std::vector<std::string> front;
  for (const auto& p : doc["pareto"]) front.push_back(p.get<std::string>());
  auto num = [](const json& v) { return v.is_null() ? std::string("-") : fmt::format("{:.3g}", v.get<double>()); };
  for (const auto& r : doc["rows"]) {
    const std::string key = r["precision"].get<std::string>() + "/" + r["method"].get<std::string>();
    const bool candidate = r.contains("source");
    fmt::print("{:<12} {:<9} {:>12.1f} {:>14} {:>14} {:>8} {:>11}  {}\n", r["precision"].get<std::string>(),
               r["method"].get<std::string>(), r["ns_per_item"].get<double>(), num(r["max_rel_error"]),
               num(r["median_rel_error"]),
               r["correct_bits"].is_null() ? std::string(candidate && !r.contains("exact_match") ? "-" : "exact")
                                           : num(r["correct_bits"]),
               candidate ? std::string("-") : fmt::format("{}/{}", r["inaccurate_items"].get<int>(), r["items"].get<int>()),
               std::find(front.begin(), front.end(), key) != front.end() ? "*" : "");
  }
  if (doc.contains("candidate")) {
    const json& c = doc["candidate"];
    for (const auto& r : doc["rows"])
      if (r.contains("source")) {
        fmt::print("\ncandidate {}: {}", c["name"].get<std::string>(), r["status"].get<std::string>());
        if (r.contains("error")) fmt::print(" ({})", r["error"].get<std::string>());
        fmt::print("; {:.3f} s per call; largest geometric error {} (target {:.3g})\n", r["seconds_per_call"].get<double>(),
                   num(r["max_geometric_error"]), c["accuracy"].get<double>());
      }
    for (const auto& rep : c["reproducers"]) fmt::print("reproducer: {}/{} ({})\n", dir, rep["scene"].get<std::string>(),
                                                        rep["reason"].get<std::string>());
  }
  fmt::print("\nwrote {0}/report.json, {0}/report.html, {0}/error-vs-time.svg\n", dir);
}

void print_stress(const json& doc, const std::string& dir) {
  for (const auto& f : doc["families"]) {
    fmt::print("\n{} ({}): geometric error of {} / object size; default double meets the target: {}\n",
               f["name"].get<std::string>(), f["parameter"].get<std::string>(), f["item"].get<std::string>(),
               f["default_meets_target"].get<bool>() ? "yes" : "NO");
    fmt::print("{:>10} {:>10} {:>10}", f["parameter"].get<std::string>(), "eps*kappa", "rounded");
    for (const auto& r : f["points"][0]["runs"]) {
      std::string label = r["run"].get<std::string>();
      fmt::print(" {:>12}", label.substr(0, label.find(' ')).substr(0, 12));
    }
    fmt::print("\n");
    auto num = [](const json& v) { return v.is_null() ? std::string("-") : fmt::format("{:.2e}", v.get<double>()); };
    for (const auto& p : f["points"]) {
      fmt::print("{:>10} {:>10} {:>10}", num(p["param"]), num(p["predicted_double_error"]), num(p["rounded_exact_error"]));
      for (const auto& r : p["runs"])
        fmt::print(" {:>12}", r["status"] == "candidate-failed" ? std::string("FAILED") : num(r["geometric_error"]));
      fmt::print("\n");
    }
    if (f.contains("candidate")) {
      const json& c = f["candidate"];
      if (c["breakdown"].is_null())
        fmt::print("candidate {}: within the target at every point\n", c["name"].get<std::string>());
      else
        fmt::print("candidate {}: breaks at {} = {:.3g}: {}\n", c["name"].get<std::string>(), f["parameter"].get<std::string>(),
                   c["breakdown"].get<double>(), c["breakdown_reason"].get<std::string>());
    }
  }
  if (doc.contains("candidate")) {
    const json& c = doc["candidate"];
    fmt::print("\ncandidate {}: {} calls, {} failed, {} beyond the target {:.3g}; {} reproducer(s){}\n",
               c["name"].get<std::string>(), c["calls"].get<int>(), c["failed_calls"].get<int>(),
               c["beyond_accuracy"].get<int>(), c["accuracy"].get<double>(), c["reproducers"].size(),
               c["reproducers"].empty() ? std::string() : " in " + dir + "/failures/");
  }
  fmt::print("\nwrote {0}/report.json, {0}/report.html and one SVG per family\n", dir);
}

void print_bench(const json& doc) {
  auto text = [](const json& j) { return j.is_string() ? j.get<std::string>() : std::string("?"); };
  const json& cpu = doc["processor"];
  fmt::print("{} items, {} threads, memory bandwidth {:.2f} GB/s (measured in this run), {} lanes ({})\n"
             "processor: {} {} (family {}, model {})\n\n",
             doc["n"].get<long>(), doc["threads"].get<int>(), doc["memory_bandwidth_gbps"].get<double>(),
             doc["simd"]["lanes"].get<int>(), doc["simd"]["instruction_set"].get<std::string>(), text(cpu["vendor"]),
             text(cpu["model_name"]), cpu["family"].dump(), cpu["model"].dump());
  fmt::print("{:<17} {:<9} {:<8} {:<14} {:>12} {:>10} {:>6} {:>8} {:>9}\n", "op", "precision", "method", "inputs",
             "items/s", "ns/item", "bytes", "roofline", "x double");
  for (const auto& r : doc["rows"]) {
    fmt::print("{:<17} {:<9} {:<8} {:<14} {:>12.4g} {:>10.2f} {:>6} {:>8.2f} {:>9.1f}", r["op"].get<std::string>(),
               r["precision"].get<std::string>(), r["method"].get<std::string>(), r["inputs"].get<std::string>(),
               r["items_per_s"].get<double>(), r["ns_per_item"].get<double>(), r["bytes_per_item"].get<long>(),
               r["roofline_fraction"].get<double>(), r["cost_vs_double_direct"].get<double>());
    if (r.contains("points"))  // verification rows: point checks
      fmt::print("  {:.3g} checks/s per thread{}", r["points_per_s_per_thread"].get<double>(),
                 r["precision"] == "exact" ? std::string(", proof mode")
                                           : fmt::format(", {} of {} past the filter", r["exact_fallbacks"].get<long>(),
                                                         r["points"].get<long>()));
    fmt::print("\n");
  }
  fmt::print("\nverification rows: point checks ((point, result) pairs) of double-valued items; sampling the exact "
             "points took {:.2f} s (shadow) and {:.2f} s (reflection), not timed in the rows\n",
             doc["verification"]["sampling_s"]["shadow"].get<double>(),
             doc["verification"]["sampling_s"]["reflection"].get<double>());
}

/// MemAvailable of /proc/meminfo in bytes, or 0 where there is none.
std::size_t available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::size_t kb = 0;
  while (in >> key >> kb) {
    if (key == "MemAvailable:") return kb * 1024;
    in.ignore(256, '\n');
  }
  return 0;
}

/// Progress lines on stderr, once a command has run for more than two seconds.
std::function<void(const std::string&)> progress_after_two_seconds() {
  const auto start = std::chrono::steady_clock::now();
  return [start](const std::string& line) {
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(2)) std::cerr << line << "\n";
  };
}

/// Wraps text at `width` columns with an indent.
std::string wrap_text(const std::string& text, std::size_t width, const std::string& indent) {
  std::string out, line;
  std::istringstream words(text);
  std::string w;
  while (words >> w) {
    if (!line.empty() && line.size() + 1 + w.size() > width) {
      out += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) out += indent + line + "\n";
  return out;
}

void print_paper(const std::vector<AuditEntry>& entries) {
  fmt::print("Audit of Hashimoto & Suenaga, 'A study on the transformation of quadric surfaces' (exact arithmetic)\n\n");
  fmt::print("{:<6} {:<20} {}\n", "eq.", "verdict", "claim");
  fmt::print("{:-<6} {:-<20} {:-<70}\n", "", "", "");
  for (const auto& e : entries)
    fmt::print("{:<6} {:<20} {}\n", e.id, e.verdict + (e.factor.empty() ? "" : " (" + e.factor.substr(0, e.factor.find(' ')) + ")"),
               e.claim.substr(0, 70) + (e.claim.size() > 70 ? "..." : ""));
  for (const auto& e : entries) {
    fmt::print("\n{} {}\n", e.id, e.verdict);
    fmt::print("  claim:\n{}", wrap_text(e.claim, 96, "    "));
    if (!e.reading.empty()) fmt::print("  reading:\n{}", wrap_text(e.reading, 96, "    "));
    if (!e.factor.empty()) fmt::print("  factor:   {}\n", e.factor);
    fmt::print("  evidence:\n{}", wrap_text(e.evidence, 96, "    "));
    if (!e.corrected.empty()) fmt::print("  corrected:\n{}", wrap_text(e.corrected, 96, "    "));
  }
}

// ------------------------------------------------------------------ render

struct RenderArgs {
  std::string out, ids, diff, method = "transforms", box, frame = "camera";
  bool compare = false;
  int threads = 0, repeat = 3;
  long max_checked = 2000;
  double min_agreement = 0.999;
};

json pixel_json(const render::Renderer& r, const render::PixelId& id) {
  return {{"surface", id.surface}, {"mirror", id.mirror}, {"shadowed", id.shadowed}, {"reads", r.describe(id)}};
}

/// Throws FileWriteError (exit 2, the path named) when the file cannot be written.
void write_image(const std::string& file, const render::Image& img, const std::vector<std::uint8_t>& rgb) {
  render::write_png(file, img.width, img.height, rgb);
}

int run_render(const Scene& sc, const RenderArgs& a, bool as_json) {
  render::RenderOptions opt;
  opt.threads = a.threads;
  opt.camera_frame = a.frame == "camera";
  if (!a.box.empty()) {
    std::string err;
    const auto v = parse_rational(a.box, err);
    if (!v || *v <= 0) throw UsageError("--box: expected a positive number, got \"" + a.box + "\"" + (err.empty() ? "" : " (" + err + ")"));
    opt.box_half = *v;
  }
  const render::Renderer r(sc, opt);
  const auto& cam = r.camera();
  if (!a.compare) {
    if (a.out.empty()) throw UsageError("render: --out image.png is required (or --compare)");
    const auto method = a.method == "raytrace" ? render::RenderMethod::raytrace : render::RenderMethod::transforms;
    const render::Image img = r.render(method);
    write_image(a.out, img, img.rgb);
    if (!a.ids.empty()) write_image(a.ids, img, render::id_image(img));
    if (as_json) {
      std::cout << json{{"format", "qverify-render/1"}, {"method", render::method_word(method)}, {"width", cam.width},
                        {"height", cam.height}, {"pixels", static_cast<long>(img.ids.size())},
                        {"seconds", {{render::method_word(method), img.seconds}}}, {"threads", r.threads()},
                        {"left_out", r.left_out()}}
                       .dump(2)
                << "\n";
    } else {
      fmt::print("rendered {} ({}x{}) by {} in {:.3f} s on {} threads\n", a.out, cam.width, cam.height,
                 render::method_word(method), img.seconds, r.threads());
      for (const auto& l : r.left_out()) fmt::print("left out: {}\n", l);
    }
    return kOk;
  }
  const render::Comparison c = render::compare_methods(r, a.repeat, a.max_checked);
  if (!a.out.empty()) write_image(a.out, c.transforms_image, c.transforms_image.rgb);
  if (!a.ids.empty()) write_image(a.ids, c.transforms_image, render::id_image(c.transforms_image));
  if (!a.diff.empty()) write_image(a.diff, c.transforms_image, c.diff_rgb);
  const bool pass = c.agreement >= a.min_agreement;
  // the disagreements grouped by what each method drew and what is certified true
  std::map<std::tuple<std::string, std::string, std::string>, long> kinds;
  for (const auto& p : c.checked)
    ++kinds[{r.describe(p.transforms), r.describe(p.raytrace),
             p.certified.decided ? r.describe(p.certified.truth) : std::string("undecided")}];
  std::vector<std::pair<long, std::tuple<std::string, std::string, std::string>>> by_count;
  for (const auto& [k, n] : kinds) by_count.push_back({n, k});
  std::sort(by_count.begin(), by_count.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  if (as_json) {
    json kinds_json = json::array();
    for (const auto& [n, k] : by_count)
      kinds_json.push_back({{"pixels", n}, {"transforms", std::get<0>(k)}, {"raytrace", std::get<1>(k)}, {"certified", std::get<2>(k)}});
    json px = json::array();
    for (const auto& p : c.checked) {
      if (px.size() >= 50) break;
      json e{{"x", p.x}, {"y", p.y}, {"transforms", pixel_json(r, p.transforms)}, {"raytrace", pixel_json(r, p.raytrace)}};
      if (p.certified.decided)
        e["certified"] = {{"id", pixel_json(r, p.certified.truth)}, {"bits", p.certified.bits},
                          {"right", p.certified.truth == p.transforms ? "transforms"
                                    : p.certified.truth == p.raytrace ? "raytrace" : "neither"}};
      else e["certified"] = nullptr;
      px.push_back(e);
    }
    json doc{{"format", "qverify-render/1"},
             {"pixels", c.pixels},
             {"agreement", c.agreement},
             {"disagreeing", c.disagreeing},
             {"seconds", {{"transforms", c.seconds_transforms}, {"raytrace", c.seconds_raytrace}}},
             {"speedup", c.seconds_transforms > 0 ? c.seconds_raytrace / c.seconds_transforms : 0.0},
             {"width", cam.width},
             {"height", cam.height},
             {"threads", r.threads()},
             {"certified", {{"checked", static_cast<long>(c.checked.size())}, {"transforms_right", c.transforms_right},
                            {"raytrace_right", c.raytrace_right}, {"neither", c.neither}, {"undecided", c.undecided},
                            {"unchecked", c.unchecked}, {"methods_differ_exactly", c.methods_differ_exactly}}},
             {"kinds", kinds_json},
             {"disagreements", px},
             {"left_out", r.left_out()}};
    std::cout << doc.dump(2) << "\n";
  } else {
    fmt::print("scene        {} ({}x{}, {} threads)\n", sc.file, cam.width, cam.height, r.threads());
    fmt::print("agreement    {:.6f}% of {} pixels ({} disagree)\n", 100 * c.agreement, c.pixels, c.disagreeing);
    fmt::print("seconds      transforms {:.4f}   raytrace {:.4f}   raytrace/transforms {:.2f}x (fastest of {})\n",
               c.seconds_transforms, c.seconds_raytrace,
               c.seconds_transforms > 0 ? c.seconds_raytrace / c.seconds_transforms : 0.0, std::max(1, a.repeat));
    fmt::print("certified    {} checked: transforms right {}, raytrace right {}, neither {}, undecided {}{}\n",
               c.checked.size(), c.transforms_right, c.raytrace_right, c.neither, c.undecided,
               c.unchecked ? fmt::format(", {} not checked", c.unchecked) : std::string());
    if (c.methods_differ_exactly)
      fmt::print("WARNING      {} pixels differ between the methods even in certified arithmetic\n", c.methods_differ_exactly);
    for (std::size_t i = 0; i < by_count.size() && i < 12; ++i) {
      const auto& [n, k] = by_count[i];
      fmt::print("  {:>6} px  transforms: {}; raytrace: {}; certified: {}\n", n, std::get<0>(k), std::get<1>(k), std::get<2>(k));
    }
    for (const auto& l : r.left_out()) fmt::print("left out: {}\n", l);
    if (!pass) fmt::print("FAIL: agreement below {}\n", a.min_agreement);
  }
  return pass ? kOk : 1;
}

/// Every option of every command, as parsed (one place: the commands share --json, --accuracy, the
/// scene and the candidate options).
struct Options {
  std::string scene_file, precision_text = "double", method_text = "direct", frame_text;
  bool as_json = false;
  double accuracy = kDefaultAccuracy;
  double tolerance = 0;                   // eval --tolerance (adaptive mode)
  int samples = kDefaultSamples;          // verify
  std::uint64_t seed = 1;                 // verify
  std::string candidate;                  // verify --candidate
  std::string out_dir;                    // audit, stress
  double batch_ms = 20;                   // audit
  std::string candidate_cmd, candidate_name = "candidate";  // audit and stress --candidate-cmd
  double candidate_timeout = 60;
  std::vector<std::string> families;      // stress
  bool list_families = false;
  int stress_samples = 8;
  BenchOptions bench;
  bool strict = false;                    // paper
  RenderArgs render;
};

/// The subcommands, and the options that say whether a candidate program was given.
struct Commands {
  CLI::App *eval, *verify, *audit, *stress, *bench, *paper, *render;
  CLI::Option *audit_candidate, *stress_candidate;
};

/// Declares every command and its options on `app`, bound to `o`.
Commands declare_commands(CLI::App& app, Options& o) {
  Commands c{};
  auto add_common = [&](CLI::App* sub) {
    sub->add_option("SCENE", o.scene_file, "Scene file (qverify-scene/1)")->required();
    sub->add_option("--precision", o.precision_text,
                    "float | double | long-double | float128 | mpfr:BITS | interval | exact")
        ->capture_default_str();
    sub->add_option("--method", o.method_text, "direct (projective formulas) | paper (equations (2)-(6))")
        ->capture_default_str();
    sub->add_flag("--json", o.as_json, "Print exactly one JSON document on stdout");
    sub->add_option("--frame", o.frame_text,
                    "local (default for floating precisions, method direct: per-object origin) | world");
  };
  auto add_accuracy = [&](CLI::App* sub) {
    sub->add_option("--accuracy", o.accuracy,
                    "Accuracy target T: largest geometric error (distance of exact points from the result, relative "
                    "to the object's size) that passes; items whose error bound exceeds it are flagged inaccurate")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
  };
  // Another program audited beside qverify's precisions (audit and stress --candidate-cmd).
  auto add_candidate = [&](CLI::App* sub) {
    CLI::Option* cmd = sub->add_option(
        "--candidate-cmd", o.candidate_cmd,
        "Also run this program on every scene: run through /bin/sh -c with {scene} and {out} replaced by file paths; "
        "it reads the scene and writes a qverify-eval/1 document to {out}");
    sub->add_option("--candidate-name", o.candidate_name, "Label of the candidate (its runs, its reproducers' file names)")
        ->capture_default_str()
        ->needs(cmd);
    sub->add_option("--candidate-timeout", o.candidate_timeout, "Seconds each call may take (then its process group is killed)")
        ->capture_default_str()
        ->needs(cmd);
    sub->add_option("--accuracy", o.accuracy,
                    "The candidate's accuracy target T: a point where its geometric error exceeds T (relative to the "
                    "object's size), or its call failed, is written as a reproducer into DIR/failures/")
        ->capture_default_str()
        ->needs(cmd);
    return cmd;
  };

  c.eval = app.add_subcommand("eval", "Compute every requested shadow volume (P, polar plane, R) and mirror image (M, B)");
  add_common(c.eval);
  add_accuracy(c.eval);
  c.eval->add_option("--tolerance", o.tolerance,
                     "Adaptive mode: escalate each item double -> interval -> mpfr (MPFI) -> exact until its result is certified within "
                     "this relative tolerance (double output; per-item 'certified' says by which stage)")
      ->check(CLI::Range(0.0, 1.0));

  c.verify = app.add_subcommand("verify",
                                "Check results on exact sample points: terminator points on A, P and R, "
                                "reflected points on B (a proof in exact arithmetic)");
  add_common(c.verify);
  c.verify->add_option("--samples", o.samples, "Points per item")->capture_default_str()->check(CLI::Range(1, 100000));
  c.verify->add_option("--seed", o.seed, "Seed of the deterministic sampler")->capture_default_str();
  add_accuracy(c.verify);
  c.verify->add_option("--candidate", o.candidate, "Check this qverify-eval/1 document (made by any program) instead of computing");

  c.audit = app.add_subcommand("audit", "Precision audit of one scene: error against run time over the whole "
                                        "precision ladder, both methods; writes report.json, report.html, "
                                        "error-vs-time.svg");
  c.audit->add_option("SCENE", o.scene_file, "Scene file (qverify-scene/1)")->required();
  c.audit->add_option("--out", o.out_dir, "Output directory")->required();
  c.audit->add_option("--batch-ms", o.batch_ms, "Minimum duration of one timed batch (7 batches, median)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 10000.0));
  c.audit->add_flag("--json", o.as_json, "Also print report.json on stdout");
  c.audit_candidate = add_candidate(c.audit);

  c.stress = app.add_subcommand("stress", "Stability sweeps of stiff and extreme cases (families: --list); "
                                          "writes report.json, report.html and one SVG per family");
  c.stress->add_option("--family", o.families, "A family to sweep (repeatable; default: all)");
  c.stress->add_flag("--list", o.list_families, "List the families and exit");
  c.stress->add_option("--out", o.out_dir, "Output directory");
  c.stress->add_option("--samples", o.stress_samples, "Exact points per item for the geometric error")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  c.stress->add_flag("--json", o.as_json, "Also print report.json on stdout");
  c.stress_candidate = add_candidate(c.stress);

  c.bench = app.add_subcommand("bench", "Batch throughput against the memory-bandwidth limit: items/s, bytes "
                                        "per item and roofline fraction per op, precision, method and kind of "
                                        "inputs; the filtered verifier's point checks per second; the processor");
  c.bench->add_option("--n", o.bench.n, "Items per run")->capture_default_str()->check(CLI::Range(1000L, 100000000L));
  c.bench->add_option("--threads", o.bench.threads, "Threads")->capture_default_str()->check(CLI::Range(1, 256));
  c.bench->add_option("--repeats", o.bench.repeats, "Rounds: each row is timed once per round, rows interleaved; best of the rounds")->capture_default_str()->check(CLI::Range(1, 50));
  c.bench->add_flag("--json", o.as_json, "Print exactly one JSON document on stdout");

  c.paper = app.add_subcommand("paper", "Audit every printed formula (1)-(11) of the paper against its definition, exactly");
  c.paper->add_flag("--json", o.as_json, "Print exactly one JSON document on stdout");
  c.paper->add_flag("--strict", o.strict, "Exit 1 when a printed formula fails its definition (errata found)");

  RenderArgs& r = o.render;
  c.render = app.add_subcommand("render", "Ray-cast the scene's camera view: shadows and mirror content from the "
                                          "transforms (P, polar plane, B) or by classic shadow/reflection rays");
  c.render->add_option("SCENE", o.scene_file, "Scene file (qverify-scene/1) with a camera")->required();
  c.render->add_option("--out", r.out, "PNG image to write (with --compare: the transforms image)");
  c.render->add_option("--method", r.method, "transforms | raytrace")->capture_default_str()->check(
      CLI::IsMember({"transforms", "raytrace"}));
  c.render->add_option("--ids", r.ids, "PNG of the ID buffer (one colour per surface, mirror and shadow set)");
  c.render->add_flag("--compare", r.compare, "Render by both methods, compare the ID buffers, certify disagreeing pixels");
  c.render->add_option("--diff", r.diff, "With --compare: PNG with the disagreeing pixels in red");
  c.render->add_option("--box", r.box, "Half side of the clipping cube around look_at (default: |eye - look_at|_inf / 2)");
  c.render->add_option("--frame", r.frame, "camera (origin at look_at, moved exactly before rounding) | world")
      ->capture_default_str()->check(CLI::IsMember({"camera", "world"}));
  c.render->add_option("--threads", r.threads, "Threads (0: all)")->capture_default_str()->check(CLI::Range(0, 256));
  c.render->add_option("--repeat", r.repeat, "With --compare: renders per method, the fastest is timed")
      ->capture_default_str()->check(CLI::Range(1, 100));
  c.render->add_option("--max-checked", r.max_checked, "With --compare: disagreeing pixels to certify at most")
      ->capture_default_str()->check(CLI::Range(0L, 100000000L));
  c.render->add_option("--min-agreement", r.min_agreement, "With --compare: exit 1 below this agreement fraction")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  c.render->add_flag("--json", o.as_json, "Print exactly one JSON document on stdout");
  return c;
}

/// The first word that is not an option names the command: an unknown one is named back, with the list
/// (CLI11 alone would say "A subcommand is required"). Returns the exit status, or nullopt to go on.
std::optional<int> refuse_unknown_command(const CLI::App& app, int argc, char** argv) {
  std::string commands;
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    commands += (commands.empty() ? "" : ", ") + sub->get_name();
    names.push_back(sub->get_name());
  }
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.empty() && word[0] == '-') continue;
    if (std::find(names.begin(), names.end(), word) == names.end()) {
      std::cerr << "qverify: unknown command \"" << word << "\" (commands: " << commands
                << ")\n(run 'qverify --help' for usage)\n";
      return kUsage;
    }
    break;
  }
  if (argc < 2) {
    std::cerr << "qverify: a command is required (commands: " << commands << ")\n(run 'qverify --help' for usage)\n";
    return kUsage;
  }
  return std::nullopt;
}

/// Checks of values that span options (CLI11 checks each option alone), before any work.
void check_options(const Options& o, const Commands& c) {
  if ((c.eval->parsed() || c.verify->parsed() || c.audit->parsed() || c.stress->parsed()) &&
      !(std::isfinite(o.accuracy) && o.accuracy > 0))
    throw UsageError("--accuracy: expected a positive finite number");
  // --candidate-cmd of audit and stress
  if ((c.audit->parsed() && c.audit_candidate->count() > 0) ||
      (c.stress->parsed() && c.stress_candidate->count() > 0 && !o.list_families)) {
    if (const std::string p = candidate_command_problem(o.candidate_cmd); !p.empty()) throw UsageError("--candidate-cmd: " + p);
    if (const std::string p = candidate_name_problem(o.candidate_name); !p.empty())
      throw UsageError("--candidate-name \"" + o.candidate_name + "\": " + p);
    if (!(std::isfinite(o.candidate_timeout) && o.candidate_timeout > 0 && o.candidate_timeout <= 1e6))
      throw UsageError("--candidate-timeout: expected a positive number of seconds (at most 1e6)");
  }
}

int run_eval(const Options& o) {
  const Precision prec = precision_of(o.precision_text);
  const Method method = method_of(o.method_text);
  const Scene sc = load_scene(o.scene_file);
  if (o.tolerance > 0 && prec.kind != Precision::Kind::f64)
    throw UsageError("--tolerance: the adaptive mode produces double results; drop --precision");
  if (o.tolerance > 0 && o.tolerance < std::ldexp(1.0, -53))
    throw UsageError("--tolerance: below 2^-53 (1.1e-16) a double result cannot be certified (even the exact "
                     "result rounded to double is that far); use --precision exact");
  const json doc = o.tolerance > 0 ? adaptive_eval_document(sc, method, o.tolerance, AccuracyOptions{o.accuracy})
                                   : eval_document(sc, prec, method, frame_of(o.frame_text), AccuracyOptions{o.accuracy});
  if (o.as_json) std::cout << doc.dump(2) << "\n";
  else print_eval(doc);
  return kOk;
}

int run_verify(const Options& o) {
  const Precision prec = precision_of(o.precision_text);
  const Method method = method_of(o.method_text);
  const Scene sc = load_scene(o.scene_file);
  const ResultSet rs = o.candidate.empty() ? computed_results(sc, prec, method, frame_of(o.frame_text),
                                                              AccuracyOptions{o.accuracy, o.samples, o.seed})
                                           : candidate_results(sc, o.candidate, prec);
  const VerifyReport v = verify_results(sc, rs, VerifyOptions{o.samples, o.seed, o.accuracy});
  const json doc = verify_document(sc, v);
  if (o.as_json) std::cout << doc.dump(2) << "\n";
  else print_verify(doc);
  return v.failed > 0 ? 1 : kOk;
}

/// The candidate program of audit and stress, after its --out directory exists (a bad --out fails
/// before the candidate's work directory is made).
Candidate candidate_of(const Options& o) {
  create_output_directory(o.out_dir);
  return process_candidate(o.candidate_name, o.candidate_cmd, o.candidate_timeout);
}

int run_audit_command(const Options& o, bool with_candidate) {
  const Scene sc = load_scene(o.scene_file);
  AuditOptions opt;
  opt.out_dir = o.out_dir;
  opt.batch_seconds = o.batch_ms / 1000;
  opt.progress = progress_after_two_seconds();
  if (with_candidate) {
    opt.candidate = candidate_of(o);
    opt.accuracy = o.accuracy;
  }
  const AuditReport report = run_audit(sc, opt);
  write_audit_report(o.out_dir, report);
  if (o.as_json) std::cout << report.document.dump(2) << "\n";
  else print_audit(report.document, o.out_dir);
  return kOk;
}

int run_stress_command(const Options& o, bool with_candidate) {
  if (o.list_families) {
    json list = json::array();
    for (const auto& f : stress_families()) {
      if (!o.as_json) fmt::print("{:<20} {}\n", f.name, f.description);
      list.push_back({{"name", f.name}, {"parameter", f.parameter}, {"description", f.description}});
    }
    if (o.as_json) std::cout << json{{"families", list}}.dump(2) << "\n";
    return kOk;
  }
  if (o.out_dir.empty()) throw UsageError("stress: --out DIR is required (or --list)");
  for (const auto& f : o.families)
    if (std::none_of(stress_families().begin(), stress_families().end(), [&](const auto& g) { return g.name == f; }))
      throw UsageError("stress: unknown family \"" + f + "\" (see qverify stress --list)");
  StressOptions opt;
  opt.out_dir = o.out_dir;
  opt.families = o.families;
  opt.samples = o.stress_samples;
  opt.progress = progress_after_two_seconds();
  if (with_candidate) {
    opt.candidate = candidate_of(o);
    opt.accuracy = o.accuracy;
  }
  const StressReport report = run_stress(opt);
  write_stress_report(o.out_dir, report);
  if (o.as_json) std::cout << report.document.dump(2) << "\n";
  else print_stress(report.document, o.out_dir);
  return kOk;
}

int run_bench_command(const Options& o) {
  BenchOptions opt = o.bench;
  const double need = static_cast<double>(bench_bytes_per_item()) * static_cast<double>(opt.n);
  if (const std::size_t have = available_memory(); have > 0 && need > 0.95 * static_cast<double>(have))
    throw UsageError(fmt::format("bench: --n {} needs about {:.1f} GB of memory ({} bytes per item), and {:.1f} GB "
                                 "are available; use a smaller --n",
                                 opt.n, need / 1e9, bench_bytes_per_item(), static_cast<double>(have) / 1e9));
  opt.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const json doc = run_bench(opt);
  if (o.as_json) std::cout << doc.dump(2) << "\n";
  else print_bench(doc);
  return kOk;
}

int run_paper(const Options& o) {
  const auto entries = audit_paper();
  if (o.as_json) std::cout << audit_json(entries).dump(2) << "\n";
  else print_paper(entries);
  const bool errata = std::any_of(entries.begin(), entries.end(), [](const AuditEntry& e) { return e.verdict == "fails"; });
  return o.strict && errata ? 1 : kOk;
}

/// Runs the parsed command; every refused input is exit 2 with its message, anything else exit 3.
int run_command(const Options& o, const Commands& c) {
  try {
    check_options(o, c);
    if (c.eval->parsed()) return run_eval(o);
    if (c.verify->parsed()) return run_verify(o);
    if (c.audit->parsed()) return run_audit_command(o, c.audit_candidate->count() > 0);
    if (c.stress->parsed()) return run_stress_command(o, c.stress_candidate->count() > 0);
    if (c.bench->parsed()) return run_bench_command(o);
    if (c.render->parsed()) return run_render(load_scene(o.scene_file), o.render, o.as_json);
    if (c.paper->parsed()) return run_paper(o);
  } catch (const UsageError& e) {
    std::cerr << "qverify: " << e.what() << "\n";
    return kUsage;
  } catch (const InputError& e) {
    std::cerr << "qverify: error: " << e.what() << "\n";
    return kUsage;
  } catch (const FileWriteError& e) {  // an output file or --out directory: nothing claims it was written
    std::cerr << "qverify: error: " << e.what() << "\n";
    return kUsage;
  } catch (const std::exception& e) {
    std::cerr << "qverify: internal error: " << e.what() << "\n";
    return kInternal;
  }
  return kInternal;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"qverify: shadow volumes and mirror images of quadrics (Hashimoto & Suenaga), computed and verified"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Help for every command");
  Options options;
  const Commands commands = declare_commands(app, options);
  if (const auto refused = refuse_unknown_command(app, argc, argv)) return *refused;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "qverify: " << e.what() << "\n(run 'qverify --help' for usage)\n";
    return kUsage;
  }
  return run_command(options, commands);
}
