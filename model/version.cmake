# Run at every build (cmake -P, from model/CMakeLists.txt): writes version.cpp with the project's
# version and the git commit the sources are at, rewriting it only when either changed, so an
# unchanged tree rebuilds nothing. Without git (a source archive) the commit is left empty.
set(commit "")
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} describe --always --dirty --abbrev=12 --match "v[0-9]*"
                  OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    set(commit "")
  endif()
endif()
configure_file(${IN} ${OUT} @ONLY)
