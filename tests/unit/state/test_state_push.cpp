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
