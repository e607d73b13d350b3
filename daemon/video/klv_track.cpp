#include "video/klv_track.hpp"

#include "klv/local_set.hpp"

namespace gimbald::video {

namespace klv = gimbal::klv;

std::string_view to_string(KlvSource source) {
    return source == KlvSource::stream ? "stream" : "generated";
}

std::vector<klv::Bytes> KlvTrack::stream_unit(std::span<const std::uint8_t> unit, double now_s) {
    std::vector<klv::Bytes> valid;
    for (const klv::SetSpan s : klv::find_sets(unit).sets) {
        const auto bytes = unit.subspan(s.offset, s.size);
        klv::DecodeResult r = klv::decode(bytes);
        if (r.status == klv::DecodeStatus::bad_checksum) {
            ++bad_checksums_;
            continue;
        }
        if (!r.ok()) {
            ++malformed_;
            continue;
        }
        ++sets_;
        last_stream_s_ = now_s;
        latest_ = Latest{{bytes.begin(), bytes.end()}, KlvSource::stream, now_s, std::move(r.json)};
        valid.push_back(latest_->bytes);
    }
    return valid;
}

void KlvTrack::generated(klv::Bytes set, double now_s) {
    ++sets_;
    latest_ = Latest{std::move(set), KlvSource::generated, now_s, std::nullopt};
}

bool KlvTrack::stream_fresh(double now_s) const {
    return last_stream_s_ && now_s - *last_stream_s_ <= stream_fresh_s_;
}

std::optional<KlvSource> KlvTrack::source() const {
    if (!latest_) return std::nullopt;
    return latest_->source;
}

const klv::Bytes* KlvTrack::latest_bytes() const {
    return latest_ ? &latest_->bytes : nullptr;
}

const nlohmann::json& KlvTrack::latest_json() const {
    static const nlohmann::json none;
    if (!latest_) return none;
    if (!latest_->decoded) latest_->decoded = klv::decode(latest_->bytes).json;
    return *latest_->decoded;
}

double KlvTrack::latest_age_s(double now_s) const {
    return latest_ ? now_s - latest_->at_s : 0;
}

const nlohmann::json* KlvTrack::latest_stream_json() const {
    if (!latest_ || latest_->source != KlvSource::stream) return nullptr;
    return &*latest_->decoded;
}

}  // namespace gimbald::video
