# Smoke test of bench_pareto (CTest: bench_pareto_smoke). Runs it on one scene
# at 32x24 with every non-bbox method at 4 and 16 spp, then checks the CSV:
# the expected rows, positive times and errors, and that the stochastic
# renderer's errors fall from 4 to 16 spp. Also checks that the markdown block
# is replaced in place and that a bad option fails with a one-line error.
#
#   cmake -DBENCH_PARETO=path/to/bench_pareto -DWORK_DIR=dir -P smoke_test.cmake
if(NOT BENCH_PARETO OR NOT WORK_DIR)
  message(FATAL_ERROR "pass -DBENCH_PARETO=<binary> -DWORK_DIR=<dir>")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(csv "${WORK_DIR}/pareto.csv")
set(md "${WORK_DIR}/bench.md")
file(WRITE "${md}" "before\n<!-- pareto-table:begin -->\nold table\n<!-- pareto-table:end -->\nafter\n")

set(methods stochastic-clip2 interleave interval accum)
string(REPLACE ";" "," methods_arg "${methods}")
execute_process(
  COMMAND "${BENCH_PARETO}" --size 32x24 --scenes hand --methods ${methods_arg} --spp 4,16
          --repeat 1 --reference-spp 256 --cache "${WORK_DIR}/cache" --csv "${csv}" --markdown "${md}"
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "bench_pareto failed (${result}):\n${errors}")
endif()

file(STRINGS "${csv}" lines)
list(LENGTH lines line_count)
list(GET lines 0 header)
if(NOT header MATCHES "^scene,method,setting,spp,ms,rmse,structured_error,")
  message(FATAL_ERROR "unexpected CSV header: ${header}")
endif()
# One row per method and sample count, plus the header.
if(NOT line_count EQUAL 9)
  message(FATAL_ERROR "expected 8 CSV rows, got ${line_count} lines:\n${lines}")
endif()
list(REMOVE_AT lines 0)
foreach(line IN LISTS lines)
  string(REPLACE "," ";" fields "${line}")
  list(GET fields 0 scene)
  list(GET fields 1 method)
  list(GET fields 3 spp)
  list(GET fields 4 ms)
  list(GET fields 5 rmse)
  list(GET fields 6 structured)
  if(NOT scene STREQUAL "hand")
    message(FATAL_ERROR "unexpected scene in: ${line}")
  endif()
  list(FIND methods "${method}" method_index)
  if(method_index LESS 0 OR NOT (spp EQUAL 4 OR spp EQUAL 16))
    message(FATAL_ERROR "unexpected method or spp in: ${line}")
  endif()
  if(NOT ms GREATER 0 OR NOT rmse GREATER 0 OR NOT structured GREATER 0)
    message(FATAL_ERROR "time and errors must be positive: ${line}")
  endif()
  # Blurring cannot add energy: the blurred error is at most the RMSE.
  if(structured GREATER rmse)
    message(FATAL_ERROR "blurred error above the RMSE: ${line}")
  endif()
  set(seen_${method}_${spp} TRUE)
  set(rmse_${method}_${spp} ${rmse})
  set(structured_${method}_${spp} ${structured})
endforeach()
foreach(method IN LISTS methods)
  foreach(spp 4 16)
    if(NOT seen_${method}_${spp})
      message(FATAL_ERROR "no row for ${method} at ${spp} spp")
    endif()
  endforeach()
endforeach()
if(NOT rmse_stochastic-clip2_16 LESS rmse_stochastic-clip2_4)
  message(FATAL_ERROR "stochastic RMSE did not fall from 4 to 16 spp: "
                      "${rmse_stochastic-clip2_4} -> ${rmse_stochastic-clip2_16}")
endif()
if(NOT structured_stochastic-clip2_16 LESS structured_stochastic-clip2_4)
  message(FATAL_ERROR "stochastic blurred error did not fall from 4 to 16 spp: "
                      "${structured_stochastic-clip2_4} -> ${structured_stochastic-clip2_16}")
endif()

file(READ "${md}" text)
if(NOT text MATCHES "^before\n<!-- pareto-table:begin -->\n.*\\| stochastic-clip2 \\| 4 spp.*<!-- pareto-table:end -->\nafter\n$"
   OR text MATCHES "old table")
  message(FATAL_ERROR "markdown block not replaced in place:\n${text}")
endif()

execute_process(COMMAND "${BENCH_PARETO}" --spp 3
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(result EQUAL 0 OR NOT errors MATCHES "^bench_pareto: error: --spp: [^\n]*square[^\n]*\n$")
  message(FATAL_ERROR "--spp 3 should fail with a one-line error, got (${result}): ${errors}")
endif()
