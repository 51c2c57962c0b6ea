# Registration of tests and V&V cases.
#
# Tests run with 2 OpenMP threads and a passive wait policy: ctest runs two tests at
# once on 2 cores, and spinning idle workers would then steal each other's cores.
#
# Every test gets the label `full`; tests that belong to the CI tier also get `ci`.
# A V&V case additionally writes <results>/<case>.h5 and is listed in
# <results>/expected_cases.tsv so that the report generator can name a case whose
# record is missing.
#
#   erythro_add_test(NAME n COMMAND cmd... LABELS unit [CI] [NO_FULL] [TIMEOUT s] [ENVIRONMENT k=v...]
#                    [PROCESSORS n] [RESOURCE_LOCK r...])
#   (NO_FULL: not in `full`, e.g. benchmarks)
#   vv_add_case(CASE c COMMAND cmd... LABELS verification [CI] [NO_FULL] [TIMEOUT s] [ENVIRONMENT k=v...]
#               [PROCESSORS n] [RESOURCE_LOCK r...])
#   (ENVIRONMENT entries come after the defaults and override them, e.g. OMP_NUM_THREADS=1
#   for a long run on a small grid, where thread start-up per step costs more than it gains)
#
# Scheduling: every test listed in ERYTHRO_TIMINGS_FILE (default reference_data/timings/full.tsv,
# "test<TAB>seconds", measured) gets that time as its ctest COST, so `ctest -j` starts the
# longest tests first, on a fresh clone too. A COST overrides ctest's own measured costs
# (Testing/Temporary/CTestCostData.txt); tests not in the file fall back to those. PROCESSORS
# (default 1: two 2-thread tests share the 2 cores under -j2, as before) and RESOURCE_LOCK are
# passed to ctest as they are. Refresh the file after a run: reports/suite.py times (docs/reports.md).

set_property(GLOBAL PROPERTY ERYTHRO_VV_MANIFEST "")

set(ERYTHRO_TIMINGS_FILE "${PROJECT_SOURCE_DIR}/reference_data/timings/full.tsv" CACHE FILEPATH
    "Measured test times (test<TAB>seconds), used as ctest COST")

function(_erythro_read_timings)
  if(NOT EXISTS "${ERYTHRO_TIMINGS_FILE}")
    return()
  endif()
  set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${ERYTHRO_TIMINGS_FILE}")
  file(STRINGS "${ERYTHRO_TIMINGS_FILE}" lines REGEX "^[^#]")
  foreach(line IN LISTS lines)
    if(line MATCHES "^([^\t ]+)[\t ]+([0-9.]+)$")
      set_property(GLOBAL PROPERTY "ERYTHRO_COST_${CMAKE_MATCH_1}" "${CMAKE_MATCH_2}")
    endif()
  endforeach()
endfunction()
_erythro_read_timings()

function(erythro_add_test)
  cmake_parse_arguments(T "CI;NO_FULL" "NAME;TIMEOUT;WORKING_DIRECTORY;PROCESSORS"
                        "COMMAND;LABELS;ENVIRONMENT;RESOURCE_LOCK" ${ARGN})
  set(labels ${T_LABELS})
  if(NOT T_NO_FULL)
    list(APPEND labels full)
  endif()
  if(T_CI)
    list(APPEND labels ci)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  if(NOT T_WORKING_DIRECTORY)
    set(T_WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  add_test(NAME ${T_NAME} COMMAND ${T_COMMAND} WORKING_DIRECTORY ${T_WORKING_DIRECTORY})
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${labels}" TIMEOUT ${T_TIMEOUT}
    ENVIRONMENT "ERYTHRO_RESULTS_DIR=${ERYTHRO_RESULTS_DIR};ERYTHRO_SOURCE_DIR=${PROJECT_SOURCE_DIR};OMP_NUM_THREADS=2;OMP_WAIT_POLICY=passive;${T_ENVIRONMENT}")
  get_property(cost GLOBAL PROPERTY "ERYTHRO_COST_${T_NAME}")
  if(cost)
    set_tests_properties(${T_NAME} PROPERTIES COST ${cost})
  endif()
  if(T_PROCESSORS)
    set_tests_properties(${T_NAME} PROPERTIES PROCESSORS ${T_PROCESSORS})
  endif()
  if(T_RESOURCE_LOCK)
    set_tests_properties(${T_NAME} PROPERTIES RESOURCE_LOCK "${T_RESOURCE_LOCK}")
  endif()
endfunction()

function(vv_add_case)
  cmake_parse_arguments(V "CI;NO_FULL" "CASE;TIMEOUT;PROCESSORS" "COMMAND;LABELS;ENVIRONMENT;RESOURCE_LOCK" ${ARGN})
  set(extra "")
  if(V_CI)
    list(APPEND extra CI)
  endif()
  if(V_NO_FULL)  # a study too long for the full tier (label `study`), or a CI subset a full study asserts
    list(APPEND extra NO_FULL)
  endif()
  if(V_ENVIRONMENT)
    list(APPEND extra ENVIRONMENT ${V_ENVIRONMENT})
  endif()
  if(V_PROCESSORS)
    list(APPEND extra PROCESSORS ${V_PROCESSORS})
  endif()
  if(V_RESOURCE_LOCK)
    list(APPEND extra RESOURCE_LOCK ${V_RESOURCE_LOCK})
  endif()
  erythro_add_test(NAME ${V_CASE} COMMAND ${V_COMMAND} LABELS ${V_LABELS} TIMEOUT ${V_TIMEOUT} ${extra})
  get_test_property(${V_CASE} LABELS labels)  # as erythro_add_test completed them (full, ci)
  list(JOIN labels "," label_text)
  set_property(GLOBAL APPEND PROPERTY ERYTHRO_VV_MANIFEST "${V_CASE}\t${label_text}")
endfunction()

function(vv_write_manifest)
  get_property(rows GLOBAL PROPERTY ERYTHRO_VV_MANIFEST)
  set(text "# case\tlabels (written by CMake; the report generator checks every case has a record)\n")
  foreach(row IN LISTS rows)
    string(APPEND text "${row}\n")
  endforeach()
  file(WRITE "${ERYTHRO_RESULTS_DIR}/expected_cases.tsv" "${text}")
endfunction()
