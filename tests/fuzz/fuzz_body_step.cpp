// Fuzz target: a STEP file read back (read_step_parts, what steadylattice.read_step calls: the reader runs in a
// process of its own), and each part it gives taken as a body (SolidBody) and checked as in fuzz_body_brep. Any bytes either read or are refused with
// InvalidInput.
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Standard_Failure.hxx>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "body_checks.hpp"
#include "fuzz_common.hpp"
#include "steady/brep/step_assembly.hpp"

// OpenCASCADE's reader prints its transfer statistics for every file: silenced, they cost most of the run.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace steady;
  // The reader takes a path: one file per fuzzing process, rewritten for each input.
  static const std::string path = "/tmp/steady_fuzz_step_" + std::to_string(getpid()) + ".step";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) fuzz::finding("cannot write " + path);
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  std::vector<StepPart> parts;
  fuzz::refusals_only("read_step_parts", [&] {
    try {
      parts = read_step_parts(path);
    } catch (const Standard_Failure& e) {
      fuzz::finding(std::string("OpenCASCADE exception escaped the STEP reader: ") + e.GetMessageString());
    }
  });
  std::remove(path.c_str());
  for (const StepPart& part : parts) {
    std::optional<SolidBody> body;
    fuzz::refusals_only("step part as a body", [&] {
      try {
        body.emplace(part.shape, "body");
      } catch (const Standard_Failure& e) {
        fuzz::finding(std::string("OpenCASCADE exception escaped SolidBody: ") + e.GetMessageString());
      }
    });
    if (body) fuzz::check_body(*body);
  }
  return 0;
}
