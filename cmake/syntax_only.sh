#!/bin/sh
# Compiler launcher of the header-hygiene units (tests/packaging/CMakeLists.txt): runs the compile
# command it is given with -fsyntax-only - the header is parsed and checked (declarations,
# templates used by its inline code, warnings as errors) as in a full compile, without generating
# code, which no hygiene unit needs - then creates the (empty) object file the build expects, so
# that the unit counts as built. GCC and Clang both still write the -MD dependency file.
# `syntax_only.sh --cxx <compiler> <build's compiler> <args...>` checks with <compiler> instead
# (STICKSLIP_PACKAGING_CXX: GCC's check of every public header in a build compiled by Clang); the
# build's flags are passed on unchanged, so both compilers must accept them.
if [ "${1:-}" = "--cxx" ]; then
  cxx=$2
  shift 3
  set -- "$cxx" "$@"
fi
obj=
prev=
for arg in "$@"; do
  if [ "$prev" = "-o" ]; then obj=$arg; fi
  prev=$arg
done
"$@" -fsyntax-only || exit $?
if [ -n "$obj" ]; then : > "$obj"; fi
