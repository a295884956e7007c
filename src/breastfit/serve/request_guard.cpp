#include "breastfit/serve/request_guard.h"

#include <algorithm>
#include <cstdio>
#include <random>

namespace breastfit::serve {

std::string random_token() {
  std::random_device rd;  // the operating system's source (/dev/urandom)
  std::string out;
  for (int i = 0; i < 4; ++i) {
    char buf[9];
    std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(rd()));
    out += buf;
  }
  return out;
}

RequestGuard::RequestGuard(std::string token, std::string host, int port) : token_(std::move(token)) {
  const std::string p = ":" + std::to_string(port);
  const bool loopback = host == "127.0.0.1" || host == "localhost" || host == "::1";
  if (loopback) {
    for (const char* h : {"127.0.0.1", "localhost", "[::1]"}) hosts_.push_back(h + p);
  } else {
    hosts_.push_back((host.find(':') != std::string::npos ? "[" + host + "]" : host) + p);
  }
}

bool RequestGuard::token_ok(const std::string& given) const {
  if (given.size() != token_.size() || token_.empty()) return false;
  unsigned diff = 0;
  for (size_t i = 0; i < given.size(); ++i) diff |= static_cast<unsigned char>(given[i] ^ token_[i]);
  return diff == 0;
}

bool RequestGuard::host_ok(const std::string& host_header) const {
  return std::find(hosts_.begin(), hosts_.end(), host_header) != hosts_.end();
}

bool RequestGuard::origin_ok(const std::string& origin_header) const {
  if (origin_header.empty()) return true;
  const std::string prefix = "http://";
  if (origin_header.rfind(prefix, 0) != 0) return false;
  return host_ok(origin_header.substr(prefix.size()));
}

std::optional<std::string> RequestGuard::refuse(const std::string& host_header, const std::string& origin_header,
                                                const std::string& token) const {
  if (!host_ok(host_header))
    return "refused: the Host header '" + host_header + "' is not this server's address (open the printed URL)";
  if (!origin_ok(origin_header))
    return "refused: requests from the origin '" + origin_header + "' are not allowed";
  if (token.empty()) return "refused: no access token (open the URL breastfit serve printed, with its ?token=...)";
  if (!token_ok(token)) return "refused: wrong access token (open the URL breastfit serve printed)";
  return std::nullopt;
}

}  // namespace breastfit::serve
