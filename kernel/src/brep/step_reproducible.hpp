#pragma once
// The same part gives the same bytes whenever it is written (issue 16, item 5), as the 3MF packages do. Applied to
// the STEP model after OpenCASCADE's translation and before it is written.
#include <StepData_StepModel.hxx>

namespace steady {

// * a fixed time stamp in the header's FILE_NAME (OpenCASCADE writes the time of writing);
// * the assembly's occurrences numbered from 1 in each file (OpenCASCADE counts them over the process);
// * the parts' colours in an order of the file's content: OpenCASCADE adds each part's presentation (an MDGPR and
//   the styles and colours under it) by iterating a map keyed by the shapes' addresses, so with two coloured
//   parts they came in either order from one write to the next, and every entity number after them with them.
void make_reproducible(const Handle(StepData_StepModel)& model);

}  // namespace steady
