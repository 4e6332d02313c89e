#pragma once
// Untrusted BREP and STEP input read in a forked child process. OpenCASCADE's readers crash (SIGSEGV) on some
// corrupted files before the kernel gets control, and poll no progress, so they can neither be guarded nor
// interrupted in-process (docs/reliability.md). The child runs the reader and the checks; the parent gets back
// only what OpenCASCADE itself wrote (BinTools binary), so a crash, a hang or a runaway allocation stays in the
// child.
#include <TopoDS_Shape.hxx>

#include <cstddef>
#include <functional>
#include <string>

namespace steady {

// Runs `work` in a child made by fork() (not exec: the child has the libraries, the input is in its memory) and
// returns the bytes it returned. In the child: the crash signals have their default action (no handler of the
// host, FreeCAD's or a sanitizer's, runs there), SIGINT is ignored (the parent decides), the address space is
// limited to what the parent may still use, and it ends with _exit (no atexit handler of the host runs).
// A refusal thrown in the child (InvalidInput, ResourceLimit) is thrown again here with its message. A child
// killed by a signal gives InvalidInput naming `field`: `input` crashed OpenCASCADE's `reader`. While it waits,
// the current progress is polled every 50 ms: on a cancel the child is killed (SIGKILL) and Cancelled thrown.
// A child still running after reader_time_limit_seconds(input_bytes) is killed, and InvalidInput names `field`.
// `work` must not use TBB (the parent's worker threads do not exist in the child); OpenCASCADE's readers and
// sequential checks do not.
std::string run_in_child(const std::function<std::string()>& work, const std::string& field, const std::string& input,
                         const std::string& reader, std::size_t input_bytes);

// How long a reader process may run on an input of `input_bytes`: STEADY_READER_SECONDS when set to a positive
// number, else 120 s plus 30 s per MB.
double reader_time_limit_seconds(std::size_t input_bytes);

// OpenCASCADE's binary B-rep (BinTools): exact, and written by OpenCASCADE, so safe to read back in the parent.
std::string shape_to_binary(const TopoDS_Shape& shape);
TopoDS_Shape shape_from_binary(const std::string& bytes);

}  // namespace steady
