# Render layer: PNG decoding through Debian's libstb (stb_image; the implementation is compiled
# into libstb.so, so no STB_*_IMPLEMENTATION is defined anywhere) and PNG encoding with Debian's
# libdeflate (libdeflate-dev; render/png_encoder.h) and zlib's CRC-32 (zlib1g-dev).
find_package(ZLIB REQUIRED)
include(${PROJECT_SOURCE_DIR}/cmake/deps/libdeflate.cmake)
if(NOT TARGET Libdeflate::Libdeflate)
  message(FATAL_ERROR "libdeflate not found (Debian: libdeflate-dev): need libdeflate.h and libdeflate")
endif()
target_link_libraries(${_target} PRIVATE Stb::Stb ZLIB::ZLIB Libdeflate::Libdeflate)
