// qverify.stress: the stress sweeps of `qverify stress` with a Python function
// as the candidate (verify/item_candidate.hpp), and qverify.stress_families.
//
// The sweep runs with the GIL released; each call of the user's function
// takes it back (gil_scoped_acquire) for the call and the conversions of its
// arguments and its result, and nothing else touches Python objects without
// it. An exception of the function (an Exception) is that point's failed call;
// KeyboardInterrupt, SystemExit and other BaseExceptions stop the sweep and
// are raised again from qverify.stress.
#include "convert.hpp"
#include "options.hpp"

#include <qverify/report/report.hpp>
#include <qverify/report/stress.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/studies/stress.hpp>
#include <qverify/verify/item_candidate.hpp>

#include <pybind11/stl.h>

#include <algorithm>
#include <memory>

namespace py = pybind11;
using namespace qverify;
using namespace qverify::py_glue;

namespace qverify::py_glue {
void bind_stress(py::module_& m);
}

namespace {

/// Thrown through run_stress when the Python function raised a BaseException
/// that is not an Exception (KeyboardInterrupt, SystemExit): not a
/// std::exception, so call_candidate does not take it for a failed call. The
/// Python error stays set on this thread (PyErr_Restore) until qverify.stress
/// raises it again.
struct PythonAbort {};

/// A Python object that may be copied and destroyed without the GIL (the
/// std::function holding it is copied by the C++ side): the last copy drops
/// the reference with the GIL held.
using SharedPy = std::shared_ptr<py::object>;
SharedPy shared_py(py::object o) {
  return SharedPy(new py::object(std::move(o)), [](py::object* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
}

template <int R, int C> py::array_t<double> to_numpy(const Eigen::Matrix<double, R, C>& m) {
  if constexpr (C == 1) {
    py::array_t<double> out(R);
    auto v = out.mutable_unchecked<1>();
    for (int i = 0; i < R; ++i) v(i) = m(i);
    return out;
  } else {
    py::array_t<double> out({R, C});
    auto v = out.mutable_unchecked<2>();
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j) v(i, j) = m(i, j);
    return out;
  }
}

/// A returned matrix or vector, each entry taken exactly and rounded to the nearest double.
template <int R, int C> Eigen::Matrix<double, R, C> returned(py::handle h, const std::string& name) {
  Kinds kinds;
  Eigen::Matrix<Rational, R, C> q;
  if constexpr (C == 1) q = to_vector<R>(h, name, kinds);
  else q = to_matrix(h, name, kinds);
  Eigen::Matrix<double, R, C> out;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) out(i, j) = nearest_double(q(i, j));
  return out;
}

/// The keys of a returned dict, checked: every key one of `allowed`.
void check_keys(const py::dict& d, const std::vector<std::string>& allowed) {
  for (auto kv : d) {
    const std::string key = py::str(kv.first).cast<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw CandidateFailure("the function returned a dict with the unknown key \"" + key + "\" (expected " + list + ")");
    }
  }
}

/// "ValueError: message" of the Python exception being handled, and its traceback (for the reproducer's log).
std::pair<std::string, std::string> describe(py::error_already_set& e) {
  std::string what = py::str(e.type().attr("__name__")).cast<std::string>();
  const std::string msg = py::str(e.value()).cast<std::string>();
  if (!msg.empty()) what += ": " + msg;
  std::string tb;
  try {
    const py::list lines = py::module_::import("traceback").attr("format_exception")(e.type(), e.value(), e.trace());
    for (py::handle l : lines) tb += l.cast<std::string>();
  } catch (py::error_already_set&) {
    tb = what + "\n";
  }
  return {what, tb};
}

/// Calls fn(args...) with the GIL and converts its result with `convert` (also with the GIL).
/// A Python Exception (in the call or the conversion) becomes CandidateFailure with its
/// message; a BaseException that is not an Exception becomes PythonAbort.
template <class Result, class Args, class Convert>
Result call_python(const SharedPy& fn, Args&& make_args, Convert&& convert) {
  std::string error, log;
  {
    py::gil_scoped_acquire gil;
    try {
      const py::tuple args = make_args();
      return convert((*fn)(*args));
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_Exception)) {
        e.restore();
        throw PythonAbort{};
      }
      std::tie(error, log) = describe(e);
    } catch (const InputError& e) {  // the result could not be read
      error = "the function returned " + (e.path.empty() ? e.problem : e.path + ": " + e.problem);
    }
  }
  CandidateOutput partial;
  partial.log = log;
  throw CandidateFailure(error, partial);
}

ShadowItemFunction shadow_function(const py::object& fn_in) {
  if (fn_in.is_none()) return nullptr;
  SharedPy fn = shared_py(fn_in);
  return [fn](const Mat4<double>& A, const Vec4<double>& L) {
    return call_python<ShadowCandidate<double>>(
        fn, [&] { return py::make_tuple(to_numpy(A), to_numpy(L)); },
        [](const py::object& res) {
          ShadowCandidate<double> c;
          if (py::isinstance<py::dict>(res)) {
            const py::dict d = res.cast<py::dict>();
            check_keys(d, {"P", "polar_plane", "R"});
            if (d.contains("P") && !d["P"].is_none()) c.P = returned<4, 4>(d["P"], "P");
            if (d.contains("polar_plane") && !d["polar_plane"].is_none())
              c.polar_plane = returned<4, 1>(d["polar_plane"], "polar_plane");
            if (d.contains("R") && !d["R"].is_none()) c.R = returned<4, 4>(d["R"], "R");
          } else if (!res.is_none()) {
            c.P = returned<4, 4>(res, "P");
          }
          return c;
        });
  };
}

