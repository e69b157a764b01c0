// The CLI contract (shared/spec/cli.md): JSON shapes, number encodings, exit codes.
#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <sys/wait.h>

namespace {

struct Run {
  int code = -1;
  std::string out;
};

/// Runs the qverify binary; stdout captured, stderr to /dev/null.
Run run(const std::string& args) {
  Run r;
  const std::string cmd = std::string(QVERIFY_EXE) + " " + args + " 2>/dev/null";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p);
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string scene(const char* name) { return std::string(QVERIFY_SCENES) + "/" + name; }

void check_matrix(const nlohmann::json& m, std::size_t rows, const char* encoding) {
  auto check_entry = [&](const nlohmann::json& x) {
    if (std::string(encoding) == "number") CHECK(x.is_number());
    else {
      REQUIRE(x.is_string());
      const std::string s = x.get<std::string>();
      CHECK(s.find_first_not_of("-0123456789/") == std::string::npos);
    }
  };
  REQUIRE(m.is_array());
  REQUIRE(m.size() == rows);
  for (const auto& row : m) {
    if (rows == 4 && row.is_array()) {
      REQUIRE(row.size() == 4);
      for (const auto& x : row) check_entry(x);
    } else check_entry(row);
  }
}

}  // namespace

TEST_CASE("eval --json has the contract's shape", "[cli]") {
  for (const char* method : {"direct", "paper"})
    for (const char* precision : {"double", "exact"}) {
      const Run r = run("eval " + scene("mixed-requests.json") + " --json --method " + method + " --precision " + precision);
      REQUIRE(r.code == 0);
      const auto doc = nlohmann::json::parse(r.out);
      CHECK(doc["format"] == "qverify-eval/1");
      CHECK(doc["scene"] == "several shapes, two lights, two mirrors, selected requests");
      CHECK(doc["precision"] == precision);
      CHECK(doc["method"] == method);
      const char* enc = std::string(precision) == "exact" ? "rational" : "number";
      REQUIRE(doc["shadows"].size() == 4);  // only the requested pairs
      for (const auto& s : doc["shadows"]) {
        CHECK(s["status"] == "ok");
        check_matrix(s["P"], 4, enc);
        check_matrix(s["R"], 4, enc);
        REQUIRE(s["polar_plane"].size() == 4);
      }
      REQUIRE(doc["reflections"].size() == 2);
      for (const auto& m : doc["reflections"]) {
        check_matrix(m["M"], 4, enc);
        check_matrix(m["B"], 4, enc);
      }
      // 5 quadrics x 2 lights - 4 requested, 5 x 2 mirrors - 2 requested
      CHECK(doc["skipped"].size() == 6 + 8);
      CHECK(doc["shadows"][0]["quadric"] == "pipe");
      CHECK(doc["shadows"][0]["light"] == "lamp");
    }
}

TEST_CASE("eval encodes every precision of the ladder", "[cli]") {
  for (const char* p : {"float", "long-double", "float128", "mpfr:128"}) {
    const Run r = run(std::string("eval ") + scene("ball-lamp-floor.json") + " --json --precision " + p);
    REQUIRE(r.code == 0);
    const auto doc = nlohmann::json::parse(r.out);
    const auto& x = doc["shadows"][0]["P"][0][0];
    if (std::string(p) == "float") CHECK(x.is_number());
    else CHECK(x.is_string());
  }
  const Run exact = run(std::string("eval ") + scene("egg-sun-wall.json") + " --json --precision exact");
  const auto doc = nlohmann::json::parse(exact.out);
  CHECK(doc["reflections"][0]["M"][0][1] == "-1");  // wall x + y = 10: M = I - n n^T (2/|n|^2)
  CHECK(doc["reflections"][0]["M"][0][3] == "10");
}

TEST_CASE("bad input and usage exit 2 with nothing on stdout", "[cli]") {
  for (const std::string& args :
       {std::string("eval /nonexistent.json --json"), "eval " + scene("ball-lamp-floor.json") + " --precision quad --json",
        "eval " + scene("ball-lamp-floor.json") + " --method magic --json", std::string("frobnicate"),
        "eval " + scene("ball-lamp-floor.json") + " --no-such-flag"}) {
    INFO(args);
    const Run r = run(args);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
  }
  CHECK(run("--help").code == 0);
  CHECK(run("eval --help").code == 0);
}
