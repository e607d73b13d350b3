#include <catch2/catch.hpp>

#include "http/site_check.hpp"

using gimbald::http::host_problem;
using gimbald::http::origin_problem;
using gimbald::http::SiteRules;

TEST_CASE("Host: addresses and localhost pass, other names only when allowed", "[http]") {
    const SiteRules none;
    CHECK_FALSE(host_problem("127.0.0.1:8761", none));
    CHECK_FALSE(host_problem("127.0.0.1", none));
    CHECK_FALSE(host_problem("[::1]:8761", none));
    CHECK_FALSE(host_problem("192.168.1.5:8761", none));
    CHECK_FALSE(host_problem("localhost:8761", none));
    CHECK_FALSE(host_problem("LOCALHOST.", none));
    CHECK_FALSE(host_problem("console.localhost:8761", none));
    // A DNS-rebinding page: its own name, resolved to 127.0.0.1.
    const auto rebinding = host_problem("attacker.example:8761", none);
    REQUIRE(rebinding);
    CHECK_THAT(*rebinding,
               Catch::Contains("attacker.example") && Catch::Contains("http.allowed_hosts"));
    CHECK(host_problem("", none));
    CHECK(host_problem(":8761", none));
    CHECK(host_problem("localhost.attacker.example", none));

    const SiteRules ground{{"Ground-1.lan"}};
    CHECK_FALSE(host_problem("ground-1.lan:8761", ground));
    CHECK_FALSE(host_problem("GROUND-1.LAN", ground));
    CHECK(host_problem("ground-2.lan:8761", ground));
}

TEST_CASE("Origin: absent or this server passes, another site is refused", "[http]") {
    CHECK_FALSE(origin_problem("", "127.0.0.1:8761"));  // curl, Python, Prometheus
    CHECK_FALSE(origin_problem("http://127.0.0.1:8761", "127.0.0.1:8761"));
    CHECK_FALSE(origin_problem("http://LOCALHOST:8761", "localhost:8761"));
    CHECK_FALSE(origin_problem("http://[::1]:8761", "[::1]:8761"));
    CHECK_FALSE(origin_problem("http://gimbal.lan", "gimbal.lan:80"));  // default port
    CHECK_FALSE(origin_problem("https://gimbal.lan", "gimbal.lan:443"));

    const auto other = origin_problem("https://attacker.example", "127.0.0.1:8761");
    REQUIRE(other);
    CHECK_THAT(*other, Catch::Contains("attacker.example") && Catch::Contains("cross-site"));
    CHECK(origin_problem("http://127.0.0.1:8762", "127.0.0.1:8761"));  // another local port
    CHECK(origin_problem("http://localhost:8761", "127.0.0.1:8761"));
    CHECK(origin_problem("null", "127.0.0.1:8761"));  // sandboxed frames, file:// pages
    CHECK(origin_problem("http://127.0.0.1:8761.attacker.example", "127.0.0.1:8761"));
}
