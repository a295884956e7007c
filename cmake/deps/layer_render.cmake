# Render layer: PNG encoding/decoding through Debian's libstb (stb_image_write / stb_image).
# The implementation is compiled into libstb.so, so no STB_*_IMPLEMENTATION is defined anywhere.
target_link_libraries(${_target} PRIVATE Stb::Stb)
