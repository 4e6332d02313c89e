#pragma once
// What every fuzz target shares: the kernel's refusals (InvalidInput, ResourceLimit) are the right answer to a bad
// input; any other exception escaping the kernel is a finding (an internal error reaching the user), and so is a
// fast path that disagrees with brute force. Findings abort, so libFuzzer saves the input.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "steady/core/errors.hpp"

namespace steady::fuzz {

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

// Runs `body`; a refusal ends the input quietly, anything else escaping is a finding.
template <class F>
void refusals_only(const char* stage, F&& body) {
  try {
    body();
  } catch (const InvalidInput&) {
  } catch (const ResourceLimit&) {
  } catch (const std::exception& e) {
    finding(std::string(stage) + ": unexpected exception escaped the kernel: " + e.what());
  } catch (...) {
    finding(std::string(stage) + ": an exception of unknown type escaped the kernel");
  }
}

// Runs `body` on an input the kernel accepted: only the memory budget may still refuse.
template <class F>
void budget_refusals_only(const char* stage, F&& body) {
  try {
    body();
  } catch (const ResourceLimit&) {
  } catch (const std::exception& e) {
    finding(std::string(stage) + ": refused or failed after the input was accepted: " + e.what());
  } catch (...) {
    finding(std::string(stage) + ": an exception of unknown type escaped the kernel");
  }
}

}  // namespace steady::fuzz
