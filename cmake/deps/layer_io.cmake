# Included inside breastfit_layer(io): zlib-compressed VTK XML arrays (.vtp) are inflated by
# Debian's zlib (zlib1g-dev); file hashes (SHA-256) come from OpenSSL's libcrypto (libssl-dev).
find_package(ZLIB REQUIRED)
find_package(OpenSSL REQUIRED COMPONENTS Crypto)
target_link_libraries(${_target} PRIVATE ZLIB::ZLIB OpenSSL::Crypto)
