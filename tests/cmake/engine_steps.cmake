# Runs an engine example at each adoption step and checks that every step writes an image and changes
# the one before: cmake -DEXE=engine_gl -DWORK=dir [-DARGS=--validate] [-DFILTER=leak_filter.sh] -P engine_steps.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
foreach(step 0 1 2 3 4)
  execute_process(COMMAND ${FILTER} ${EXE} ${ARGS} --step ${step} --out ${WORK}/step${step}.png RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/step${step}.png OR "${err}" MATCHES "GL:|validation")
    message(FATAL_ERROR "step ${step} failed (${rc}):\n${out}\n${err}")
  endif()
  if(step GREATER 0)
    math(EXPR before "${step} - 1")
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/step${before}.png ${WORK}/step${step}.png
                    RESULT_VARIABLE same)
    if(same EQUAL 0)
      message(FATAL_ERROR "step ${step} draws the same image as step ${before}")
    endif()
  endif()
endforeach()
message("engine steps: ok")
