// DLMFD_AVX2_CLONES: a hot loop compiled for AVX2 and for the baseline, the one this CPU runs
// chosen at load time (GCC function multi-versioning: an ifunc resolver per function).
// Not under ThreadSanitizer: the resolvers are instrumented too, and ld.so runs them while it
// relocates the program, before the sanitizer's runtime exists, so a TSan build died at load
// (SIGSEGV in OnePanelRow's resolver; issue 38, scripts/tsan.sh). A TSan build runs the baseline.
#pragma once

// DLMFD_TSAN_BUILD: defined by cmake/Sanitizers.cmake (which undefines __SANITIZE_THREAD__).
#if defined(DLMFD_TSAN_BUILD) || defined(__SANITIZE_THREAD__)
#define DLMFD_NO_CLONES 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define DLMFD_NO_CLONES 1
#endif
#endif

#if defined(DLMFD_NO_CLONES)
#define DLMFD_AVX2_CLONES
#else
#define DLMFD_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#endif
