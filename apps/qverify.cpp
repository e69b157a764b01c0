// qverify command line: see shared/spec/cli.md for the contract.
#include <qverify/verify/eval.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>

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
  if (p->kind == Precision::Kind::interval)
    throw UsageError("--precision interval: certified intervals are not available yet in this build");
  return *p;
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

void print_eval(const json& doc) {
  fmt::print("scene      {}\nprecision  {}   method {}\n", doc["scene"].get<std::string>(),
             doc["precision"].get<std::string>(), doc["method"].get<std::string>());
  for (const auto& s : doc["shadows"]) {
    fmt::print("\nshadow  {} lit by {}: {}\n", s["quadric"].get<std::string>(), s["light"].get<std::string>(),
               s["status"].get<std::string>());
    print_matrix("P", s["P"]);
    print_matrix("polar_plane", s["polar_plane"]);
    print_matrix("R", s["R"]);
  }
  for (const auto& r : doc["reflections"]) {
    fmt::print("\nreflection  {} in {}: {}\n", r["quadric"].get<std::string>(), r["mirror"].get<std::string>(),
               r["status"].get<std::string>());
    print_matrix("M", r["M"]);
    print_matrix("B", r["B"]);
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"qverify: shadow volumes and mirror images of quadrics (Hashimoto & Suenaga), computed and verified"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Help for every command");

  std::string scene_file, precision_text = "double", method_text = "direct";
  bool as_json = false;

  auto add_common = [&](CLI::App* sub) {
    sub->add_option("SCENE", scene_file, "Scene file (qverify-scene/1)")->required();
    sub->add_option("--precision", precision_text,
                    "float | double | long-double | float128 | mpfr:BITS | interval | exact")
        ->capture_default_str();
    sub->add_option("--method", method_text, "direct (projective formulas) | paper (equations (2)-(6))")
        ->capture_default_str();
    sub->add_flag("--json", as_json, "Print exactly one JSON document on stdout");
  };

  CLI::App* eval = app.add_subcommand("eval", "Compute every requested shadow volume (P, polar plane, R) and mirror image (M, B)");
  add_common(eval);

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

  try {
    if (eval->parsed()) {
      const Precision prec = precision_of(precision_text);
      const Method method = method_of(method_text);
      const Scene sc = load_scene(scene_file);
      const json doc = eval_document(sc, prec, method);
      if (as_json) std::cout << doc.dump(2) << "\n";
      else print_eval(doc);
      return kOk;
    }
  } catch (const UsageError& e) {
    std::cerr << "qverify: " << e.what() << "\n";
    return kUsage;
  } catch (const InputError& e) {
    std::cerr << "qverify: error: " << e.what() << "\n";
    return kUsage;
  } catch (const std::exception& e) {
    std::cerr << "qverify: internal error: " << e.what() << "\n";
    return kInternal;
  }
  return kInternal;
}
