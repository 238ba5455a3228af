# Warning flags for our own targets (not for generated protobuf code).
function(dlmfd_warnings target)
  # -Wshadow=local is GCC's (clang, used by the fuzz build, has no such option).
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic
                                           $<$<CXX_COMPILER_ID:GNU>:-Wshadow=local>
                                           -Wno-unused-parameter)
  if(DLMFD_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
