#pragma once
/// \file Base64 and data: URIs, so a report can carry its images inside one self-contained HTML
/// file (no network, no side files).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace breastfit::pipeline {

/// Standard base64 (RFC 4648, alphabet A–Z a–z 0–9 + /, '=' padding, no line breaks).
std::string base64_encode(const std::vector<std::uint8_t>& bytes);

/// "data:<mime>;base64,<base64 of bytes>", e.g. for an <img src>.
std::string data_uri(std::string_view mime, const std::vector<std::uint8_t>& bytes);

}  // namespace breastfit::pipeline
