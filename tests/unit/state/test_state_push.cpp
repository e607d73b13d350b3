// The pushes of a delta stream and their sharing among subscribers (state_push.hpp).
#include <catch2/catch.hpp>

#include "state/merge_patch.hpp"
#include "state/state_push.hpp"

using gimbal::state::DeltaCursor;
using gimbal::state::PushBatch;
using gimbal::state::StreamOptions;
using nlohmann::json;

namespace {

json state_at(double pan, double age) {
    return {{"protocol", "orion"},
            {"link", {{"connected", true}, {"rx_bytes", 100}}},
            {"stale", false},
            {"telemetry", {{"pan", pan}, {"tilt", -10.0}, {"age_s", age}}},
            {"gps", {{"sats", 9}, {"age_s", age}}}};
}

StreamOptions delta(double full_every_s = 10.0) {
    StreamOptions o;
    o.changes = true;
    o.full_every_s = full_every_s;
    return o;
}

}  // namespace

TEST_CASE("a plain stream sends the STATE message of section 4.1, without `full`") {
    PushBatch batch("main", state_at(1, 0.1));
    DeltaCursor unused;
    const auto& m = batch.next(StreamOptions{}, unused, 0.0);
    CHECK(m.json() == json{{"type", "state"}, {"gimbal", "main"}, {"state", state_at(1, 0.1)}});
    CHECK(*m.text() == m.json().dump());
    CHECK_FALSE(m.full());
}

TEST_CASE("a message's text is what dumping its JSON gives, for every kind and any name") {
    DeltaCursor cursor;
    const auto options = delta();
    PushBatch first("n\"ame\u00e9", state_at(1, 0.1));
    const auto& full = first.next(options, cursor, 0.0);
    CHECK(*full.text() == full.json().dump());
    CHECK(full.full() == true);
    PushBatch second("n\"ame\u00e9", state_at(2, 0.2));
    const auto& patch = second.next(options, cursor, 0.1);
    CHECK(*patch.text() == patch.json().dump());
    CHECK(patch.full() == false);
}

TEST_CASE("a delta stream: full first, then patches, a full again every full_every_s") {
    DeltaCursor cursor;
    const auto options = delta(1.0);
    {
        PushBatch batch("main", state_at(1, 0.1));
        const auto& m = batch.next(options, cursor, 0.0);
        CHECK(m.json() == json{{"type", "state"},
                               {"gimbal", "main"},
                               {"full", true},
                               {"state", state_at(1, 0.1)}});
    }
    {
        PushBatch batch("main", state_at(2, 0.2));
        const auto& m = batch.next(options, cursor, 0.5);
        CHECK(m.json() == json{{"type", "state"},
                               {"gimbal", "main"},
                               {"full", false},
                               {"state", {{"telemetry", {{"pan", 2.0}, {"age_s", 0.2}}}}}});
    }
    {
        PushBatch batch("main", state_at(2, 0.3));  // only ages moved: an empty patch
        CHECK(batch.next(options, cursor, 0.9).json()["state"] == json::object());
    }
    {
        PushBatch batch("main", state_at(2, 0.4));
        CHECK(batch.next(options, cursor, 1.0).json()["full"] == true);
    }
    cursor.restart();
    PushBatch batch("main", state_at(2, 0.5));
    CHECK(batch.next(options, cursor, 1.1).json()["full"] == true);
}

TEST_CASE("subscribers that got the same previous push share one patch") {
    DeltaCursor a, b, c;
    const auto options = delta();
    {
        PushBatch batch("main", state_at(1, 0.1));
        batch.next(options, a, 0.0);
        batch.next(options, b, 0.0);
    }
    {
        PushBatch batch("main", state_at(2, 0.2));
        batch.next(options, c, 0.1);  // c joins: its first push is full
        const auto& ma = batch.next(options, a, 0.1);
        const auto& mb = batch.next(options, b, 0.1);
        CHECK(&ma == &mb);
        CHECK(ma.text() == mb.text());  // one dump for both
        CHECK(ma.json()["full"] == false);
    }
    PushBatch batch("main", state_at(3, 0.3));
    const auto& ma = batch.next(options, a, 0.2);
    const auto& mc = batch.next(options, c, 0.2);
    CHECK(&ma == &mc);  // a and c both got the 0.1 STATE
    CHECK(ma.json()["state"]["telemetry"]["pan"] == 3.0);
}

