# Debian's libdeflate-dev (1.14 ships a pkg-config file but no CMake package): header libdeflate.h
# and library libdeflate. Defines the imported target Libdeflate::Libdeflate when both are found.
# Also installed next to breastfitConfig.cmake, which includes it to recreate the target for
# consumers of the installed package (the render layer links it privately: a static library
# still passes it on to whatever links the layer).
if(TARGET Libdeflate::Libdeflate)
  return()
endif()
find_path(LIBDEFLATE_INCLUDE_DIR libdeflate.h)
find_library(LIBDEFLATE_LIBRARY deflate)
if(LIBDEFLATE_INCLUDE_DIR AND LIBDEFLATE_LIBRARY)
  add_library(Libdeflate::Libdeflate INTERFACE IMPORTED)
  set_target_properties(Libdeflate::Libdeflate PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${LIBDEFLATE_INCLUDE_DIR}"
                                                          INTERFACE_LINK_LIBRARIES "${LIBDEFLATE_LIBRARY}")
endif()
