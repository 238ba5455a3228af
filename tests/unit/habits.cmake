# The code's habits, checked with the unit tests (CONTRIBUTING.md): every tracked C++ file as
# clang-format writes it, the commit-message rule its hook enforces, and every link of the docs
# and `docs/...` path the code cites resolves (docs/README.md). They skip (77) outside a git
# checkout, where the tracked files are unknown.
find_program(DLMFD_CLANG_FORMAT clang-format)
if(DLMFD_CLANG_FORMAT)
  add_test(NAME habits_clang_format COMMAND ${PROJECT_SOURCE_DIR}/scripts/check_format.sh)
  set_tests_properties(habits_clang_format PROPERTIES LABELS unit SKIP_RETURN_CODE 77)
endif()
add_test(NAME habits_commit_message_rule
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/unit/commit_message_test.sh)
set_tests_properties(habits_commit_message_rule PROPERTIES LABELS unit)
add_test(NAME habits_doc_links COMMAND ${PROJECT_SOURCE_DIR}/scripts/check_doc_links.py)
set_tests_properties(habits_doc_links PROPERTIES LABELS unit SKIP_RETURN_CODE 77)
add_test(NAME habits_doc_links_checker COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/unit/doc_links_test.sh)
set_tests_properties(habits_doc_links_checker PROPERTIES LABELS unit)
