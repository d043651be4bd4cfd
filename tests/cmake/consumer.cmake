# Builds and runs a consumer project: cmake -DKIND=subdir|installed -DSOURCE=... -DBUILD=... -DWORK=...
#   [-DSANITIZE=-fsanitize=...] [-DFILTER=leak_filter.sh] [-DLAUNCHER=ccache] -P consumer.cmake
# For KIND=installed, dstrans is first installed from BUILD into WORK/prefix. SANITIZE builds the consumer
# with those flags (and, with add_subdirectory, dstrans too); FILTER runs it; LAUNCHER compiles through
# a launcher such as ccache.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message("${out}")
endfunction()

file(REMOVE_RECURSE ${WORK})
set(args -DDSTRANS_SOURCE_DIR=${SOURCE})
if(LAUNCHER)
  list(APPEND args -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
if(SANITIZE)
  list(APPEND args -DCMAKE_CXX_FLAGS=${SANITIZE} -DCMAKE_EXE_LINKER_FLAGS=${SANITIZE})
endif()
if(KIND STREQUAL "installed")
  run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
  list(APPEND args -DCMAKE_PREFIX_PATH=${WORK}/prefix)
endif()
run(${CMAKE_COMMAND} -S ${SOURCE}/tests/consumers/${KIND} -B ${WORK}/build ${args})
run(${CMAKE_COMMAND} --build ${WORK}/build)
run(${FILTER} ${WORK}/build/consumer)
