#pragma once
/// \file Who may talk to the workstation server: a random token on every request (in the printed
/// URL, then a cookie), and the Host and Origin headers checked against the address the server
/// listens on, so that a web page from elsewhere (DNS rebinding, cross-site requests) cannot use it.
#include <optional>
#include <string>
#include <vector>

namespace breastfit::serve {

/// A fresh random token: 32 hex digits from the operating system's random source.
std::string random_token();

class RequestGuard {
 public:
  /// \param token  the token every request must carry
  /// \param host   the address the server listens on (e.g. "127.0.0.1")
  /// \param port   its port
  RequestGuard(std::string token, std::string host, int port);

  const std::string& token() const { return token_; }

  /// Whether `given` (a header, cookie or query value) is the token (constant-time comparison).
  bool token_ok(const std::string& given) const;

  /// Whether a Host header names this server: the listening address, or for a loopback address
  /// also "localhost", "127.0.0.1" and "[::1]", each with this port.
  bool host_ok(const std::string& host_header) const;

  /// Whether an Origin header (when a browser sends one) is this server's own origin
  /// ("http://" + an accepted Host value). An absent Origin (empty) is accepted.
  bool origin_ok(const std::string& origin_header) const;

  /// The reason a request is refused (nullopt: accepted). `token` is what the request carried
  /// (empty: none). Checked in the order Host, Origin, token.
  std::optional<std::string> refuse(const std::string& host_header, const std::string& origin_header,
                                    const std::string& token) const;

 private:
  std::string token_;
  std::vector<std::string> hosts_;  // accepted Host values
};

}  // namespace breastfit::serve
