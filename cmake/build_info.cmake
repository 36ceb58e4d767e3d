# Writes the CLI's build_info.cpp with the project version and `git describe --always --dirty`
# ("unknown" without git or outside a checkout). Run at every build as a script
# (cmake -DSOURCE_DIR=.. -DTEMPLATE=.. -DOUTPUT=.. -DTS_VERSION=.. -P build_info.cmake);
# configure_file leaves OUTPUT untouched when nothing changed, so nothing recompiles then.
set(TS_GIT_REVISION "unknown")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --always --dirty
                  WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE _rev OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE _rc ERROR_QUIET)
  if(_rc EQUAL 0 AND NOT _rev STREQUAL "")
    set(TS_GIT_REVISION "${_rev}")
  endif()
endif()
configure_file("${TEMPLATE}" "${OUTPUT}" @ONLY)
