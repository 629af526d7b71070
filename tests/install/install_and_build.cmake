# CTest: installs the build BUILD into a temporary prefix WORK/prefix, configures and builds the
# consumer project (tests/install/consumer) against it with find_package(mcws), and runs it.
# cmake -DBUILD=... -DWORK=... -DCONSUMER=... -DCXX=... -DCC=... [-DSANITIZE=ON]
#   -P install_and_build.cmake
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix
                OUTPUT_QUIET RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${WORK}/prefix failed (${status})")
endif()
foreach(file lib/cmake/mcws/mcwsConfig.cmake include/mcws/filters/orthant_boundary.h
             include/mcws/io/cloud_io.h bin/mcws_boundary)
  if(NOT EXISTS ${WORK}/prefix/${file})
    message(FATAL_ERROR "the install has no ${file}")
  endif()
endforeach()
file(GLOB_RECURSE private_headers ${WORK}/prefix/include/*/detail/*)
if(private_headers)
  message(FATAL_ERROR "private headers were installed: ${private_headers}")
endif()
set(flags "")
if(SANITIZE)
  # -O1, as the sanitizer build itself: the instrumented PCL templates compile in half the time.
  # EIGEN_MALLOC_ALREADY_ALIGNED=1, as mcws's sanitizer build: Eigen's buffers (the point clouds')
  # are then allocated and freed the same way on both sides (top CMakeLists.txt, MCWS_SANITIZE).
  set(flags "-DCMAKE_CXX_FLAGS=-fsanitize=address,undefined -DEIGEN_MALLOC_ALREADY_ALIGNED=1"
            "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"
            -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined)
endif()
# The tree's own compiler: a library built by clang calls clang's OpenMP runtime, which a GCC
# consumer would not link.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${CONSUMER} -B ${WORK}/consumer
                        -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_C_COMPILER=${CC}
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=Release ${flags}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "configuring the consumer with find_package(mcws) failed (${status})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/consumer RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "building the consumer failed (${status})")
endif()
execute_process(COMMAND ${WORK}/consumer/rim RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the consumer's boundary is wrong (exit ${status})")
endif()
