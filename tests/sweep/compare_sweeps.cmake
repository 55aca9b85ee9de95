# Runs the blade sweep with the serial backend and with RANKS (1, 2, 3: MPI ranks; threads: the
# thread backend; blade_damper: the example's own --sweep) and compares sweep.csv (without the
# cpu_seconds column, a measured time) and, except for blade_damper, sweep.json byte for byte.
# The MPI and thread sweeps include a preload of -1 N, which fails (negative damper mass): its row
# must carry the error naming the preload and every other row must be complete. RANKS=resume: see
# below.
set(preloads "-1,1.5,2.1,2.7,3.5,8,26")
set(duration 0.6)  # E over [0, 0.1] s and regimes over the last 0.6 s: every column is exercised
set(out ${WORK_DIR}/${RANKS})
file(REMOVE_RECURSE ${out})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${log}\n${err}")
  endif()
endfunction()

# sweep.csv as lines, the 10th column (cpu_seconds) removed.
# RANKS=help: --help on two ranks prints the usage once (rank 0) and ends normally, every rank
# having finalised MPI (it used to call exit() before MPI_Finalize, which mpirun reports as an
# abnormal end with a non-zero status).
if(RANKS STREQUAL "help")
  execute_process(COMMAND ${MPIEXEC} -np 2 --oversubscribe --allow-run-as-root ${SWEEP_EXE} --help
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "--help on 2 ranks failed (${rc}):\n${log}\n${err}")
  endif()
  string(REGEX MATCHALL "Usage: mpirun" usages "${log}")
  list(LENGTH usages n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "--help on 2 ranks printed the usage ${n} times:\n${log}")
  endif()
  return()
endif()

