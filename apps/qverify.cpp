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
#include <qverify/report/audit_document.hpp>
#include <qverify/report/bench.hpp>
#include <qverify/report/eval_document.hpp>
#include <qverify/report/paper_document.hpp>
#include <qverify/report/render_document.hpp>
#include <qverify/report/report.hpp>
#include <qverify/report/stress.hpp>
#include <qverify/report/verify_document.hpp>
#include <qverify/render/render.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <chrono>
#include <fstream>
#include <vector>
#include <functional>
#include <iostream>
#include <sstream>
#include <map>
#include <memory>
#include <tuple>

#include <unistd.h>  // isatty

namespace {

using namespace qverify;

constexpr int kOk = 0, kFound = 1, kUsage = 2, kInternal = 3;

/// Usage errors (bad flag values): exit 2 with a message.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A value of --accuracy: a positive finite number, the whole text read (CLI11's own range check prints its
/// bounds in full, 309 digits, and says nothing of NaN).
const CLI::Validator kPositiveFinite(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(text.c_str(), &end);
      // (strtod sets ERANGE for a subnormal too: only a value that became 0 or infinite is refused)
      const std::string problem = "expected a positive finite number, found \"" + text + "\"";
      const bool whole = !text.empty() && end == text.c_str() + text.size();
      if (whole && errno == ERANGE && v == 0 && !std::signbit(v))  // a positive value that underflowed
        return problem + " (a value below the smallest double, which reads as 0)";
      if (whole && errno == ERANGE && std::isinf(v) && text.find_first_of("iInN") == std::string::npos)
        return problem + " (a value beyond the largest double)";
      if (!whole || !std::isfinite(v) || !(v > 0)) return problem;
      return "";
    },
    "POSITIVE");

/// A file or directory path given on the command line: an empty one is an error, never "not given"
/// (`verify --candidate "$DOC"` with DOC unset checked qverify's own results and passed; render
/// --ids '' wrote nothing, silently: audit 37b F3, F4).
const CLI::Validator kPath(
    [](std::string& text) -> std::string { return text.empty() ? "expected a path, found \"\"" : ""; }, "PATH");

/// A value of --seed: an integer from 0 to 2^64 - 1, the whole text read (a conversion to unsigned alone
/// takes -1 and 2^64 both as 2^64 - 1).
const CLI::Validator kSeedText(
    [](std::string& text) -> std::string {
      const std::string problem = "expected an integer from 0 to 18446744073709551615, found \"" + text + "\"";
      if (text.empty() || text.size() > 20 || text.find_first_not_of("0123456789") != std::string::npos) return problem;
      errno = 0;
      std::strtoull(text.c_str(), nullptr, 10);
      return errno == ERANGE ? problem : "";
    },
    "UINT64");

/// An integer option from lo to hi, the whole text read (CLI11's Range calls "abc" a value "not in range").
CLI::Validator integer_in(long lo, long hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long v = std::strtol(text.c_str(), &end, 10);
        const bool whole = !text.empty() && end == text.c_str() + text.size() && errno != ERANGE;
        if (!whole || v < lo || v > hi) return fmt::format("expected an integer from {} to {}, found \"{}\"", lo, hi, text);
        return "";
      },
      fmt::format("INT in [{} - {}]", lo, hi));
}

/// A number option from lo to hi, the whole text read: NaN is in no range (CLI11's Range lets it through,
/// every comparison with it being false).
CLI::Validator number_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool whole = !text.empty() && end == text.c_str() + text.size();
        if (!whole || !(v >= lo && v <= hi)) return fmt::format("expected a number from {} to {}, found \"{}\"", lo, hi, text);
        return "";
      },
      fmt::format("NUMBER in [{} - {}]", lo, hi));
}

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

