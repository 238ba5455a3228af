# ASan+UBSan (DLMFD_SANITIZE), TSan (DLMFD_TSAN), and libFuzzer's targets (DLMFD_FUZZ, clang, on
# top of DLMFD_SANITIZE) for every target of the build.
#
# DLMFD_FUZZ adds the fuzzer's coverage (-fsanitize=fuzzer-no-link) to the libraries the fuzz
# targets reach (tests/fuzz/CMakeLists.txt), not to the engine: so one clang tree with
# DLMFD_SANITIZE and DLMFD_FUZZ serves CI's sanitizer tests and its fuzz targets, and the daemon the
# sanitizer tests run is the code the fuzzers cover (ASan's runtime answers the coverage hooks when
# no fuzzer is linked). docs/evidence/service.md, "One clang tree for the sanitizers and the fuzzers".
if(DLMFD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "DLMFD_FUZZ needs clang: -DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz.sh)")
  endif()
  if(NOT DLMFD_SANITIZE OR DLMFD_TSAN)
    message(FATAL_ERROR "DLMFD_FUZZ runs under ASan+UBSan: set DLMFD_SANITIZE, leave DLMFD_TSAN off")
  endif()
endif()
if(DLMFD_SANITIZE AND DLMFD_TSAN)
  message(FATAL_ERROR "DLMFD_SANITIZE and DLMFD_TSAN cannot be combined")
endif()
if(DLMFD_SANITIZE)
  # GCC 12 reports false -Wmaybe-uninitialized inside libstdc++ (std::regex, std::function) once the
  # sanitizers' instrumentation is inlined; the release build keeps the warning.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
                      $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  # GCC names ASan by __SANITIZE_ADDRESS__, clang by __has_feature: code that must know (tests of
  # memory and allocations) asks DLMFD_ASAN_BUILD.
  add_compile_definitions(DLMFD_ASAN_BUILD=1)
  add_link_options(-fsanitize=address,undefined)
endif()
if(DLMFD_TSAN)
  # Instrumented code, but headers read as in the build of Debian's uninstrumented libraries: with
  # __SANITIZE_THREAD__ defined, protobuf's MapFieldBase gains two members (map_field.h), so the
  # inline code of a map field and libprotobuf's disagree on its layout (a SEGV in
  # SyncRepeatedFieldWithMap when reflection fills SubmitRequest.labels), and abseil and gRPC
  # switch their own TSan variants. libstdc++'s shared_ptr keeps its TSan-visible release
  # (_GLIBCXX_TSAN); our code asks DLMFD_TSAN_BUILD (core/target_clones.h). scripts/tsan.sh.
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer -U__SANITIZE_THREAD__
                      -D_GLIBCXX_TSAN=1)
  add_compile_definitions(DLMFD_TSAN_BUILD=1)
  add_link_options(-fsanitize=thread)
endif()

# DLMFD_NUMERICS_FLAGS: compile flags for the targets that compute (the engine, the results files,
# the pictures and dlmfd-solve), added after the build type's. CI's ASan+UBSan tree compiles at -O0
# and names -O1 here: the code that waits on clients, gRPC and files (the daemon, the CLI, the
# dashboard, their tests: 80 % of that tree's compile time) builds in half the time at -O0, while
# the solver the e2e tests run over the paper's cases keeps -O1 (docs/evidence/service.md, "CI's
# time"). Empty (the default) adds nothing.
set(DLMFD_NUMERICS_FLAGS "" CACHE STRING "Compile flags added to the computing targets (a list)")
function(dlmfd_numerics_flags target)
  if(DLMFD_NUMERICS_FLAGS)
    target_compile_options(${target} PRIVATE ${DLMFD_NUMERICS_FLAGS})
  endif()
endfunction()
