# Builds the man page jumpcyl.1 with help2man from the tool's own texts, so
# that it can never disagree with them: the top-level help and --version
# make NAME, SYNOPSIS and DESCRIPTION; each command's --help, without the
# option sets every command shares, is a subsection of COMMANDS, verbatim;
# the shared sets appear once: SETUP OPTIONS (the setup options' help, each
# parameter with its unit, range, file key and presets' values from
# `jumpcyl params`) and SIMULATION OPTIONS. Then EXIT STATUS, ENVIRONMENT,
# FILES, EXAMPLES and SEE ALSO (help2man orders the sections).
#   cmake -DTOOL=path/to/jumpcyl -DHELP2MAN=path -DOUT=jumpcyl.1 -DWORK=dir -P manpage.cmake
set(commands paper predict simulate plot animate sweep mc map design track compare fit presets params)
# Where the shared sets start in a command's --help (cli_setup_help, cli_sim_help).
set(setup_head "Setup options (a plain number is SI")
set(sim_head "Simulation options:")

function(run_tool out)
  execute_process(COMMAND "${TOOL}" ${ARGN} OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "jumpcyl ${ARGN} exited ${rc}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# roff: a backslash is \e; a line that starts with . or ' (a request) or [
# (a section of help2man's include file) is protected by \&.
function(roff_text out text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'[])" "\\1\\\\&\\2" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Splits a command's --help at the shared sets: its own part, and the two
# sets (empty when it has none).
function(split_help text own_out sim_out setup_out)
  set(own "${text}")
  set(sim "")
  set(setup "")
  string(FIND "${own}" "\n${setup_head}" at)
  if(at GREATER -1)
    math(EXPR from "${at} + 1")
    string(SUBSTRING "${own}" ${from} -1 setup)
    string(SUBSTRING "${own}" 0 ${from} own)
  endif()
  string(FIND "${own}" "\n${sim_head}" at)
  if(at GREATER -1)
    math(EXPR from "${at} + 1")
    string(SUBSTRING "${own}" ${from} -1 sim)
    string(SUBSTRING "${own}" 0 ${from} own)
  endif()
  string(REGEX REPLACE "\n+$" "\n" own "${own}")
  string(REGEX REPLACE "\n+$" "\n" sim "${sim}")
  set(${own_out} "${own}" PARENT_SCOPE)
  set(${sim_out} "${sim}" PARENT_SCOPE)
  set(${setup_out} "${setup}" PARENT_SCOPE)
endfunction()

# The lines of a text as a list. CMake's lists take ';' as separators and
# no ';' within square brackets, so both are stood in for here and given
# back by line_text.
function(text_lines out text)
  string(REPLACE ";" "<semicolon>" text "${text}")
  string(REPLACE "[" "<lbracket>" text "${text}")
  string(REPLACE "]" "<rbracket>" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()
function(line_text out line)
  string(REPLACE "<semicolon>" ";" line "${line}")
  string(REPLACE "<lbracket>" "[" line "${line}")
  string(REPLACE "<rbracket>" "]" line "${line}")
  set(${out} "${line}" PARENT_SCOPE)
endfunction()

# An option part of a help entry ("--rtol X, --atol X") as roff: the
# options bold (with \- so that they copy as minus signs), their arguments
# italic.
function(roff_option_part out text)
  roff_text(text "${text}")
  string(REGEX REPLACE "(^| )(-[^ ,]*)" "\\1\\\\fB\\2\\\\fR" text "${text}")
  string(REGEX REPLACE "(^| )([A-Z][A-Z0-9_:=]*(,\\.\\.\\.)?)" "\\1\\\\fI\\2\\\\fR" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# The entries of a help block ("  --name ARG   what it does", continued on
# lines indented to the description's column) as roff .TP paragraphs; a
# line of text outside an entry is a paragraph of its own. Sets <out> to
# the roff, and <out>_ARG_<name> to each option's argument ("" for a flag).
function(help_entries out text)
  text_lines(lines "${text}")
  # The description's column: where the continuation lines start.
  set(col 0)
  foreach(line IN LISTS lines)
    if(line MATCHES "^(     +)[^ ]")
      string(LENGTH "${CMAKE_MATCH_1}" indent)
      if(col EQUAL 0 OR indent LESS col)
        set(col ${indent})
      endif()
    endif()
  endforeach()
  set(roff "")
  set(in_entry 0)
  foreach(line IN LISTS lines)
    line_text(line "${line}")
    string(LENGTH "${line}" n)
    if(line MATCHES "^  -")
      set(option "${line}")
      set(desc "")
      if(col GREATER 0 AND n GREATER col)
        math(EXPR before "${col} - 1")
        string(SUBSTRING "${line}" ${before} 1 gap)
        if(gap STREQUAL " ")
          string(SUBSTRING "${line}" 0 ${col} option)
          string(SUBSTRING "${line}" ${col} -1 desc)
        endif()
      endif()
      string(STRIP "${option}" option)
      # Each option's argument: the word after it, when it is no option.
      string(REPLACE ", " ";" parts "${option}")
      foreach(part IN LISTS parts)
        if(part MATCHES "^--?([^ ]+)( (.*))?$")
          set(${out}_ARG_${CMAKE_MATCH_1} "${CMAKE_MATCH_3}" PARENT_SCOPE)
        endif()
      endforeach()
      roff_option_part(o "${option}")
      roff_text(d "${desc}")
      string(APPEND roff ".TP\n${o}\n")
      if(NOT desc STREQUAL "")
        string(APPEND roff "${d}\n")
      endif()
      set(in_entry 1)
    elseif(in_entry AND line MATCHES "^ +(.*)$")
      roff_text(d "${CMAKE_MATCH_1}")
      string(APPEND roff "${d}\n")
    elseif(line STREQUAL "")
      set(in_entry 0)
    else()
      string(STRIP "${line}" line)
      roff_text(d "${line}")
      if(in_entry OR NOT roff MATCHES "(^|\n)[^.\n][^\n]*\n$")
        string(APPEND roff ".PP\n")
      endif()
      string(APPEND roff "${d}\n")
      set(in_entry 0)
    endif()
  endforeach()
  set(${out} "${roff}" PARENT_SCOPE)
endfunction()

# ---- the commands, each without the shared sets ----
set(include "${WORK}/jumpcyl.h2m")
file(WRITE "${include}" "[COMMANDS]\nEach command's own options, as `jumpcyl COMMAND --help' prints them; the "
     "setup and simulation options every command takes follow in SETUP OPTIONS and SIMULATION OPTIONS.\n")
set(ref_sim "")
set(ref_setup "")
foreach(cmd ${commands})
  if(cmd STREQUAL "presets")
    run_tool(text presets)
    set(text "Built-in setups (--preset NAME):\n${text}")
  else()
    run_tool(text ${cmd} --help)
  endif()
  split_help("${text}" own sim setup)
  # The sets are the same in every command, or the page would hide a difference.
  foreach(set sim setup)
    if(NOT "${${set}}" STREQUAL "")
      if("${ref_${set}}" STREQUAL "")
        set(ref_${set} "${${set}}")
        set(ref_${set}_from ${cmd})
      elseif(NOT "${${set}}" STREQUAL "${ref_${set}}")
        message(FATAL_ERROR "jumpcyl ${cmd} --help: its ${set} options differ from ${ref_${set}_from}'s; "
                            "the man page shows them once")
      endif()
    endif()
  endforeach()
  roff_text(own "${own}")
  file(APPEND "${include}" ".SS ${cmd}\n.nf\n${own}.fi\n")
endforeach()
if(ref_setup STREQUAL "" OR ref_sim STREQUAL "")
  message(FATAL_ERROR "no command's --help has the setup or simulation options")
endif()

# ---- SETUP OPTIONS: the help's own entries (--preset, --config,
# --dump-config, --part), then each parameter of the table with its help,
# unit and range, file key and presets' values (`jumpcyl params`) and the
# help's argument name ----
run_tool(params_text params)
text_lines(params_lines "${params_text}")
set(param_names "")
set(name "")
foreach(line IN LISTS params_lines)
  line_text(line "${line}")
  if(line MATCHES "^([a-z][a-z0-9-]*)  +(.*)$")
    set(name "${CMAKE_MATCH_1}")
    list(APPEND param_names "${name}")
    set(param_${name}_range "${CMAKE_MATCH_2}")
    set(row 1)
  elseif(name AND line MATCHES "^ +(.*)$")
    if(row EQUAL 1)
      set(param_${name}_help "${CMAKE_MATCH_1}")
    else()
      set(param_${name}_file "${CMAKE_MATCH_1}")
    endif()
    math(EXPR row "${row} + 1")
  endif()
endforeach()
if(NOT param_names)
  message(FATAL_ERROR "jumpcyl params listed no parameter")
endif()
# The help up to its first parameter's entry: the introduction and the
# options of its own.
list(GET param_names 0 first)
string(FIND "${ref_setup}" "\n  --${first} " at)
if(at LESS 0)
  message(FATAL_ERROR "the setup options' help has no --${first}")
endif()
string(SUBSTRING "${ref_setup}" 0 ${at} own_setup)
help_entries(own_roff "${own_setup}\n")
help_entries(all_roff "${ref_setup}")
set(setup_section "${own_roff}")
string(APPEND setup_section ".PP\nThe setup's parameters (`jumpcyl params'): each is also an experiment-file key "
       "([section] key) and a name for sweep \\-\\-vary, mc \\-\\-sigma/\\-\\-range, map \\-\\-x/\\-\\-y and design "
       "\\-\\-free. Under each: its quantity and the unit shown, its range; its file key and each preset's value.\n")
foreach(name IN LISTS param_names)
  if(NOT DEFINED all_roff_ARG_${name})
    message(FATAL_ERROR "the parameter ${name} has no option in the setup options' help")
  endif()
  roff_option_part(o "--${name} ${all_roff_ARG_${name}}")
  roff_text(h "${param_${name}_help}")
  roff_text(r "${param_${name}_range}")
  roff_text(f "${param_${name}_file}")
  string(APPEND setup_section ".TP\n${o}\n${h}\n.br\n${r}\n.br\n${f}\n")
endforeach()
file(APPEND "${include}" "[SETUP OPTIONS]\n${setup_section}")

# ---- SIMULATION OPTIONS ----
# (Without its head line. CMake's REGEX REPLACE finds "^" again after each
# match, so the line is cut at its end instead.)
string(FIND "${ref_sim}" "\n" at)
math(EXPR at "${at} + 1")
string(SUBSTRING "${ref_sim}" ${at} -1 sim_entries)
help_entries(sim_roff "${sim_entries}")
file(APPEND "${include}" "[SIMULATION OPTIONS]\nThe commands that run the full model (their usage line says "
     "[SIMULATION OPTIONS]) take these too.\n${sim_roff}")

file(APPEND "${include}" [=[
[EXIT STATUS]
.TP
.B 0
success (also after \-\-help and \-\-version)
.TP
.B 1
failure: a numerical method failed, memory ran out, or an output (standard output, a CSV, a figure, a film) could not be written; the previous file is left as it was
.TP
.B 2
bad usage or input: an unknown command or option, a repeated option, a bad number or unit, an invalid setup, an unreadable or malformed experiment file, a figure or film over its budget; nothing is written
.TP
.B 3
fit only: the model does not describe the video (\-\-allow\-misfit makes it 0)
.TP
.B 128 + N
stopped by signal N: 129 SIGHUP, 130 SIGINT, 131 SIGQUIT, 141 SIGPIPE (quietly: the reader of standard output went away), 143 SIGTERM; no output file is left half-written
[ENVIRONMENT]
.TP
.B PATH
where gnuplot (figures) and ffmpeg (films) are found
.TP
.B TMPDIR
where the private scratch directories of gnuplot and ffmpeg are made (default /tmp)
[FILES]
.TP
.I FILE.ini
an experiment file (\-\-config FILE, \-\-dump\-config): the setup in sections and keys (docs/config.md; examples/*.ini in the source tree)
.TP
.I jumpcyl.tmp\-XXXXXX
beside each output file while it is written; checked, synced and renamed over the target, or removed
.TP
.I FILE.part
the rows of sweep and mc \-\-output FILE while the job runs; \-\-resume continues it, and it becomes FILE when complete
.TP
.I $TMPDIR/jumpcyl\-COMMAND\-XXXXXX
the scratch directory where gnuplot and ffmpeg run, removed at the end or on a signal
.TP
.I STEM.gp
plot \-\-keep\-script: the figure's gnuplot script beside it, its data inside
[EXAMPLES]
.TP
.B jumpcyl paper
the paper's Table 1 recomputed and compared with its measurements
.TP
.B jumpcyl predict \-\-incline 15deg \-\-mu 0.4 \-\-json
the three models for one setup, as JSON
.TP
.B jumpcyl simulate \-\-preset hoop
every event of the hopping hoop's motion
.TP
.B jumpcyl simulate \-\-sample\-dt 0.01 \-\-csv run.csv
the trajectory every 10 ms into run.csv
.TP
.B jumpcyl predict \-\-preset hoop \-\-omega0 8 \-\-dump\-config > hoop.ini
a setup as an experiment file, to edit and run with \-\-config hoop.ini
.TP
.B jumpcyl plot \-\-incline 30 \-\-what overview \-\-output fig.png
the paper's criterion, forces, gap and energy on one page
.TP
.B jumpcyl animate \-\-incline 45 \-\-output jump.mp4
a film of the jump, forces to scale
.TP
.B jumpcyl sweep \-\-vary incline=10:60:1 \-\-vary mu=0.3,0.5,1 \-\-output grid.csv
a grid of runs on every core, one CSV row each
.TP
.B jumpcyl mc \-\-incline 30 \-\-samples 100000
how sure the first lift-off is, given the inputs' uncertainties
.TP
.B jumpcyl design \-\-jump\-at 1.20m \-\-free rod\-offset \-\-incline 20
the rod offsets that make it first lift off 1.20 m down the ramp
.TP
.B jumpcyl fit \-\-track video.trk \-\-free mu_s,mu_k,restitution
friction and restitution fitted to a video tracked with Tracker, with a verdict
[SEE ALSO]
.BR gnuplot (1),
.BR ffmpeg (1).
The documentation in the source tree: README.md, docs/cli.md (every option, the JSON and CSV fields),
docs/config.md, docs/figures.md, docs/batch.md, docs/design.md, docs/tracker.md, docs/physics.md,
docs/api.md, docs/python.md.
]=])
execute_process(COMMAND "${HELP2MAN}" --no-info --no-discard-stderr --section=1
                        "--name=where an off-centre-mass cylinder rolling down an incline jumps"
                        "--include=${include}" --output=${OUT} "${TOOL}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "help2man failed (${rc})")
endif()