/// A progress bar on stderr for runs longer than a second: redrawn in place on
/// a terminal, a line per tenth otherwise (a log stays short).
std::function<void(std::size_t, std::size_t)> progress_bar(std::string what) {
  struct State {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    bool shown = false;
    std::size_t last_tenth = 0;
  };
  auto st = std::make_shared<State>();
  const bool tty = isatty(2) != 0;
  return [st, tty, what = std::move(what)](std::size_t done, std::size_t total) {
    if (!st->shown && std::chrono::steady_clock::now() - st->start < std::chrono::seconds(1)) return;
    const std::size_t tenth = total ? done * 10 / total : 10;
    if (!tty && st->shown && tenth == st->last_tenth && done != total) return;
    st->shown = true;
    st->last_tenth = tenth;
    const int width = 30, filled = static_cast<int>(total ? done * width / total : width);
    std::cerr << (tty ? "\r" : "") << "qverify " << what << ": [" << std::string(static_cast<std::size_t>(filled), '#')
              << std::string(static_cast<std::size_t>(width - filled), '.') << "] " << done << "/" << total << " items"
              << (tty && done != total ? "" : "\n") << std::flush;
  };
}

// ------------------------------------------------------------------ render

struct RenderArgs {
  std::string out, ids, diff, method = "transforms", box, frame = "camera";
  bool compare = false;
  int threads = 0, repeat = 3;
  long max_checked = 2000;
  double min_agreement = 0.999;
};

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
  if (!a.compare && a.out.empty()) throw UsageError("render: --out image.png is required (or --compare)");
  // every image's file before any work: an unwritable --ids must not leave --out written and exit 2
  for (const std::string* file : {&a.out, &a.ids, &a.diff})
    if (!file->empty() && (a.compare || file != &a.diff)) check_writable(*file);  // (--diff: with --compare only)
  const render::Renderer r(sc, opt);
  if (!a.compare) {
    const auto method = a.method == "raytrace" ? render::RenderMethod::raytrace : render::RenderMethod::transforms;
    const render::Image img = r.render(method);
    write_image(a.out, img, img.rgb);
    if (!a.ids.empty()) write_image(a.ids, img, render::id_image(img));
    const render::RenderReport report = render::render_report(r, img, method, a.out);
    if (as_json) std::cout << render_json(report).dump(2) << "\n";
    else std::cout << render_text(report);
    return kOk;
  }
  const render::Comparison c = render::compare_methods(r, a.repeat, a.max_checked);
  if (!a.out.empty()) write_image(a.out, c.transforms_image, c.transforms_image.rgb);
  if (!a.ids.empty()) write_image(a.ids, c.transforms_image, render::id_image(c.transforms_image));
  if (!a.diff.empty()) write_image(a.diff, c.transforms_image, c.diff_rgb);
  const render::CompareReport report = render::compare_report(sc, r, c, a.repeat, a.min_agreement);
  if (as_json) std::cout << compare_json(report).dump(2) << "\n";
  else std::cout << compare_text(report);
  return report.pass() ? kOk : 1;
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
    sub->add_option("SCENE", o.scene_file, "Scene file (qverify-scene/1)")->required()->check(kPath);
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
        ->check(kPositiveFinite);
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
        ->check(kPositiveFinite)
        ->needs(cmd);
    return cmd;
  };

  c.eval = app.add_subcommand("eval", "Compute every requested shadow volume (P, polar plane, R) and mirror image (M, B)");
  add_common(c.eval);
  add_accuracy(c.eval);
  c.eval->add_option("--tolerance", o.tolerance,
                     "Adaptive mode: escalate each item double -> interval -> mpfr (MPFI) -> exact until its result is certified within "
                     "this relative tolerance (double output; per-item 'certified' says by which stage)")
      // (0 would read as "no adaptive mode" and silently compute the plain double results instead)
      ->check(kPositiveFinite & number_in(0.0, 1.0));

  c.verify = app.add_subcommand("verify",
                                "Check results on exact sample points: terminator points on A, P and R, "
                                "reflected points on B (a proof in exact arithmetic)");
  add_common(c.verify);
  c.verify->add_option("--samples", o.samples, "Points per item")->capture_default_str()->check(integer_in(1, kMaxSamples));
  c.verify->add_option("--seed", o.seed, "Seed of the deterministic sampler (0 to 2^64 - 1)")
      ->capture_default_str()
      ->check(kSeedText);
  add_accuracy(c.verify);
  c.verify->add_option("--candidate", o.candidate, "Check this qverify-eval/1 document (made by any program) instead of computing")
      ->check(kPath);

  c.audit = app.add_subcommand("audit", "Precision audit of one scene: error against run time over the whole "
                                        "precision ladder, both methods; writes report.json, report.html, "
                                        "error-vs-time.svg");
  c.audit->add_option("SCENE", o.scene_file, "Scene file (qverify-scene/1)")->required()->check(kPath);
  c.audit->add_option("--out", o.out_dir, "Output directory")->required()->check(kPath);
  c.audit->add_option("--batch-ms", o.batch_ms, "Minimum duration of one timed batch (7 batches, median)")
      ->capture_default_str()
      ->check(number_in(1.0, 10000.0));
  c.audit->add_flag("--json", o.as_json, "Also print report.json on stdout");
  c.audit_candidate = add_candidate(c.audit);

  c.stress = app.add_subcommand("stress", "Stability sweeps of stiff and extreme cases (families: --list); "
                                          "writes report.json, report.html and one SVG per family");
  c.stress->add_option("--family", o.families, "A family to sweep (repeatable; default: all)");
  c.stress->add_flag("--list", o.list_families, "List the families and exit");
  c.stress->add_option("--out", o.out_dir, "Output directory")->check(kPath);
  c.stress->add_option("--samples", o.stress_samples, "Exact points per item for the geometric error")
      ->capture_default_str()
      ->check(integer_in(1, 1000));
  c.stress->add_flag("--json", o.as_json, "Also print report.json on stdout");
  c.stress_candidate = add_candidate(c.stress);

  c.bench = app.add_subcommand("bench", "Batch throughput against the memory-bandwidth limit: items/s, bytes "
                                        "per item and roofline fraction per op, precision, method and kind of "
                                        "inputs; the filtered verifier's point checks per second; the processor");
  c.bench->add_option("--n", o.bench.n, "Items per run")->capture_default_str()->check(integer_in(1000, 100000000));
  c.bench->add_option("--threads", o.bench.threads, "Threads")->capture_default_str()->check(integer_in(1, 256));
  c.bench->add_option("--repeats", o.bench.repeats, "Rounds: each row is timed once per round, rows interleaved; best of the rounds")->capture_default_str()->check(integer_in(1, 50));
  c.bench->add_flag("!--no-huge-pages", o.bench.huge_pages,
                    "Do not advise huge pages for the buffers of the double and interval rows and of the bandwidth "
                    "copy (they are advised by default, as the batch functions do for the outputs they allocate): "
                    "the pages malloc gives, for comparison");
  c.bench->add_flag("--json", o.as_json, "Print exactly one JSON document on stdout");

  c.paper = app.add_subcommand("paper", "Audit every printed formula (1)-(11) of the paper against its definition, exactly");
  c.paper->add_flag("--json", o.as_json, "Print exactly one JSON document on stdout");
  c.paper->add_flag("--strict", o.strict, "Exit 1 when a printed formula fails its definition (errata found)");

  RenderArgs& r = o.render;
  c.render = app.add_subcommand("render", "Ray-cast the scene's camera view: shadows and mirror content from the "
                                          "transforms (P, polar plane, B) or by classic shadow/reflection rays");
  c.render->add_option("SCENE", o.scene_file, "Scene file (qverify-scene/1) with a camera")->required()->check(kPath);
  c.render->add_option("--out", r.out, "PNG image to write (with --compare: the transforms image)")->check(kPath);
  c.render->add_option("--method", r.method, "transforms | raytrace")->capture_default_str()->check(
      CLI::IsMember({"transforms", "raytrace"}));
  c.render->add_option("--ids", r.ids, "PNG of the ID buffer (one colour per surface, mirror and shadow set)")->check(kPath);
  c.render->add_flag("--compare", r.compare, "Render by both methods, compare the ID buffers, certify disagreeing pixels");
  c.render->add_option("--diff", r.diff, "With --compare: PNG with the disagreeing pixels in red")->check(kPath);
  c.render->add_option("--box", r.box, "Half side of the clipping cube around look_at (default: |eye - look_at|_inf / 2)");
  c.render->add_option("--frame", r.frame, "camera (origin at look_at, moved exactly before rounding) | world")
      ->capture_default_str()->check(CLI::IsMember({"camera", "world"}));
  c.render->add_option("--threads", r.threads, "Threads (0: all)")->capture_default_str()->check(integer_in(0, 256));
  c.render->add_option("--repeat", r.repeat, "With --compare: renders per method, the fastest is timed")
      ->capture_default_str()->check(integer_in(1, 100));
  c.render->add_option("--max-checked", r.max_checked, "With --compare: disagreeing pixels to certify at most")
      ->capture_default_str()->check(integer_in(0, 100000000));
  c.render->add_option("--min-agreement", r.min_agreement, "With --compare: exit 1 below this agreement fraction")
      ->capture_default_str()->check(number_in(0.0, 1.0));
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
  // --candidate-cmd of audit and stress
  if ((c.audit->parsed() && c.audit_candidate->count() > 0) ||
      (c.stress->parsed() && c.stress_candidate->count() > 0 && !o.list_families)) {
    if (const std::string p = candidate_command_problem(o.candidate_cmd); !p.empty()) throw UsageError("--candidate-cmd: " + p);
    if (const std::string w = candidate_command_warning(o.candidate_cmd); !w.empty())
      std::cerr << "qverify: warning: --candidate-cmd: " << w << "\n";
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
  AccuracyOptions aopt{o.accuracy};
  aopt.progress = progress_bar("eval (accuracy measure)");
  const EvalReport report = o.tolerance > 0 ? adaptive_eval_report(sc, method, o.tolerance, aopt)
                                            : eval_report(sc, prec, method, frame_of(o.frame_text), aopt);
  if (o.as_json) std::cout << eval_json(report).dump(2) << "\n";
  else std::cout << eval_text(report);
  return kOk;
}

