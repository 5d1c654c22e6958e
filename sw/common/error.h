#pragma once

#include <stdexcept>
#include <string>

namespace lancer {

// Bad input from the user: a file, a ray, an option. The CLI prints what() on one
// line and exits non-zero; messages name the file and line (or the ray index).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lancer

namespace lancer {

// The run completed but its check failed (a model disagreed with the golden
// model). The CLI has already printed the report; it exits with status 4.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lancer
