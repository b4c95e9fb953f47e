# Runs every row of the bad-input table (TABLE, tests/examples/bad_inputs.txt) and checks that the program refuses
# the input: its exit status, and its stdout + stderr against the row's regex. A row fails on another status, on a
# signal or on a timeout (TIMEOUT seconds, 30 by default); all rows are run and every failing one is reported.
# Arguments: TABLE, WORK (a scratch folder, emptied first), DATA (tests/motion/data), BAD (tests/examples/bad_inputs),
# EXAMPLES (tests/examples), and PROGRAM_<name> for each program of the table (its path).
#
# Row format (one per line, '#' starts a comment line):  program | arguments | exit status | regex
# The arguments are split as a shell would (quotes allowed); @DATA@, @BAD@, @EXAMPLES@ and @TMP@ (= WORK) are
# replaced by the folders. The regex (CMake syntax, '.' matches a newline) is the rest of the line.

if(NOT TIMEOUT)
  set(TIMEOUT 30)
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/folder")  # a folder given where a file is expected
file(READ "${TABLE}" table)
string(APPEND table "\n")

set(failures "")
set(rows 0)
set(failed 0)
set(line_number 0)
string(LENGTH "${table}" remaining)
while(remaining GREATER 0)
  # The next line, without list operations (the regexes hold ';' and unbalanced '[').
  string(FIND "${table}" "\n" end)
  string(SUBSTRING "${table}" 0 ${end} line)
  math(EXPR next "${end} + 1")
  string(SUBSTRING "${table}" ${next} -1 table)
  string(LENGTH "${table}" remaining)
  math(EXPR line_number "${line_number} + 1")
  string(STRIP "${line}" line)
  if(line STREQUAL "" OR line MATCHES "^#")
    continue()
  endif()

  # program | arguments | status | regex (the regex is the rest of the line: it may hold " | ").
  set(rest "${line}")
  foreach(field program arguments status)
    string(FIND "${rest}" " | " bar)
    if(bar LESS 0)
      message(FATAL_ERROR "${TABLE}:${line_number}: expected 'program | arguments | exit status | regex', got: ${line}")
    endif()
    string(SUBSTRING "${rest}" 0 ${bar} ${field})
    string(STRIP "${${field}}" ${field})
    math(EXPR after "${bar} + 3")
    string(SUBSTRING "${rest}" ${after} -1 rest)
  endforeach()
  string(STRIP "${rest}" regex)
  if(NOT DEFINED PROGRAM_${program} OR regex STREQUAL "")
    message(FATAL_ERROR "${TABLE}:${line_number}: unknown program '${program}' or no regex")
  endif()
  math(EXPR rows "${rows} + 1")

  foreach(placeholder DATA BAD EXAMPLES)
    string(REPLACE "@${placeholder}@" "${${placeholder}}" arguments "${arguments}")
  endforeach()
  string(REPLACE "@TMP@" "${WORK}" arguments "${arguments}")
  separate_arguments(argv UNIX_COMMAND "${arguments}")

  string(TIMESTAMP start "%s")
  execute_process(COMMAND "${PROGRAM_${program}}" ${argv} WORKING_DIRECTORY "${WORK}" TIMEOUT ${TIMEOUT}
                  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(TIMESTAMP stop "%s")
  math(EXPR seconds "${stop} - ${start}")
  set(all "${out}${err}")

  set(why "")
  if(NOT "${result}" STREQUAL "${status}")
    set(why "exit status '${result}', expected ${status}")
  endif()
  if(NOT all MATCHES "${regex}")
    if(why)
      string(APPEND why "; ")
    endif()
    string(APPEND why "output does not match '${regex}'")
  endif()
  if(why)
    math(EXPR failed "${failed} + 1")
    # The first lines of the output, indented.
    string(SUBSTRING "${all}" 0 400 head)
    string(REGEX REPLACE "\n+$" "" head "${head}")
    string(REPLACE "\n" "\n      | " head "${head}")
    string(APPEND failures "  row ${rows} (line ${line_number}): ${program} ${arguments}\n    ${why} (${seconds} s)\n      | ${head}\n")
  else()
    message(STATUS "ok row ${rows}: ${program} ${arguments} (${seconds} s)")
  endif()
endwhile()

if(failed GREATER 0)
  message(FATAL_ERROR "${failed} of ${rows} bad-input rows failed:\n${failures}")
endif()
message(STATUS "all ${rows} bad-input rows refused as expected")