int run_verify(const Options& o) {
  const Precision prec = precision_of(o.precision_text);
  const Method method = method_of(o.method_text);
  const Scene sc = load_scene(o.scene_file);
  // Computed results are eval's (its accuracy measure with its own samples and seed decides
  // escalation and the inaccurate flag): verify checks what `eval --accuracy T` prints.
  AccuracyOptions aopt{o.accuracy};
  aopt.progress = progress_bar("verify (eval's accuracy measure)");
  const ResultSet rs = o.candidate.empty() ? computed_results(sc, prec, method, frame_of(o.frame_text), aopt)
                                           : candidate_results(sc, o.candidate, prec);
  VerifyOptions vopt{o.samples, o.seed, o.accuracy};
  // --precision exact with a candidate: its numbers are read in the document's precision, and
  // judged in proof mode
  vopt.prove = !o.candidate.empty() && prec.kind == Precision::Kind::exact;
  vopt.progress = progress_bar("verify");
  const VerifyReport v = verify_results(sc, rs, vopt);
  if (o.as_json) std::cout << verify_document(sc, v).dump(2) << "\n";
  else std::cout << verify_text(sc, v);
  return v.failed > 0 ? kFound : kOk;
}

/// The candidate program of audit and stress.
Candidate candidate_of(const Options& o) {
  return process_candidate(o.candidate_name, o.candidate_cmd, o.candidate_timeout);
}

