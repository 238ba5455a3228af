// TSan-only shim, preloaded by scripts/tsan.sh into the daemon and the server tests: makes the
// absl::Mutex / absl::CondVar synchronisation of Debian's uninstrumented gRPC visible to
// ThreadSanitizer. gRPC (libgrpc, libgpr, libgrpc++) locks its queues, thread pools and calls
// with absl::Mutex, whose futex-based implementation TSan cannot see, so every hand-off of an
// object from one gRPC thread to another (a reactor's OnDone after its last write, a request
// freed after the handler returned) looked like a race.
// Method: calls from those libraries to absl's exported functions go through the PLT, so the
// definitions here (found first) wrap them. After an acquisition the shim calls
// __tsan_acquire(mutex), before a release __tsan_release(mutex); CondVar waits release before
// and acquire after. Reader locks are treated like writer locks (over-synchronises between
// readers: may hide a race, never invents one).
// Not covered: gRPC's lock-free hand-offs (gpr_atm, combiners); LockWhen/Await with a timeout.
// Symbols are those of Debian's abseil 20220623 (inline namespace debian3); with another abseil
// build the wrappers are never called (scripts/tsan.sh warns).
#include <dlfcn.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);

namespace {

struct Duration {  // absl::Duration / absl::Time: passed by value in two integer registers
  int64_t hi;
  uint32_t lo;
};

template <class Function>
Function Real(const char* symbol) {
  void* address = dlsym(RTLD_NEXT, symbol);
  if (!address) {
    std::fprintf(stderr, "tsan_absl_sync: %s not found\n", symbol);
    std::abort();
  }
  return reinterpret_cast<Function>(address);
}

}  // namespace

#define DLMFD_SYMBOL(name) __asm__(name)

extern "C" {
void MutexLock(void* mu) DLMFD_SYMBOL("_ZN4absl7debian35Mutex4LockEv");
void MutexUnlock(void* mu) DLMFD_SYMBOL("_ZN4absl7debian35Mutex6UnlockEv");
void MutexReaderLock(void* mu) DLMFD_SYMBOL("_ZN4absl7debian35Mutex10ReaderLockEv");
void MutexReaderUnlock(void* mu) DLMFD_SYMBOL("_ZN4absl7debian35Mutex12ReaderUnlockEv");
bool MutexTryLock(void* mu) DLMFD_SYMBOL("_ZN4absl7debian35Mutex7TryLockEv");
bool MutexReaderTryLock(void* mu) DLMFD_SYMBOL("_ZN4absl7debian35Mutex13ReaderTryLockEv");
void MutexLockWhen(void* mu, const void* condition)
    DLMFD_SYMBOL("_ZN4absl7debian35Mutex8LockWhenERKNS0_9ConditionE");
void MutexAwait(void* mu, const void* condition)
    DLMFD_SYMBOL("_ZN4absl7debian35Mutex5AwaitERKNS0_9ConditionE");
void CondVarWait(void* cv, void* mu) DLMFD_SYMBOL("_ZN4absl7debian37CondVar4WaitEPNS0_5MutexE");
bool CondVarWaitWithTimeout(void* cv, void* mu, Duration timeout)
    DLMFD_SYMBOL("_ZN4absl7debian37CondVar15WaitWithTimeoutEPNS0_5MutexENS0_8DurationE");
bool CondVarWaitWithDeadline(void* cv, void* mu, Duration deadline)
    DLMFD_SYMBOL("_ZN4absl7debian37CondVar16WaitWithDeadlineEPNS0_5MutexENS0_4TimeE");

void MutexLock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex4LockEv");
  real(mu);
  __tsan_acquire(mu);
}
void MutexUnlock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex6UnlockEv");
  __tsan_release(mu);
  real(mu);
}
void MutexReaderLock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex10ReaderLockEv");
  real(mu);
  __tsan_acquire(mu);
}
void MutexReaderUnlock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex12ReaderUnlockEv");
  __tsan_release(mu);
  real(mu);
}
bool MutexTryLock(void* mu) {
  static auto real = Real<bool (*)(void*)>("_ZN4absl7debian35Mutex7TryLockEv");
  const bool locked = real(mu);
  if (locked) __tsan_acquire(mu);
  return locked;
}
bool MutexReaderTryLock(void* mu) {
  static auto real = Real<bool (*)(void*)>("_ZN4absl7debian35Mutex13ReaderTryLockEv");
  const bool locked = real(mu);
  if (locked) __tsan_acquire(mu);
  return locked;
}
void MutexLockWhen(void* mu, const void* condition) {
  static auto real =
      Real<void (*)(void*, const void*)>("_ZN4absl7debian35Mutex8LockWhenERKNS0_9ConditionE");
  real(mu, condition);
  __tsan_acquire(mu);
}
void MutexAwait(void* mu, const void* condition) {
  static auto real =
      Real<void (*)(void*, const void*)>("_ZN4absl7debian35Mutex5AwaitERKNS0_9ConditionE");
  __tsan_release(mu);
  real(mu, condition);
  __tsan_acquire(mu);
}
void CondVarWait(void* cv, void* mu) {
  static auto real = Real<void (*)(void*, void*)>("_ZN4absl7debian37CondVar4WaitEPNS0_5MutexE");
  __tsan_release(mu);
  real(cv, mu);
  __tsan_acquire(mu);
}
bool CondVarWaitWithTimeout(void* cv, void* mu, Duration timeout) {
  static auto real = Real<bool (*)(void*, void*, Duration)>(
      "_ZN4absl7debian37CondVar15WaitWithTimeoutEPNS0_5MutexENS0_8DurationE");
  __tsan_release(mu);
  const bool timed_out = real(cv, mu, timeout);
  __tsan_acquire(mu);
  return timed_out;
}
bool CondVarWaitWithDeadline(void* cv, void* mu, Duration deadline) {
  static auto real = Real<bool (*)(void*, void*, Duration)>(
      "_ZN4absl7debian37CondVar16WaitWithDeadlineEPNS0_5MutexENS0_4TimeE");
  __tsan_release(mu);
  const bool timed_out = real(cv, mu, deadline);
  __tsan_acquire(mu);
  return timed_out;
}
}  // extern "C"
