#include <catch2/catch.hpp>

#include <vector>

#include "link/backoff.hpp"
#include "link/lifetime.hpp"

using gimbald::Backoff;
using gimbald::BackoffOptions;

namespace {

std::vector<double> first_delays(Backoff& backoff, int n) {
    std::vector<double> delays;
    for (int i = 0; i < n; ++i) delays.push_back(backoff.next());
    return delays;
}

}  // namespace

TEST_CASE("backoff doubles from min to max and stays there", "[backoff]") {
    Backoff backoff({.min_s = 0.2, .max_s = 5.0, .jitter = 0.2}, [] { return 0.5; });  // no jitter
    const std::vector<double> delays = first_delays(backoff, 8);
    const std::vector<double> expected{0.2, 0.4, 0.8, 1.6, 3.2, 5.0, 5.0, 5.0};
    REQUIRE(delays.size() == expected.size());
    for (std::size_t i = 0; i < delays.size(); ++i) CHECK(delays[i] == Approx(expected[i]));
}

TEST_CASE("backoff starts again at min after reset", "[backoff]") {
    Backoff backoff({.min_s = 0.5, .max_s = 4.0, .jitter = 0.2}, [] { return 0.5; });
    first_delays(backoff, 5);
    CHECK(backoff.base_s() == Approx(4.0));
    backoff.reset();
    CHECK(backoff.next() == Approx(0.5));
    CHECK(backoff.next() == Approx(1.0));
}

TEST_CASE("backoff jitter spans plus and minus the jitter fraction", "[backoff]") {
    Backoff low({.min_s = 1.0, .max_s = 10.0, .jitter = 0.2}, [] { return 0.0; });
    CHECK(low.next() == Approx(0.8));
    CHECK(low.next() == Approx(1.6));

    Backoff high({.min_s = 1.0, .max_s = 10.0, .jitter = 0.2}, [] { return 1.0; });
    CHECK(high.next() == Approx(1.2));
    CHECK(high.next() == Approx(2.4));
}

TEST_CASE("backoff never exceeds max even with positive jitter", "[backoff]") {
    Backoff backoff({.min_s = 1.0, .max_s = 3.0, .jitter = 0.2}, [] { return 1.0; });
    for (double delay : first_delays(backoff, 10)) CHECK(delay <= 3.0);
}

TEST_CASE("seeded backoff is deterministic and within the jitter band", "[backoff]") {
    const BackoffOptions options{.min_s = 0.2, .max_s = 5.0, .jitter = 0.2};
    Backoff a(options, 42u);
    Backoff b(options, 42u);
    Backoff c(options, 43u);
    const std::vector<double> da = first_delays(a, 12);
    const std::vector<double> db = first_delays(b, 12);
    const std::vector<double> dc = first_delays(c, 12);
    CHECK(da == db);
    CHECK(da != dc);

    Backoff reference(options, [] { return 0.5; });
    for (double delay : da) {
        const double base = reference.next();
        CHECK(delay >= base * 0.8 - 1e-12);
        CHECK(delay <= std::min(base * 1.2, 5.0) + 1e-12);
    }
    // Jitter actually varies the delays.
    CHECK(da[0] != Approx(0.2).epsilon(1e-9));
}

TEST_CASE("backoff repairs inverted limits", "[backoff]") {
    Backoff backoff({.min_s = 2.0, .max_s = 1.0, .jitter = 0.2}, [] { return 0.5; });
    CHECK(backoff.next() == Approx(2.0));
    CHECK(backoff.next() == Approx(2.0));
}

TEST_CASE("lifetime reset orphans wrapped handlers", "[lifetime]") {
    gimbald::Lifetime lifetime;
    int calls = 0;
    auto before = lifetime.wrap([&calls](int n) { calls += n; });
    before(1);
    CHECK(calls == 1);
    const auto generation = lifetime.generation();
    lifetime.reset();
    CHECK(lifetime.generation() != generation);
    before(10);
    CHECK(calls == 1);
    auto after = lifetime.wrap([&calls](int n) { calls += n; });
    after(100);
    CHECK(calls == 101);
}
