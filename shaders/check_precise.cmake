# Build step (shaders/CMakeLists.txt): the kernel library compiles as Vulkan
# GLSL to SPIR-V, and every floating-point operation of its functions is
# `precise` (docs/glsl.md, "The GPU arithmetic model").
#   cmake -DVALIDATOR=glslangValidator -DSOURCE=check_kernel.comp
#         -DSPIRV=out.spv -DDISASSEMBLY=out.txt -DREPORT=report.txt -P check_precise.cmake
# glslangValidator -V compiles SOURCE (library + check main) for Vulkan 1.0
# and writes glslang's disassembly (-H). In it, every OpFAdd, OpFSub, OpFMul,
# OpFDiv, OpFRem, OpFMod, OpFNegate, OpDot, OpVectorTimesScalar and the
# matrix products inside a function named bc_* (the library: every public
# function is renamed bc_<name>, helpers are bc_* already, the check main's are
# not) must carry the NoContraction decoration that `precise` gives; and no
# such function may call the GLSL.std.450 built-ins whose inner products and
# sums a driver may fuse (Fma, Cross, Length, Distance, Normalize,
# FaceForward, Reflect, Refract): the emission spells dot and cross out. Any
# operation that does not is listed with its function, and the step fails.
cmake_minimum_required(VERSION 3.16)

execute_process(COMMAND "${VALIDATOR}" -V --target-env vulkan1.0 -H -o "${SPIRV}" "${SOURCE}"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the kernel library does not compile as Vulkan GLSL (glslangValidator -V ${SOURCE}):\n${output}")
endif()
file(WRITE "${DISASSEMBLY}" "${output}")

# ';', '[' and ']' (in the names of functions and types) would split CMake's lists.
string(REPLACE ";" "," output "${output}")
string(REPLACE "[" "<" output "${output}")
string(REPLACE "]" ">" output "${output}")

string(REGEX MATCHALL "Decorate [0-9]+ NoContraction" decorations "${output}")
set(precise_ids ",")
foreach(decoration ${decorations})
  string(REGEX REPLACE "Decorate ([0-9]+) NoContraction" "\\1" id "${decoration}")
  string(APPEND precise_ids "${id},")
endforeach()

set(arithmetic "FAdd|FSub|FMul|FDiv|FRem|FMod|FNegate|Dot|VectorTimesScalar|MatrixTimesScalar|VectorTimesMatrix|MatrixTimesVector|MatrixTimesMatrix")
set(fusable_builtins "Fma|Cross|Length|Distance|Normalize|FaceForward|Reflect|Refract")
string(REGEX MATCHALL "[^\n]*\n" lines "${output}")
set(function "")
set(total 0)
set(covered 0)
set(uncovered "")
set(functions 0)
foreach(line IN LISTS lines)
  if(line MATCHES "^ *[0-9]+\\((.*)\\):.* Function (None|Inline|DontInline|Pure|Const)")
    set(function "${CMAKE_MATCH_1}")
    if(function MATCHES "^bc_")
      math(EXPR functions "${functions} + 1")
    endif()
  elseif(NOT function MATCHES "^bc_")
    continue()
  elseif(line MATCHES "^ *([0-9]+): +[^ ]+ +(${arithmetic}) ")
    set(id "${CMAKE_MATCH_1}")
    set(op "${CMAKE_MATCH_2}")
    math(EXPR total "${total} + 1")
    string(FIND "${precise_ids}" ",${id}," at)
    if(at GREATER_EQUAL 0)
      math(EXPR covered "${covered} + 1")
    else()
      string(REGEX REPLACE "\\(.*$" "" name "${function}")
      list(APPEND uncovered "  ${name}: Op${op} %${id} without NoContraction")
    endif()
  elseif(line MATCHES "ExtInst [0-9]+\\(GLSL.std.450\\) [0-9]+\\((${fusable_builtins})\\)")
    string(REGEX REPLACE "\\(.*$" "" name "${function}")
    list(APPEND uncovered "  ${name}: GLSL.std.450 ${CMAKE_MATCH_1}, whose inner arithmetic may be fused")
  endif()
endforeach()

list(LENGTH uncovered uncovered_count)
set(summary "${functions} library functions in SPIR-V (Vulkan 1.0); ${total} floating-point operations, ${covered} NoContraction, ${uncovered_count} not precise")
string(REPLACE ";" "\n" uncovered_text "${uncovered}")
file(WRITE "${REPORT}" "${summary}\n${uncovered_text}\n")
# Fewer means the patterns above stopped matching glslang's listing.
if(functions LESS 100 OR total LESS 500)
  message(FATAL_ERROR "check_precise: found only ${functions} bc_ functions and ${total} operations in ${DISASSEMBLY}")
endif()
if(uncovered_count GREATER 0)
  message(FATAL_ERROR "${summary}:\n${uncovered_text}\n(docs/glsl.md, \"The GPU arithmetic model\": name the value, or avoid the built-in)")
endif()
message(STATUS "${summary}")
