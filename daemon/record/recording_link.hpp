// A Link wrapper that records a gimbal link for the flight recorder: every packet the session
// writes (outbound, when the link accepts it) and every byte the gimbal sends (inbound), split
// into the protocol's frames and the junk runs between them exactly as the session's framer
// splits them - the inbound PDUs of a link, concatenated, are the bytes the gimbal sent.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "link/link.hpp"
#include "record/recorder.hpp"

namespace gimbald::record {

// Splits a received byte stream into frames and junk and records each piece.
class InboundSplitter {
  public:
    virtual ~InboundSplitter() = default;
    virtual void push(std::span<const std::uint8_t> bytes) = 0;
    // A (re)connect or disconnect: the held partial frame belongs to nothing; record it as junk.
    virtual void flush() = 0;
};

// A splitter running the framer of `protocol` (a registry name); frames are recorded with its
// dissector, junk as "data".
std::unique_ptr<InboundSplitter> make_inbound_splitter(std::string_view protocol,
                                                       Recorder& recorder,
                                                       std::uint32_t interface_id);

class RecordingLink : public Link {
  public:
    // `protocol`: a registry name.
    RecordingLink(std::unique_ptr<Link> inner, Recorder& recorder, std::uint32_t interface_id,
                  std::string protocol);
    ~RecordingLink() override;

    void start(DataHandler on_data, StateHandler on_state, ErrorHandler on_error) override;
    void stop() override;
    bool connected() const override { return inner_->connected(); }
    bool send(std::vector<std::uint8_t> packet) override;
    void send_now(std::span<const std::uint8_t> packet) override;
    const LinkStats& stats() const override { return inner_->stats(); }
    std::string type() const override { return inner_->type(); }
    std::string endpoint() const override { return inner_->endpoint(); }

  private:
    std::unique_ptr<Link> inner_;
    Recorder& recorder_;
    std::uint32_t interface_id_;
    std::string_view dissector_;  // the registry's, of this link's protocol
    std::unique_ptr<InboundSplitter> splitter_;
    std::vector<std::uint8_t> outgoing_;  // copy of the packet being sent (capacity reused)
};

}  // namespace gimbald::record
