# Common compile options for every octomotion target: warnings (errors in CI) and sanitizers.
# Library code also gets -Wconversion; tests, benchmarks and demos (pass TEST) do not.
function(octomotion_set_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
  if(NOT "${ARGN}" STREQUAL "TEST")
    target_compile_options(${target} PRIVATE -Wconversion -Wno-sign-conversion)
  endif()
  if(OCTOMOTION_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(OCTOMOTION_SANITIZE)
  add_compile_options(-fsanitize=${OCTOMOTION_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${OCTOMOTION_SANITIZE})
endif()
