#pragma once
/// \file Exception types. Library code throws these; only the CLI maps them to exit codes.
#include <stdexcept>
#include <string>

namespace breastfit {

/// Bad input or a violated precondition (arrives in Python as ValueError).
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A file could not be read or written. The message names the path and the problem.
class IoError : public std::runtime_error {
 public:
  IoError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem), path_(path), problem_(problem) {}
  const std::string& path() const { return path_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string path_;
  std::string problem_;
};

}  // namespace breastfit
