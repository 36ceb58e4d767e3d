# CTest install.consumer: installs this build into a prefix inside the build folder, configures and
# builds tests/install/consumer against it (find_package(treesketch), treesketch::treesketch),
# runs it, and runs the installed CLI's --version; with -DPYTHON=<interpreter> (when the build has the
# Python module) also imports the installed module. Run as
#   cmake -DBUILD_DIR=.. -DSOURCE_DIR=.. -DCXX=.. -DLAUNCHER=.. -DVERSION=.. [-DPYTHON=..] -P check_install.cmake
set(root ${BUILD_DIR}/install_test)
set(prefix ${root}/prefix)
file(REMOVE_RECURSE ${root})

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f bin/treesketch include/treesketch/util/error.h lib/libtreesketch.a lib/cmake/treesketch/treesketchConfig.cmake
          lib/cmake/treesketch/treesketchConfigVersion.cmake lib/cmake/treesketch/treesketchTargets.cmake)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install: ${prefix}/${f} is missing")
  endif()
endforeach()

set(launcher "")
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${root}/consumer
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX} ${launcher})
run("build the consumer" ${CMAKE_COMMAND} --build ${root}/consumer)
run("run the consumer" ${root}/consumer/consumer)
message(STATUS "${last_output}")

run("installed treesketch --version" ${prefix}/bin/treesketch --version)
if(NOT last_output MATCHES "^treesketch ${VERSION} \\(git [^)]+\\)")
  message(FATAL_ERROR "installed treesketch --version printed '${last_output}', expected 'treesketch ${VERSION} (git ...)'")
endif()
message(STATUS "installed: ${last_output}")

if(PYTHON)
  # The rule of python/CMakeLists.txt for a prefix other than /usr: lib/python3.X/dist-packages.
  # (Python one-liners without ';', which would split the command's arguments.)
  run("python version" ${PYTHON} -c "print('%d.%d' % __import__('sys').version_info[:2])")
  string(STRIP "${last_output}" pyver)
  set(site ${prefix}/lib/python${pyver}/dist-packages)
  run("import the installed module" ${CMAKE_COMMAND} -E env PYTHONPATH=${site} ${PYTHON} -c
      "print(len(__import__('treesketch').Cloud.from_numpy(__import__('numpy').eye(4, 3))), __import__('treesketch').__file__)")
  if(NOT last_output MATCHES "^4 ${site}/treesketch[.]")
    message(FATAL_ERROR "the installed module printed '${last_output}', expected it from ${site}")
  endif()
  message(STATUS "installed Python module: ${last_output}")
endif()
