# cmake -P script: install, configure and build the consumer, run it.
file(REMOVE_RECURSE ${PREFIX} ${CONSUMER_BUILD} ${CONSUMER_BUILD}-sdk)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX} RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${CONSUMER_BUILD}
  -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Release RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer against the installed package failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${CONSUMER_BUILD} -j 2 RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
# The SDK alone, with every host dependency made unfindable.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SDK_CONSUMER_SOURCE} -B ${CONSUMER_BUILD}-sdk
  -DCMAKE_PREFIX_PATH=${PREFIX}
  -DCMAKE_DISABLE_FIND_PACKAGE_Simbody=ON -DCMAKE_DISABLE_FIND_PACKAGE_urdfdom=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_tinyxml2=ON -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON
  -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON -DCMAKE_DISABLE_FIND_PACKAGE_assimp=ON
  RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring a plugin with find_package(pronk COMPONENTS sdk) failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${CONSUMER_BUILD}-sdk RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the SDK-only plugin failed: ${rc}")
endif()
execute_process(COMMAND ${CONSUMER_BUILD}/consumer ${SCENARIO} ${CONSUMER_BUILD}/libconsumer_plugin.so
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}${err}")
if(rc)
  message(FATAL_ERROR "the consumer failed: ${rc}")
endif()
