# Renders every built-in scene through every backend, method and cull at a
# small size with `blurcull render`, and compares each PNG's SHA-256 and the
# render's samples_hit with tests/golden/golden_renders.txt, which holds the
# values taken on main before the architecture change (issue 10): a
# restructuring that changes no output keeps this test green. The stochastic
# cases render with `--sampler hashed`, the pattern of those values.
#
#   cmake -DBLURCULL=path/to/blurcull -DEXPECTED=golden_renders.txt -DWORK_DIR=dir
#         [-DBACKENDS=cpu;embree;gl] [-DUPDATE=ON] -P golden_renders.cmake
#
# UPDATE=ON rewrites EXPECTED from the current build (only when an output
# change is intended; say why in the commit). BACKENDS limits the run (the
# sanitizer build skips gl, whose llvmpipe time is spent in Mesa).
cmake_minimum_required(VERSION 3.16)
foreach(var BLURCULL EXPECTED WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "golden_renders.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED BACKENDS)
  set(BACKENDS cpu embree gl)
endif()

set(size 32x24)
set(spp 4)
# scenes|backend|method|cull|extra flags ("-" for none): every backend, method
# and cull on every scene.
set(all hand,car,dragonfly,forest)
set(cases
  "${all}|cpu|stochastic|bbox|-" "${all}|cpu|stochastic|hull|-" "${all}|cpu|stochastic|dualspace|-"
  "${all}|cpu|stochastic|bbox|--occlusion=off" "${all}|cpu|stochastic|hull|--occlusion=off"
  "${all}|cpu|stochastic|clip2|-" "${all}|cpu|stochastic|clip2|--precision=float"
  "${all}|cpu|stochastic|dualspace|--footprint=1"
  "${all}|cpu|interleave|clip2|-" "${all}|cpu|interval|clip2|-" "${all}|cpu|accum|clip2|-"
  "${all}|embree|stochastic|clip2|-"
  "${all}|gl|stochastic|clip2|-"
  "${all}|gl|stochastic|bbox|-" "${all}|gl|stochastic|hull|-" "${all}|gl|stochastic|dualspace|-"
  "${all}|gl|interleave|clip2|-" "${all}|gl|interval|clip2|-" "${all}|gl|accum|clip2|-")

file(MAKE_DIRECTORY ${WORK_DIR})
set(actual "")
set(failures 0)
set(checked 0)
if(NOT UPDATE)
  file(STRINGS ${EXPECTED} expected_lines REGEX "^[^#]")
endif()
foreach(case ${cases})
  string(REPLACE "|" ";" fields "${case}")
  list(GET fields 0 case_scenes)
  list(GET fields 1 backend)
  list(GET fields 2 method)
  list(GET fields 3 cull)
  list(GET fields 4 extra)
  list(FIND BACKENDS ${backend} wanted)
  if(wanted EQUAL -1)
    continue()
  endif()
  string(REPLACE "," ";" case_scenes "${case_scenes}")
  foreach(scene ${case_scenes})
    set(key "${scene} ${backend} ${method} ${cull} ${extra}")
    string(MAKE_C_IDENTIFIER "${key}" file_stem)
    set(png ${WORK_DIR}/${file_stem}.png)
    set(args render --scene ${scene} --backend ${backend} --method ${method} --size ${size} --spp ${spp}
             --seed 7 -q --json -o ${png})
    if(NOT backend STREQUAL "embree" AND method STREQUAL "stochastic")
      list(APPEND args --cull ${cull})
    endif()
    # The stochastic renders are pinned to the pattern the hashes were taken
    # with (the default before --sampler existed; docs/sampling.md), so a new
    # default pattern leaves them provably unchanged.
    if(method STREQUAL "stochastic")
      list(APPEND args --sampler hashed)
    endif()
    if(NOT extra STREQUAL "-")
      list(APPEND args ${extra})
    endif()
    file(REMOVE ${png})
    execute_process(COMMAND ${BLURCULL} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0 OR NOT EXISTS ${png})
      message(SEND_ERROR "${key}: blurcull ${args} failed (exit ${rc}): ${err}")
      math(EXPR failures "${failures} + 1")
      continue()
    endif()
    file(SHA256 ${png} hash)
    string(REGEX MATCH "\"samples_hit\":([0-9]+)" _ "${out}")
    set(hits ${CMAKE_MATCH_1})
    set(line "${key} ${hash} ${hits}")
    string(APPEND actual "${line}\n")
    math(EXPR checked "${checked} + 1")
    if(NOT UPDATE)
      set(found "")
      foreach(expected_line ${expected_lines})
        string(FIND "${expected_line}" "${key} " at)
        if(at EQUAL 0)
          set(found "${expected_line}")
        endif()
      endforeach()
      if(NOT found STREQUAL line)
        message(SEND_ERROR "${key}: got '${hash} ${hits}', expected '${found}' (image ${png})")
        math(EXPR failures "${failures} + 1")
      endif()
    endif()
  endforeach()
endforeach()

if(UPDATE)
  file(WRITE ${EXPECTED} "# scene backend method cull extra-flags png-sha256 samples_hit (tests/golden/golden_renders.cmake)\n${actual}")
  message(STATUS "wrote ${checked} renders to ${EXPECTED}")
elseif(failures GREATER 0)
  message(FATAL_ERROR "${failures} of ${checked} renders differ from ${EXPECTED}")
else()
  message(STATUS "${checked} renders bit-identical to ${EXPECTED}")
endif()
