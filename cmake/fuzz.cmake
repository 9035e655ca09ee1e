# libFuzzer targets, one per parser (test/fuzz/). Built only by scripts/fuzz, with clang and
# -DHEX_SLAM_FUZZ=ON in a workspace of its own. The default build instead replays each target's
# seed corpus through the same harness as a gtest (hex_slam_fuzz_<target>_replay_test).
option(HEX_SLAM_FUZZ "build the libFuzzer targets (clang only; see scripts/fuzz)" OFF)
set(HEX_SLAM_FUZZERS carmen bag_message hexmap parameters)

function(hex_slam_link_fuzz_harness target name)
  if(name STREQUAL "carmen")
    target_link_libraries(${target} hex_slam_logs)
  elseif(name STREQUAL "bag_message")
    target_include_directories(${target} PRIVATE ${catkin_INCLUDE_DIRS})
    target_link_libraries(${target} hex_slam_bag ${catkin_LIBRARIES})
  elseif(name STREQUAL "hexmap")
    target_link_libraries(${target} hex_slam_io)
  elseif(name STREQUAL "parameters")
    target_link_libraries(${target} hex_slam_logs hex_slam_io)
  endif()
endfunction()

if(CATKIN_ENABLE_TESTING AND NOT HEX_SLAM_FUZZ)
  foreach(name ${HEX_SLAM_FUZZERS})
    catkin_add_gtest(hex_slam_fuzz_${name}_replay_test
      test/fuzz/${name}_fuzzer.cpp test/fuzz/corpus_replay_test.cpp test/test_main.cpp)
    if(TARGET hex_slam_fuzz_${name}_replay_test)
      target_compile_definitions(hex_slam_fuzz_${name}_replay_test PRIVATE
        HEX_SLAM_FUZZ_CORPUS="${PROJECT_SOURCE_DIR}/test/fuzz/corpus/${name}")
      hex_slam_link_fuzz_harness(hex_slam_fuzz_${name}_replay_test ${name})
    endif()
  endforeach()
endif()

if(HEX_SLAM_FUZZ)
  foreach(name ${HEX_SLAM_FUZZERS})
    add_executable(hex_slam_fuzz_${name} test/fuzz/${name}_fuzzer.cpp)
    target_link_options(hex_slam_fuzz_${name} PRIVATE -fsanitize=fuzzer)
    hex_slam_link_fuzz_harness(hex_slam_fuzz_${name} ${name})
  endforeach()
  add_custom_target(hex_slam_fuzzers)
  foreach(name ${HEX_SLAM_FUZZERS})
    add_dependencies(hex_slam_fuzzers hex_slam_fuzz_${name})
  endforeach()
endif()
