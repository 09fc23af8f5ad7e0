// <qmotion/kernel/error.hpp>: the one exception type, its exit codes, and how messages print
// a figure.
#pragma once
#include <sstream>
#include <stdexcept>
#include <string>

namespace qmotion {

/// What kind of failure an Error reports; the CLI maps it to an exit status (docs/formats.md).
enum class Errc {
  invalid_input,      ///< bad user data or usage: exit 2
  numerical_failure,  ///< singular system, no convergence, pole on the interval: exit 3
  export_failed,      ///< a writer or reader of a CAD library failed: exit 1
  internal            ///< a bug: exit 1
};

/// The one exception type qmotion throws for user-facing failures.
class Error : public std::runtime_error {
 public:
  Error(Errc code, const std::string& message) : std::runtime_error(message), code_(code) {}
  Errc code() const { return code_; }
  /// Exit status of docs/formats.md for this error.
  int exit_code() const {
    switch (code_) {
      case Errc::invalid_input:
        return 2;
      case Errc::numerical_failure:
        return 3;
      default:
        return 1;
    }
  }

 private:
  Errc code_;
};

namespace kernel::detail {

/// x with three significant digits, as messages print a figure.
inline std::string format_double(double x) {
  std::ostringstream os;
  os.precision(3);
  os << x;
  return os.str();
}

}  // namespace kernel::detail

/// Precondition check for caller bugs (STYLE §5); active unless NDEBUG.
#ifdef NDEBUG
#define QMOTION_EXPECTS(cond, msg) ((void)0)
#else
#define QMOTION_EXPECTS(cond, msg) \
  ((cond) ? (void)0 : throw std::logic_error(std::string("precondition failed: ") + (msg)))
#endif

}  // namespace qmotion
