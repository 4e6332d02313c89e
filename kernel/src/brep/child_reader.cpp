#include "brep/child_reader.hpp"

#include <BinTools.hxx>
#include <Standard_Failure.hxx>
#include <Standard_OutOfMemory.hxx>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <sstream>
#include <stdexcept>

#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/progress.hpp"

namespace steady {
namespace {

// The first byte the child writes says how its work ended; the rest is the result or the message.
constexpr char kDone = 'S', kInvalid = 'I', kLimit = 'R', kOutOfMemory = 'M', kFailed = 'F';

// How often the parent looks at the progress while the child reads: well within the 0.1 s of a progress poll.
constexpr int kPollMilliseconds = 50;

// The reader's time limit when STEADY_READER_SECONDS does not set one: OpenCASCADE reads some 10 MB of STEP or BREP
// a second here, so 120 s plus 30 s per MB leaves a valid file a margin of ten or more, while a reader spinning on
// a corrupt file (docs/reliability.md) is stopped in a headless script where nobody presses Ctrl-C.
constexpr double kBaseSeconds = 120.0, kSecondsPerMegabyte = 30.0;

// A positive finite number of seconds from STEADY_READER_SECONDS, or 0 when it is unset or not such a number.
double seconds_from_environment() {
  const char* text = std::getenv("STEADY_READER_SECONDS");
  if (!text) return 0;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(seconds) && seconds > 0 ? seconds : 0;
}

void write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(3);  // the parent is gone or closed the pipe: nobody to tell
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

// The address space the child may take: what it maps at the fork (shared with the parent, copy on write) plus the
// parent's memory budget, so that a reader allocating without end fails with bad_alloc in the child, within the
// limit the parent itself respects (RLIMIT_AS, the machine's available memory). 0: no limit to set.
rlim_t child_address_space() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  return static_cast<rlim_t>(pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) + memory_budget_bytes());
}

[[noreturn]] void child_main(int fd, pid_t parent, rlim_t address_space, const std::function<std::string()>& work) {
  // The host's handlers (FreeCAD's, Python's faulthandler, a sanitizer's) must not run in a copy of the host: a
  // crash of the reader ends the child by the signal, which is what the parent reports.
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS}) ::signal(s, SIG_DFL);
  ::signal(SIGINT, SIG_IGN);  // Ctrl-C reaches the whole process group; the parent kills the child itself
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) _exit(4);  // the parent died before the line above
  rlimit limit{};
  if (address_space > 0 && ::getrlimit(RLIMIT_AS, &limit) == 0 && address_space < limit.rlim_cur) {
    limit.rlim_cur = address_space;
    ::setrlimit(RLIMIT_AS, &limit);
  }
  char status = kFailed;
  std::string out;
  try {
    out = work();
    status = kDone;
  } catch (const InvalidInput& e) {
    status = kInvalid, out = e.what();
  } catch (const ResourceLimit& e) {
    status = kLimit, out = e.what();
  } catch (const std::bad_alloc&) {
    status = kOutOfMemory;
  } catch (const Standard_OutOfMemory&) {
    status = kOutOfMemory;
  } catch (const Standard_Failure& e) {
    out = e.GetMessageString();
  } catch (const std::exception& e) {
    out = e.what();
  } catch (...) {
    out = "an unknown exception";
  }
  write_all(fd, &status, 1);
  write_all(fd, out.data(), out.size());
  ::close(fd);
  _exit(0);  // not exit(): the host's atexit handlers and static destructors belong to the parent
}

std::string signal_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV, a segmentation fault";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT, an abort";
    case SIGKILL: return "SIGKILL (killed from outside, or by the system for lack of memory)";
    default: return "signal " + std::to_string(sig);
  }
}

// Owns the child until it is reaped: any way out of run_in_child (a cancel included) leaves no child behind.
class Child {
 public:
  Child(pid_t pid, int fd) : pid_(pid), fd_(fd) {}
  ~Child() {
    if (fd_ >= 0) ::close(fd_);
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  // Everything the child writes, until it closes the pipe; polls the current progress meanwhile. False when the
  // time limit passed first (the child is still running; the destructor kills it).
  bool read_all(std::string& bytes, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    char buffer[1 << 16];
    for (;;) {
      poll_progress();
      if (std::chrono::steady_clock::now() > deadline) return false;
      pollfd p{fd_, POLLIN, 0};
      const int ready = ::poll(&p, 1, kPollMilliseconds);
      if (ready < 0 && errno != EINTR) throw std::runtime_error(std::string("reader process: poll: ") + std::strerror(errno));
      if (ready <= 0) continue;
      const ssize_t n = ::read(fd_, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw std::runtime_error(std::string("reader process: read: ") + std::strerror(errno));
      if (n == 0) return true;
      bytes.append(buffer, static_cast<std::size_t>(n));
    }
  }

  // The child's wait status, once it has ended.
  int wait() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return status;
  }

 private:
  pid_t pid_;
  int fd_;
};

}  // namespace

double reader_time_limit_seconds(std::size_t input_bytes) {
  const double fixed = seconds_from_environment();
  return fixed > 0 ? fixed : kBaseSeconds + kSecondsPerMegabyte * static_cast<double>(input_bytes) / 1e6;
}

std::string run_in_child(const std::function<std::string()>& work, const std::string& field, const std::string& input,
                         const std::string& reader, std::size_t input_bytes) {
  const rlim_t address_space = child_address_space();
  const pid_t parent = ::getpid();
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("reader process: pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start a reader process for ") + input + ": " + std::strerror(error));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child_main(fds[1], parent, address_space, work);
  }
  ::close(fds[1]);
  Child child(pid, fds[0]);
  std::string bytes;
  const double seconds = reader_time_limit_seconds(input_bytes);
  if (!child.read_all(bytes, seconds)) {
    std::ostringstream limit;
    limit << seconds;
    fail_input(field, "OpenCASCADE's " + reader + " was still reading " + input + " after " + limit.str() +
                          " s (in a reader process of its own, now stopped): it is corrupt and the reader loops on "
                          "it, or it is larger than the limit allows; for a large valid file, set "
                          "STEADY_READER_SECONDS to more seconds");
  }
  const int status = child.wait();
  if (WIFSIGNALED(status))
    fail_input(field, input + " crashed OpenCASCADE's " + reader + " (" + signal_name(WTERMSIG(status)) +
                          ", in a reader process of its own; nothing else is affected): it is corrupt, or holds what "
                          "the reader does not support");
  if (bytes.empty()) throw std::runtime_error("the reader process for " + input + " ended without an answer (exit status " +
                                              std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  const std::string message = bytes.substr(1);
  switch (bytes[0]) {
    case kDone: return message;
    case kInvalid: throw InvalidInput(message);
    case kLimit: throw ResourceLimit(message);
    case kOutOfMemory:
      throw ResourceLimit(field + ": reading " + input + " with OpenCASCADE's " + reader + " ran out of " +
                          memory_budget_description() + "; give a smaller file, or free memory");
    default: fail_input(field, "OpenCASCADE's " + reader + " failed on " + input + " (" + message + ")");
  }
}

std::string shape_to_binary(const TopoDS_Shape& shape) {
  std::ostringstream os(std::ios::binary);
  BinTools::Write(shape, os);
  return os.str();
}

TopoDS_Shape shape_from_binary(const std::string& bytes) {
  std::istringstream is(bytes, std::ios::binary);
  TopoDS_Shape shape;
  BinTools::Read(shape, is);
  return shape;
}

}  // namespace steady
