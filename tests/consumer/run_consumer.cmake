# Installs the already-built patchspin into a scratch prefix, then configures,
# builds and runs a small consumer project that uses find_package(patchspin).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build
                -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                -DCONSUMER_WITH_BULLET=${BULLET}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j2 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer build failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer_core RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message(STATUS "consumer_core printed: ${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer_core failed (${rc})")
endif()
if(BULLET)
  execute_process(COMMAND ${WORK_DIR}/build/consumer_bullet RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer_bullet (README example) failed (${rc}): ${out}")
  endif()
  message(STATUS "consumer_bullet ran the README example")
endif()
