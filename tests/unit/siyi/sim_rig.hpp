// A controller for the simulated SIYI gimbal in tests: sends messages through the codec,
// advances time, and keeps every frame the gimbal sent, decoded. Not a test file itself.
#pragma once

#include <catch2/catch.hpp>
#include <vector>

#include "protocols/siyi/codec/framer.hpp"
#include "protocols/siyi/codec/messages.hpp"
#include "protocols/siyi/sim/siyi_sim.hpp"

namespace siyi_test {

struct Received {
    gimbal::siyi::Frame frame;
    gimbal::siyi::FromGimbal message;
    double time_s;
};

struct Rig {
    explicit Rig(gimbal::protocols::SiyiSimOptions options = {}) : sim(options) {
        sim.advance(t, raw);
    }

    gimbal::protocols::SiyiSim sim;
    double t = 100.0;  // any epoch
    std::uint16_t seq = 0;
    gimbal::siyi::Framer framer;
    std::vector<std::uint8_t> raw;
    std::vector<Received> got;

    template <class M>
    void send(const M& m) {
        send_bytes(
            gimbal::siyi::encode(m, gimbal::siyi::Header{gimbal::siyi::ctrl_need_ack, seq++}));
    }
    void send_bytes(const std::vector<std::uint8_t>& bytes) { sim.receive(bytes, t); }

    // Runs the gimbal for `seconds` in steps of `step` and collects what it sends.
    void run(double seconds, double step = 0.01) {
        const double end = t + seconds;
        while (t < end - 1e-9) {
            t = std::min(end, t + step);
            collect();
        }
        collect();
    }
    void collect() {
        std::vector<std::uint8_t> out;
        sim.advance(t, out);
        raw.insert(raw.end(), out.begin(), out.end());
        framer.push(out, [&](const gimbal::siyi::Frame& f) {
            const auto d = gimbal::siyi::decode_from_gimbal(f);
            REQUIRE(d.ok());
            got.push_back({f, d.value, t});
        });
    }

    // The messages of type M received so far.
    template <class M>
    std::vector<M> all() const {
        std::vector<M> out;
        for (const Received& r : got)
            if (const auto* m = std::get_if<M>(&r.message)) out.push_back(*m);
        return out;
    }
    template <class M>
    M last() const {
        const auto v = all<M>();
        REQUIRE_FALSE(v.empty());
        return v.back();
    }
    // Sends a request and returns the one reply of type M it causes.
    template <class M, class Q>
    M ask(const Q& q) {
        const std::size_t before = all<M>().size();
        send(q);
        collect();
        const auto v = all<M>();
        REQUIRE(v.size() == before + 1);
        return v.back();
    }
    gimbal::siyi::GimbalAttitude attitude() {
        return ask<gimbal::siyi::GimbalAttitude>(gimbal::siyi::GimbalAttitudeRequest{});
    }
    void clear() { got.clear(); }
};

}  // namespace siyi_test
