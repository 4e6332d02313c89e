#pragma once
// Internal to the layouts: the limits every layout enforces, and their shared refusals.
#include <cstdint>
#include <string>

#include "steady/lattice/layout.hpp"

namespace steady {

namespace detail {
// Group scales are exp(ln s); beyond this the doubles of a ball's radius over- or underflow (exp(700) ~ 1e304),
// so such a layout is refused.
constexpr double kMaxGroupLogScale = 690.0;
// Steps' integer powers are cached by a layout up to this many per direction (104 bytes each): rows longer
// than this evaluate their powers from the generator (~0.1 us each).
constexpr std::int64_t kMaxCachedLayoutPowers = std::int64_t(1) << 16;
}  // namespace detail

// InvalidInput naming `field` when a group's |ln scale| reaches kMaxGroupLogScale.
void require_representable_scales(double max_abs_log_scale, const std::string& field);
[[noreturn]] void fail_group_outside(const Counts& counts, std::int64_t i, std::int64_t j, std::int64_t k);

}  // namespace steady
