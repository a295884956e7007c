# Included inside breastfit_layer(pipeline): the version report.json's provenance names — the
# project version and `git describe` of the source tree at configure time (empty outside git).
find_package(Git QUIET)
set(_breastfit_git_describe "")
if(GIT_FOUND AND EXISTS ${PROJECT_SOURCE_DIR}/.git)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --abbrev=12
                  WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} OUTPUT_VARIABLE _breastfit_git_describe
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
endif()
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/breastfit/pipeline/provenance.cpp PROPERTIES
  COMPILE_DEFINITIONS "BREASTFIT_VERSION=\"${PROJECT_VERSION}\";BREASTFIT_GIT_DESCRIBE=\"${_breastfit_git_describe}\"")
