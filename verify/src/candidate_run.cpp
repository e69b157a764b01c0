#include <qverify/verify/candidate_run.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/scene/json_tree.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

namespace qverify {

namespace {

using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

bool safe_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
}

/// A label usable as a file name: unsafe characters become '_'.
std::string safe_label(const std::string& label) {
  std::string s = label.empty() ? std::string("case") : label.substr(0, 128);
  for (char& c : s)
    if (!safe_char(c)) c = '_';
  if (s[0] == '.' || s[0] == '-') s[0] = '_';
  return s;
}

// ------------------------------------------------------------------ interrupts
//
// A call runs in its own process group (so that a time-out kills the whole of it), which a terminal's
// Ctrl-C does not reach, and it works in a private temporary directory. So an interrupt (SIGINT, SIGTERM,
// SIGHUP) of qverify while candidates may run first kills every running call's group and removes the
// calls' files and directories, then ends qverify by the same signal, as it would have ended. Only
// async-signal-safe calls run in the handler: the groups, files and directories are registered in fixed
// slots beforehand (a slot is read once it is `ready`). The handler is installed only where the signal's
// disposition is the default: an ignored SIGHUP (nohup) stays ignored, and a host's own handler (Python's
// SIGINT, which raises KeyboardInterrupt) stays its own.

constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;

/// One registered thing: a process group, a file or a directory (a path, written before `ready`).
struct Slot {
  std::atomic<int> state{0};  ///< 0 free, 1 being written, 2 ready
  std::atomic<pid_t> group{0};
  char path[kPathBytes] = {};
};
Slot g_groups[kSlots], g_files[kSlots], g_dirs[kSlots];

/// (A slot released and taken again while the handler reads it could give it a torn path: the window
/// is a few instructions of another thread during an interrupt, and the worst case an unlinked path that
/// is not the call's; left as it is.)
/// Takes a free slot of `slots` and fills it (nullptr when all are taken: the thing is then not cleaned
/// up at an interrupt, as before; 64 concurrent calls are far beyond the threads a run uses).
Slot* take_slot(Slot (&slots)[kSlots], pid_t group, const std::string& path) {
  if (path.size() >= kPathBytes) return nullptr;
  for (Slot& s : slots) {
    int expected = 0;
    if (!s.state.compare_exchange_strong(expected, 1)) continue;
    s.group.store(group);
    std::memcpy(s.path, path.c_str(), path.size() + 1);
    s.state.store(2);
    return &s;
  }
  return nullptr;
}

/// Registers one thing for the handler while it exists.
class Registered {
 public:
  Registered(Slot (&slots)[kSlots], pid_t group, const std::string& path = {}) : slot_(take_slot(slots, group, path)) {}
  ~Registered() {
    if (slot_) slot_->state.store(0);
  }
  Registered(const Registered&) = delete;
  Registered& operator=(const Registered&) = delete;

 private:
  Slot* slot_;
};

extern "C" void on_interrupt(int sig) {
  const int saved = errno;
  for (Slot& s : g_groups)
    if (s.state.load() == 2 && s.group.load() > 0) ::kill(-s.group.load(), SIGKILL);
  for (Slot& s : g_files)
    if (s.state.load() == 2) ::unlink(s.path);
  for (Slot& s : g_dirs)
    if (s.state.load() == 2) ::rmdir(s.path);
  ::signal(sig, SIG_DFL);
  errno = saved;
  ::raise(sig);  // delivered on return: qverify ends by the signal
}

/// Installs on_interrupt, once, for the interrupts whose disposition is the default.
void install_interrupt_cleanup() {
  static const bool installed = [] {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) continue;
      struct sigaction sa {};
      sa.sa_handler = on_interrupt;
      sigemptyset(&sa.sa_mask);
      for (const int other : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&sa.sa_mask, other);
      sa.sa_flags = SA_RESTART;
      ::sigaction(sig, &sa, nullptr);
    }
    return true;
  }();
  (void)installed;
}

