#pragma once
/// \file input_error.hpp
/// The one error of every input door (scene files, candidate documents, the
/// JSON tree under both, the C++ check API): which file, where in it (a JSON
/// path such as `quadrics[0].radius`, or an argument such as `A[1][2]`), and
/// what is wrong. Nothing is computed from an input that raised it.

#include <stdexcept>
#include <string>
#include <utility>

namespace qverify {

/// A rejected scene (or candidate document): file, JSON path, problem.
struct InputError : std::runtime_error {
  std::string file, path, problem;
  InputError(std::string f, std::string p, std::string what)
      : std::runtime_error(f + ": " + (p.empty() ? std::string("(document)") : p) + ": " + what),
        file(std::move(f)), path(std::move(p)), problem(std::move(what)) {}
};

}  // namespace qverify
