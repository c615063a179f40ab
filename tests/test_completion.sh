#!/bin/bash
# The bash completion (completions/jumpcyl.bash) sourced in bash and run on
# command lines: what COMPREPLY offers after --free, --vary, --x, --y, --sigma,
# --range, the output options and an option's prefix, against the names the
# tool itself accepts (jumpcyl params, design --help, fit --help).
# usage: test_completion.sh COMPLETION_FILE JUMPCYL
COMPLETION=$1
TOOL=$2
. "$COMPLETION" || exit 1
failed=0

# complete WORD...: COMPREPLY for the words after "jumpcyl", the last one
# being completed, one entry per line in $reply
complete_words() {
    COMP_WORDS=("$TOOL" "$@")
    COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
    COMPREPLY=()
    _jumpcyl 2>/dev/null
    reply=$(printf '%s\n' "${COMPREPLY[@]}")
}

# offers "LINE" WORD...: the completion of the words offers WORD
offers() {
    local line=$1 w
    shift
    for w in "$@"; do
        if ! grep -qxF -- "$w" <<<"$reply"; then
            echo "FAIL: 'jumpcyl $line' does not offer '$w'; it offers: $(tr '\n' ' ' <<<"$reply")"
            failed=1
        fi
    done
}

# lacks "LINE" WORD...: the completion does not offer WORD
lacks() {
    local line=$1 w
    shift
    for w in "$@"; do
        if grep -qxF -- "$w" <<<"$reply"; then
            echo "FAIL: 'jumpcyl $line' offers '$w'"
            failed=1
        fi
    done
}

# design --free: exactly the names design --help lists as choices, not fit's.
complete_words design --free ""
offers "design --free " rod-offset incline mu-k radius
lacks "design --free " mark-angle tilt restitution impact-law rod_offset
design_names=$("$TOOL" design --help | awk '/the option to choose, one of/ {on = 1; next}
    on && /^ *\(/ {exit} on {gsub(/,/, " "); print}' | tr -s ' ' '\n' | grep . | sort)
if [ "$(sort <<<"$reply")" != "$design_names" ]; then
    echo "FAIL: design --free offers $(tr '\n' ' ' <<<"$reply") but design --help lists $(tr '\n' ' ' <<<"$design_names")"
    failed=1
fi
complete_words design --free "rod-o"
offers "design --free rod-o" rod-offset

# fit --free: fit's names, in the options' spelling, the list's head kept.
complete_words fit --free ""
offers "fit --free " mu-s mu-k restitution mark-angle theta0 rod-offset x0
lacks "fit --free " mu_k mark_angle rod_offset and the "body's:"
complete_words fit --free "mu-s,mu-"
offers "fit --free mu-s,mu-" mu-s,mu-k
lacks "fit --free mu-s,mu-" mu-s,restitution

# --vary, --sigma, --range, --x, --y: the table's names, each with '='.
complete_words sweep --vary "mu"
offers "sweep --vary mu" mu= mu-s= mu-k=
lacks "sweep --vary mu" mu_k=
complete_words mc --sigma "rod-o"
offers "mc --sigma rod-o" rod-offset=
complete_words mc --range "inc"
offers "mc --range inc" incline=
complete_words map --x ""
offers "map --x " incline= rod-offset= mu-k=
lacks "map --x " impact-law=   # an axis is numeric (map refuses a name-valued one)
complete_words map --y "rod-"
offers "map --y rod-" rod-mass= rod-offset= rod-radius=
every=$("$TOOL" params | awk '/^[a-z][a-z0-9-]*  / {print $1 "="}' | sort)
complete_words sweep --vary ""
if [ "$(sort <<<"$reply")" != "$every" ]; then
    echo "FAIL: sweep --vary offers $(tr '\n' ' ' <<<"$reply") but jumpcyl params lists $(tr '\n' ' ' <<<"$every")"
    failed=1
fi
# after the '=' nothing (values), and not where the option takes a value
complete_words sweep --vary "incline="
[ -z "$reply" ] || { echo "FAIL: 'sweep --vary incline=' offers $reply"; failed=1; }
complete_words fit --sigma ""
[ -z "$reply" ] || { echo "FAIL: 'fit --sigma ' (a length) offers $reply"; failed=1; }
complete_words design --range ""
[ -z "$reply" ] || { echo "FAIL: 'design --range ' (LO:HI) offers $reply"; failed=1; }

# Every output option takes a FILE: files are offered (here, in a scratch directory).
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
cd "$dir" || exit 1
touch results.json rows.csv
for cmd_opt in "paper --json" "predict --json" "simulate --json" "mc --json" "params --json" "design --json" \
               "track --json" "simulate --csv" "design --csv" "design --figure" "sweep --output"; do
    # shellcheck disable=SC2086
    complete_words $cmd_opt "r"
    offers "$cmd_opt r" results.json rows.csv
done

# An option by its prefix; a name-valued parameter's choices.
complete_words simulate "--incl"
offers "simulate --incl" --incline
complete_words paper "--js"
offers "paper --js" --json
complete_words simulate --impact-law ""
offers "simulate --impact-law " stronge poisson newton

[ $failed = 0 ] && echo "completion: every case as expected"
exit $failed
