#!/bin/sh
# The installed tree (make install DESTDIR=... PREFIX=/usr/local): the tool
# runs from it without LD_LIBRARY_PATH, `man -l` renders its man page with
# every command, and the bash completion completes commands, options and
# named values. Usage: test_install.sh DESTDIR PREFIX
set -eu
root=$1$2
fail() { echo "FAILED: $*" >&2; exit 1; }
tool=$root/bin/jumpcyl
[ -x "$tool" ] || fail "no $tool"
"$tool" --version | grep -q '^jumpcyl [0-9]' || fail "the installed tool does not run on its own"
"$tool" predict --json > /dev/null || fail "the installed tool cannot predict"
echo "passed: the installed tool runs without LD_LIBRARY_PATH"

man=$root/share/man/man1/jumpcyl.1
[ -f "$man" ] || fail "no man page"
sh "$(dirname "$0")/test_manpage.sh" "$man" "$tool" || fail "the installed man page"

comp=$root/share/bash-completion/completions/jumpcyl
[ -f "$comp" ] || fail "no bash completion"
complete_words() { # the words the completion offers for a command line (last word: the one completed)
  bash -c '. "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _jumpcyl; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$comp" "$@"
}
complete_words "$tool" sw | grep -qx sweep || fail "completion: sw -> sweep"
complete_words "$tool" mc --sa | grep -qx -- --samples || fail "completion: mc --sa -> --samples"
complete_words "$tool" sweep --va | grep -qx -- --vary || fail "completion: sweep --va -> --vary"
complete_words "$tool" simulate --preset ho | grep -qx hoop || fail "completion: --preset ho -> hoop"
complete_words "$tool" plot --what paper-u | grep -qx paper-uncertainty || fail "completion: --what paper-u"
complete_words "$tool" simulate --impact-law n | grep -qx newton || fail "completion: --impact-law n"
complete_words "$tool" fit --free su | grep -qx surface || fail "completion: fit --free su -> surface"
complete_words "$tool" fit --free mu_k,ti | grep -qx mu_k,tilt || fail "completion: fit --free mu_k,ti -> mu_k,tilt"
complete_words "$tool" sweep --vary rod-o | grep -qx rod-offset= || fail "completion: sweep --vary rod-o -> rod-offset="
complete_words "$tool" design --free rod-o | grep -qx rod-offset || fail "completion: design --free rod-o -> rod-offset"
echo "passed: bash completion of commands, options, presets, figure kinds, impact laws, fit's values and parameter names"
echo "3 passed, 0 failed"