int run_audit_command(const Options& o, bool with_candidate) {
  const Scene sc = load_scene(o.scene_file);
  AuditOptions opt;
  opt.out_dir = o.out_dir;
  opt.batch_seconds = o.batch_ms / 1000;
  opt.progress = progress_after_two_seconds();
  check_report_outputs(o.out_dir, audit_report_files(o.out_dir), with_candidate);  // before any work
  if (with_candidate) {
    opt.candidate = candidate_of(o);
    opt.accuracy = o.accuracy;
  }
  const AuditReport report = run_audit(sc, opt);
  write_audit_report(o.out_dir, report);
  if (o.as_json) std::cout << audit_json(report).dump(2) << "\n";
  else std::cout << audit_text(report, o.out_dir);
  // exit 1: the audit found an error beyond tolerance: the audited program failed or missed its target,
  // or eval missed its own flag (a ladder row's item beyond 1e-9 not flagged inaccurate). The ladder's
  // errors themselves are measurements: float is beyond 1e-9 by design, and flagged so.
  return audit_found_error(report) ? kFound : kOk;
}

int run_stress_command(const Options& o, bool with_candidate) {
  // (an unknown family is an error with --list too: it listed every family and exited 0, audit 31b)
  for (const auto& f : o.families)
    if (std::none_of(stress_families().begin(), stress_families().end(), [&](const auto& g) { return g.name == f; }))
      throw UsageError("stress: unknown family \"" + f + "\" (see qverify stress --list)");
  if (o.list_families) {
    if (o.as_json) std::cout << stress_families_json(stress_families()).dump(2) << "\n";
    else std::cout << stress_families_text(stress_families());
    return kOk;
  }
  if (o.out_dir.empty()) throw UsageError("stress: --out DIR is required (or --list)");
  StressOptions opt;
  opt.out_dir = o.out_dir;
  opt.families = o.families;
  opt.samples = o.stress_samples;
  opt.progress = progress_after_two_seconds();
  std::vector<std::string> run_families = o.families;
  if (run_families.empty())
    for (const auto& f : stress_families()) run_families.push_back(f.name);
  check_report_outputs(o.out_dir, stress_report_files(o.out_dir, run_families), with_candidate);
  if (with_candidate) {
    opt.candidate = candidate_of(o);
    opt.accuracy = o.accuracy;
  }
  const StressReport report = run_stress(opt);
  write_stress_report(o.out_dir, report);
  if (o.as_json) std::cout << stress_json(report).dump(2) << "\n";
  else std::cout << stress_text(report, o.out_dir);
  // exit 1: an error beyond tolerance found, in the audited program (a failed call, an item beyond its
  // target, a failed check) or in eval's own flag (a run beyond 1e-9 that eval did not flag inaccurate)
  const bool candidate_bad = report.candidate && !report.candidate->reproducers.empty();
  const bool flag_missed = std::any_of(report.families.begin(), report.families.end(),
                                       [](const StressFamilyResult& f) { return !f.flag_check.ok(); });
  return candidate_bad || flag_missed ? kFound : kOk;
}

