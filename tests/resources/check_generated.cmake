# Regenerates committed resource files into the build tree and requires each
# to equal the committed one byte for byte, so a committed file cannot drift
# from its generator (or the generator from it) unnoticed.
#   cmake -DGENERATOR=<program> -DOUTPUT_DIR=<build folder> -DCOMMITTED_DIR=<source folder>
#         -DFILES=<name,name...> -DTARGET=<regenerate target> [-DSINGLE_FILE=ON] -P check_generated.cmake
# The generator is run as `<program> <OUTPUT_DIR>` (it writes every file of
# FILES there), or with SINGLE_FILE as `<program> <OUTPUT_DIR>/<the one file>`.
foreach(var GENERATOR OUTPUT_DIR COMMITTED_DIR FILES TARGET)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_generated.cmake: -D${var}=... is required")
  endif()
endforeach()

string(REPLACE "," ";" FILES "${FILES}")
file(REMOVE_RECURSE "${OUTPUT_DIR}")
file(MAKE_DIRECTORY "${OUTPUT_DIR}")
if(SINGLE_FILE)
  list(LENGTH FILES count)
  if(NOT count EQUAL 1)
    message(FATAL_ERROR "check_generated.cmake: SINGLE_FILE needs exactly one name in FILES")
  endif()
  set(argument "${OUTPUT_DIR}/${FILES}")
else()
  set(argument "${OUTPUT_DIR}")
endif()
execute_process(COMMAND "${GENERATOR}" "${argument}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} ${argument} failed (exit ${rc})")
endif()

foreach(name IN LISTS FILES)
  if(NOT EXISTS "${COMMITTED_DIR}/${name}")
    message(FATAL_ERROR "committed file missing: ${COMMITTED_DIR}/${name}\n"
                        "Create it with: cmake --build <build-dir> --target ${TARGET}")
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUTPUT_DIR}/${name}" "${COMMITTED_DIR}/${name}"
                  RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    message(FATAL_ERROR "${COMMITTED_DIR}/${name} differs from the generator's output ${OUTPUT_DIR}/${name}.\n"
                        "If the generator changed on purpose, run: cmake --build <build-dir> --target ${TARGET}\n"
                        "and commit both; otherwise restore the committed file.")
  endif()
  message(STATUS "${name} matches its generator")
endforeach()