/// The last lines of a program's output, on one line, at most `max` characters.
std::string tail_line(const std::string& text, std::size_t max = 300) {
  std::string t = text;
  while (!t.empty() && (t.back() == '\n' || t.back() == '\r' || t.back() == ' ')) t.pop_back();
  if (t.size() > max) t = "..." + t.substr(t.size() - max);
  for (char& c : t)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  return t;
}

const char* signal_text(int sig) {
  const char* s = ::strsignal(sig);
  return s ? s : "unknown signal";
}

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

/// Reads what is available on fd into `into` (up to `cap` kept); false at end of file or on an error.
bool read_some(int fd, std::string& into, bool& truncated, std::size_t cap) {
  char buf[8192];
  const ssize_t n = ::read(fd, buf, sizeof buf);
  if (n < 0) return errno == EINTR || errno == EAGAIN;
  if (n == 0) return false;
  const std::size_t room = into.size() < cap ? cap - into.size() : 0;
  const std::size_t keep = std::min(room, static_cast<std::size_t>(n));
  into.append(buf, keep);
  if (keep < static_cast<std::size_t>(n)) truncated = true;
  return true;
}

}  // namespace

// ------------------------------------------------------------------ processes

std::string ProcessResult::failure() const {
  if (timed_out) {
    std::ostringstream s;
    s << "timed out after " << timeout_seconds << " s (process group killed)";
    return s.str();
  }
  if (signal != 0) return "killed by signal " + std::to_string(signal) + " (" + signal_text(signal) + ")";
  if (exit_code > 128 && exit_code < 128 + 65)  // how a shell reports a command killed by a signal
    return "exit status " + std::to_string(exit_code) + " (a command killed by signal " + std::to_string(exit_code - 128) +
           ", " + signal_text(exit_code - 128) + ")";
  if (exit_code != 0) return "exit status " + std::to_string(exit_code);
  return "";
}

