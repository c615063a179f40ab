# bash completion for jumpcyl. Commands, and each command's options as its
# own --help lists them (so completion never disagrees with the tool), with
# the values that have names: presets, figure kinds, files, and from the
# parameter table ('jumpcyl params'): the choices of a name-valued parameter
# (--impact-law) and the parameter names of sweep --vary, mc --sigma/--range,
# map --x/--y (numeric ones) and design --free (those design --help lists),
# and fit --free's names as fit --help lists them. Every output option takes a
# FILE (- is standard output): files are offered.
_jumpcyl()
{
    local cur prev cmd words
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD-1]}
    if [ "$COMP_CWORD" -eq 1 ]; then
        COMPREPLY=($(compgen -W "paper predict simulate plot animate sweep mc map design track compare fit presets params --help --version" -- "$cur"))
        return
    fi
    cmd=${COMP_WORDS[1]}
    case $prev in
        --preset)
            COMPREPLY=($(compgen -W "$("${COMP_WORDS[0]}" presets 2>/dev/null | awk '{print $1}')" -- "$cur"))
            return ;;
        --what)
            COMPREPLY=($(compgen -W "$("${COMP_WORDS[0]}" plot --help 2>/dev/null |
                awk '/--what KIND/ {on = 1; next} on && /^    [a-z]/ {print $1} on && /^  --output/ {exit}')" -- "$cur"))
            return ;;
        --vary|--sigma|--range|--x|--y)
            # NAME= for the parameters of 'jumpcyl params' (sweep --vary, mc --sigma/--range,
            # map --x/--y; fit's --sigma and design's --range take values); after the '=', nothing
            case "$cmd:$prev" in
                sweep:--vary|mc:--sigma|mc:--range|map:--x|map:--y) ;;
                *) return ;;
            esac
            if [[ $cur != *=* ]]; then
                # a map axis is numeric: not the name-valued rows ("impact-law  name: ...")
                COMPREPLY=($(compgen -S = -W "$("${COMP_WORDS[0]}" params 2>/dev/null |
                    awk -v axis="$([ "$cmd" = map ] && echo 1)" '/^[a-z][a-z0-9-]*  / && !(axis && $2 == "name:") {print $1}')" -- "$cur"))
                compopt -o nospace 2>/dev/null
            fi
            return ;;
        --loss)
            COMPREPLY=($(compgen -W "linear huber cauchy" -- "$cur"))
            return ;;
        --free)
            if [ "$cmd" = design ]; then
                # the parameters design --help lists on the lines after "the option to choose,
                # one of", up to the line that begins with "(" (those it cannot free)
                COMPREPLY=($(compgen -W "$("${COMP_WORDS[0]}" design --help 2>/dev/null |
                    awk '/the option to choose, one of/ {on = 1; next} on && /^ *\(/ {exit}
                         on {gsub(/,/, " "); print}')" -- "$cur"))
                return
            fi
            [ "$cmd" = fit ] || return
            # the names fit --help lists under --free, from "): " to "(those its parts have)";
            # the list's earlier names kept before the one completed
            COMPREPLY=($(compgen -P "${cur%"${cur##*,}"}" -W "$("${COMP_WORDS[0]}" fit --help 2>/dev/null |
                awk '/^  --free / {on = 1; sub(/.*\): /, "")} on {s = s " " $0} on && /\(those/ {exit}
                     END {sub(/\(those.*/, "", s); gsub(/and the +body.s:/, "", s); gsub(/,/, " ", s); print s}')" \
                -- "${cur##*,}"))
            return ;;
        --track)
            COMPREPLY=($(compgen -f -- "$cur"))
            return ;;
        --axes)
            COMPREPLY=($(compgen -W "level incline" -- "$cur"))
            return ;;
        --output|--config|--csv|--json|--figure|--summarize)
            COMPREPLY=($(compgen -f -- "$cur"))
            return ;;
    esac
    # a parameter whose value is one of its names (--impact-law): the names 'jumpcyl params' lists
    if [[ $prev == --?* ]]; then
        local choices
        choices=$("${COMP_WORDS[0]}" params 2>/dev/null |
            awk -v n="${prev#--}" '$1 == n && $2 == "name:" {sub(/^[^:]*: /, ""); gsub(/,/, ""); print; exit}')
        if [ -n "$choices" ]; then
            COMPREPLY=($(compgen -W "$choices" -- "$cur"))
            return
        fi
    fi
    if [[ $cur == -* ]]; then
        words=$("${COMP_WORDS[0]}" "$cmd" --help 2>/dev/null | grep -oE -- '--[a-z0-9][a-z0-9-]*' | sort -u)
        COMPREPLY=($(compgen -W "$words" -- "$cur"))
    fi
}
complete -o default -F _jumpcyl jumpcyl
