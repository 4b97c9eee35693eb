# Runs the mrcloth host once and checks its exit code and output; used by
# tests that a self-checking script cannot express (exit codes, stderr, the
# command line). CTest's PASS_REGULAR_EXPRESSION would ignore the exit code
# and accepts any one of several expressions; this checks all of them.
#
# cmake -DHOST=<mrcloth> -DARGS=<a@@b@@...> [-DEXIT_CODE=<n>]
#       [-DSTDOUT=<re@@re...>] [-DSTDERR=...] [-DNOT_STDOUT=...] [-DNOT_STDERR=...]
#       [-DFILES=<path@@path...>] [-DWORKING_DIRECTORY=<dir>] -P run_and_check.cmake
# Lists are joined with "@@" because ";" does not survive add_test, and a
# carriage return in a pattern is written "<CR>" because neither does it.
cmake_minimum_required(VERSION 3.25)

foreach(list_name ARGS STDOUT STDERR NOT_STDOUT NOT_STDERR FILES)
  string(REPLACE "@@" ";" ${list_name} "${${list_name}}")
  string(REPLACE "<CR>" "\r" ${list_name} "${${list_name}}")
endforeach()
if(NOT DEFINED EXIT_CODE)
  set(EXIT_CODE 0)
endif()
if(NOT WORKING_DIRECTORY)
  set(WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
endif()
foreach(file IN LISTS FILES)
  file(REMOVE "${file}")
endforeach()

execute_process(COMMAND "${HOST}" ${ARGS}
  WORKING_DIRECTORY "${WORKING_DIRECTORY}"
  RESULT_VARIABLE exit_code
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)

set(failures "")
if(NOT exit_code STREQUAL EXIT_CODE)
  string(APPEND failures "exit code ${exit_code}, expected ${EXIT_CODE}\n")
endif()
foreach(pattern IN LISTS STDOUT)
  if(NOT out MATCHES "${pattern}")
    string(APPEND failures "stdout does not match: ${pattern}\n")
  endif()
endforeach()
foreach(pattern IN LISTS STDERR)
  if(NOT err MATCHES "${pattern}")
    string(APPEND failures "stderr does not match: ${pattern}\n")
  endif()
endforeach()
foreach(pattern IN LISTS NOT_STDOUT)
  if(out MATCHES "${pattern}")
    string(APPEND failures "stdout matches, but must not: ${pattern}\n")
  endif()
endforeach()
foreach(pattern IN LISTS NOT_STDERR)
  if(err MATCHES "${pattern}")
    string(APPEND failures "stderr matches, but must not: ${pattern}\n")
  endif()
endforeach()
foreach(file IN LISTS FILES)
  if(NOT EXISTS "${file}")
    string(APPEND failures "file was not written: ${file}\n")
  endif()
endforeach()

string(REPLACE ";" " " command_line "${HOST};${ARGS}")
set(report "command: ${command_line}\n--- stdout\n${out}--- stderr\n${err}---")
if(failures)
  message(FATAL_ERROR "${failures}${report}")
endif()
message(STATUS "ok\n${report}")
