# ASan+UBSan (DLMFD_SANITIZE) or TSan (DLMFD_TSAN) for every target of the build.
if(DLMFD_SANITIZE AND DLMFD_TSAN)
  message(FATAL_ERROR "DLMFD_SANITIZE and DLMFD_TSAN cannot be combined")
endif()
if(DLMFD_SANITIZE)
  # GCC 12 reports false -Wmaybe-uninitialized inside libstdc++ (std::regex, std::function) once the
  # sanitizers' instrumentation is inlined; the release build keeps the warning.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
                      -Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
endif()
if(DLMFD_TSAN)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
