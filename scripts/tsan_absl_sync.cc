// TSan-only shim, preloaded by scripts/tsan.sh into the daemon and the server tests: tells
// ThreadSanitizer about the synchronisation that Debian's uninstrumented gRPC/abseil performs where
// TSan cannot see it, so that objects handed from one gRPC thread to another are not reported as
// races. Three hand-offs, each a documented guarantee of the library, mirrored by an acquire on the
// receiving thread of what the sending thread released on the same address:
//  1. absl::Mutex / absl::CondVar (gRPC locks its queues, thread pools and calls with them; their
//     futex-based implementation is invisible): acquire after a lock, release before an unlock,
//     CondVar waits release before and acquire after. Reader locks are treated like writer locks
//     (over-synchronises between readers: may hide a race, never invents one).
//  2. A batch's completion happens after grpc_call_start_batch started it (see the comment there):
//     e.g. a Watch stream's OnWriteDone after the StartWrite it completes.
//  3. OnDone/OnCancel of a callback call happen after every decrement of the call's counters (see
//     the comment at ScheduleOnDone).
// Method: libgrpc/libgpr/libgrpc++ and the inline gRPC code compiled into our objects call these
// exported functions through the PLT, so the definitions here (found first) wrap them.
// Not covered: other lock-free hand-offs inside gRPC (gpr_atm, combiners) that do not end in one of
// these calls; LockWhen/Await with a timeout; the callback completion queue of a gRPC built with
// an EventEngine that runs functors directly (Debian's 1.51 uses libgrpc++'s "alternative" queue
// threads, which call grpc_completion_queue_next).
// Symbols are those of Debian's abseil 20220623 (inline namespace debian3) and gRPC 1.51; with
// other builds a wrapper is never called (scripts/tsan.sh warns for abseil) or, for
// ServerCallbackCall's layout, the static_assert below fails.
#include <dlfcn.h>
#include <grpc/grpc.h>
#include <grpcpp/support/server_callback.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

// Weak: the shim is built without -fsanitize=thread and takes these from the TSan runtime of the
// instrumented process (GCC's libtsan.so; clang's runtime linked into the executable). The preload
// is inherited by the uninstrumented processes the tests start (/bin/sh running the solver
// wrapper): there the symbols are null, nothing calls absl or gRPC, and nothing here runs.
extern "C" __attribute__((weak)) void __tsan_acquire(void* address);
extern "C" __attribute__((weak)) void __tsan_release(void* address);

namespace {

void Acquire(void* address) {
  if (__tsan_acquire) __tsan_acquire(address);
}
void Release(void* address) {
  if (__tsan_release) __tsan_release(address);
}

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

// The data of grpc::internal::ServerCallbackCall (grpcpp/support/server_callback.h, gRPC 1.51): the
// two counters whose acq_rel decrements decide when OnCancel and OnDone may run.
struct ServerCallbackCallData {
  void* vtable;
  std::atomic_int on_cancel_conditions_remaining;
  std::atomic_int callbacks_outstanding;
};
static_assert(sizeof(ServerCallbackCallData) == sizeof(grpc::internal::ServerCallbackCall),
              "grpc::internal::ServerCallbackCall changed: update ServerCallbackCallData");

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
  Acquire(mu);
}
void MutexUnlock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex6UnlockEv");
  Release(mu);
  real(mu);
}
void MutexReaderLock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex10ReaderLockEv");
  real(mu);
  Acquire(mu);
}
void MutexReaderUnlock(void* mu) {
  static auto real = Real<void (*)(void*)>("_ZN4absl7debian35Mutex12ReaderUnlockEv");
  Release(mu);
  real(mu);
}
bool MutexTryLock(void* mu) {
  static auto real = Real<bool (*)(void*)>("_ZN4absl7debian35Mutex7TryLockEv");
  const bool locked = real(mu);
  if (locked) Acquire(mu);
  return locked;
}
bool MutexReaderTryLock(void* mu) {
  static auto real = Real<bool (*)(void*)>("_ZN4absl7debian35Mutex13ReaderTryLockEv");
  const bool locked = real(mu);
  if (locked) Acquire(mu);
  return locked;
}
void MutexLockWhen(void* mu, const void* condition) {
  static auto real =
      Real<void (*)(void*, const void*)>("_ZN4absl7debian35Mutex8LockWhenERKNS0_9ConditionE");
  real(mu, condition);
  Acquire(mu);
}
void MutexAwait(void* mu, const void* condition) {
  static auto real =
      Real<void (*)(void*, const void*)>("_ZN4absl7debian35Mutex5AwaitERKNS0_9ConditionE");
  Release(mu);
  real(mu, condition);
  Acquire(mu);
}
void CondVarWait(void* cv, void* mu) {
  static auto real = Real<void (*)(void*, void*)>("_ZN4absl7debian37CondVar4WaitEPNS0_5MutexE");
  Release(mu);
  real(cv, mu);
  Acquire(mu);
}
bool CondVarWaitWithTimeout(void* cv, void* mu, Duration timeout) {
  static auto real = Real<bool (*)(void*, void*, Duration)>(
      "_ZN4absl7debian37CondVar15WaitWithTimeoutEPNS0_5MutexENS0_8DurationE");
  Release(mu);
  const bool timed_out = real(cv, mu, timeout);
  Acquire(mu);
  return timed_out;
}
bool CondVarWaitWithDeadline(void* cv, void* mu, Duration deadline) {
  static auto real = Real<bool (*)(void*, void*, Duration)>(
      "_ZN4absl7debian37CondVar16WaitWithDeadlineEPNS0_5MutexENS0_4TimeE");
  Release(mu);
  const bool timed_out = real(cv, mu, deadline);
  Acquire(mu);
  return timed_out;
}

