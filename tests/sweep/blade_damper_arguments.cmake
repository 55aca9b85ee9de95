# blade_damper with a bad numeric value ends before any run with a non-zero status and a message
# naming the option (not the parser's "stod"/"stoi"). -DBLADE_EXE=<blade_damper> -DWORK_DIR=<dir>
# "<arguments>|<expected message>" (refused_arguments.cmake)
set(cases
    "--duration abc|--duration expects a number, got 'abc'"
    "--duration 2x|--duration expects a number, got '2x'"
    "--sweep-duration x|--sweep-duration expects a number, got 'x'"
    "--preload 1N|--preload expects a number, got '1N'"
    "--preloads 1,x|--preloads \\(item 2\\) expects a number, got 'x'"
    "--mu-k abc|--mu-k expects a number, got 'abc'"
    "--rtol 1e-9x|--rtol expects a number, got '1e-9x'"
    "--modes 3.5|--modes expects an integer in .1, "
    "--modes 0|--modes expects an integer in .1, "
    "--platform-elements x|--platform-elements expects an integer in .2, "
    "--threads -1|--threads expects an integer in .0, 1024. .0: all cores., got '-1'"
    "--frc 100:200 --frc-parts 0|--frc-parts expects an integer in .1, ")
include(${CMAKE_CURRENT_LIST_DIR}/refused_arguments.cmake)
expect_refused(${BLADE_EXE} --out ${WORK_DIR}/bad CASES ${cases})
