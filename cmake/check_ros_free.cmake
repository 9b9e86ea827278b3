# Fails when a source of the ROS-free core includes a ROS header, or when the core proper
# (core/) reaches up into the solvers or the curved model built on it.
# ROS headers live in /usr/include on Debian, so include directories alone cannot
# keep them out. Usage: cmake -DROOT=<package dir> -P check_ros_free.cmake
set(dirs src/core src/solvers src/curved include/virtual_origami/core
         include/virtual_origami/solvers include/virtual_origami/curved)
# ros/..., *_msgs/..., *_srvs/..., tf2_ros/..., the ROS layer, generated messages (CamelCase).
set(ros_include "^[ \t]*#[ \t]*include[ \t]*[<\"](ros/|[a-z0-9_]+_msgs/|[a-z0-9_]+_srvs/|tf2_ros/|virtual_origami/ros/|virtual_origami/[A-Z])")

set(offenders "")
foreach(dir ${dirs})
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.h" "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.cpp" "${ROOT}/${dir}/*.cc")
  foreach(f ${files})
    file(STRINGS "${f}" lines REGEX "${ros_include}")
    foreach(line ${lines})
      file(RELATIVE_PATH rel "${ROOT}" "${f}")
      string(APPEND offenders "  ${rel}: ${line}\n")
    endforeach()
  endforeach()
endforeach()

if(offenders)
  message(FATAL_ERROR "The core must stay ROS-free, but these sources include ROS headers:\n${offenders}")
endif()
message(STATUS "core is ROS-free")

set(upward "^[ \t]*#[ \t]*include[ \t]*[<\"]virtual_origami/(solvers|curved)/")
foreach(dir src/core include/virtual_origami/core)
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.h" "${ROOT}/${dir}/*.cpp")
  foreach(f ${files})
    file(STRINGS "${f}" lines REGEX "${upward}")
    foreach(line ${lines})
      file(RELATIVE_PATH rel "${ROOT}" "${f}")
      string(APPEND offenders "  ${rel}: ${line}\n")
    endforeach()
  endforeach()
endforeach()
if(offenders)
  message(FATAL_ERROR "core/ is the lowest layer, but these sources include solvers/ or curved/:\n${offenders}")
endif()
message(STATUS "core/ includes nothing from solvers/ or curved/")
