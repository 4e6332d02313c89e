#pragma once
#include <stdexcept>
#include <string>

namespace steady {

// Bad input: a parameter outside its domain. The message always names the parameter (for example
// "nodes[2].radius: must be > 0 (got -1)"). Python sees it as ValueError.
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A request that would exceed the memory budget (for example listing 10^10 balls).
// Python sees it as MemoryError; nothing has been allocated when it is thrown.
class ResourceLimit : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Helpers that build messages naming a field.
[[noreturn]] void fail_input(const std::string& field, const std::string& what);
void require_finite(double value, const std::string& field);
void require_positive(double value, const std::string& field);

}  // namespace steady
