#pragma once
/// \file candidate_run.hpp
/// Another implementation audited by `qverify stress` and `qverify audit`
/// (`--candidate-cmd`, README "audit another program").
///
/// A *candidate* is anything that, given a scene, returns a `qverify-eval/1`
/// document: an external program run through `/bin/sh -c` (process_candidate)
/// or any C++ callable (Candidate::call). Each call is timed, its document is
/// read exactly as `verify --candidate` reads one (candidate_results_text),
/// and a call that crashes, hangs, prints garbage or leaves requested items
/// out is a *failed call* with the reason, never an exception that stops a
/// sweep.

#include <qverify/verify/verifier.hpp>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace qverify {

/// What one call of a candidate is given.
struct CandidateInput {
  const Scene& scene;             ///< the scene, parsed (exact numbers)
  const std::string& scene_text;  ///< the qverify-scene/1 document exactly as written to the reproducers
  std::string label;              ///< the case, e.g. "far-from-origin-3": letters, digits, '.', '_', '-' only
};

/// What one call returned: a qverify-eval/1 document as text (read exactly,
/// as with `verify --candidate`) or, from a C++ callable, the results typed.
struct CandidateOutput {
  std::string document;              ///< the qverify-eval/1 text (ignored when `results` is set)
  std::optional<ResultSet> results;  ///< typed results instead of a document
  std::string log;                   ///< anything else it said (a process: its stdout and stderr, bounded)
  std::optional<double> seconds;     ///< the call's own wall time (a process: fork to exit); else the callable is timed
};

/// Thrown by a candidate's call to say that the call failed (the reason in
/// what()); `partial` keeps whatever it produced. Any other std::exception
/// thrown by a C++ callable is a failed call too (its what() the reason).
struct CandidateFailure : std::runtime_error {
  explicit CandidateFailure(const std::string& why, CandidateOutput partial_output = {})
      : std::runtime_error(why), partial(std::move(partial_output)) {}
  CandidateOutput partial;
};

using CandidateFunction = std::function<CandidateOutput(const CandidateInput&)>;

/// A named candidate.
struct Candidate {
  std::string name = "candidate";  ///< see candidate_name_problem
  std::string description;         ///< for the reports (a process: its command line)
  double timeout_seconds = 0;      ///< for the reports: the bound of each call (0: none)
  CandidateFunction call;
};

/// One call of a candidate, measured and read.
struct CandidateCall {
  bool ok = false;       ///< false: the call failed ("candidate-failed")
  std::string error;     ///< why it failed: exit status, signal, time-out, the reader's InputError text, a missing item
  ResultSet results;     ///< the results read (when ok: every requested item present and finite)
  std::string returned;  ///< the document it returned, as returned (empty when none)
  std::string log;       ///< its other output (bounded)
  double seconds = 0;    ///< wall time of the call (a process: from fork to exit, start-up included)
};

/// Calls `c` once on the scene: times it, reads its document
/// (candidate_results_text, file named "NAME output") and requires every
/// requested item present with finite entries. Never throws for a failing
/// candidate: every failure is in the returned call (ok false, error).
CandidateCall call_candidate(const Candidate& c, const Scene& sc, const std::string& scene_text, const std::string& label);

/// Empty when `name` can label a candidate (its runs, its reproducers'
/// file names): 1 to 64 characters out of letters, digits, '.', '_' and '-',
/// not starting with '.' or '-'. Otherwise the problem, in words.
std::string candidate_name_problem(const std::string& name);

/// Empty when `command` can be a candidate command: not blank. Otherwise the
/// problem, in words.
std::string candidate_command_problem(const std::string& command);

/// A warning when `command` names neither {scene} nor {out}, or only one: it is
/// still run (a command that fails on purpose, `false` or `exit 3`, is a
/// legitimate test of the recording of failed calls), but a call that writes
/// no document to {out} is recorded as candidate-failed. Empty otherwise.
std::string candidate_command_warning(const std::string& command);

/// A reproducer of one failing case, as written: the case, why, and its files'
/// paths relative to the report's directory ("failures/...").
struct Reproducer {
  std::string family;  ///< the stress family, or "audit"
  std::size_t k = 0;   ///< the point's index in the family
  double param = 0;    ///< the family's parameter at the point
  std::string reason;
  std::string scene;                    ///< the scene exactly as the candidate was given it
  std::optional<std::string> returned;  ///< what it returned (none when it returned nothing)
  std::string log;                      ///< the reason and the candidate's other output
};

/// Writes a reproducer of one failing case into `failures_dir` (created when
/// missing): BASE.json, the scene exactly as the candidate was given it;
/// BASE.out.json, what it returned (when it returned anything); BASE.log,
/// `reason` and its other output. BASE is NAME-FAMILY-K. Checked writes
/// (FileWriteError).
Reproducer write_reproducer(const std::filesystem::path& failures_dir, const std::string& name,
                            const std::string& family, std::size_t k, double param, const std::string& scene_text,
                            const CandidateCall& call, const std::string& reason);

/// Removes the reproducers NAME-* left in `failures_dir` by an earlier run.
void remove_candidate_reproducers(const std::filesystem::path& failures_dir, const std::string& name);

// ------------------------------------------------------------------ processes

/// How a process ended.
struct ProcessResult {
  int exit_code = -1;      ///< its exit status when it exited (else -1)
  int signal = 0;          ///< the signal that killed it, when not killed for the time-out
  bool timed_out = false;  ///< killed (with its process group) at the time-out
  std::string out, err;    ///< stdout and stderr: the first `capture_limit` bytes of each
  bool out_truncated = false, err_truncated = false;
  double seconds = 0;          ///< wall time
  double timeout_seconds = 0;  ///< the limit it ran under
  /// "exit status 1", "killed by signal 11 (Segmentation fault)", "timed out after 1 s (process group killed)" or "".
  std::string failure() const;
};

/// Runs `/bin/sh -c command` in a process group of its own (stdin from
/// /dev/null; stdout and stderr captured up to `capture_limit` bytes each,
/// the rest read and dropped, so a chatty program never blocks). After
/// `timeout_seconds` the whole group is killed (SIGKILL); when the shell
/// exits, whatever is left of its group (a background child) is killed too.
/// Throws std::system_error when no process can be started.
ProcessResult run_shell(const std::string& command, double timeout_seconds, std::size_t capture_limit = 64 * 1024);

/// `s` as one shell word: unchanged when made only of characters the shell
/// leaves alone ([A-Za-z0-9_./:@%+=,-]), else single-quoted ('\'' for a quote).
/// Unquoted paths also work inside the user's own quotes ('{scene}', "{out}").
std::string shell_word(const std::string& s);

/// `command` with every `{scene}` and `{out}` replaced by shell_word of the paths.
std::string substitute_command(const std::string& command, const std::string& scene_path, const std::string& out_path);

/// A candidate that runs `command` for every call: the scene is written
/// (write_file) to LABEL.json in a private temporary directory, `command`
/// is run with {scene} and {out} (LABEL.out.json there, removed before the
/// call) substituted; the call fails on a non-zero exit, a signal, the
/// time-out or no {out} file. The directory is created here (FileWriteError
/// when it cannot be) and removed when the last copy of the candidate is gone.
Candidate process_candidate(const std::string& name, const std::string& command, double timeout_seconds);

}  // namespace qverify
