// The ground filter against simulated fixes with the noise it assumes for their slant range
// (1.5 km: 9 m per axis at 15 fixes a second, the tracker's frame rate): a straight drive,
// a sharp turn, a gap, outliers, a long drive past the rebasing distance.
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "ground_truth.hpp"
#include "track/ground/ground_filter.hpp"

using namespace gimbal::track;
using namespace ground_test;

namespace {

constexpr double rate = 15;
constexpr double range = 1500;

double p95(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(0.95 * static_cast<double>(v.size() - 1))];
}

double sigma(const GroundFilter& f) {
    return f.options().base_sigma_m + f.options().sigma_per_km * range / 1000;
}

}  // namespace

TEST_CASE("ground filter: a straight drive at 15 m/s converges within 1 m/s", "[track][ground]") {
    GroundFilter f;
    Noise noise(1);
    const double vn = 15 * std::cos(0.6), ve = 15 * std::sin(0.6);  // course 34.4 degrees
    std::vector<double> speed_errors, position_errors;
    for (int i = 0; i <= 60 * rate; ++i) {
        const double t = i / rate;
        const auto outcome =
            f.update({t, at(vn * t + noise(sigma(f)), ve * t + noise(sigma(f)), 430), range});
        CHECK(outcome ==
              (i == 0 ? GroundFilter::Outcome::started : GroundFilter::Outcome::accepted));
        if (t < 20) continue;  // converging
        const auto e = f.estimate(t);
        REQUIRE(e);
        speed_errors.push_back(std::hypot(e->north_mps - vn, e->east_mps - ve));
        const auto [n, east] = local(e->position);
        position_errors.push_back(std::hypot(n - vn * t, east - ve * t));
    }
    CHECK(p95(speed_errors) < 1.0);
    CHECK(p95(position_errors) < 4.0);  // well inside one fix's 9 m
    const auto e = *f.estimate(60);
    CHECK(e.speed_mps == Approx(15).margin(1.0));
    CHECK(e.course_deg == Approx(0.6 * 180 / 3.14159265358979).margin(3.0));
    CHECK(e.position.alt_m == Approx(430).margin(0.5));
    CHECK(e.fixes == 901);
    CHECK(f.rejected() == 0);
    CHECK(f.restarts() == 0);
    // The reported spread is honest: the velocity error is within its 3 sigma.
    CHECK(speed_errors.back() < 3 * e.speed_sigma_mps);
    CHECK(e.speed_sigma_mps < 1.0);
    // The covariance is symmetric with a positive diagonal.
    for (int r = 0; r < 4; ++r) {
        CHECK(e.covariance[static_cast<std::size_t>(r * 5)] > 0);
        for (int c = 0; c < 4; ++c)
            CHECK(e.covariance[static_cast<std::size_t>(r * 4 + c)] ==
                  e.covariance[static_cast<std::size_t>(c * 4 + r)]);
    }
}

TEST_CASE("ground filter: a sharp turn is followed, not rejected", "[track][ground]") {
    // East at 15 m/s, a left turn of radius 60 m (3.75 m/s^2: a street corner), then north.
    GroundFilter f;
    Noise noise(2);
    const double t1 = 20, r = 60, w = 15 / r, turn_s = (3.14159265358979 / 2) / w;
    std::vector<double> after;
    for (int i = 0; i <= 50 * rate; ++i) {
        const double t = i / rate;
        double n = 0, e = 0, vn = 0, ve = 15;
        if (t >= t1 && t < t1 + turn_s) {
            const double a = w * (t - t1);
            n = r * (1 - std::cos(a));
            e = 15 * t1 + r * std::sin(a);
            vn = 15 * std::sin(a);
            ve = 15 * std::cos(a);
        } else if (t >= t1 + turn_s) {
            n = r + 15 * (t - t1 - turn_s);
            e = 15 * t1 + r;
            vn = 15;
            ve = 0;
        } else {
            e = 15 * t;
        }
        f.update({t, at(n + noise(sigma(f)), e + noise(sigma(f))), range});
        if (t > t1 + turn_s + 8) {
            const auto est = f.estimate(t);
            after.push_back(std::hypot(est->north_mps - vn, est->east_mps - ve));
        }
    }
    CHECK(f.restarts() == 0);
    CHECK(f.rejected() <= 3);  // a few fixes at the height of the turn at most
    CHECK(p95(after) < 1.0);
    const auto est = *f.estimate(50);
    CHECK((est.course_deg < 5 || est.course_deg > 355));
    CHECK(est.speed_mps == Approx(15).margin(1.0));
}

