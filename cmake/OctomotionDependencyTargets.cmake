# OMPL's and OctoMap's Debian package configs set variables holding absolute paths
# (OMPL_INCLUDE_DIR, OMPL_LIBRARIES, OCTOMAP_LIBRARIES), not usable imported targets. The
# libraries link these imported targets instead, created from whatever find_package found: in
# the build, and again in the installed package, whose config calls find_dependency(ompl) and
# find_dependency(octomap) and then includes this file. So nothing of the build machine's
# OMPL or OctoMap location is written into the installed octomotionTargets.cmake.
# OCTOMOTION_DEPENDENCY_TARGET_SCOPE: GLOBAL in the build (the targets are used from every
# subdirectory), empty in a consumer.
if(ompl_FOUND AND NOT TARGET octomotion::ompl)
  add_library(octomotion::ompl INTERFACE IMPORTED ${OCTOMOTION_DEPENDENCY_TARGET_SCOPE})
  # Only OMPL's own directory: OMPL_INCLUDE_DIRS also lists /usr/include and Eigen.
  set_target_properties(octomotion::ompl PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
endif()
if(octomap_FOUND AND NOT TARGET octomotion::octomap)
  add_library(octomotion::octomap INTERFACE IMPORTED ${OCTOMOTION_DEPENDENCY_TARGET_SCOPE})
  set_target_properties(octomotion::octomap PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${OCTOMAP_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${OCTOMAP_LIBRARIES}")
endif()
