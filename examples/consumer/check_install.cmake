# Installs the build tree into WORK_DIR/prefix, then builds and runs the consumer against it.
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix --config ${CONFIG}
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build
  -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "configuring the consumer with find_package(qmotion) failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer ${WORK_DIR}/out RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the consumer program failed: ${rc}")
endif()
# The installed Python module imports from the prefix (its RPATH finds libqmotion) and
# does the main job.
file(GLOB_RECURSE _modules ${WORK_DIR}/prefix/lib/python*/dist-packages/qmotion*.so)
if(_modules)
  list(GET _modules 0 _module)
  get_filename_component(_dir ${_module} DIRECTORY)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${_dir} /usr/bin/python3 -c
    "import qmotion; m = qmotion.interpolate([[0,0,0,0,1,0,0,0],[1,0,0,10,0.9,0,0,0.43]]); qmotion.export(m, '${WORK_DIR}/out/py.step', profile='circle:3'); assert qmotion.check('${WORK_DIR}/out/py.step', m, profile='circle:3')['relative_deviation'] < 1e-11"
    RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "the installed Python module failed: ${rc}")
  endif()
  message(STATUS "installed Python module: ${_module}")
endif()
