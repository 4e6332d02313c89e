#pragma once
// Mathematical constants of the kernel, written once.
namespace steady {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kHalfPi = 0.5 * kPi;

}  // namespace steady
