// No heap allocation inside the time loop (design.md section 5; issue 6, point 3): after a few
// warm-up steps, Simulation::Step allocates nothing, for the paper's Oldroyd-B pair (5.2) with
// either advection scheme, for a Newtonian scene and for the 102-disk bed with collisions, on 1 and
// 2 threads. Every operator new of the process is counted while a step runs, and, outside sanitizer
// builds (whose runtime owns malloc), every malloc, calloc and realloc too, from any library
// (glibc's allocator is replaced by forwarders to its __libc_ entry points). Observers (file
// output) are not attached, since writing results is not part of the step. Coarse grids (h = 1/24),
// a few seconds in all.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "dlmfd/core/simulation.h"
#include "dlmfd/scene/scene_file.h"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace

namespace {
void CountAllocation() {
  if (g_counting.load(std::memory_order_relaxed))
    g_allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

#if !defined(DLMFD_ASAN_BUILD) && !defined(DLMFD_TSAN_BUILD) && defined(__GLIBC__)
// glibc allows a program to replace malloc, free, calloc and realloc (the other functions of its
// allocator then still work on the same heap); these count and forward.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t size) {
  CountAllocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  CountAllocation();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
  CountAllocation();
  return __libc_realloc(p, size);
}
void free(void* p) { __libc_free(p); }
}
constexpr bool kMallocCounted = true;  // operator new below calls malloc, which counts
#else
constexpr bool kMallocCounted = false;
#endif

// Replacements of the global allocation functions (the other forms forward to these). GCC, seeing
// a delete inlined after a new, takes the free() below for a mismatch; here new is malloc.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  if (!kMallocCounted) CountAllocation();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace dlmfd {
namespace {

// Allocations during `steps` steps after `warmup` steps.
long AllocationsPerSteps(const std::string& scene, std::vector<std::string> overrides, int threads,
                         int warmup = 5, int steps = 5) {
  overrides.push_back("domain.h=0.041666666666666664");        // 1/24
  overrides.push_back("particle_mesh.h=0.05714285714285714");  // 1/17.5, the paper's h_p / h
  overrides.push_back("output.fields_every=0");
  overrides.push_back("output.particles_every=0");
  overrides.push_back("output.checkpoint_every=0");
  std::vector<SceneOverride> parsed;
  for (const auto& o : overrides) parsed.push_back(ParseOverride(o));
  Params params = LoadSceneFile(std::string(DLMFD_SOURCE_DIR) + "/cases/paper/" + scene, parsed);
  params.threads = threads;
  Simulation sim(params);
  for (int k = 0; k < warmup; ++k) sim.Step();
  g_allocations = 0;
  g_counting = true;
  for (int k = 0; k < steps; ++k) sim.Step();
  g_counting = false;
  return g_allocations.load();
}

// The counter itself: it sees operator new and, where counted, malloc (so a zero below means
// something).
TEST(AllocationCounter, SeesNewAndMalloc) {
  g_allocations = 0;
  g_counting = true;
  auto* vector = new std::vector<double>(100);
  void* volatile block = std::malloc(64);
  g_counting = false;
  std::free(block);
  delete vector;
  EXPECT_EQ(g_allocations.load(), kMallocCounted ? 3 : 2);
}

TEST(TimeLoopAllocation, OldroydBPairWave) {
  for (int threads : {1, 2}) {
    EXPECT_EQ(AllocationsPerSteps("5.2_pair_oldroyd_b.toml", {"splitting.advection=wave"}, threads),
              0)
        << threads << " threads";
  }
}

TEST(TimeLoopAllocation, OldroydBPairLeastSquares) {
  EXPECT_EQ(
      AllocationsPerSteps("5.2_pair_oldroyd_b.toml", {"splitting.advection=least_squares"}, 1), 0);
}

TEST(TimeLoopAllocation, NewtonianPair) {
  EXPECT_EQ(AllocationsPerSteps("5.2_pair_newtonian.toml", {"splitting.advection=wave"}, 1), 0);
}

TEST(TimeLoopAllocation, FluidizedBedWithContacts) {
  // 102 disks, touching neighbours in the initial lattice: the collision and the OpenMP
  // particle paths (32 disks or more) run.
  for (int threads : {1, 2}) {
    EXPECT_EQ(
        AllocationsPerSteps("5.4_fluidized_bed_102.toml", {"splitting.advection=wave"}, threads), 0)
        << threads << " threads";
  }
}

}  // namespace
}  // namespace dlmfd
