# Writes the version header with the source tree's git revision, at build time (a configure-time
# revision goes stale as soon as the next commit is built incrementally). "-dirty" marks a build
# of uncommitted changes. configure_file rewrites the header only when the text changes, so an
# unchanged revision recompiles nothing.
# Inputs: SRC (source dir), IN (template), OUT (header), PROJECT_VERSION.
execute_process(COMMAND git describe --always --dirty --abbrev=7 WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE SEEDCAL_GIT_REVISION OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT SEEDCAL_GIT_REVISION)
  set(SEEDCAL_GIT_REVISION "unknown")
endif()
configure_file(${IN} ${OUT} @ONLY)
