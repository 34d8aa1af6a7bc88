# Fails when the C code block of README.md (the one fenced with ```c) differs from tests/readme_example.c, so the
# README shows the program the test readme_example compiles and runs.
# Usage: cmake -DREADME=<README.md> -DEXAMPLE=<readme_example.c> -P readme_example_check.cmake
file(READ ${README} readme)
file(READ ${EXAMPLE} example)
string(FIND "${readme}" "\n```c\n" begin)
if(begin EQUAL -1)
  message(FATAL_ERROR "${README}: no ```c code block (the \"Embed it\" example of ${EXAMPLE})")
endif()
math(EXPR begin "${begin} + 6")
string(SUBSTRING "${readme}" ${begin} -1 rest)
string(FIND "${rest}" "\n```" end)
if(end EQUAL -1)
  message(FATAL_ERROR "${README}: the ```c code block is not closed")
endif()
math(EXPR end "${end} + 1")
string(SUBSTRING "${rest}" 0 ${end} block)
if(NOT block STREQUAL example)
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/readme_block.c "${block}")
  message(FATAL_ERROR "${README}'s ```c block differs from ${EXAMPLE}: copy the file into the README (or the README's "
                      "block into the file and rerun the test readme_example). The README's block is in "
                      "${CMAKE_CURRENT_BINARY_DIR}/readme_block.c; compare with diff.")
endif()
string(REGEX MATCHALL "\n" lines "${example}")
list(LENGTH lines line_count)
if(line_count GREATER 25)
  message(FATAL_ERROR "${EXAMPLE}: ${line_count} lines; the README's example stays at 25 at most")
endif()
message(STATUS "README.md's C block is ${EXAMPLE} (${line_count} lines)")
