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
#   erythro_add_test(NAME n COMMAND cmd... LABELS unit [CI] [NO_FULL] [TIMEOUT s] [ENVIRONMENT k=v...])
#   (NO_FULL: not in `full`, e.g. benchmarks)
#   vv_add_case(CASE c COMMAND cmd... LABELS verification [CI] [TIMEOUT s] [ENVIRONMENT k=v...])
#   (ENVIRONMENT entries come after the defaults and override them, e.g. OMP_NUM_THREADS=1
#   for a long run on a small grid, where thread start-up per step costs more than it gains)

set_property(GLOBAL PROPERTY ERYTHRO_VV_MANIFEST "")

function(erythro_add_test)
  cmake_parse_arguments(T "CI;NO_FULL" "NAME;TIMEOUT;WORKING_DIRECTORY" "COMMAND;LABELS;ENVIRONMENT" ${ARGN})
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
endfunction()

function(vv_add_case)
  cmake_parse_arguments(V "CI" "CASE;TIMEOUT" "COMMAND;LABELS;ENVIRONMENT" ${ARGN})
  set(ci_flag "")
  if(V_CI)
    set(ci_flag CI)
  endif()
  set(env "")
  if(V_ENVIRONMENT)
    set(env ENVIRONMENT ${V_ENVIRONMENT})
  endif()
  erythro_add_test(NAME ${V_CASE} COMMAND ${V_COMMAND} LABELS ${V_LABELS} ${ci_flag} TIMEOUT ${V_TIMEOUT} ${env})
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
