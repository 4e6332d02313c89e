#include "steady/core/errors.hpp"

#include <cmath>
#include <sstream>

namespace steady {

void fail_input(const std::string& field, const std::string& what) { throw InvalidInput(field + ": " + what); }

void require_finite(double value, const std::string& field) {
  if (!std::isfinite(value)) {
    std::ostringstream os;
    os << "must be a finite number (got " << value << ")";
    fail_input(field, os.str());
  }
}

void require_positive(double value, const std::string& field) {
  require_finite(value, field);
  if (!(value > 0.0)) {
    std::ostringstream os;
    os << "must be > 0 (got " << value << ")";
    fail_input(field, os.str());
  }
}

}  // namespace steady
