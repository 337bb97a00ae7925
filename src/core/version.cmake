# Writes the provenance header (src/core/version.hpp.in: version, git revision, instruction
# set) to OUT; configure_file leaves OUT untouched when its text would not change, so only
# the sources that include it recompile, and only after a commit or an edit changed the
# revision. Run at configure time (include) and at every build (cmake -P, the
# bkquake_provenance target), with SOURCE_DIR, OUT, PROJECT_VERSION and BKQUAKE_BUILD_ARCH set.
# --exclude=*: the commit's own name even where tags exist (a tag would print tag-N-gHASH).
execute_process(COMMAND git describe --always --dirty --abbrev=12 --exclude=*
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE BKQUAKE_GIT_REVISION OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
if(NOT BKQUAKE_GIT_REVISION)
  set(BKQUAKE_GIT_REVISION "unknown")
endif()
configure_file(${SOURCE_DIR}/src/core/version.hpp.in ${OUT} @ONLY)
