# The dashboard's tests (label browser): dlmfd-web in front of a real dlmfdd running the real
# solver, over HTTP (web_security_test.py) and in Debian's headless Chromium driven by Selenium
# (dashboard_test.py). They exit 77, which ctest reports as skipped, only when Chromium,
# chromium-driver, python3-selenium or python3-pil is missing (the message names the package).
if(NOT DLMFD_TEST_PYTHON OR NOT TARGET dlmfd-web OR NOT TARGET dlmfdd OR NOT TARGET dlmfd)
  return()
endif()
set(browser_tests ${CMAKE_CURRENT_SOURCE_DIR}/browser)
set(browser_env "DLMFD_BINARY_DIR=${PROJECT_BINARY_DIR}" "PYTHONDONTWRITEBYTECODE=1"
    "PYTHONPATH=${browser_tests}")
add_test(NAME Dashboard.SecurityRulesOverHttp
         COMMAND ${DLMFD_TEST_PYTHON} ${browser_tests}/web_security_test.py -v)
add_test(NAME Dashboard.InHeadlessChromium
         COMMAND ${DLMFD_TEST_PYTHON} ${browser_tests}/dashboard_test.py -v)
set_tests_properties(Dashboard.SecurityRulesOverHttp Dashboard.InHeadlessChromium PROPERTIES
  LABELS browser SKIP_RETURN_CODE 77 ENVIRONMENT "${browser_env}")
