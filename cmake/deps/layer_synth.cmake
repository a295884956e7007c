# Included inside breastfit_layer(synth): truth/meta.json is written with nlohmann_json (only
# inside src/breastfit/synth/synth_case.cpp), so it is a PRIVATE dependency.
if(NOT "${_scope}" STREQUAL "INTERFACE")
  target_link_libraries(${_target} PRIVATE nlohmann_json::nlohmann_json)
endif()