TEST_CASE("key selections get their own messages, and merging them rebuilds the STATE") {
    DeltaCursor all, lean;
    StreamOptions options_lean = delta();
    options_lean.keys = {"telemetry"};
    json held_all, held_lean;
    for (int i = 0; i < 5; ++i) {
        const json state = state_at(i, 0.1 * i);
        PushBatch batch("main", state);
        const auto& m_all = batch.next(delta(), all, 0.1 * i);
        const auto& m_lean = batch.next(options_lean, lean, 0.1 * i);
        for (auto [m, held] : {std::pair{&m_all, &held_all}, std::pair{&m_lean, &held_lean}}) {
            if (m->json()["full"] == true)
                *held = m->json()["state"];
            else
                gimbal::state::merge_patch_apply(*held, m->json()["state"]);
        }
        CHECK(gimbal::state::same_ignoring_age(held_all, state));
        CHECK_FALSE(held_lean.contains("gps"));
        CHECK(held_lean["telemetry"]["pan"] == static_cast<double>(i));
    }
}

namespace {

// A STATE whose 1 Hz reports (gps, diagnostics, software: about 400 bytes each) change
// together with the telemetry once a second, as the simulated Orion's do.
json busy_state(int tick) {
    const std::string second = std::to_string(tick / 10);
    return {
        {"protocol", "orion"},
        {"link", {{"connected", true}, {"rx_bytes", 1000 * tick}}},
        {"stale", false},
        {"telemetry", {{"pan", tick}, {"age_s", 0.01}, {"pad", std::string(500, 't') + second}}},
        {"gps", {{"sats", tick / 10}, {"note", std::string(400, 'g') + second}}},
        {"diagnostics", {{"temp", tick / 10}, {"note", std::string(380, 'd') + second}}},
        {"software", {{"load", tick / 10}, {"note", std::string(420, 's') + second}}}};
}

}  // namespace

TEST_CASE("a patch over one payload goes as patches that fit, merging to the same STATE") {
    using gimbal::state::merge_patch_apply;
    using gimbal::state::patch_budget_bytes;
    using gimbal::state::same_ignoring_age;
    DeltaCursor cursor, twin;
    const auto options = delta(100.0);
    json held;
    std::size_t patches = 0, split = 0;
    for (int tick = 5; tick < 45; ++tick) {
        const json state = busy_state(tick);
        PushBatch batch("main", state);
        const auto& m = batch.next(options, cursor, 0.1 * tick);
        const auto& parts = batch.split(m, patch_budget_bytes);
        // A second subscriber with the same history shares the message and its parts.
        CHECK(&batch.split(batch.next(options, twin, 0.1 * tick), patch_budget_bytes) == &parts);
        if (m.json()["full"] == true) {
            REQUIRE(parts.size() == 1);  // a full STATE is never cut
            held = parts.front().json()["state"];
            continue;
        }
        ++patches;
        if (parts.size() > 1) ++split;
        for (const auto& part : parts) {
            // Each fits one payload, though the whole change of a tick (the telemetry and
            // the three reports, about 1,800 bytes) would not.
            CHECK(part.json()["full"] == false);
            CHECK(part.text()->size() <= patch_budget_bytes);
            CHECK(*part.text() == part.json().dump());
            merge_patch_apply(held, part.json()["state"]);
        }
        // Merged in order, the parts give what the one patch gives: the STATE.
        CHECK(same_ignoring_age(held, state));
    }
    CHECK(patches == 39);
    CHECK(split >= 4);  // each second's burst
}

TEST_CASE("split_patch: whole members, first-fit decreasing, one part when it fits") {
    const json patch = {{"a", std::string(100, 'a')},
                        {"b", std::string(300, 'b')},
                        {"c", std::string(50, 'c')},
                        {"d", std::string(200, 'd')}};
    // With their keys and commas: a 106, b 306, c 56, d 206 bytes; {} 2.
    const auto parts = gimbal::state::split_patch(patch, 380);
    REQUIRE(parts.size() == 2);
    CHECK(parts[0] == json{{"b", patch["b"]}, {"c", patch["c"]}});
    CHECK(parts[1] == json{{"d", patch["d"]}, {"a", patch["a"]}});
    for (const auto& part : parts) CHECK(part.dump().size() <= 380);
    CHECK(gimbal::state::split_patch(patch, 1000) == std::vector<json>{patch});
    // A member larger than the budget goes alone; nothing is lost.
    const auto small = gimbal::state::split_patch(patch, 120);
    CHECK(small.size() == 4);
    json merged = json::object();
    for (const auto& part : small) gimbal::state::merge_patch_apply(merged, part);
    CHECK(merged == patch);
    CHECK(gimbal::state::split_patch(json::object(), 10) == std::vector<json>{json::object()});
}
