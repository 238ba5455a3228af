# The Python tests, run by Debian's python3 (its python3-* packages: scripts/setup.sh):
#   python    the client package (python/): its own logic (client_units_test.py), and against the
#             real daemon on loopback (client_test.py)
#   paraview  fields.xmf in ParaView's XDMF readers, through pvbatch, and a screenshot of trA with
#             the disks as glyphs under Xvfb (paraview_test.py)
# Each exits 77, which ctest reports as skipped, only when what it needs is not installed; the
# message names the Debian package.
if(EXISTS /usr/bin/python3)
  set(python_default /usr/bin/python3)
else()
  find_program(python_default python3)
endif()
set(DLMFD_TEST_PYTHON ${python_default} CACHE FILEPATH
    "the Python of the Python tests (Debian's, which sees the python3-* packages)")
if(NOT DLMFD_TEST_PYTHON)
  message(STATUS "dlmfd: no python3; the Python and ParaView tests are not registered")
  return()
endif()

set(python_tests ${CMAKE_CURRENT_SOURCE_DIR}/python)
set(python_env "DLMFD_BINARY_DIR=${PROJECT_BINARY_DIR}" "PYTHONDONTWRITEBYTECODE=1")
if(TARGET dlmfd_python)
  add_test(NAME PythonClient.OwnLogic COMMAND ${DLMFD_TEST_PYTHON} ${python_tests}/client_units_test.py -v)
  set_tests_properties(PythonClient.OwnLogic PROPERTIES LABELS python SKIP_RETURN_CODE 77
    ENVIRONMENT "${python_env};PYTHONPATH=${DLMFD_PYTHON_DIR}")
endif()
if(TARGET dlmfd_python AND TARGET dlmfd-solve)
  # dlmfd.open and dlmfd.table on real runs (run_reader_test.py); the package installed into a
  # fresh venv by pip (package_test.py).
  add_test(NAME PythonClient.ReadsRuns COMMAND ${DLMFD_TEST_PYTHON} ${python_tests}/run_reader_test.py -v)
  set_tests_properties(PythonClient.ReadsRuns PROPERTIES LABELS python SKIP_RETURN_CODE 77
    ENVIRONMENT "${python_env};PYTHONPATH=${DLMFD_PYTHON_DIR}")
  add_test(NAME PythonClient.InstallsWithPip COMMAND ${DLMFD_TEST_PYTHON} ${python_tests}/package_test.py -v)
  set_tests_properties(PythonClient.InstallsWithPip PROPERTIES LABELS python SKIP_RETURN_CODE 77
    ENVIRONMENT "${python_env};PYTHONPATH=${DLMFD_PYTHON_DIR}")
endif()
if(TARGET dlmfd_python AND TARGET dlmfdd)
  add_test(NAME PythonClient.AgainstTheDaemon
           COMMAND ${DLMFD_TEST_PYTHON} ${python_tests}/client_test.py -v)
  set_tests_properties(PythonClient.AgainstTheDaemon PROPERTIES LABELS python SKIP_RETURN_CODE 77
    ENVIRONMENT "${python_env};PYTHONPATH=${DLMFD_PYTHON_DIR}")
endif()
add_test(NAME ParaView.OpensFieldsXmf COMMAND ${DLMFD_TEST_PYTHON} ${python_tests}/paraview_test.py -v)
set_tests_properties(ParaView.OpensFieldsXmf PROPERTIES LABELS paraview SKIP_RETURN_CODE 77
  ENVIRONMENT "${python_env}")
if(TARGET dlmfd-solve)
  # Issue 32 point 3: every file of cases/, its numerics keys removed, is admitted and takes its
  # first step at the defaults (bench/cases_at_defaults.py runs them to their ends: docs/accuracy.md).
  add_test(NAME CaseFiles.EveryCaseStepsAtTheDefaults
           COMMAND ${DLMFD_TEST_PYTHON} ${PROJECT_SOURCE_DIR}/bench/cases_at_defaults.py --steps 1
                   --solve $<TARGET_FILE:dlmfd-solve> --out ${CMAKE_CURRENT_BINARY_DIR}/cases_at_defaults
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(CaseFiles.EveryCaseStepsAtTheDefaults PROPERTIES LABELS e2e)
endif()
