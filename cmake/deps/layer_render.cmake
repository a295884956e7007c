# Render layer: PNG decoding through Debian's libstb (stb_image; the implementation is compiled
# into libstb.so, so no STB_*_IMPLEMENTATION is defined anywhere) and PNG encoding with Debian's
# zlib (zlib1g-dev; render/png_encoder.h).
find_package(ZLIB REQUIRED)
target_link_libraries(${_target} PRIVATE Stb::Stb ZLIB::ZLIB)
