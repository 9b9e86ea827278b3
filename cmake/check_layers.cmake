# The libraries are layered: core <- numerics <- solvers <- curved <- ros <- nodes. Each layer may
# include the layers below it and nothing above; the four below ros never include ROS.
# ROS headers live in /usr/include on Debian, so include directories alone cannot enforce this.
# Usage: cmake -DROOT=<package dir> -DLAYER=<core|numerics|solvers|curved|ros> -P check_layers.cmake

set(layers core numerics solvers curved ros)
list(FIND layers "${LAYER}" position)
if(position LESS 0)
  message(FATAL_ERROR "LAYER must be one of ${layers}, not \"${LAYER}\"")
endif()

# The include lines matching `pattern` in the sources of `dirs`, one "file: line" a line.
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

set(sources src/${LAYER} include/virtual_origami/${LAYER})

# Every layer above this one, as a folder name after virtual_origami/ or a relative "../".
math(EXPR above_start "${position} + 1")
list(LENGTH layers count)
set(above "")
if(above_start LESS count)
  list(SUBLIST layers ${above_start} -1 above)
endif()
list(APPEND above nodes rviz_plugin)
list(JOIN above "|" above_alternatives)
find_includes("^[ \t]*#[ \t]*include[ \t]*[<\"](virtual_origami/|\\.\\./)(${above_alternatives})/" upward ${sources})
if(upward)
  message(FATAL_ERROR "${LAYER}/ may include only the layers below it (${layers} in order), but these reach up:\n${upward}")
endif()
message(STATUS "${LAYER}/ includes nothing from the layers above it")

if(NOT LAYER STREQUAL "ros")
  # ros/..., *_msgs/..., *_srvs/..., tf2_ros/..., generated messages (virtual_origami/CamelCase).
  find_includes("^[ \t]*#[ \t]*include[ \t]*[<\"](ros/|[a-z0-9_]+_msgs/|[a-z0-9_]+_srvs/|tf2_ros/|virtual_origami/[A-Z])" ros
                ${sources})
  if(ros)
    message(FATAL_ERROR "${LAYER}/ must stay ROS-free, but these sources include ROS headers:\n${ros}")
  endif()
  message(STATUS "${LAYER}/ is ROS-free")
endif()
