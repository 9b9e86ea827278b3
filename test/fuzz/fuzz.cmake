# Included by the top CMakeLists.txt inside its testing block. Every fuzz target also builds
# with g++ against a plain driver (replay_main.cpp): ctest replays its committed corpus and
# crash regressions, then runs a fixed number of seeded mutations of them — a bounded,
# deterministic fuzz smoke run in `make test`. The real fuzzing is `make fuzz` (clang).
foreach(target fold_reader session_ops)
  add_executable(${target}_replay
    ${CMAKE_CURRENT_LIST_DIR}/${target}_fuzz.cpp ${CMAKE_CURRENT_LIST_DIR}/replay_main.cpp)
  target_link_libraries(${target}_replay PRIVATE virtual_origami_core)
  set_target_properties(${target}_replay PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/test/fuzz)
  set(inputs ${CMAKE_CURRENT_LIST_DIR}/corpus/${target})
  if(EXISTS ${CMAKE_CURRENT_LIST_DIR}/crashes/${target})
    list(APPEND inputs ${CMAKE_CURRENT_LIST_DIR}/crashes/${target})
  endif()
  # A few seconds each: the reader is fast, an operation sequence folds and solves.
  if(target STREQUAL "fold_reader")
    set(mutations 50000)
  else()
    set(mutations 10000)
  endif()
  add_test(NAME fuzz_replay_${target}
    COMMAND ${target}_replay --mutations ${mutations} --seed 20240601 ${inputs}
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}/test/fuzz)
  set_tests_properties(fuzz_replay_${target} PROPERTIES TIMEOUT 300)
endforeach()