TEST_CASE("ground filter: a gap is bridged by the prediction", "[track][ground]") {
    GroundFilter f;
    Noise noise(3);
    const double ve = 12;
    for (int i = 0; i <= 30 * rate; ++i) {
        const double t = i / rate;
        f.update({t, at(noise(sigma(f)), ve * t + noise(sigma(f))), range});
    }
    // Three seconds without fixes (under a bridge): the prediction moves on with the object.
    const auto during = *f.estimate(31.5);
    CHECK(local(during.position).second == Approx(ve * 31.5).margin(5));
    CHECK(during.position_sigma_m > f.estimate(30)->position_sigma_m);  // less sure meanwhile
    CHECK(f.update({33, at(noise(sigma(f)), ve * 33 + noise(sigma(f))), range}) ==
          GroundFilter::Outcome::accepted);
    const auto resumed = *f.estimate(33);
    CHECK(local(resumed.position).second == Approx(ve * 33).margin(5));
    CHECK(resumed.speed_mps == Approx(ve).margin(1.0));
    // A gap longer than max_gap_s starts again from the new fix, at rest.
    CHECK(f.update({60, at(0, 500), range}) == GroundFilter::Outcome::restarted);
    CHECK(f.estimate(60)->speed_mps == 0);
    CHECK(f.estimate(60)->fixes == 1);
}

TEST_CASE("ground filter: an outlier is rejected; a run of them restarts", "[track][ground]") {
    GroundFilter f;
    Noise noise(4);
    const double vn = 10;
    double t = 0;
    for (int i = 0; i <= 20 * rate; ++i) {
        t = i / rate;
        f.update({t, at(vn * t + noise(sigma(f)), noise(sigma(f))), range});
    }
    const auto before = *f.estimate(t);
    // A ray that met a roof 150 m away.
    t += 1 / rate;
    CHECK(f.update({t, at(vn * t + 150, 0), range}) == GroundFilter::Outcome::rejected);
    CHECK(f.rejected() == 1);
    const auto after = *f.estimate(t);
    CHECK(local(after.position).first == Approx(vn * t).margin(5));
    CHECK(after.speed_mps == Approx(before.speed_mps).margin(1e-9));  // untouched
    // Normal fixes go on being accepted.
    t += 1 / rate;
    CHECK(f.update({t, at(vn * t + noise(sigma(f)), noise(sigma(f))), range}) ==
          GroundFilter::Outcome::accepted);
    // An object that is really elsewhere (the tracker moved on to another one): after
    // restart_after rejections in a row the filter starts again there.
    GroundFilter::Outcome last{};
    for (int i = 0; i < f.options().restart_after; ++i) {
        t += 1 / rate;
        last = f.update({t, at(vn * t + 800, 800), range});
    }
    CHECK(last == GroundFilter::Outcome::restarted);
    CHECK(f.restarts() == 1);
    CHECK(local(f.estimate(t)->position).first == Approx(vn * t + 800).margin(0.01));
    // Not-a-number is rejected whatever the state.
    CHECK(f.update({t + 0.1, {std::nan(""), 8.5, 400}, range}) == GroundFilter::Outcome::rejected);
}

TEST_CASE("ground filter: the noise grows with slant range", "[track][ground]") {
    // The same fixes far away move the estimate less than near by.
    GroundFilter near, far;
    for (GroundFilter* f : {&near, &far}) f->update({0, at(0, 0), f == &near ? 300.0 : 5000.0});
    near.update({0.1, at(5, 0), 300});
    far.update({0.1, at(5, 0), 5000});
    CHECK(local(near.estimate(0.1)->position).first > local(far.estimate(0.1)->position).first);
    CHECK(near.estimate(0.1)->position_sigma_m < far.estimate(0.1)->position_sigma_m);
}

TEST_CASE("ground filter: a long drive keeps its accuracy past the rebasing distance",
          "[track][ground]") {
    // 25 m/s for 400 s: 10 km, twice past rebase_m; the estimate stays on the truth.
    GroundFilter f;
    Noise noise(5);
    for (int i = 0; i <= 400 * 5; ++i) {  // 5 fixes a second
        const double t = i / 5.0;
        f.update({t, at(25 * t + noise(sigma(f)), noise(sigma(f))), range});
    }
    const auto e = *f.estimate(400);
    const auto [n, east] = local(e.position);
    CHECK(n == Approx(10000).margin(6));
    CHECK(east == Approx(0).margin(6));
    CHECK(e.speed_mps == Approx(25).margin(1.0));
    CHECK(f.restarts() == 0);
}

TEST_CASE("ground filter: nothing before the first fix; estimate does not change it",
          "[track][ground]") {
    GroundFilter f;
    CHECK_FALSE(f.estimate(0));
    f.update({10, at(0, 0), range});
    f.update({11, at(0, 10), range});
    const auto a = *f.estimate(20);
    const auto b = *f.estimate(20);
    CHECK(a.position.lon_deg == b.position.lon_deg);
    CHECK(f.estimate(5)->position.lon_deg == f.estimate(11)->position.lon_deg);  // not before
    f.reset();
    CHECK_FALSE(f.estimate(12));
}
