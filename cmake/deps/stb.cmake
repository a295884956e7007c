# Debian's libstb-dev: headers in /usr/include/stb, implementation in libstb. Defines the imported
# target Stb::Stb when both are found. Also installed next to breastfitConfig.cmake, which includes
# it to recreate Stb::Stb for consumers of the installed package (the render layer links it).
if(TARGET Stb::Stb)
  return()
endif()
find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
find_library(STB_LIBRARY stb)
if(STB_INCLUDE_DIR AND STB_LIBRARY)
  add_library(Stb::Stb INTERFACE IMPORTED)
  set_target_properties(Stb::Stb PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${STB_INCLUDE_DIR}"
                                            INTERFACE_LINK_LIBRARIES "${STB_LIBRARY}")
endif()
