# Developer builds under the compiler's run-time checkers, e.g.
#   cmake -S . -B build-asan -DMRCLOTH_SANITIZE=address,undefined
# Applied to every target, because the checkers' run-time must see every allocation and the
# plugin is loaded into the host.
set(MRCLOTH_SANITIZE "" CACHE STRING
  "Comma-separated -fsanitize= checkers for every target (address, undefined, ...); empty: none")
if(MRCLOTH_SANITIZE)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    message(FATAL_ERROR "MRCLOTH_SANITIZE needs GCC or Clang, not ${CMAKE_CXX_COMPILER_ID}")
  endif()
  # Stop at the first report (a finding fails its test instead of scrolling
  # by), and keep frames so the report names the caller.
  add_compile_options(-fsanitize=${MRCLOTH_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=${MRCLOTH_SANITIZE} -fno-sanitize-recover=all)
endif()

# mrcloth_scale_test_timeouts(): the checked build runs several times slower;
# every test of the calling directory with a TIMEOUT gets four times as long.
function(mrcloth_scale_test_timeouts)
  if(NOT MRCLOTH_SANITIZE)
    return()
  endif()
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(test IN LISTS tests)
    get_test_property(${test} TIMEOUT timeout)
    if(timeout)
      math(EXPR timeout "${timeout} * 4")
      set_tests_properties(${test} PROPERTIES TIMEOUT ${timeout})
    endif()
  endforeach()
endfunction()