# RANKS=arguments: bad arguments end the program before any run with a non-zero status and a
# message naming the option; a sweep where every item fails prints no optimum, writes
# "optimum": null and ends with a non-zero status.
if(RANKS STREQUAL "arguments")
  # "<arguments>|<expected message>" (a regex; no brackets: they would hide the list's separators)
  set(cases
      "--sweep-preloads abc|--sweep-preloads \\(item 1\\) expects a number, got 'abc'"
      "--sweep-preloads 1,2x|--sweep-preloads \\(item 2\\) expects a number, got '2x'"
      "--duration inf|--duration must be in .0.5, 1000. s .*got inf"
      "--duration 1e-300|--duration must be in .0.5, 1000. s .*got 1e-300"
      "--modes 0|--modes expects an integer in .1, "
      "--modes 100000|--modes 100000: compute_modes: .*num_modes = 100000 exceeds"
      "--sweep 1:2:3x|--sweep expects lo:hi:count"
      "--sweep 1:inf:3|--sweep expects lo:hi:count"
      "--threads -1|--threads expects an integer in .0, 1024.")
  include(${CMAKE_CURRENT_LIST_DIR}/refused_arguments.cmake)
  set(REFUSED_RUN_STARTED "preloads on")
  expect_refused(${SWEEP_EXE} --backend serial --out ${out}/bad CASES ${cases})
  execute_process(COMMAND ${SWEEP_EXE} --backend serial --sweep-preloads -1,0 --duration ${duration} --out ${out}/none
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  file(READ ${out}/none/sweep.json json)
  if(rc EQUAL 0 OR NOT log MATCHES "sweep optimum: none" OR NOT json MATCHES "\"optimum\": null"
     OR NOT err MATCHES "every preload failed")
    message(FATAL_ERROR "a sweep where every item fails (${rc}):\n${log}\n${err}\n${json}")
  endif()
  return()
endif()

function(read_sweep_csv path var)
  file(STRINGS ${path} lines)
  set(result "")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^([^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,)[^,]*," "\\1" stripped "${line}")
    string(APPEND result "${stripped}\n")
  endforeach()
  set(${var} "${result}" PARENT_SCOPE)
endfunction()

# RANKS=resume: a sweep ended abruptly after 3 rows (--abort-after 3, as a killed job: the process
# ends with _Exit, writing nothing more) whose journal's last line is then cut in half (killed
# while writing it), resumed on 2 MPI ranks: it keeps the 2 whole rows, runs the 5 others only,
# and writes the uninterrupted serial sweep's files. A --resume with other settings is refused.
function(expect_journal_lines path count what)
  file(STRINGS ${path} journal)
  list(LENGTH journal n)
  if(NOT n EQUAL ${count})
    message(FATAL_ERROR "expected ${what} in ${path}, got ${n} lines")
  endif()
endfunction()

if(RANKS STREQUAL "resume")
  set(sweep_args --sweep-preloads ${preloads} --duration ${duration})
  run(${SWEEP_EXE} --backend serial ${sweep_args} --out ${out}/serial)
  execute_process(COMMAND ${SWEEP_EXE} --backend serial ${sweep_args} --abort-after 3 --out ${out}/other
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(rc EQUAL 0 OR EXISTS ${out}/other/sweep.csv)
    message(FATAL_ERROR "--abort-after 3 did not end the sweep early (${rc})")
  endif()
  expect_journal_lines(${out}/other/sweep.journal 4 "the head and 3 rows")
  file(READ ${out}/other/sweep.journal text)
  string(LENGTH "${text}" length)
  math(EXPR cut "${length} - 20")
  string(SUBSTRING "${text}" 0 ${cut} text)
  file(WRITE ${out}/other/sweep.journal "${text}")
  execute_process(COMMAND ${SWEEP_EXE} --backend serial --sweep-preloads ${preloads} --duration 0.7 --resume
                          --out ${out}/other RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "--resume: .*sweep.journal is the journal of another sweep")
    message(FATAL_ERROR "a --resume with another duration was not refused (${rc}): ${err}")
  endif()
  execute_process(COMMAND ${MPIEXEC} -np 2 --oversubscribe --allow-run-as-root ${SWEEP_EXE} ${sweep_args} --resume
                          --out ${out}/other RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT log MATCHES "\\(2 kept from ")
    message(FATAL_ERROR "--resume failed or did not keep the 2 whole rows (${rc}):\n${log}\n${err}")
  endif()
  expect_journal_lines(${out}/other/sweep.journal 8 "the head and 7 rows (none run twice)")
  file(READ ${out}/serial/sweep.json serial_json)
  file(READ ${out}/other/sweep.json other_json)
  if(NOT serial_json STREQUAL other_json)
    message(FATAL_ERROR "sweep.json differs (resumed vs serial):\n${other_json}\n---\n${serial_json}")
  endif()
elseif(RANKS STREQUAL "blade_damper")
  set(sweep_args --sweep 1:30:6 --duration ${duration})
  run(${SWEEP_EXE} --backend serial ${sweep_args} --out ${out}/serial)
  run(${BLADE_EXE} ${sweep_args} --sweep-duration ${duration} --out ${out}/other)
else()
  set(sweep_args --sweep-preloads ${preloads} --duration ${duration})
  run(${SWEEP_EXE} --backend serial ${sweep_args} --out ${out}/serial)
  if(RANKS STREQUAL "threads")
    run(${SWEEP_EXE} --backend threads --threads 3 ${sweep_args} --out ${out}/other)
  else()
    run(${MPIEXEC} -np ${RANKS} --oversubscribe --allow-run-as-root ${SWEEP_EXE} ${sweep_args} --out ${out}/other)
  endif()
  file(READ ${out}/serial/sweep.json serial_json)
  file(READ ${out}/other/sweep.json other_json)
  if(NOT serial_json STREQUAL other_json)
    message(FATAL_ERROR "sweep.json differs (${RANKS} vs serial):\n${other_json}\n---\n${serial_json}")
  endif()
endif()

read_sweep_csv(${out}/serial/sweep.csv serial_csv)
read_sweep_csv(${out}/other/sweep.csv other_csv)
if(NOT serial_csv STREQUAL other_csv)
  message(FATAL_ERROR "sweep.csv differs (${RANKS} vs serial, cpu_seconds removed):\n${other_csv}\n---\n${serial_csv}")
endif()
file(STRINGS ${out}/other/sweep.csv rows)
list(LENGTH rows n)
if(NOT RANKS STREQUAL "blade_damper")
  # 7 items + header; the -1 N row holds the error, the others end with an empty error cell.
  if(NOT n EQUAL 8)
    message(FATAL_ERROR "expected 8 lines in sweep.csv, got ${n}")
  endif()
  list(GET rows 1 failed)
  if(NOT failed MATCHES "^-1,,,,,,,,,,,,\"preload_N = -1: a preload must be finite and > 0 .*\"$")
    message(FATAL_ERROR "the -1 N row does not carry its error: ${failed}")
  endif()
  list(SUBLIST rows 2 -1 good)
  foreach(row IN LISTS good)
    string(REGEX MATCHALL "," commas "${row}")
    list(LENGTH commas cells)
    if(NOT cells EQUAL 12 OR NOT row MATCHES "^[0-9.]+,[-+.e0-9na]+,[a-z /-]+,.*[0-9],$")
      message(FATAL_ERROR "incomplete row (13 cells, the error cell empty): ${row}")
    endif()
  endforeach()
endif()
message(STATUS "${RANKS}: ${n} lines of sweep.csv identical to the serial sweep's")
