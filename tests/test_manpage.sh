#!/bin/sh
# The man page (cmake/manpage.cmake) as man renders it: its sections in
# order, every command's subsection, and the option sets every command
# shares printed once (SETUP OPTIONS, with every parameter of `jumpcyl
# params`; SIMULATION OPTIONS), not once per command.
# Usage: test_manpage.sh PAGE JUMPCYL
set -eu
page_file=$1
tool=$2
fail() { echo "FAILED: $*" >&2; exit 1; }
[ -f "$page_file" ] || fail "no man page $page_file"
page=$(MANWIDTH=100 man -l "$page_file" 2> /dev/null) || fail "man -l failed"
lines() { printf '%s\n' "$page" | grep -c -- "$1" || true; }

expected="NAME SYNOPSIS DESCRIPTION COMMANDS SETUP_OPTIONS SIMULATION_OPTIONS EXIT_STATUS ENVIRONMENT FILES EXAMPLES SEE_ALSO"
found=$(printf '%s\n' "$page" | grep '^[A-Z][A-Z ]*$' | tr ' ' _ | tr '\n' ' ' | sed 's/ $//')
[ "$found" = "$expected" ] || fail "sections: '$found', expected '$expected'"

for cmd in paper predict simulate plot animate sweep mc map design track compare fit presets params; do
  printf '%s\n' "$page" | grep -qx "   $cmd" || fail "no subsection for the command $cmd"
done
printf '%s\n' "$page" | grep -q -- "--vary NAME=START:STOP:STEP" || fail "sweep's options are missing"

[ "$(lines 'Setup options (a plain number')" = 1 ] || fail "the setup options' introduction is not there once"
[ "$(lines '^       --preset NAME')" = 1 ] || fail "--preset is not listed once"
[ "$(lines '^       --t-max T')" = 1 ] || fail "--t-max is not listed once"
for name in $("$tool" params | sed -n 's/^\([a-z][a-z0-9-]*\)  .*/\1/p'); do
  [ "$(lines "^       --$name\( \|$\)")" = 1 ] || fail "the parameter --$name is not listed once"
done
echo "passed: the man page's sections, commands and shared options ($(printf '%s\n' "$page" | wc -l) lines)"