ReflectionItemFunction reflection_function(const py::object& fn_in) {
  if (fn_in.is_none()) return nullptr;
  SharedPy fn = shared_py(fn_in);
  return [fn](const Mat4<double>& A, const Vec4<double>& plane) {
    return call_python<ReflectionCandidate<double>>(
        fn, [&] { return py::make_tuple(to_numpy(A), to_numpy(plane)); },
        [](const py::object& res) {
          ReflectionCandidate<double> c;
          if (py::isinstance<py::dict>(res)) {
            const py::dict d = res.cast<py::dict>();
            check_keys(d, {"B", "M"});
            if (d.contains("B") && !d["B"].is_none()) c.B = returned<4, 4>(d["B"], "B");
            if (d.contains("M") && !d["M"].is_none()) c.M = returned<4, 4>(d["M"], "M");
          } else if (!res.is_none()) {
            c.B = returned<4, 4>(res, "B");
          }
          return c;
        });
  };
}

const StressFamily* find_family(const std::string& name) {
  for (const StressFamily& f : stress_families())
    if (f.name == name) return &f;
  return nullptr;
}

std::string family_names() {
  std::string s;
  for (const StressFamily& f : stress_families()) s += (s.empty() ? "" : ", ") + f.name;
  return s;
}

/// qverify._stress: the checked arguments of qverify.stress (the wrapper in __init__.py
/// has resolved fn into shadow / reflection and made `out` a path).
py::object stress_py(const py::object& shadow_in, const py::object& reflection_in, const py::object& families_in,
                     const std::string& out_dir, bool write_report, const std::string& name, const py::object& samples_in,
                     const py::object& accuracy_in) {
  if (shadow_in.is_none() && reflection_in.is_none())
    bad_argument("fn", "no function to audit: give fn, shadow= or reflection=");
  StressOptions opt;
  opt.out_dir = out_dir;
  if (!samples_in.is_none()) opt.samples = samples_arg(samples_in);
  if (!accuracy_in.is_none()) opt.accuracy = accuracy_arg(accuracy_in);
  if (families_in.is_none()) {
    for (const StressFamily& f : stress_families())
      if (f.reflection ? !reflection_in.is_none() : !shadow_in.is_none()) opt.families.push_back(f.name);
  } else {
    const auto names = families_in.cast<std::vector<std::string>>();
    if (names.empty()) bad_argument("families", "no family given (None runs every family of the functions given)");
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string path = "families[" + std::to_string(i) + "]";
      const StressFamily* f = find_family(names[i]);
      if (!f) bad_argument(path, "unknown family \"" + names[i] + "\" (the families: " + family_names() + ")");
      if (f->reflection && reflection_in.is_none())
        bad_argument(path, "\"" + names[i] + "\" is a reflection family and no reflection function was given");
      if (!f->reflection && shadow_in.is_none())
        bad_argument(path, "\"" + names[i] + "\" is a shadow family and no shadow function was given");
      if (std::find(opt.families.begin(), opt.families.end(), names[i]) == opt.families.end())
        opt.families.push_back(names[i]);
    }
  }
  // the report's files checked before the sweeps, as the CLI does: an unwritable one fails at once
  if (write_report) check_report_outputs(out_dir, stress_report_files(out_dir, opt.families), true);
  opt.candidate = item_candidate(name, shadow_function(shadow_in), reflection_function(reflection_in));
  StressReport report;
  bool aborted = false;
  {
    py::gil_scoped_release nogil;
    try {
      report = run_stress(opt);
      if (write_report) write_stress_report(out_dir, report);
    } catch (const PythonAbort&) {
      aborted = true;
    }
    opt.candidate.reset();  // drops the functions (their deleters take the GIL)
  }
  if (aborted) throw py::error_already_set();  // the KeyboardInterrupt (...) the function raised
  return json_to_python(stress_json(report));
}

py::list families_py() {
  py::list out;
  for (const StressFamily& f : stress_families()) {
    py::dict d;
    d["name"] = f.name;
    d["kind"] = f.reflection ? "reflection" : "shadow";
    d["parameter"] = f.parameter;
    d["description"] = f.description;
    d["values"] = f.values;
    out.append(d);
  }
  return out;
}

}  // namespace

namespace qverify::py_glue {

void bind_stress(py::module_& m) {
  // A file or directory that cannot be written: OSError(errno, reason, path), as Python's own file functions
  // raise it (errno, strerror and filename set; str() "[Errno 21] Is a directory: 'PATH'"), its subclass
  // chosen by errno (IsADirectoryError, FileNotFoundError, PermissionError ...).
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const FileWriteError& e) {
      // the path as os.fsdecode gives it: a name that is not UTF-8 still reaches Python
      const py::object path = py::reinterpret_steal<py::object>(PyUnicode_DecodeFSDefault(e.path.c_str()));
      if (!path) throw py::error_already_set();
      py::object err = py::reinterpret_borrow<py::object>(PyExc_OSError)(e.code, e.reason, path);
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(err.ptr())), err.ptr());
    }
  });
  m.def("_stress", &stress_py, py::arg("shadow"), py::arg("reflection"), py::arg("families"), py::arg("out"),
        py::arg("write_report"), py::arg("name"), py::arg("samples"), py::arg("accuracy"),
        "The stress sweeps with Python functions as the candidate; see qverify.stress.");
  m.def("stress_families", &families_py, R"(The families of qverify.stress (and `qverify stress --list`).

Returns:
    list of dict: name, kind ("shadow": the function is called as fn(A, L)
    and returns P; "reflection": fn(A, plane) returns B), parameter (the
    swept parameter's name), description, values (the parameter's values,
    one stress point each).
)");
}

}  // namespace qverify::py_glue
