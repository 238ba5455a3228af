# ctest cli_links_no_numerics: fails when the CLI binary (-DBINARY=...) is built from or loads the
# engine's numerics. Three views, because each alone can miss it:
#   LINKED (comma-separated) the libraries the CLI target links, transitively, as CMake knows them:
#     no dlmfd_engine, FFTW or OpenMP (the linker's --as-needed would hide them from the binary);
#   ldd: every shared library the loader maps, the CLI's own and those of its libraries;
#   nm (-DNM=...): the symbols linked in, which catches a static FFTW or libgomp that ldd cannot see.
# A tool that fails, or an empty view, is a failure of the test, never a pass.
foreach(var BINARY NM LINKED)
  if(NOT ${var})
    message(FATAL_ERROR "cli_links_no_numerics: -D${var}= is required")
  endif()
endforeach()
if(NOT EXISTS "${BINARY}")
  message(FATAL_ERROR "cli_links_no_numerics: ${BINARY} does not exist")
endif()

string(REPLACE "," ";" linked "${LINKED}")
set(numerics_targets "")
foreach(library ${linked})
  if(library MATCHES "^(dlmfd_engine|PkgConfig::FFTW3|OpenMP::)" OR library MATCHES "fftw|gomp")
    list(APPEND numerics_targets "${library}")
  endif()
endforeach()
if(numerics_targets)
  message(FATAL_ERROR "the CLI links numerics: ${numerics_targets}\n(all it links: ${linked})")
endif()

execute_process(COMMAND ldd "${BINARY}" RESULT_VARIABLE ldd_status OUTPUT_VARIABLE libraries
                ERROR_VARIABLE ldd_error)
if(NOT ldd_status EQUAL 0 OR NOT libraries MATCHES "libc\\.so")
  message(FATAL_ERROR "ldd ${BINARY} failed (${ldd_status}): ${ldd_error}${libraries}")
endif()
string(REGEX MATCHALL "lib(fftw3[^ \t\n]*|gomp)\\.so[^ \t\n]*" numerics_libraries "${libraries}")
if(numerics_libraries)
  list(REMOVE_DUPLICATES numerics_libraries)
  message(FATAL_ERROR "${BINARY} loads numerics libraries: ${numerics_libraries}\n${libraries}")
endif()

execute_process(COMMAND "${NM}" "${BINARY}" RESULT_VARIABLE nm_status OUTPUT_VARIABLE symbols
                ERROR_VARIABLE nm_error)
if(NOT nm_status EQUAL 0 OR NOT symbols MATCHES "main")
  message(FATAL_ERROR "${NM} ${BINARY} failed (${nm_status}): ${nm_error}")
endif()
string(REGEX MATCHALL "[ \t](fftw_[A-Za-z0-9_]+|GOMP_[A-Za-z0-9_]+|omp_[a-z_]+)" numerics_symbols
       "${symbols}")
if(numerics_symbols)
  list(REMOVE_DUPLICATES numerics_symbols)
  message(FATAL_ERROR "${BINARY} links numerics symbols: ${numerics_symbols}")
endif()
list(LENGTH linked count)
message(STATUS "${BINARY}: ${count} libraries linked, none of them numerics; no FFTW or OpenMP loaded")
