# SWARD_GIT_REVISION: the source revision recorded in dataset manifests and printed by every tool's --version
# (re-read at every configure; ./sward.sh configures each run).
execute_process(COMMAND git describe --always --dirty --abbrev=12 WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                OUTPUT_VARIABLE SWARD_GIT_REVISION OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT SWARD_GIT_REVISION)
  set(SWARD_GIT_REVISION "unknown")
endif()
