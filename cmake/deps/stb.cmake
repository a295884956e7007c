if(TARGET breastfit_stb)
  return()
endif()
# Debian's libstb-dev: headers in /usr/include/stb, implementation in libstb.
find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb REQUIRED)
find_library(STB_LIBRARY stb REQUIRED)
add_library(breastfit_stb INTERFACE)
target_include_directories(breastfit_stb INTERFACE ${STB_INCLUDE_DIR})
target_link_libraries(breastfit_stb INTERFACE ${STB_LIBRARY})
