#include "record/recording_link.hpp"

#include "protocols/registry.hpp"

namespace gimbald::record {

namespace {

constexpr std::string_view junk_dissector = "data";

// The registry's splitter of the protocol's frames, recording each piece.
class RecordingSplitter : public InboundSplitter {
  public:
    RecordingSplitter(const gimbal::protocols::Entry& protocol, Recorder& recorder,
                      std::uint32_t interface_id)
        : splitter_(protocol.make_splitter()),
          dissector_(protocol.dissector),
          piece_(
              [&recorder, interface_id, this](std::span<const std::uint8_t> bytes, bool is_frame) {
                  recorder.record(interface_id, Direction::inbound,
                                  is_frame ? dissector_ : junk_dissector, bytes);
              }) {}

    void push(std::span<const std::uint8_t> bytes) override { splitter_->push(bytes, piece_); }
    void flush() override { splitter_->flush(piece_); }

  private:
    std::unique_ptr<gimbal::framing::StreamSplitter> splitter_;
    std::string_view dissector_;
    gimbal::framing::StreamSplitter::Piece piece_;
};

}  // namespace

std::unique_ptr<InboundSplitter> make_inbound_splitter(std::string_view protocol,
                                                       Recorder& recorder,
                                                       std::uint32_t interface_id) {
    const auto* entry = gimbal::protocols::find(protocol);
    if (!entry) return nullptr;
    return std::make_unique<RecordingSplitter>(*entry, recorder, interface_id);
}

// `protocol` is a configured one, so the registry has it and splitter_ is never null.
RecordingLink::RecordingLink(std::unique_ptr<Link> inner, Recorder& recorder,
                             std::uint32_t interface_id, std::string protocol)
    : inner_(std::move(inner)),
      recorder_(recorder),
      interface_id_(interface_id),
      dissector_(gimbal::protocols::find(protocol)->dissector),
      splitter_(make_inbound_splitter(protocol, recorder, interface_id)) {}

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
    recorder_.record(interface_id_, Direction::outbound, dissector_, outgoing_);
    return true;
}

void RecordingLink::send_now(std::span<const std::uint8_t> packet) {
    recorder_.record(interface_id_, Direction::outbound, dissector_, packet);
    inner_->send_now(packet);
}

}  // namespace gimbald::record
