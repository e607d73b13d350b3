#include "record/recording_link.hpp"

#include <memory>

#include "orion/framer.hpp"
#include "viewpro/output_framer.hpp"

namespace gimbald::record {

namespace {

constexpr std::string_view junk_dissector = "data";

std::size_t frame_size(const gimbal::orion::Frame& f) {
    return gimbal::orion::header_size + f.payload.size + gimbal::orion::checksum_size;
}

std::size_t frame_size(const gimbal::viewpro::OutputFrame& f) {
    return f.size;
}

// Runs its own copy of the session's framer over the same bytes. The framer counts every
// byte it discards (dropped_bytes) before it delivers the frame that follows them, and frames
// are contiguous, so the counter's growth at each frame is the junk run just before it.
template <class Framer>
class FramedSplitter : public InboundSplitter {
  public:
    FramedSplitter(Recorder& recorder, std::uint32_t interface_id, std::string_view dissector)
        : recorder_(recorder), interface_id_(interface_id), dissector_(dissector) {}

    void push(std::span<const std::uint8_t> bytes) override {
        held_.insert(held_.end(), bytes.begin(), bytes.end());
        std::size_t at = 0;
        framer_.push(bytes, [&](const auto& frame) {
            at = emit_junk(at);
            const std::size_t size = std::min(frame_size(frame), held_.size() - at);
            recorder_.record(interface_id_, Direction::inbound, dissector_,
                             std::span(held_).subspan(at, size));
            at += size;
        });
        at = emit_junk(at);
        // What the framer still holds is an unfinished frame; anything else beyond it would
        // mean the two views disagree - record it as junk rather than lose or repeat bytes.
        const std::size_t pending = framer_.pending_bytes();
        if (held_.size() - at > pending) {
            const std::size_t extra = held_.size() - at - pending;
            recorder_.record(interface_id_, Direction::inbound, junk_dissector,
                             std::span(held_).subspan(at, extra));
            at += extra;
        }
        held_.erase(held_.begin(), held_.begin() + static_cast<long>(at));
    }

    void flush() override {
        framer_.reset();
        dropped_seen_ = framer_.stats().dropped_bytes;
        if (!held_.empty())
            recorder_.record(interface_id_, Direction::inbound, junk_dissector, held_);
        held_.clear();
    }

  private:
    std::size_t emit_junk(std::size_t at) {
        const std::uint64_t dropped = framer_.stats().dropped_bytes;
        auto junk = static_cast<std::size_t>(dropped - dropped_seen_);
        dropped_seen_ = dropped;
        junk = std::min(junk, held_.size() - at);
        if (junk == 0) return at;
        recorder_.record(interface_id_, Direction::inbound, junk_dissector,
                         std::span(held_).subspan(at, junk));
        return at + junk;
    }

    Recorder& recorder_;
    std::uint32_t interface_id_;
    std::string_view dissector_;
    Framer framer_;
    std::uint64_t dropped_seen_ = 0;
    std::vector<std::uint8_t> held_;  // received bytes not recorded yet
};

}  // namespace

std::unique_ptr<InboundSplitter> make_inbound_splitter(std::string_view protocol,
                                                       Recorder& recorder,
                                                       std::uint32_t interface_id) {
    if (protocol == "viewpro")
        return std::make_unique<FramedSplitter<gimbal::viewpro::OutputFramer>>(
            recorder, interface_id, "viewpro");
    return std::make_unique<FramedSplitter<gimbal::orion::Framer>>(recorder, interface_id, "orion");
}

RecordingLink::RecordingLink(std::unique_ptr<Link> inner, Recorder& recorder,
                             std::uint32_t interface_id, std::string protocol)
    : inner_(std::move(inner)),
      recorder_(recorder),
      interface_id_(interface_id),
      protocol_(std::move(protocol)),
      splitter_(make_inbound_splitter(protocol_, recorder, interface_id)) {}

RecordingLink::~RecordingLink() = default;

void RecordingLink::start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) {
    inner_->start(
        [this, on_data = std::move(on_data)](std::span<const std::uint8_t> bytes) {
            splitter_->push(bytes);
            on_data(bytes);
        },
        [this, on_state = std::move(on_state)](bool up) {
            splitter_->flush();
            on_state(up);
        },
        std::move(on_error));
}

void RecordingLink::stop() {
    inner_->stop();
    splitter_->flush();
}

bool RecordingLink::send(std::vector<std::uint8_t> packet) {
    outgoing_.assign(packet.begin(), packet.end());
    if (!inner_->send(std::move(packet))) return false;
    recorder_.record(interface_id_, Direction::outbound, protocol_, outgoing_);
    return true;
}

bool RecordingLink::send_kept(std::vector<std::uint8_t> packet) {
    outgoing_.assign(packet.begin(), packet.end());
    if (!inner_->send_kept(std::move(packet))) return false;
    recorder_.record(interface_id_, Direction::outbound, protocol_, outgoing_);
    return true;
}

bool RecordingLink::send_safety(std::vector<std::uint8_t> packet, WrittenHandler on_written) {
    auto copy = std::make_shared<std::vector<std::uint8_t>>(packet);
    return inner_->send_safety(
        std::move(packet), [this, copy, on_written = std::move(on_written)](bool written) {
            if (written) recorder_.record(interface_id_, Direction::outbound, protocol_, *copy);
            if (on_written) on_written(written);
        });
}

bool RecordingLink::send_now(std::span<const std::uint8_t> packet) {
    recorder_.record(interface_id_, Direction::outbound, protocol_, packet);
    return inner_->send_now(packet);
}

}  // namespace gimbald::record
