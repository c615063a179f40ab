# bash completion for jumpcyl. Commands, and each command's options as its
# own --help lists them (so completion never disagrees with the tool), with
# the values that have names: presets, figure kinds, impact laws, files.
_jumpcyl()
{
    local cur prev cmd words
    cur=${COMP_WORDS[COMP_CWORD]}
    prev=${COMP_WORDS[COMP_CWORD-1]}
    if [ "$COMP_CWORD" -eq 1 ]; then
        COMPREPLY=($(compgen -W "paper predict simulate plot animate sweep mc map design track compare fit presets --help --version" -- "$cur"))
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
        --impact-law)
            COMPREPLY=($(compgen -W "stronge poisson newton" -- "$cur"))
            return ;;
        --loss)
            COMPREPLY=($(compgen -W "linear huber cauchy" -- "$cur"))
            return ;;
        --free)
            # the names fit --help lists under --free, from "): " to "(those its parts have)";
            # the list's earlier names kept before the one completed
            COMPREPLY=($(compgen -P "${cur%"${cur##*,}"}" -W "$("${COMP_WORDS[0]}" fit --help 2>/dev/null |
                awk '/^  --free / {on = 1; sub(/.*\): /, "")} on {s = s " " $0} on && /\(those/ {exit}
                     END {sub(/\(those.*/, "", s); gsub(/and the body.s:/, "", s); gsub(/,/, " ", s); print s}')" \
                -- "${cur##*,}"))
            return ;;
        --track)
            COMPREPLY=($(compgen -f -- "$cur"))
            return ;;
        --axes)
            COMPREPLY=($(compgen -W "level incline" -- "$cur"))
            return ;;
        --json)
            # a file only for track; elsewhere --json takes no value
            if [ "$cmd" = track ]; then COMPREPLY=($(compgen -f -- "$cur")); return; fi ;;
        --output|--config|--csv|--summarize)
            COMPREPLY=($(compgen -f -- "$cur"))
            return ;;
    esac
    if [[ $cur == -* ]]; then
        words=$("${COMP_WORDS[0]}" "$cmd" --help 2>/dev/null | grep -oE -- '--[a-z0-9][a-z0-9-]*' | sort -u)
        COMPREPLY=($(compgen -W "$words" -- "$cur"))
    fi
}
complete -o default -F _jumpcyl jumpcyl
