// LD_PRELOAD shim for Debian 12's user-mode Linux (6.1) on hosts whose XSAVE area is larger than
// the one UML was built for (AMX: 11,008 bytes against UML's 2,696). UML restores a process's
// floating-point state with PTRACE_SETREGSET(NT_X86_XSTATE) and its own buffer size, and the host
// kernel accepts that request only for a buffer of exactly its own XSAVE size (EFAULT otherwise):
// UML's init dies with "ptrace set fp regs failed, errno = 14". Here the short buffer is laid over
// the tracee's current full state (read first; partial reads are allowed), and the full buffer
// is written. The components past UML's buffer are AMX tiles, which nothing inside UML can use
// (a process must ask the host for them), so they stay what they are. Other requests, and hosts
// whose XSAVE area fits UML's buffer, pass through unchanged. run_in_uml.sh preloads it.

#include <dlfcn.h>
#include <elf.h>
#include <sys/ptrace.h>
#include <sys/types.h>
#include <sys/uio.h>

#include <cstdarg>
#include <cstring>

namespace {

using PtraceFunction = long (*)(enum __ptrace_request, ...);

PtraceFunction RealPtrace() {
  static const auto real = reinterpret_cast<PtraceFunction>(dlsym(RTLD_NEXT, "ptrace"));
  return real;
}

}  // namespace

extern "C" long ptrace(enum __ptrace_request request, ...) noexcept {
  va_list args;
  va_start(args, request);
  const pid_t pid = va_arg(args, pid_t);
  void* const address = va_arg(args, void*);
  void* const data = va_arg(args, void*);
  va_end(args);
  const PtraceFunction real = RealPtrace();
  const auto* iov = static_cast<const struct iovec*>(data);
  if (request == PTRACE_SETREGSET && reinterpret_cast<long>(address) == NT_X86_XSTATE && iov != nullptr) {
    // One UML process restores registers at a time (UML is single-threaded here): a static buffer.
    alignas(64) static unsigned char full_state[1 << 16];
    struct iovec full = {full_state, sizeof full_state};
    if (real(PTRACE_GETREGSET, pid, address, &full) == 0 && full.iov_len > iov->iov_len) {
      std::memcpy(full_state, iov->iov_base, iov->iov_len);
      return real(PTRACE_SETREGSET, pid, address, &full);
    }
  }
  return real(request, pid, address, data);
}
