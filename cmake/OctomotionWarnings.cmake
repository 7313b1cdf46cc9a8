# Common compile options for every octomotion target: warnings (errors in CI) and sanitizers.
# Library code also gets -Wconversion; tests, benchmarks and demos (pass TEST) do not.
function(octomotion_set_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
  if(NOT "${ARGN}" STREQUAL "TEST")
    target_compile_options(${target} PRIVATE -Wconversion -Wno-sign-conversion)
    # The libraries are position-independent (for the Python module); GCC then treats each
    # exported function as replaceable at load time and inlines none of them into its callers,
    # not even in its own file. Nothing here is meant to be replaced.
    target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  endif()
  if(OCTOMOTION_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# The octree's hot loops index children by popcount; without this GCC calls libgcc for it.
# Every x86-64 CPU since 2008 has the instruction (x86-64-v2).
option(OCTOMOTION_POPCNT "Use the POPCNT instruction on x86-64" ON)
if(OCTOMOTION_POPCNT AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
  add_compile_options(-mpopcnt)
endif()

if(OCTOMOTION_SANITIZE)
  add_compile_options(-fsanitize=${OCTOMOTION_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${OCTOMOTION_SANITIZE})
endif()
