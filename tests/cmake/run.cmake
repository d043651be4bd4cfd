# Runs one command and checks it: cmake -DCMD="a|b|c" [-DRC=0] [-DMATCH=regex] [-DSTDOUT=file]
#   [-DVALIDATOR=glslangValidator [-DVULKAN=ON]] -P run.cmake
# RC is the exit code it must give (default 0); MATCH a regex its output (stdout and stderr) must match;
# STDOUT a file that receives stdout; VALIDATOR a glslangValidator that must accept that file as a fragment shader
# (with VULKAN, compiled to SPIR-V with Vulkan semantics, which needs an entry point: an empty main is added).
# CTest splits arguments at semicolons, so the command's words come separated by bars.
string(REPLACE "|" ";" CMD "${CMD}")
if(NOT DEFINED RC)
  set(RC 0)
endif()
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL RC)
  message(FATAL_ERROR "exit code ${rc}, expected ${RC}: ${CMD}\n${out}\n${err}")
endif()
if(DEFINED MATCH AND NOT "${out}${err}" MATCHES "${MATCH}")
  message(FATAL_ERROR "output does not match '${MATCH}':\n${out}\n${err}")
endif()
if(DEFINED STDOUT)
  file(WRITE ${STDOUT} "${out}")
  if(DEFINED VALIDATOR)
    set(checked ${STDOUT})
    set(flags -S frag)
    if(VULKAN)
      set(checked ${STDOUT}.main)
      file(WRITE ${checked} "${out}void main() {}\n")
      set(flags -V -S frag -o ${STDOUT}.spv)
    endif()
    execute_process(COMMAND ${VALIDATOR} ${flags} ${checked} RESULT_VARIABLE vrc OUTPUT_VARIABLE vout ERROR_VARIABLE verr)
    if(NOT vrc EQUAL 0)
      message(FATAL_ERROR "glslangValidator rejects ${STDOUT}:\n${vout}\n${verr}")
    endif()
  endif()
endif()
message("ok: ${CMD}")
