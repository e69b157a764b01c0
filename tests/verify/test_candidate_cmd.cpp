// Another program audited by stress and audit (--candidate-cmd, issue 19): the process runner, and the CLI
// with candidates that crash, hang, print garbage, leave items out, or are right.
#include "cli_run.hpp"

#include <qverify/verify/candidate_run.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <unistd.h>

using namespace qverify;
using qverify_test::run;
using qverify_test::Run;
using qverify_test::temp_file;
using qverify_test::fresh_dir;

namespace {

nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  REQUIRE(in);
  return nlohmann::json::parse(in);
}

/// Is process `pid` gone (or a zombie waiting for its parent)?
bool gone(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  if (!stat) return true;
  std::string line;
  std::getline(stat, line);
  const auto close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

}  // namespace

TEST_CASE("run_shell: exit status, signals, bounded output", "[cli][candidate]") {
  const ProcessResult ok = run_shell("echo out; echo err >&2", 10);
  CHECK(ok.exit_code == 0);
  CHECK(ok.out == "out\n");
  CHECK(ok.err == "err\n");
  CHECK(ok.failure().empty());

  const ProcessResult crash = run_shell("exit 3", 10);
  CHECK(crash.exit_code == 3);
  CHECK(crash.failure() == "exit status 3");

  const ProcessResult killed = run_shell("kill -SEGV $$", 10);
  CHECK(killed.signal == SIGSEGV);
  CHECK(killed.failure().rfind("killed by signal 11", 0) == 0);

  // a chatty program neither blocks nor fills memory: 1 MB written, the first 1000 bytes kept
  const ProcessResult chatty = run_shell("head -c 1000000 /dev/zero", 10, 1000);
  CHECK(chatty.exit_code == 0);
  CHECK(chatty.out.size() == 1000);
  CHECK(chatty.out_truncated);

  // stdin is /dev/null: a program reading it does not wait
  CHECK(run_shell("cat", 10).exit_code == 0);
}

TEST_CASE("run_shell: the time-out kills the whole process group", "[cli][candidate]") {
  const std::string pidfile = temp_file("bg.pid", "");
  const auto t0 = std::chrono::steady_clock::now();
  const ProcessResult r = run_shell("sleep 30 & echo $! > " + pidfile + "; sleep 30", 0.5);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(r.timed_out);
  CHECK(r.failure() == "timed out after 0.5 s (process group killed)");
  CHECK(s < 5);
  std::ifstream in(pidfile);
  pid_t bg = 0;
  in >> bg;
  REQUIRE(bg > 0);
  for (int i = 0; i < 100 && !gone(bg); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(gone(bg));  // the background child went with the group

  // a shell that exits leaving a background child: the child is killed too, and the call does not wait for it
  const auto t1 = std::chrono::steady_clock::now();
  const ProcessResult left = run_shell("sleep 30 & echo $! > " + pidfile + "; exit 0", 10);
  CHECK(left.exit_code == 0);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count() < 5);
  std::ifstream in2(pidfile);
  in2 >> bg;
  for (int i = 0; i < 100 && !gone(bg); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(gone(bg));
}

TEST_CASE("candidate commands: paths substituted as shell words, names and commands checked", "[cli][candidate]") {
  CHECK(shell_word("/tmp/a-b_c.d/x.json") == "/tmp/a-b_c.d/x.json");
  CHECK(shell_word("/tmp/with space/it's.json") == "'/tmp/with space/it'\\''s.json'");
  CHECK(substitute_command("prog {scene} > {out}; cat {out}", "/s.json", "/o x.json") ==
        "prog /s.json > '/o x.json'; cat '/o x.json'");
  // a path with spaces and quotes reaches the program as one argument
  const ProcessResult r = run_shell(substitute_command("printf '%s|' {scene} {out}", "/tmp/a b/it's", "/o"), 10);
  CHECK(r.out == "/tmp/a b/it's|/o|");

  CHECK(candidate_name_problem("naive").empty());
  CHECK(candidate_name_problem("my-impl_2.0").empty());
  CHECK_FALSE(candidate_name_problem("").empty());
  CHECK_FALSE(candidate_name_problem("a/b").empty());
  CHECK_FALSE(candidate_name_problem("../x").empty());
  CHECK_FALSE(candidate_name_problem("-x").empty());
  CHECK_FALSE(candidate_name_problem(std::string(65, 'a')).empty());
  CHECK(candidate_command_problem("prog {scene} {out}").empty());
  CHECK_FALSE(candidate_command_problem("").empty());
  CHECK_FALSE(candidate_command_problem("   ").empty());
  // a command without the placeholders is still run (its calls fail and are recorded), with a warning
  CHECK(candidate_command_problem("false").empty());
  CHECK(candidate_command_problem("prog {scene}").empty());
  CHECK(candidate_command_warning("prog {scene} {out}").empty());
  CHECK(candidate_command_warning("prog {scene}").find("does not name {out}") != std::string::npos);
  CHECK(candidate_command_warning("prog > {out}").find("does not name {scene}") != std::string::npos);
  CHECK(candidate_command_warning("false").find("{scene} nor {out}") != std::string::npos);
}

TEST_CASE("stress --candidate-cmd: crash, garbage, missing items, hang and signal are recorded and the sweep completes",
          "[cli][candidate]") {
  const auto dir = fresh_dir("flaky");
  // A different failure at each of the first five points of far-from-origin, qverify's own eval at the others.
  const std::string script = temp_file("flaky.sh", std::string(R"(scene=$1; out=$2
case "$scene" in
  *-0.json) echo "crashing on purpose" >&2; exit 1;;
  *-1.json) echo 'garbage {' > "$out"; exit 0;;
  *-2.json) echo '{"format": "qverify-eval/1", "shadows": []}' > "$out"; exit 0;;
  *-3.json) sleep 600; exit 0;;
  *-4.json) kill -SEGV $$;;
