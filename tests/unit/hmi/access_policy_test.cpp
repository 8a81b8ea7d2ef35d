#include "hmi_bridge/core/access_policy.hpp"

#include <gtest/gtest.h>

namespace mcnc::hmi {
namespace {

TEST(AccessPolicy, TokensGiveTheirRoles) {
  const AccessPolicy p("operator-token-0123", "viewer-token-01234");
  EXPECT_EQ(p.role_of("operator-token-0123"), Role::operator_);
  EXPECT_EQ(p.role_of("viewer-token-01234"), Role::viewer);
  EXPECT_EQ(p.role_of("operator-token-012"), Role::none);
  EXPECT_EQ(p.role_of("operator-token-01234"), Role::none);
  EXPECT_EQ(p.role_of(""), Role::none);
  EXPECT_EQ(p.initial_role(), Role::none);  // a viewer token is set: viewing needs it
}

TEST(AccessPolicy, WithoutAViewerTokenEveryConnectionViews) {
  const AccessPolicy p("operator-token-0123", "");
  EXPECT_EQ(p.initial_role(), Role::viewer);
  EXPECT_EQ(p.role_of(""), Role::none);  // an empty token is no viewer token
}

TEST(AccessPolicy, OnlyTheServersOwnPagesOpenTheSocket) {
  const std::vector<std::string> loopback = allowed_origins("127.0.0.1:8080", {});
  EXPECT_TRUE(origin_allowed("http://127.0.0.1:8080", loopback));
  EXPECT_TRUE(origin_allowed("http://localhost:8080", loopback));
  EXPECT_TRUE(origin_allowed("", loopback));  // not a browser
  EXPECT_FALSE(origin_allowed("http://127.0.0.1:8081", loopback));
  EXPECT_FALSE(origin_allowed("http://evil.example:8080", loopback));
  EXPECT_FALSE(origin_allowed("null", loopback));
  EXPECT_FALSE(origin_allowed("https://127.0.0.1:8080", loopback));

  const std::vector<std::string> cell = allowed_origins("10.0.0.7:80", {"http://cell-7.local:80"});
  EXPECT_TRUE(origin_allowed("http://10.0.0.7:80", cell));
  EXPECT_TRUE(origin_allowed("http://cell-7.local:80", cell));
  EXPECT_FALSE(origin_allowed("http://localhost:80", cell));
}

TEST(AccessPolicy, GeneratedTokensAreLongAndDiffer) {
  const std::string a = generate_token();
  const std::string b = generate_token();
  EXPECT_EQ(a.size(), 32U);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
}

}  // namespace
}  // namespace mcnc::hmi