ProcessResult run_shell(const std::string& command, double timeout_seconds, std::size_t capture_limit) {
  ProcessResult res;
  res.timeout_seconds = timeout_seconds;
  int outp[2] = {-1, -1}, errp[2] = {-1, -1};
  if (::pipe2(outp, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  if (::pipe2(errp, O_CLOEXEC) != 0) {
    const int e = errno;
    close_fd(outp[0]), close_fd(outp[1]);
    throw std::system_error(e, std::generic_category(), "pipe");
  }
  int devnull = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  const char* cmd = command.c_str();
  [[maybe_unused]] const pid_t parent = ::getpid();
  const auto t0 = clock_type::now();
  // The interrupts wait until the shell is registered (on_interrupt then kills its group); the child
  // unblocks them before it runs the command.
  sigset_t interrupts, before;
  sigemptyset(&interrupts);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&interrupts, sig);
  ::pthread_sigmask(SIG_BLOCK, &interrupts, &before);
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int e = errno;
    ::pthread_sigmask(SIG_SETMASK, &before, nullptr);
    close_fd(outp[0]), close_fd(outp[1]), close_fd(errp[0]), close_fd(errp[1]), close_fd(devnull);
    throw std::system_error(e, std::generic_category(), "fork");
  }
  if (pid == 0) {  // the child: async-signal-safe calls only
    ::setpgid(0, 0);
#ifdef __linux__
    // qverify killed (Ctrl-C reaches its group, not this one): the shell goes too, not left running
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
#endif
    if (devnull >= 0) ::dup2(devnull, 0);
    ::dup2(outp[1], 1);
    ::dup2(errp[1], 2);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::signal(SIGPIPE, SIG_DFL);
    ::execl("/bin/sh", "sh", "-c", cmd, static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here: whichever runs first (EACCES once the child has exec'd is fine)
  std::optional<Registered> running;
  running.emplace(g_groups, pid);  // killed at an interrupt, until it is killed below
  ::pthread_sigmask(SIG_SETMASK, &before, nullptr);
  close_fd(outp[1]), close_fd(errp[1]), close_fd(devnull);

  const auto deadline = t0 + std::chrono::duration_cast<clock_type::duration>(std::chrono::duration<double>(timeout_seconds));
  int fds[2] = {outp[0], errp[0]};
  std::string* bufs[2] = {&res.out, &res.err};
  bool* truncs[2] = {&res.out_truncated, &res.err_truncated};
  auto pump = [&](int wait_ms) {  // waits up to wait_ms for output, reads what is there
    pollfd p[2];
    nfds_t n = 0;
    int which[2];
    for (int i = 0; i < 2; ++i)
      if (fds[i] >= 0) {
        p[n] = {fds[i], POLLIN, 0};
        which[n++] = i;
      }
    if (n == 0) {
      if (wait_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
      return;
    }
    if (::poll(p, n, wait_ms) <= 0) return;
    for (nfds_t k = 0; k < n; ++k)
      if (p[k].revents & (POLLIN | POLLHUP | POLLERR)) {
        const int i = which[k];
        if (!read_some(fds[i], *bufs[i], *truncs[i], capture_limit)) close_fd(fds[i]);
      }
  };
  auto exited = [&] {  // has the shell exited? (not reaped: its pid, and so its group id, stay reserved)
    siginfo_t si;
    std::memset(&si, 0, sizeof si);
    return ::waitid(P_PID, static_cast<id_t>(pid), &si, WEXITED | WNOHANG | WNOWAIT) == 0 && si.si_pid == pid;
  };

  int step_ms = 1;
  while (true) {
    if (exited()) break;
    const auto now = clock_type::now();
    if (now >= deadline) {
      res.timed_out = true;
      break;
    }
    const auto left_ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count() + 1;
    // With output pipes open, poll wakes up on output and on their closing (usually the exit); without, step up.
    const int wait = static_cast<int>(std::min<long long>(left_ms, (fds[0] >= 0 || fds[1] >= 0) ? 20 : step_ms));
    pump(wait);
    if (fds[0] < 0 && fds[1] < 0) step_ms = std::min(step_ms * 2, 20);
  }
  // Whatever is left of the group (the whole of it at a time-out, background children after an exit) is killed.
  ::kill(-pid, SIGKILL);
  running.reset();  // before the shell is reaped: then its pid, the group's id, may be another's
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  res.seconds = seconds_since(t0);
  // The rest of the output: the writers are gone (a process that left the group may still hold a pipe: 1 s at most).
  const auto drain_until = clock_type::now() + std::chrono::seconds(1);
  while ((fds[0] >= 0 || fds[1] >= 0) && clock_type::now() < drain_until) pump(50);
  close_fd(fds[0]), close_fd(fds[1]);
  if (!res.timed_out) {
    if (WIFEXITED(status)) res.exit_code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) res.signal = WTERMSIG(status);
  }
  return res;
}

std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return safe_char(c) || c == '/' || c == ':' || c == '@' || c == '%' || c == '+' || c == '=' || c == ',';
  });
  if (plain) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string substitute_command(const std::string& command, const std::string& scene_path, const std::string& out_path) {
  std::string r;
  const std::string scene = shell_word(scene_path), out = shell_word(out_path);
  for (std::size_t i = 0; i < command.size();) {
    if (command.compare(i, 7, "{scene}") == 0) {
      r += scene;
      i += 7;
    } else if (command.compare(i, 5, "{out}") == 0) {
      r += out;
      i += 5;
    } else r += command[i++];
  }
  return r;
}

// ------------------------------------------------------------------ candidates

std::string candidate_name_problem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > 64) return "at most 64 characters";
  for (char c : name)
    if (!safe_char(c))
      return std::string("may hold only letters, digits, '.', '_' and '-' (it names files), found '") + c + "'";
  if (name[0] == '.' || name[0] == '-') return "must not start with '.' or '-'";
  return "";
}

std::string candidate_command_problem(const std::string& command) {
  if (std::all_of(command.begin(), command.end(), [](unsigned char c) { return std::isspace(c); }))
    return "the command is empty";
  return "";
}

