#include "video/klv_track.hpp"

#include "klv/local_set.hpp"

namespace gimbald::video {

namespace klv = gimbal::klv;

std::string_view to_string(KlvSource source) {
    return source == KlvSource::stream ? "stream" : "generated";
}

void KlvTrack::stream_sets(klv::CheckedSets checked, double now_s) {
    bad_checksums_ += checked.bad_checksums;
    refused_ += checked.refused;
    if (checked.sets.empty()) return;
    sets_ += checked.sets.size();
    last_stream_s_ = now_s;
    // Cut to max_json_bytes already, where it was checked (TsWorker).
    klv::CheckedSet& last = checked.sets.back();
    latest_ = Latest{std::move(last.bytes), KlvSource::stream, now_s, std::move(last.json)};
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
    if (!latest_->decoded) {
        latest_->decoded = klv::decode(latest_->bytes).json;
        klv::fit_json(*latest_->decoded, max_json_bytes);
    }
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
