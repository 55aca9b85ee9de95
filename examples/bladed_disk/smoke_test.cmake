# ctest's smoke run of the example (examples/bladed_disk/CMakeLists.txt): runs EXE with ARGS
# (a ;-list) into the directory OUT and checks that it exits 0 and writes its three CSV files
# (each with a header and at least one row), that every travelling-wave point of frc.csv converged
# (ok = 1) with a finite, positive tip amplitude (the quick grid lies where the shooting converges
# from the stuck guess: a 0 there is a lost point, not a feature of the disk), and its JSON
# summary, whose mistuning amplification
# (largest blade peak over the tuned disk's, dampers stuck, 2 % stiffness scatter) lies between
# 0.95 and Whitehead's bound (1 + sqrt N) / 2: the peak of a mistuned disk near the tuned one's
# resonance cannot fall far below it for small scatter, and the bound holds for one dominant
# family per blade, as here (measured 1.21 against 1.73 at N = 6). A window that misses the
# tuned resonance gives ratios of thousands.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${EXE}" ${ARGS} --out "${OUT}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "bladed_disk exited with ${rc}")
endif()
foreach(csv frc linear mistuning)
  if(NOT EXISTS "${OUT}/${csv}.csv")
    message(FATAL_ERROR "bladed_disk wrote no ${OUT}/${csv}.csv")
  endif()
  file(STRINGS "${OUT}/${csv}.csv" lines)
  list(LENGTH lines n)
  if(n LESS 2)
    message(FATAL_ERROR "${OUT}/${csv}.csv has ${n} lines (a header and at least one row expected)")
  endif()
endforeach()
# frc.csv: preload,omega,ok,tip,stable,max_multiplier,runs,events,seconds,settled_periods
file(STRINGS "${OUT}/frc.csv" rows)
list(REMOVE_AT rows 0)
foreach(row IN LISTS rows)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 2 ok)
  list(GET fields 3 tip)
  if(NOT ok STREQUAL "1")
    message(FATAL_ERROR "frc.csv: a travelling-wave point did not converge: ${row}")
  endif()
  if(NOT tip MATCHES "^[0-9]" OR NOT tip GREATER 0)
    message(FATAL_ERROR "frc.csv: the tip amplitude is not a positive number: ${row}")
  endif()
endforeach()
if(NOT EXISTS "${OUT}/summary.json")
  message(FATAL_ERROR "bladed_disk wrote no ${OUT}/summary.json")
endif()
file(READ "${OUT}/summary.json" summary)
if(NOT summary MATCHES "\"max_amplification\"")
  message(FATAL_ERROR "${OUT}/summary.json lacks the mistuning summary: ${summary}")
endif()
string(JSON amplification GET "${summary}" mistuning max_amplification)
string(JSON bound GET "${summary}" mistuning whitehead_bound)
if(amplification LESS 0.95 OR amplification GREATER bound)
  message(FATAL_ERROR "mistuning amplification ${amplification} outside [0.95, Whitehead's bound ${bound}]")
endif()