// gRPC core's completion-queue contract: the event carrying tag T is delivered after the
// grpc_call_start_batch(..., T, ...) that started the batch. The C++ layer (libgrpc++) calls both
// through the PLT: CoreCodegen::grpc_call_start_batch on the thread that starts a write/read/finish
// (our reactor's StartWrite, via gRPC's inline CallOpSet::FillOps), and, on Debian's build, the
// callback API's completions come from libgrpc++'s "alternative" completion-queue threads, which
// call grpc_completion_queue_next and then the tag's functor (CallbackWithSuccessTag::StaticRun,
// inline code in our binary). The release happens before the batch starts (its completion can be
// delivered before grpc_call_start_batch returns); the acquire right after the event is taken.
// The C++ API keeps at most one batch in flight per tag, so no ordering is added beyond the one
// gRPC guarantees. Pluck (the synchronous API) gets the same acquire.
grpc_call_error grpc_call_start_batch(grpc_call* call, const grpc_op* ops, size_t nops, void* tag,
                                      void* reserved) {
  static auto real = Real<grpc_call_error (*)(grpc_call*, const grpc_op*, size_t, void*, void*)>(
      "grpc_call_start_batch");
  Release(tag);
  return real(call, ops, nops, tag, reserved);
}
grpc_event grpc_completion_queue_next(grpc_completion_queue* cq, gpr_timespec deadline,
                                      void* reserved) {
  static auto real = Real<grpc_event (*)(grpc_completion_queue*, gpr_timespec, void*)>(
      "grpc_completion_queue_next");
  const grpc_event event = real(cq, deadline, reserved);
  if (event.type == GRPC_OP_COMPLETE) Acquire(event.tag);
  return event;
}
grpc_event grpc_completion_queue_pluck(grpc_completion_queue* cq, void* tag, gpr_timespec deadline,
                                       void* reserved) {
  static auto real = Real<grpc_event (*)(grpc_completion_queue*, void*, gpr_timespec, void*)>(
      "grpc_completion_queue_pluck");
  const grpc_event event = real(cq, tag, deadline, reserved);
  if (event.type == GRPC_OP_COMPLETE) Acquire(event.tag);
  return event;
}

// A reactor's OnDone runs only after every decrement of callbacks_outstanding_ (each an acq_rel
// fetch_sub, after the callback it ends), OnCancel only after both decrements of
// on_cancel_conditions_remaining_. Our binary's copies of MaybeDone/MaybeCallOnCancel (inline
// header code) decrement with instrumented atomics, but the last decrement is often done by
// libgrpc++'s own copy (the ServerContext's CompletionOp, when the RPC ends or is cancelled),
// which TSan cannot see: the hand-off from the earlier callbacks to the thread that runs
// OnDone/OnCancel and destroys the call object was lost. Both then call these exported functions
// through the PLT; the wrappers perform the acquire of that last acq_rel decrement on the counter's
// address, where TSan recorded the releases of the instrumented decrements. This is the C++ memory
// model's guarantee for the counter, not an extra ordering.
void ScheduleOnDone(void* call, bool inline_ondone)
    DLMFD_SYMBOL("_ZN4grpc8internal18ServerCallbackCall14ScheduleOnDoneEb");
void CallOnCancel(void* call, void* reactor)
    DLMFD_SYMBOL("_ZN4grpc8internal18ServerCallbackCall12CallOnCancelEPNS0_13ServerReactorE");

void ScheduleOnDone(void* call, bool inline_ondone) {
  static auto real =
      Real<void (*)(void*, bool)>("_ZN4grpc8internal18ServerCallbackCall14ScheduleOnDoneEb");
  Acquire(&static_cast<ServerCallbackCallData*>(call)->callbacks_outstanding);
  real(call, inline_ondone);
}
void CallOnCancel(void* call, void* reactor) {
  static auto real = Real<void (*)(void*, void*)>(
      "_ZN4grpc8internal18ServerCallbackCall12CallOnCancelEPNS0_13ServerReactorE");
  Acquire(&static_cast<ServerCallbackCallData*>(call)->on_cancel_conditions_remaining);
  real(call, reactor);
}
}  // extern "C"
