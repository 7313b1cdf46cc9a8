# Installs the build tree into a scratch prefix, moves the installed tree elsewhere (a package
# must not depend on where it was installed), then configures, builds and runs a tiny project
# that finds octomotion with find_package, as a downstream user would. Also checks that the
# exported targets name no absolute path of the build machine's OMPL or of the install prefix,
# and that the installed `octomotion view` finds the installed viewer.
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed (${rc})")
endif()
file(RENAME ${WORK_DIR}/prefix ${WORK_DIR}/moved)
file(GLOB_RECURSE target_files ${WORK_DIR}/moved/*Targets*.cmake)
if(NOT target_files)
  message(FATAL_ERROR "no installed *Targets*.cmake under ${WORK_DIR}/moved")
endif()
foreach(f IN LISTS target_files)
  file(READ ${f} text)
  foreach(forbidden "/usr/include/ompl" "libompl" "liboctomap" "${WORK_DIR}/prefix")
    string(FIND "${text}" "${forbidden}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${f} holds the absolute path ${forbidden}")
    endif()
  endforeach()
endforeach()
set(flags "")
if(SANITIZE)
  # The installed static library was built with sanitizers; the consumer must link their runtime.
  set(flags "-fsanitize=${SANITIZE}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build
  "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=${flags}"
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/moved -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
  -DCMAKE_BUILD_TYPE=Release RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer build failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message(STATUS "consumer said: ${out}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "intersects=1")
  message(FATAL_ERROR "consumer run failed (${rc}): ${out}")
endif()

# The installed command finds the installed viewer (<prefix>/share/octomotion/viewer), run from a
# directory without viewer/ and with OCTOMOTION_VIEWER_DIR unset.
set(exe ${WORK_DIR}/moved/bin/octomotion)
if(EXISTS ${exe})
  foreach(f index.html files.txt viewer.js)
    if(NOT EXISTS ${WORK_DIR}/moved/share/octomotion/viewer/${f})
      message(FATAL_ERROR "the viewer's ${f} is not installed")
    endif()
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=OCTOMOTION_VIEWER_DIR
    ${exe} view ${SOURCE_DIR}/tests/data/scenes/l_piece_urdf.yaml --no-link-trees
    --out-dir ${WORK_DIR}/view
    WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR err MATCHES "were not found" OR NOT EXISTS ${WORK_DIR}/view/index.html
     OR NOT EXISTS ${WORK_DIR}/view/viewer.js)
    message(FATAL_ERROR "installed view did not copy the installed viewer (${rc}): ${out} ${err}")
  endif()
  message(STATUS "installed view: ${out}")
endif()
