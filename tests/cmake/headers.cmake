# Fails if a public header pulls in anything but dstrans, GLM and the C++ standard library (DESIGN.md
# principle 2): cmake -DCXX=... -DINCLUDE=... -DTU=... -P headers.cmake
execute_process(COMMAND ${CXX} -std=c++17 -M -I${INCLUDE} ${TU} RESULT_VARIABLE rc OUTPUT_VARIABLE deps ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "could not list the headers' dependencies:\n${err}")
endif()
string(REGEX MATCHALL "[^ \\\n]+\\.h[p]*" files "${deps}")
foreach(f ${files})
  if(f MATCHES "/(GL|GLES[0-9]*|EGL|KHR|vulkan|glslang|spirv_cross|GLFW)/")
    message(FATAL_ERROR "a public header includes a graphics-API header: ${f}")
  endif()
endforeach()
list(LENGTH files n)
message("${n} headers checked: dstrans, GLM and the standard library only")
