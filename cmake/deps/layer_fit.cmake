# The fit layer reads its options from JSON config files.
target_link_libraries(${_target} PUBLIC nlohmann_json::nlohmann_json)
