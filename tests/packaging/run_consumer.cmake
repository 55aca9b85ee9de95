# Builds and runs a tiny consumer project against stickslip.
#   MODE=find_package     : install this build tree into a temporary prefix, then find_package().
#   MODE=add_subdirectory : the consumer adds the source tree with add_subdirectory().
cmake_minimum_required(VERSION 3.20)
set(root ${WORK_DIR}/consumer_${MODE})
file(REMOVE_RECURSE ${root})
file(MAKE_DIRECTORY ${root})

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "command failed (${rc}): ${ARGV}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

if(MODE STREQUAL "find_package")
  set(prefix ${root}/prefix)
  run(${CMAKE_COMMAND} --install ${STICKSLIP_BINARY_DIR} --prefix ${prefix})
  if(NOT EXISTS ${prefix}/share/stickslip/cmake/stickslipConfig.cmake)
    message(FATAL_ERROR "install did not produce stickslipConfig.cmake")
  endif()
  set(src ${STICKSLIP_SOURCE_DIR}/tests/consumer_find_package)
  set(extra -DCMAKE_PREFIX_PATH=${prefix})
else()
  set(src ${STICKSLIP_SOURCE_DIR}/tests/consumer_subdirectory)
  set(extra -DSTICKSLIP_SOURCE_DIR=${STICKSLIP_SOURCE_DIR})
endif()

# No build type (no optimisation): the check is about packaging, and an -O3 compile of the
# umbrella header with Spectra costs about two minutes per consumer.
run(${CMAKE_COMMAND} -S ${src} -B ${root}/build -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_BUILD_TYPE= ${extra})
run(${CMAKE_COMMAND} --build ${root}/build)
run(${root}/build/consumer)
if(MODE STREQUAL "find_package")
  run(${root}/build/consumer_compiled)
endif()
