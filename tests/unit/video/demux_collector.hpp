// Collects what a TsDemuxer delivers, as owned copies, for the video tests.
#pragma once

#include <vector>

#include "video/ts_demuxer.hpp"

namespace gimbal::test {

struct KlvCopy {
    gimbal::video::KlvCarriage carriage;
    std::optional<std::uint64_t> pts;
    std::vector<std::uint8_t> data;
    friend bool operator==(const KlvCopy&, const KlvCopy&) = default;
};

struct Collector {
    std::vector<gimbal::video::AccessUnitBuffer> units;
    std::vector<KlvCopy> klv;
    std::vector<gimbal::video::ProgramInfo> programs;

    gimbal::video::TsDemuxer::Handlers handlers() {
        return {[this](const gimbal::video::AccessUnit& au) { units.emplace_back(au); },
                [this](const gimbal::video::KlvUnit& k) {
                    klv.push_back({k.carriage, k.pts, {k.data.begin(), k.data.end()}});
                },
                [this](const gimbal::video::ProgramInfo& p) { programs.push_back(p); }};
    }
};

inline bool same_unit(const gimbal::video::AccessUnitBuffer& a,
                      const gimbal::video::AccessUnitBuffer& b) {
    return a.codec == b.codec && a.pts == b.pts && a.dts == b.dts && a.key_frame == b.key_frame &&
           a.data == b.data;
}

}  // namespace gimbal::test
