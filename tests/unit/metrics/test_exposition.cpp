#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "metrics/exposition.hpp"
#include "metrics/histogram.hpp"

using namespace gimbal::metrics;

TEST_CASE("label values escape backslash, quote and newline; help escapes backslash and newline") {
    CHECK(escape_label_value(R"(a\b"c)"
                             "\nd") == R"(a\\b\"c\nd)");
    CHECK(escape_label_value("plain") == "plain");
    CHECK(escape_help("x \"q\" \\ y\nz") == "x \"q\" \\\\ y\\nz");
}

TEST_CASE("values in the format's spelling") {
    CHECK(format_value(0) == "0");
    CHECK(format_value(3) == "3");
    CHECK(format_value(1234567890123.0) == "1234567890123");
    CHECK(format_value(0.25) == "0.25");
    CHECK(format_value(-1.5) == "-1.5");
    CHECK(format_value(std::numeric_limits<double>::infinity()) == "+Inf");
    CHECK(format_value(-std::numeric_limits<double>::infinity()) == "-Inf");
    CHECK(format_value(std::nan("")) == "NaN");
    CHECK(std::stod(format_value(0.1 + 0.2)) == 0.1 + 0.2);  // round-trips
}

TEST_CASE("metric and label names") {
    CHECK(valid_metric_name("gimbald_link_up"));
    CHECK(valid_metric_name("a:b_c9"));
    CHECK_FALSE(valid_metric_name("9abc"));
    CHECK_FALSE(valid_metric_name("a-b"));
    CHECK_FALSE(valid_metric_name(""));
    CHECK(valid_label_name("gimbal"));
    CHECK_FALSE(valid_label_name("a:b"));
    CHECK_FALSE(valid_label_name("__reserved"));
}

TEST_CASE("families: HELP and TYPE once, then samples with labels") {
    Exposition e;
    e.family("gimbald_link_up", Type::gauge, "1 when the link is connected");
    e.sample({{"gimbal", "main"}}, 1);
    e.sample({{"gimbal", "no\"se"}}, 0);
    e.family("gimbald_subscribers", Type::gauge, "Subscribers");
    e.sample({}, 3);
    CHECK(e.text() ==
          "# HELP gimbald_link_up 1 when the link is connected\n"
          "# TYPE gimbald_link_up gauge\n"
          "gimbald_link_up{gimbal=\"main\"} 1\n"
          "gimbald_link_up{gimbal=\"no\\\"se\"} 0\n"
          "# HELP gimbald_subscribers Subscribers\n"
          "# TYPE gimbald_subscribers gauge\n"
          "gimbald_subscribers 3\n");
}

TEST_CASE("misuse is refused") {
    Exposition e;
    CHECK_THROWS(e.sample({}, 1));
    CHECK_THROWS(e.family("bad-name", Type::gauge, "x"));
    e.family("x", Type::gauge, "x");
    CHECK_THROWS(e.sample({{"bad-label", "v"}}, 1));
    CHECK_THROWS(e.histogram({}, Histogram({1.0})));
}

TEST_CASE("histogram: cumulative buckets, +Inf, sum and count") {
    Histogram h({0.1, 0.5, 1.0});
    h.observe(0.05);
    h.observe(0.1);  // le is inclusive
    h.observe(0.3);
    h.observe(2.0);  // only in +Inf
    CHECK(h.count() == 4);
    CHECK(h.sum() == Approx(2.45));
    CHECK(h.cumulative(0) == 2);
    CHECK(h.cumulative(1) == 3);
    CHECK(h.cumulative(2) == 3);

    Exposition e;
    e.family("d_seconds", Type::histogram, "Duration");
    e.histogram({{"cmd", "ping"}}, h);
    CHECK(e.text() ==
          "# HELP d_seconds Duration\n"
          "# TYPE d_seconds histogram\n"
          "d_seconds_bucket{cmd=\"ping\",le=\"0.1\"} 2\n"
          "d_seconds_bucket{cmd=\"ping\",le=\"0.5\"} 3\n"
          "d_seconds_bucket{cmd=\"ping\",le=\"1\"} 3\n"
          "d_seconds_bucket{cmd=\"ping\",le=\"+Inf\"} 4\n"
          "d_seconds_sum{cmd=\"ping\"} 2.45\n"
          "d_seconds_count{cmd=\"ping\"} 4\n");
}

TEST_CASE("histogram bounds must increase") {
    CHECK_THROWS(Histogram({1.0, 0.5}));
    CHECK_THROWS(Histogram({1.0, 1.0}));
    CHECK_NOTHROW(Histogram(latency_buckets_s()));
}
