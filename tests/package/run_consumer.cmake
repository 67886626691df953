# Configures, builds and runs the consumer project in tests/package/.
#   cmake -DMODE=find_package|add_subdirectory -DBLURCULL_SOURCE=<src>
#         -DBLURCULL_BUILD=<build tree> -DWORK_DIR=<scratch> -DGENERATOR=<gen>
#         -DCXX_COMPILER=<c++> [-DBUILD_TYPE=<type>] -P run_consumer.cmake
# find_package mode first installs BLURCULL_BUILD into WORK_DIR/prefix.
cmake_minimum_required(VERSION 3.20)

foreach(required MODE BLURCULL_SOURCE BLURCULL_BUILD WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${required} OR "${${required}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: -D${required}=... is required")
  endif()
endforeach()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "run_consumer.cmake: ${what} failed (${result})")
  endif()
endfunction()

# Start clean so a stale install or cache cannot hide a packaging bug.
file(REMOVE_RECURSE "${WORK_DIR}")
set(consumer_build "${WORK_DIR}/build")
set(configure_args
  -S "${BLURCULL_SOURCE}/tests/package" -B "${consumer_build}" -G "${GENERATOR}"
  "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
  # Only the prefix given here may satisfy find_package.
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)

if(MODE STREQUAL "find_package")
  set(prefix "${WORK_DIR}/prefix")
  run("installing ${BLURCULL_BUILD}" ${CMAKE_COMMAND} --install "${BLURCULL_BUILD}" --prefix "${prefix}")
  list(APPEND configure_args "-DCMAKE_PREFIX_PATH=${prefix}" "-DBLURCULL_EXPECTED_PREFIX=${prefix}")
elseif(MODE STREQUAL "add_subdirectory")
  list(APPEND configure_args "-DBLURCULL_SOURCE_DIR=${BLURCULL_SOURCE}")
else()
  message(FATAL_ERROR "run_consumer.cmake: MODE must be find_package or add_subdirectory, not '${MODE}'")
endif()

run("configuring the consumer" ${CMAKE_COMMAND} ${configure_args})
run("building the consumer" ${CMAKE_COMMAND} --build "${consumer_build}")
run("running the consumer" "${consumer_build}/blurcull_consumer")
