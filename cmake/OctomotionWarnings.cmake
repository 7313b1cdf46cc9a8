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

# Eigen's fixed-size types keep the 16-byte alignment, and so the layout, that the Debian builds
# of FCL and OMPL were compiled with, whatever instruction set this build uses: with AVX, Eigen
# would align them to 32 bytes and silently change the layout of types shared with those
# libraries. The libraries export the same definitions to their users (octree/CMakeLists.txt).
set(OCTOMOTION_EIGEN_ALIGNMENT EIGEN_MAX_ALIGN_BYTES=16 EIGEN_MAX_STATIC_ALIGN_BYTES=16)
add_compile_definitions(${OCTOMOTION_EIGEN_ALIGNMENT})

# x86-64-v3 (AVX2, FMA, BMI2: Intel since Haswell, AMD since Excavator): the geometry's vector
# and 3x3 arithmetic (forward kinematics, GJK, bounds) gets fused multiply-adds and wider
# registers. AUTO uses it when the compiler accepts it and the building machine runs it; the
# libraries and programs built then need such a CPU. OFF builds for any x86-64 CPU.
set(OCTOMOTION_X86_64_V3 AUTO CACHE STRING "Compile for x86-64-v3 (AVX2, FMA): AUTO, ON or OFF")
set_property(CACHE OCTOMOTION_X86_64_V3 PROPERTY STRINGS AUTO ON OFF)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64" AND NOT OCTOMOTION_X86_64_V3 STREQUAL "OFF")
  if(OCTOMOTION_X86_64_V3 STREQUAL "ON")
    add_compile_options(-march=x86-64-v3)
  else()
    include(CheckCXXSourceRuns)
    set(CMAKE_REQUIRED_FLAGS "-march=x86-64-v3")
    check_cxx_source_runs("
      int main() {
        __builtin_cpu_init();
        return __builtin_cpu_supports(\"avx2\") && __builtin_cpu_supports(\"fma\") &&
               __builtin_cpu_supports(\"bmi2\") ? 0 : 1;
      }" OCTOMOTION_RUNS_X86_64_V3)
    unset(CMAKE_REQUIRED_FLAGS)
    if(OCTOMOTION_RUNS_X86_64_V3)
      add_compile_options(-march=x86-64-v3)
    endif()
  endif()
endif()

if(OCTOMOTION_SANITIZE)
  add_compile_options(-fsanitize=${OCTOMOTION_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${OCTOMOTION_SANITIZE})
endif()
