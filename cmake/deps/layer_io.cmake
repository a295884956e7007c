# Included inside breastfit_layer(io): zlib-compressed VTK XML arrays (.vtp) are inflated by
# Debian's zlib (zlib1g-dev); file hashes (SHA-256) come from Nettle (nettle-dev).
find_package(ZLIB REQUIRED)
include(${PROJECT_SOURCE_DIR}/cmake/deps/nettle.cmake)
if(NOT TARGET Nettle::Nettle)
  message(FATAL_ERROR "Nettle not found (Debian: nettle-dev; scripts/setup.sh installs it): need nettle/sha2.h and libnettle")
endif()
target_link_libraries(${_target} PRIVATE ZLIB::ZLIB Nettle::Nettle)
