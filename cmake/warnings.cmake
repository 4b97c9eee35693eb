# Warnings as an INTERFACE target, linked privately by every project target,
# so nothing leaks into consumers and no global flags are set.
add_library(mrcloth_warnings INTERFACE)
add_library(mrcloth::warnings ALIAS mrcloth_warnings)
target_compile_options(mrcloth_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wno-deprecated-declarations>)
