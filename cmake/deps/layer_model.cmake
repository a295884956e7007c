# Included inside breastfit_layer(model): the glTF reader/writer needs tinygltf (Debian's shared
# libtinygltf holds the implementation: never define TINYGLTF_IMPLEMENTATION); params_json.h
# exposes nlohmann::json. template_library.cpp falls back to the source tree's shipped template.
target_link_libraries(${_target} PRIVATE TinyGLTF::TinyGLTF)
target_link_libraries(${_target} PUBLIC nlohmann_json::nlohmann_json)
target_compile_definitions(${_target} PRIVATE BREASTFIT_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
