#include "steady/core/numeric_range.hpp"

#include <cmath>
#include <sstream>

#include "steady/core/errors.hpp"

namespace steady {

void require_within(double value, double limit, const std::string& field) {
  require_finite(value, field);
  if (std::abs(value) > limit) {
    std::ostringstream os;
    os << "is " << value << ", beyond the supported range of +-" << limit << " (docs/design.md, numerical range)";
    fail_input(field, os.str());
  }
}

void require_within(const Vec3& value, double limit, const std::string& field) {
  for (int c = 0; c < 3; ++c) require_within(value[c], limit, field);
}

}  // namespace steady
