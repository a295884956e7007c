if(TARGET TinyGLTF::TinyGLTF)
  return()
endif()
# Debian's libtinygltf-dev: the shared library holds the implementation (never define TINYGLTF_IMPLEMENTATION).
find_package(TinyGLTF REQUIRED)