esac
exec )") + QVERIFY_EXE + " eval \"$scene\" --json > \"$out\"\n");
  const auto t0 = std::chrono::steady_clock::now();
  const Run r = run("stress --family far-from-origin --out " + dir.string() + " --candidate-cmd 'sh " + script +
                    " {scene} {out}' --candidate-name flaky --candidate-timeout 1");
  // the hang was cut, not waited for (the whole sweep takes about 10 s here, 30 s under the sanitizers)
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 300);
  CHECK(r.code == 1);  // stress measures and reports, and exits 1: it found a program failing
  CHECK(r.out.find("candidate flaky: breaks at d = 1") != std::string::npos);
  const auto doc = read_json(dir / "report.json");
  const auto& pts = doc["families"][0]["points"];
  REQUIRE(pts.size() == 13);
  const char* reasons[] = {"exit status 1; stderr: crashing on purpose", "unreadable output: flaky output: (document): invalid JSON",
                           "incomplete output: shadow (obj, light): requested item missing",
                           "timed out after 1 s (process group killed)", ""};
  for (std::size_t k = 0; k < 5; ++k) {
    INFO("point " << k);
    const auto& c = pts[k]["runs"].back();
    CHECK(c["source"] == "candidate");
    CHECK(c["run"] == "flaky");
    CHECK(c["status"] == "candidate-failed");
    if (k < 4) CHECK(c["error"].get<std::string>().rfind(reasons[k], 0) == 0);
    // killed by SIGSEGV: seen directly, or through the shell that ran it (exit status 139)
    else CHECK(c["error"].get<std::string>().find("signal 11") != std::string::npos);
    const std::string base = "failures/flaky-far-from-origin-" + std::to_string(k);
    CHECK(c["reproducer"] == base + ".json");
    CHECK(std::filesystem::exists(dir / (base + ".json")));
    CHECK(std::filesystem::exists(dir / (base + ".log")));
    CHECK(pts[k]["runs"][3]["geometric_error"].get<double>() < 1e-9);  // qverify's own runs are all there
  }
  CHECK(std::filesystem::exists(dir / "failures/flaky-far-from-origin-1.out.json"));  // the garbage it returned
  for (std::size_t k = 5; k < pts.size(); ++k) {
    INFO("point " << k);
    CHECK(pts[k]["runs"].back()["status"] == "ok");
    CHECK(pts[k]["runs"].back()["item_geometric_error"].get<double>() < 1e-9);
  }
  CHECK(doc["candidate"]["failed_calls"] == 5);
  CHECK(doc["candidate"]["reproducers"].size() == 5);
  CHECK(doc["candidate"]["command"] == "sh " + script + " {scene} {out}");
  CHECK(doc["families"][0]["candidate"]["breakdown"] == 1.0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("stress and audit --candidate-cmd: a right candidate passes with no reproducers", "[cli][candidate]") {
  const auto dir = fresh_dir("right");
  const std::string cmd = std::string(" --candidate-cmd '") + QVERIFY_EXE + " eval {scene} --json > {out}'";
  const Run s = run("stress --family far-from-origin --out " + dir.string() + cmd + " --json");
  REQUIRE(s.code == 0);
  const auto doc = nlohmann::json::parse(s.out);
  CHECK(doc["candidate"]["name"] == "candidate");
  CHECK(doc["candidate"]["failed_calls"] == 0);
  CHECK(doc["candidate"]["beyond_accuracy"] == 0);
  CHECK(doc["candidate"]["reproducers"].empty());
  CHECK(doc["families"][0]["candidate"]["breakdown"].is_null());
  CHECK(doc["families"][0]["breakdown"]["candidate"].is_null());
  for (const auto& p : doc["families"][0]["points"]) CHECK(p["runs"].back()["item_geometric_error"].get<double>() < 1e-9);
  CHECK_FALSE(std::filesystem::exists(dir / "failures"));

  const Run a = run("audit " + std::string(QVERIFY_SCENES) + "/far-ball-lamp-floor.json --batch-ms 1 --out " +
                    (dir / "audit").string() + cmd + " --candidate-name self --json");
  REQUIRE(a.code == 0);
  const auto ad = nlohmann::json::parse(a.out);
  const auto& row = ad["rows"].back();
  CHECK(row["source"] == "candidate");
  CHECK(row["run"] == "self");
  CHECK(row["status"] == "pass");
  CHECK(row["seconds_per_call"].get<double>() > 0);
  CHECK(ad["candidate"]["reproducers"].empty());
  std::ifstream html(dir / "audit/report.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  CHECK(page.find("self (candidate; wall time per call)") != std::string::npos);  // in the plot
  std::filesystem::remove_all(dir);
}

TEST_CASE("audit --candidate-cmd: a failing candidate is a row with its reason and a reproducer", "[cli][candidate]") {
  const auto dir = fresh_dir("audit-fail");
  // a command that names neither placeholder is run all the same (a warning on stderr): it fails on purpose
  const Run a = run("audit " + std::string(QVERIFY_SCENES) + "/ball-lamp-floor.json --batch-ms 1 --out " + dir.string() +
                    " --candidate-cmd 'echo nothing useful; exit 4' --json");
  REQUIRE(a.code == 1);  // the audit found the program failing
  const auto ad = nlohmann::json::parse(a.out);
  const auto& row = ad["rows"].back();
  CHECK(row["status"] == "candidate-failed");
  CHECK(row["error"] == "exit status 4");
  CHECK(ad["rows"].size() == 17);  // the ladder is all there
  CHECK(std::filesystem::exists(dir / "failures/candidate-audit-0.json"));
  std::ifstream log(dir / "failures/candidate-audit-0.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  CHECK(text.find("nothing useful") != std::string::npos);
  // report.html says so too, with the reproducer (it showed the row alone, its correct bits as "exact")
  std::ifstream html(dir / "report.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  CHECK(page.find("Candidate candidate: candidate-failed") != std::string::npos);
  CHECK(page.find("The call failed: exit status 4") != std::string::npos);
  CHECK(page.find("href=\"failures/candidate-audit-0.json\"") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("usage errors of --candidate-cmd exit 2 before any work", "[cli][candidate]") {
  const auto dir = fresh_dir("usage");
  const std::string base = "stress --family far-from-origin --out " + dir.string();
  for (const std::string bad : {" --candidate-cmd 'p {scene} {out}' --candidate-timeout 0",
                                " --candidate-cmd 'p {scene} {out}' --candidate-timeout -1",
                                " --candidate-cmd 'p {scene} {out}' --candidate-timeout nan",
                                " --candidate-cmd ''", " --candidate-cmd '  '",
                                " --candidate-cmd 'p {scene} {out}' --candidate-name a/b",
                                " --candidate-cmd 'p {scene} {out}' --accuracy 0",
                                " --candidate-name x", " --candidate-timeout 5"}) {
    INFO(bad);
    const Run r = run(base + bad);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
  }
  const Run a = run("audit " + std::string(QVERIFY_SCENES) + "/ball-lamp-floor.json --out " + dir.string() +
                    " --candidate-cmd 'p {scene} {out}' --candidate-timeout 0");
  CHECK(a.code == 2);
  CHECK_FALSE(std::filesystem::exists(dir / "report.json"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("an interrupt of qverify kills the running candidate and removes its files", "[cli][candidate]") {
  // A call runs in its own process group (so that a time-out kills the whole of it), which a terminal's
  // Ctrl-C does not reach: interrupted, qverify left the candidate running, bounded by nothing, and its
  // temporary directory behind.
  for (const int sig : {SIGINT, SIGTERM}) {
    INFO("signal " << sig);
    const std::filesystem::path tmp = fresh_dir("interrupt-tmp-" + std::to_string(sig));
    const std::filesystem::path out = fresh_dir("interrupt-out-" + std::to_string(sig));
    const std::string pidfile = (out / "candidate.pid").string();
    const std::string cmd = "echo $$ > " + pidfile + "; exec sleep 30 # {scene} {out}";
    const pid_t q = ::fork();
    REQUIRE(q >= 0);
    if (q == 0) {
      ::setenv("TMPDIR", tmp.c_str(), 1);
      ::execl(QVERIFY_EXE, QVERIFY_EXE, "stress", "--family", "light-far", "--out", out.c_str(), "--candidate-cmd",
              cmd.c_str(), "--candidate-timeout", "60", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    pid_t candidate = 0;
    for (int i = 0; i < 3000 && candidate == 0; ++i) {  // (the sweep's first call: within a minute)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      std::ifstream in(pidfile);
      in >> candidate;
    }
    REQUIRE(candidate > 0);
    CHECK(std::filesystem::directory_iterator(tmp) != std::filesystem::directory_iterator());  // its work directory
    ::kill(q, sig);
    int status = 0;
    REQUIRE(::waitpid(q, &status, 0) == q);
    CHECK(WIFSIGNALED(status));
    if (WIFSIGNALED(status)) CHECK(WTERMSIG(status) == sig);  // ended by the signal, as it would have been
    for (int i = 0; i < 100 && !gone(candidate); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    CHECK(gone(candidate));
    CHECK(std::filesystem::directory_iterator(tmp) == std::filesystem::directory_iterator());  // removed
  }
}
