# Man pages of handlab and handlab-cli and handlab-cli's bash completion, written from the
# programs' own --help at build time, so that they say what the programs do.
#   cmake -DCLI=... -DGUI=... -DVERSION=... -DOUT=DIR -P cli_docs.cmake
# writes DIR/handlab-cli.1, DIR/handlab.1 and DIR/handlab-cli.bash.

function(run_help out)
  execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE text ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN} failed (${rc}): ${err}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Roff for literal text: backslashes and leading dots or quotes escaped, kept as written.
function(roff_literal out text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# The options a --help lists ("  --name ...").
function(help_options out text)
  string(REGEX MATCHALL "\n  --[a-z0-9-]+" found "\n${text}")
  set(options "")
  foreach(f IN LISTS found)
    string(STRIP "${f}" f)
    list(APPEND options "${f}")
  endforeach()
  list(REMOVE_DUPLICATES options)
  set(${out} "${options}" PARENT_SCOPE)
endfunction()

# The subcommands a command's --help names ("Usage: handlab-cli CMD SUB ...").
function(help_subcommands out command text)
  string(REGEX MATCHALL "handlab-cli ${command} [a-z]+" found "${text}")
  set(subs "")
  foreach(f IN LISTS found)
    string(REGEX REPLACE "^handlab-cli ${command} " "" f "${f}")
    list(APPEND subs "${f}")
  endforeach()
  list(REMOVE_DUPLICATES subs)
  set(${out} "${subs}" PARENT_SCOPE)
endfunction()

string(TIMESTAMP month "%B %Y" UTC)
run_help(main "${CLI}" --help)
string(REGEX MATCH "Commands:\n\n(.*)\n\n'" _ "${main}")
string(REGEX MATCHALL "\n  [a-z]+ " names "\n${CMAKE_MATCH_1}")
set(commands "")
foreach(n IN LISTS names)
  string(STRIP "${n}" n)
  list(APPEND commands "${n}")
endforeach()
if(NOT commands)
  message(FATAL_ERROR "cli_docs: no commands found in handlab-cli --help (its wording changed?)")
endif()

roff_literal(main_roff "${main}")
set(man ".TH HANDLAB-CLI 1 \"${month}\" \"handlab ${VERSION}\" \"User Commands\"\n")
string(APPEND man ".SH NAME\nhandlab-cli \\- run and analyse studies of fine virtual manipulation, headless\n")
string(APPEND man ".SH SYNOPSIS\n.B handlab-cli\n.I COMMAND\n[\\fIoptions\\fR]\n")
string(APPEND man ".SH DESCRIPTION\n.nf\n${main_roff}.fi\n")
set(cases "")
set(sub_cases "")
foreach(command IN LISTS commands)
  run_help(text "${CLI}" ${command} --help)
  roff_literal(roff "${text}")
  string(APPEND man ".SH \"handlab-cli ${command}\"\n.nf\n${roff}\n.fi\n")
  help_subcommands(subs ${command} "${text}")
  help_options(options "${text}")
  if(subs)
    list(JOIN subs " " joined)
    string(APPEND cases "    ${command}) words=\"${joined}\" subcommands=1 ;;\n")
    foreach(sub IN LISTS subs)
      run_help(subtext "${CLI}" ${command} ${sub} --help)
      roff_literal(subroff "${subtext}")
      string(APPEND man ".SS \"handlab-cli ${command} ${sub}\"\n.nf\n${subroff}\n.fi\n")
      help_options(suboptions "${subtext}")
      list(JOIN suboptions " " joined)
      string(APPEND sub_cases "    ${command}/${sub}) words=\"${joined}\" ;;\n")
    endforeach()
  else()
    list(JOIN options " " joined)
    string(APPEND cases "    ${command}) words=\"${joined}\" ;;\n")
  endif()
endforeach()
string(APPEND man ".SH \"SEE ALSO\"\n.BR handlab (1)\n")
file(WRITE "${OUT}/handlab-cli.1" "${man}")

list(JOIN commands " " command_words)
file(WRITE "${OUT}/handlab-cli.bash"
"# bash completion for handlab-cli (generated from its --help by cmake/cli_docs.cmake)
_handlab_cli() {
  local cur=\${COMP_WORDS[COMP_CWORD]} words='' subcommands=0
  if (( COMP_CWORD == 1 )); then
    COMPREPLY=(\$(compgen -W \"${command_words} --help --version\" -- \"\$cur\"))
    return
  fi
  case \${COMP_WORDS[1]} in
${cases}  esac
  if (( subcommands && COMP_CWORD == 2 )); then
    COMPREPLY=(\$(compgen -W \"\$words\" -- \"\$cur\"))
    return
  fi
  if (( subcommands )); then
    words=''
    case \${COMP_WORDS[1]}/\${COMP_WORDS[2]} in
${sub_cases}    esac
  fi
  if [[ \$cur == -* ]]; then
    COMPREPLY=(\$(compgen -W \"\$words\" -- \"\$cur\"))
  else
    COMPREPLY=(\$(compgen -f -- \"\$cur\"))
  fi
}
complete -o filenames -F _handlab_cli handlab-cli
")

run_help(gui env QT_QPA_PLATFORM=offscreen "${GUI}" --help)
string(REGEX REPLACE "^Usage: [^ ]*handlab" "Usage: handlab" gui "${gui}")
roff_literal(gui_roff "${gui}")
set(man ".TH HANDLAB 1 \"${month}\" \"handlab ${VERSION}\" \"User Commands\"\n")
string(APPEND man ".SH NAME\nhandlab \\- run and analyse studies of fine virtual manipulation (the app)\n")
string(APPEND man ".SH SYNOPSIS\n.B handlab\n[\\fIoptions\\fR]\n")
string(APPEND man ".SH DESCRIPTION\n.nf\n${gui_roff}.fi\n")
string(APPEND man ".SH \"SEE ALSO\"\n.BR handlab-cli (1)\n")
file(WRITE "${OUT}/handlab.1" "${man}")
