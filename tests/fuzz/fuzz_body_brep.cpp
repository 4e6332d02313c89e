// Fuzz target: a CAD body given as BREP text (what LatticePart, InsideBody and brep_properties read from FreeCAD):
// read_body_brep (OpenCASCADE's reader and checks in a reader process of their own, so a crash of the reader is a
// refusal), then SolidBody (the validation every trimming runs) in this process. Any bytes either give a body or are
// refused with InvalidInput; an accepted body must answer, at points inside and around its bounding box, with a
// fast distance bound that never exceeds the exact distance, and containment consistent with the exact distance
// (a point farther than the tolerance from the boundary is classified the same way from both sides of it).
#include <Standard_Failure.hxx>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "body_checks.hpp"
#include "fuzz_common.hpp"
#include "steady/brep/brep_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace steady;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<SolidBody> body;
  fuzz::refusals_only("brep body", [&] {
    try {
      body.emplace(read_body_brep(text, "body"), "body");
    } catch (const Standard_Failure& e) {
      fuzz::finding(std::string("OpenCASCADE exception escaped the body reader: ") + e.GetMessageString());
    }
  });
  if (body) fuzz::check_body(*body);
  return 0;
}