std::string candidate_command_warning(const std::string& command) {
  const bool scene = command.find("{scene}") != std::string::npos, out = command.find("{out}") != std::string::npos;
  if (scene && out) return "";
  const char* what = !scene && !out ? "{scene} nor {out} (the scene file to read, the file to write the "
                                       "qverify-eval/1 document to)"
                     : !scene         ? "{scene} (the scene file to read)"
                                      : "{out} (the file to write the qverify-eval/1 document to)";
  return std::string("the command does not name ") + what +
         ": it is run all the same, and a call that writes no document is recorded as candidate-failed";
}

namespace {

/// A private temporary directory, removed with its contents by the destructor.
struct WorkDir {
  std::filesystem::path path;
  WorkDir() {
    std::string templ = (std::filesystem::temp_directory_path() / "qverify-candidate-XXXXXX").string();
    if (!::mkdtemp(templ.data())) {
      const int code = errno;
      const std::string reason = std::strerror(code);
      throw FileWriteError("cannot create directory " + templ + ": " + reason, templ, reason, code);
    }
    path = templ;
    registered_ = std::make_unique<Registered>(g_dirs, 0, path.string());
    install_interrupt_cleanup();
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  std::unique_ptr<Registered> registered_;  ///< removed at an interrupt (once its files are)
  ~WorkDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
    registered_.reset();  // (after: an interrupt meanwhile still removes what is left)
  }
};

std::string process_log(const std::string& command, const ProcessResult& p) {
  std::string log = "command: " + command + "\n";
  log += "ended: " + (p.failure().empty() ? std::string("exit status 0") : p.failure()) + " after " +
         std::to_string(p.seconds) + " s\n";
  log += "stdout" + std::string(p.out_truncated ? " (first bytes)" : "") + ":\n" + p.out;
  if (!p.out.empty() && p.out.back() != '\n') log += "\n";
  log += "stderr" + std::string(p.err_truncated ? " (first bytes)" : "") + ":\n" + p.err;
  if (!p.err.empty() && p.err.back() != '\n') log += "\n";
  return log;
}

}  // namespace

Candidate process_candidate(const std::string& name, const std::string& command, double timeout_seconds) {
  auto dir = std::make_shared<WorkDir>();
  Candidate c;
  c.name = name;
  c.description = command;
  c.timeout_seconds = timeout_seconds;
  c.call = [dir, command, timeout_seconds](const CandidateInput& in) {
    const std::string label = safe_label(in.label);
    const std::filesystem::path scene = dir->path / (label + ".json"), out = dir->path / (label + ".out.json");
    std::error_code ec;
    std::filesystem::remove(out, ec);  // never read a stale document
    const Registered scene_file(g_files, 0, scene.string()), out_file(g_files, 0, out.string());  // at an interrupt
    write_file(scene, in.scene_text);
    const std::string cmd = substitute_command(command, scene.string(), out.string());
    const ProcessResult p = run_shell(cmd, timeout_seconds);
    CandidateOutput o;
    o.log = process_log(cmd, p);
    o.seconds = p.seconds;
    const bool wrote = std::filesystem::is_regular_file(out, ec);
    std::string read_error;
    if (wrote) {
      try {
        o.document = read_text_file(out.string(), JsonLimits{}.max_bytes);
      } catch (const std::exception& e) {
        read_error = std::string("its output cannot be read: ") + e.what();
      }
    }
    std::filesystem::remove(out, ec);
    std::filesystem::remove(scene, ec);
    if (const std::string f = p.failure(); !f.empty()) {
      const std::string err = tail_line(p.err);
      throw CandidateFailure(f + (err.empty() ? std::string() : "; stderr: " + err), std::move(o));
    }
    if (!read_error.empty()) throw CandidateFailure(read_error, std::move(o));
    if (!wrote) throw CandidateFailure("no output: the command exited 0 without writing {out}", std::move(o));
    return o;
  };
  return c;
}

