# Warnings as an INTERFACE target, linked privately by every project target,
# so nothing leaks into consumers and no global flags are set.
add_library(mrcloth_warnings INTERFACE)
add_library(mrcloth::warnings ALIAS mrcloth_warnings)
target_compile_options(mrcloth_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wno-deprecated-declarations>
  # GCC 12 reports OpenMesh's own PropertyT<VectorT>::push_back (a VectorT()
  # left uninitialised by design) in every file that adds mesh properties,
  # 34 times a build, from a system header it does not otherwise warn in.
  $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
