# CTest glsl_emission: the emitted GLSL holds the headers' formulas, and only
# them (docs/glsl.md, "One source").
#  1. Every function defined with BC_FN in the bodies is defined in
#     blurcull_kernel.glsl.
#  2. Every public one (not bc_-prefixed) is renamed bc_<name> for GLSL by the
#     prelude (`#define <name> bc_<name>`), #undef'd again after the library,
#     and called as bc_<name> by check_kernel.comp, so glslangValidator sees it
#     used under its GLSL name.
#  3. With one definition renamed away (as if deleted from the header), the
#     check shader fails glslangValidator: the build would break.
#  4. The emission made the bodies precise, and check_precise.cmake notices
#     when it did not: with `precise` taken off one declaration (in the
#     prelude's bc_dot) and off the bodies' `if (bc_cond = ...)` conditions, it
#     fails.
cmake_minimum_required(VERSION 3.16)

file(READ "${KERNEL_GLSL}" glsl)
file(READ "${CHECK_GLSL}" check)
# The check main is what follows the library in check_kernel.comp.
string(FIND "${check}" "// ---- end of the blurcull kernel library ----" library_end)
if(library_end LESS 0)
  message(FATAL_ERROR "check_kernel.comp has no end-of-library marker")
endif()
string(SUBSTRING "${check}" ${library_end} -1 check_main)

string(REPLACE "|" ";" body_files "${BODIES}")
set(function_count 0)
set(public_functions "")
foreach(body ${body_files})
  file(READ "${body}" text)
  string(REGEX MATCHALL "BC_FN[ \t\r\n]+[A-Za-z_][A-Za-z_0-9]*[ \t\r\n]+[A-Za-z_][A-Za-z_0-9]*[ \t\r\n]*\\(" definitions "${text}")
  foreach(definition ${definitions})
    string(REGEX REPLACE "^BC_FN[ \t\r\n]+([A-Za-z_][A-Za-z_0-9]*)[ \t\r\n]+([A-Za-z_][A-Za-z_0-9]*).*$" "\\1;\\2" parts "${definition}")
    list(GET parts 0 return_type)
    list(GET parts 1 name)
    math(EXPR function_count "${function_count} + 1")
    if(NOT glsl MATCHES "[ \t\n]${return_type}[ \t]+${name}[ \t]*\\(")
      message(SEND_ERROR "${name} (${body}) is not defined in ${KERNEL_GLSL}")
    endif()
    if(NOT name MATCHES "^bc_")
      list(APPEND public_functions ${name})
      if(NOT glsl MATCHES "\n#define[ \t]+${name}[ \t]+bc_${name}[ \t]*\n")
        message(SEND_ERROR "${name} is public but shaders/glsl/prelude.glsl does not #define it as bc_${name}")
      endif()
      if(NOT glsl MATCHES "\n#undef[ \t]+${name}[ \t]*\n")
        message(SEND_ERROR "${name} is public but the emitted library does not #undef it after the bodies")
      endif()
      if(NOT check_main MATCHES "[^A-Za-z_0-9]bc_${name}[ \t]*\\(")
        message(SEND_ERROR "${name} is public but shaders/glsl/check_kernel.comp does not call bc_${name}")
      endif()
    endif()
  endforeach()
endforeach()
list(LENGTH public_functions public_count)
# The bodies define about 57 functions, 25 of them public; fewer means the
# pattern above stopped matching them.
if(function_count LESS 20 OR public_count LESS 10)
  message(FATAL_ERROR "found only ${function_count} BC_FN functions (${public_count} public) in ${BODIES}")
endif()
message(STATUS "${function_count} BC_FN functions, all in the GLSL; ${public_count} public, all called as bc_<name>: ${public_functions}")

# 3. Delete `covers` (rename its definition, which the prelude's macro then no
#    longer turns into bc_covers) and expect glslangValidator to fail.
string(REGEX REPLACE "BC_FN[ \t]+(precise[ \t]+)?bool[ \t]+covers[ \t]*\\(" "BC_FN bool covers_deleted(" broken "${check}")
if(broken STREQUAL check)
  message(FATAL_ERROR "could not find the definition of covers in ${CHECK_GLSL}")
endif()
file(MAKE_DIRECTORY "${WORK_DIR}")
file(WRITE "${WORK_DIR}/without_covers.comp" "${broken}")
execute_process(COMMAND "${VALIDATOR}" -l "${WORK_DIR}/without_covers.comp"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "glslangValidator accepted the check shader without covers():\n${output}")
endif()
message(STATUS "without covers() glslangValidator fails as it should")

# 4. Every declaration precise: the emitted bodies declare with `precise`, and
#    the SPIR-V check fails on a library where some value is not.
string(REGEX MATCHALL "[ \t(]precise[ \t]+(real|float|vec[234]|bool)[ \t]" precise_declarations "${glsl}")
list(LENGTH precise_declarations precise_count)
if(precise_count LESS 500)
  message(FATAL_ERROR "only ${precise_count} precise declarations in ${KERNEL_GLSL}: the emission no longer makes the bodies precise")
endif()
string(REPLACE "precise float d = a.x * b.x + a.y * b.y;" "float d = a.x * b.x + a.y * b.y;" imprecise "${check}")
string(REPLACE "(bc_cond = " "(" imprecise "${imprecise}")
if(imprecise STREQUAL check)
  message(FATAL_ERROR "could not find bc_dot or the precise conditions in ${CHECK_GLSL}")
endif()
file(WRITE "${WORK_DIR}/imprecise.comp" "${imprecise}")
execute_process(COMMAND "${CMAKE_COMMAND}" -DVALIDATOR=${VALIDATOR} -DSOURCE=${WORK_DIR}/imprecise.comp
                        -DSPIRV=${WORK_DIR}/imprecise.spv -DDISASSEMBLY=${WORK_DIR}/imprecise.spv.txt
                        -DREPORT=${WORK_DIR}/imprecise.txt -P "${CHECK_PRECISE}"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(result EQUAL 0)
  message(FATAL_ERROR "check_precise.cmake accepted a library with imprecise dot products and conditions:\n${output}")
endif()
file(READ "${WORK_DIR}/imprecise.txt" report)
string(REGEX MATCH "^[^\n]*" report_line "${report}")
if(NOT report MATCHES "bc_dot: OpF")
  message(FATAL_ERROR "check_precise.cmake failed without naming bc_dot:\n${report}")
endif()
message(STATUS "${precise_count} precise declarations; without some, check_precise fails as it should: ${report_line}")
