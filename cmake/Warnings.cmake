# Warning flags for our own targets (not for generated protobuf code).
function(dlmfd_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local -Wno-unused-parameter)
  if(DLMFD_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
