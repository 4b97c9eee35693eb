# Regenerates the default skirt into the build tree and requires it to equal
# the committed file byte for byte, so the committed garment cannot drift
# from its generator (or the generator from it) unnoticed.
#   cmake -DGENERATOR=<make_default_skirt> -DOUTPUT=<build obj> -DCOMMITTED=<source obj> -P check_default_skirt.cmake
foreach(var GENERATOR OUTPUT COMMITTED)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_default_skirt.cmake: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE "${OUTPUT}")
execute_process(COMMAND "${GENERATOR}" "${OUTPUT}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} ${OUTPUT} failed (exit ${rc})")
endif()
if(NOT EXISTS "${COMMITTED}")
  message(FATAL_ERROR "committed garment missing: ${COMMITTED}\n"
                      "Create it with: cmake --build <build-dir> --target regenerate_default_skirt")
endif()

execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUTPUT}" "${COMMITTED}" RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "${COMMITTED} differs from the generator's output ${OUTPUT}.\n"
                      "If the generator changed on purpose, run: cmake --build <build-dir> --target regenerate_default_skirt\n"
                      "and commit both; otherwise restore the committed file.")
endif()
message(STATUS "default skirt matches its generator: ${COMMITTED}")