int run_bench_command(const Options& o) {
  BenchOptions opt = o.bench;
  const double need = static_cast<double>(bench_bytes_per_item()) * static_cast<double>(opt.n);
  if (const std::size_t have = available_memory(); have > 0 && need > 0.95 * static_cast<double>(have))
    throw UsageError(fmt::format("bench: --n {} needs about {:.1f} GB of memory ({} bytes per item), and {:.1f} GB "
                                 "are available; use a smaller --n",
                                 opt.n, need / 1e9, bench_bytes_per_item(), static_cast<double>(have) / 1e9));
  opt.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  const BenchReport report = run_bench(opt);
  if (o.as_json) std::cout << bench_json(report).dump(2) << "\n";
  else std::cout << bench_text(report);
  return kOk;
}

int run_paper(const Options& o) {
  const auto entries = audit_paper();
  if (o.as_json) std::cout << paper_json(entries).dump(2) << "\n";
  else std::cout << paper_text(entries);
  const bool errata = std::any_of(entries.begin(), entries.end(), [](const AuditEntry& e) { return e.verdict == "fails"; });
  return o.strict && errata ? kFound : kOk;
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
  const int code = run_command(options, commands);
  // Output that did not reach stdout (a full disk, an I/O error) is an error like a file that cannot be
  // written: never a silent success. (A pipe whose reader is gone ends the process with SIGPIPE.) The
  // commands' exit 1 becomes 2: what they found was not delivered.
  errno = 0;
  std::cout.flush();
  if (!std::cout) {
    std::cerr << "qverify: error: cannot write to standard output" << (errno ? std::string(": ") + std::strerror(errno) : "")
              << "\n";
    return code == kInternal ? kInternal : kUsage;
  }
  return code;
}
