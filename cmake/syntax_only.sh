#!/bin/sh
# Compiler launcher of the header-hygiene units (tests/packaging/CMakeLists.txt): runs the compile
# command it is given with -fsyntax-only - the header is parsed and checked (declarations,
# templates used by its inline code, warnings as errors) as in a full compile, without generating
# code, which no hygiene unit needs - then creates the (empty) object file the build expects, so
# that the unit counts as built. GCC and Clang both still write the -MD dependency file.
obj=
prev=
for arg in "$@"; do
  if [ "$prev" = "-o" ]; then obj=$arg; fi
  prev=$arg
done
"$@" -fsyntax-only || exit $?
if [ -n "$obj" ]; then : > "$obj"; fi
