#include "breastfit/serve/request_guard.h"

#include <set>

#include <gtest/gtest.h>

namespace breastfit::serve {
namespace {

TEST(RequestGuard, TokensAreRandomHex) {
  std::set<std::string> seen;
  for (int i = 0; i < 20; ++i) {
    const std::string t = random_token();
    EXPECT_EQ(t.size(), 32u);
    EXPECT_EQ(t.find_first_not_of("0123456789abcdef"), std::string::npos);
    seen.insert(t);
  }
  EXPECT_EQ(seen.size(), 20u);
}

TEST(RequestGuard, ChecksTokenHostAndOrigin) {
  const RequestGuard g("0123456789abcdef0123456789abcdef", "127.0.0.1", 8470);
  EXPECT_TRUE(g.token_ok("0123456789abcdef0123456789abcdef"));
  EXPECT_FALSE(g.token_ok("0123456789abcdef0123456789abcdee"));
  EXPECT_FALSE(g.token_ok(""));
  EXPECT_TRUE(g.host_ok("127.0.0.1:8470"));
  EXPECT_TRUE(g.host_ok("localhost:8470"));
  EXPECT_FALSE(g.host_ok("evil.example:8470"));  // DNS rebinding: a foreign name resolving to us
  EXPECT_FALSE(g.host_ok("127.0.0.1:8471"));
  EXPECT_TRUE(g.origin_ok(""));
  EXPECT_TRUE(g.origin_ok("http://localhost:8470"));
  EXPECT_FALSE(g.origin_ok("http://evil.example"));
  EXPECT_FALSE(g.origin_ok("null"));
  EXPECT_EQ(g.refuse("127.0.0.1:8470", "", g.token()), std::nullopt);
  EXPECT_NE(g.refuse("127.0.0.1:8470", "", "")->find("no access token"), std::string::npos);
  EXPECT_NE(g.refuse("evil:8470", "", g.token())->find("Host"), std::string::npos);
  EXPECT_NE(g.refuse("127.0.0.1:8470", "http://evil", g.token())->find("origin"), std::string::npos);
}

TEST(RequestGuard, OtherHostsAcceptOnlyThemselves) {
  const RequestGuard g("t", "192.168.1.5", 80);
  EXPECT_TRUE(g.host_ok("192.168.1.5:80"));
  EXPECT_FALSE(g.host_ok("localhost:80"));
}

}  // namespace
}  // namespace breastfit::serve
