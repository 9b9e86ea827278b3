# Fails when a source of the ROS-free core includes a ROS header, or when the core proper
# (core/) reaches up into the solvers or the curved model built on it.
# ROS headers live in /usr/include on Debian, so include directories alone cannot
# keep them out. Usage: cmake -DROOT=<package dir> -P check_ros_free.cmake

# The include lines matching `pattern` in the sources under `dirs`, one "file: line" a line.
function(find_includes pattern out)
  set(found "")
  foreach(dir ${ARGN})
    file(GLOB_RECURSE files "${ROOT}/${dir}/*.h" "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.cpp" "${ROOT}/${dir}/*.cc")
    foreach(f ${files})
      file(STRINGS "${f}" lines REGEX "${pattern}")
      foreach(line ${lines})
        file(RELATIVE_PATH rel "${ROOT}" "${f}")
        string(APPEND found "  ${rel}: ${line}\n")
      endforeach()
    endforeach()
  endforeach()
  set(${out} "${found}" PARENT_SCOPE)
endfunction()

# ros/..., *_msgs/..., *_srvs/..., tf2_ros/..., the ROS layer, generated messages (CamelCase).
find_includes("^[ \t]*#[ \t]*include[ \t]*[<\"](ros/|[a-z0-9_]+_msgs/|[a-z0-9_]+_srvs/|tf2_ros/|virtual_origami/ros/|virtual_origami/[A-Z])"
              ros src/core src/solvers src/curved include/virtual_origami/core include/virtual_origami/solvers
              include/virtual_origami/curved)
if(ros)
  message(FATAL_ERROR "The core must stay ROS-free, but these sources include ROS headers:\n${ros}")
endif()
message(STATUS "core is ROS-free")

find_includes("^[ \t]*#[ \t]*include[ \t]*[<\"]virtual_origami/(solvers|curved)/" upward src/core include/virtual_origami/core)
if(upward)
  message(FATAL_ERROR "core/ is the lowest layer, but these sources include solvers/ or curved/:\n${upward}")
endif()
message(STATUS "core/ includes nothing from solvers/ or curved/")
