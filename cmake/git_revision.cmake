# Writes applications/version.h with the version and the git revision of the source tree. Run at
# every build (target sealfe_version) so that a summary.json never names a stale revision;
# configure_file leaves the header untouched when nothing changed, so nothing recompiles then.
#   cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DPROJECT_VERSION=... -P git_revision.cmake
set(SEALFE_GIT_REVISION unknown)
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12
    WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE revision
    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE git_result)
  if(git_result EQUAL 0 AND revision)
    set(SEALFE_GIT_REVISION ${revision})
  endif()
endif()
configure_file(${SOURCE_DIR}/applications/version.h.in ${BINARY_DIR}/applications/version.h @ONLY)