Reproducer write_reproducer(const std::filesystem::path& failures_dir, const std::string& name,
                            const std::string& family, std::size_t k, double param, const std::string& scene_text,
                            const CandidateCall& call, const std::string& reason) {
  create_output_directory(failures_dir);
  const std::string base = safe_label(name + "-" + family + "-" + std::to_string(k));
  const std::string rel = failures_dir.filename().string() + "/";
  Reproducer r{family, k, param, reason, rel + base + ".json", std::nullopt, rel + base + ".log"};
  write_file(failures_dir / (base + ".json"), scene_text);
  if (!call.returned.empty()) {
    write_file(failures_dir / (base + ".out.json"), call.returned);
    r.returned = rel + base + ".out.json";
  }
  std::string log = "candidate: " + name + "\ncase: " + family + " point " + std::to_string(k) + "\nreason: " + reason +
                    "\nwall time: " + std::to_string(call.seconds) + " s\n";
  if (!call.log.empty()) log += call.log;
  write_file(failures_dir / (base + ".log"), log);
  return r;
}

void remove_candidate_reproducers(const std::filesystem::path& failures_dir, const std::string& name) {
  std::error_code ec;
  if (!std::filesystem::is_directory(failures_dir, ec)) return;
  const std::string prefix = name + "-";
  std::vector<std::filesystem::path> old;
  for (const auto& e : std::filesystem::directory_iterator(failures_dir, ec))
    if (e.is_regular_file(ec) && e.path().filename().string().rfind(prefix, 0) == 0) old.push_back(e.path());
  for (const auto& f : old) std::filesystem::remove(f, ec);
}

CandidateCall call_candidate(const Candidate& c, const Scene& sc, const std::string& scene_text, const std::string& label) {
  CandidateCall r;
  if (!c.call) {
    r.error = "the candidate has nothing to call";
    return r;
  }
  CandidateOutput out;
  const auto t0 = clock_type::now();
  try {
    out = c.call(CandidateInput{sc, scene_text, safe_label(label)});
  } catch (const FileWriteError&) {
    throw;  // qverify could not write the scene: not the candidate's failure
  } catch (const CandidateFailure& e) {
    r.seconds = e.partial.seconds ? *e.partial.seconds : seconds_since(t0);
    r.error = e.what();
    r.returned = e.partial.document;
    r.log = e.partial.log;
    return r;
  } catch (const std::exception& e) {
    r.seconds = seconds_since(t0);
    r.error = std::string("the call threw: ") + e.what();
    return r;
  }
  r.seconds = out.seconds ? *out.seconds : seconds_since(t0);
  r.returned = out.document;
  r.log = out.log;
  try {
    if (out.results) {
      r.results = *out.results;
      if (r.results.shadows.size() != sc.shadows.size() || r.results.reflections.size() != sc.reflections.size()) {
        r.error = "incomplete output: the typed results do not match the scene's requested items";
        return r;
      }
    } else {
      r.results = candidate_results_text(sc, out.document, c.name + " output", *parse_precision("double"));
    }
  } catch (const InputError& e) {
    r.error = std::string("unreadable output: ") + e.what();
    return r;
  } catch (const std::exception& e) {
    r.error = std::string("unreadable output: ") + e.what();
    return r;
  }
  for (std::size_t k = 0; k < r.results.shadows.size(); ++k)
    if (!r.results.shadows[k].present) {
      const Pair& p = sc.shadows[k];
      r.error = "incomplete output: shadow (" + sc.quadrics[p.quadric].id + ", " + sc.lights[p.other].id +
                "): " + r.results.shadows[k].problem;
      return r;
    }
  for (std::size_t k = 0; k < r.results.reflections.size(); ++k)
    if (!r.results.reflections[k].present) {
      const Pair& p = sc.reflections[k];
      r.error = "incomplete output: reflection (" + sc.quadrics[p.quadric].id + ", " + sc.mirrors[p.other].id +
                "): " + r.results.reflections[k].problem;
      return r;
    }
  r.ok = true;
  return r;
}

}  // namespace qverify
