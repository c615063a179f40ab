# Builds the man page jumpcyl.1 with help2man from the tool's own --help
# texts, so that it can never disagree with them: the top-level help and
# --version make NAME, SYNOPSIS and DESCRIPTION; each command's --help becomes
# a subsection of COMMANDS, verbatim; `jumpcyl params` (the library's
# parameter table) is the section PARAMETERS.
#   cmake -DTOOL=path/to/jumpcyl -DHELP2MAN=path -DOUT=jumpcyl.1 -DWORK=dir -P manpage.cmake
set(commands paper predict simulate plot animate sweep mc map design track compare fit presets params)
set(include "${WORK}/jumpcyl.h2m")
file(WRITE "${include}" "[COMMANDS]\nEach command's options, as `jumpcyl COMMAND --help' prints them.\n")
foreach(cmd ${commands})
  if(cmd STREQUAL "presets")
    execute_process(COMMAND "${TOOL}" presets OUTPUT_VARIABLE text RESULT_VARIABLE rc)
    set(text "Built-in setups (--preset NAME):\n${text}")
  else()
    execute_process(COMMAND "${TOOL}" ${cmd} --help OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  endif()
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "jumpcyl ${cmd} --help exited ${rc}")
  endif()
  # roff: a backslash is \e; a line that starts with . or ' is protected by \&.
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  file(APPEND "${include}" ".SS ${cmd}\n.nf\n${text}.fi\n")
endforeach()
execute_process(COMMAND "${TOOL}" params OUTPUT_VARIABLE text RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "jumpcyl params exited ${rc}")
endif()
string(REPLACE "\\" "\\e" text "${text}")
string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
file(APPEND "${include}" "[PARAMETERS]\n.nf\n${text}.fi\n")
file(APPEND "${include}" "[FILES]\nExperiment files: docs/config.md in the source tree; examples/*.ini.\n"
     "[SEE ALSO]\nThe documentation in the source tree: README.md, docs/cli.md, docs/batch.md, docs/figures.md,\n"
     "docs/physics.md, docs/api.md, docs/tracker.md.\n")
execute_process(COMMAND "${HELP2MAN}" --no-info --no-discard-stderr --section=1
                        "--name=where an off-centre-mass cylinder rolling down an incline jumps"
                        "--include=${include}" --output=${OUT} "${TOOL}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "help2man failed (${rc})")
endif()
