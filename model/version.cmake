# Run at every build (cmake -P, from model/CMakeLists.txt): writes version.cpp with the project's
# version and the git commit the sources are at, rewriting it only when either changed, so an
# unchanged tree rebuilds nothing. Without git, or for sources that are not a git checkout of
# their own (an archive, even one unpacked inside another repository), the commit is left empty.
set(commit "")
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} rev-parse --show-toplevel
                  OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  file(REAL_PATH "${SOURCE_DIR}" source_real)
  if(rc EQUAL 0 AND top)
    file(REAL_PATH "${top}" top_real)
  endif()
  if(rc EQUAL 0 AND top_real STREQUAL source_real)
    execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} describe --always --dirty --abbrev=12 --match "v[0-9]*"
                    OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      set(commit "")
    endif()
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)
