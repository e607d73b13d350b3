// A simulated camera's video sent over UDP as MPEG-TS with KLV (contract section 17's last
// bullet): gimbal-sim --video and gimbald's in-process sim link with a `video` section.
//
// Why a thread: rendering and encoding a frame costs about 10-15 ms of CPU (640x360,
// docs/simulator.md "Cost"), which on the io thread would hold up the model's 10 ms tick and
// every link and socket served there. So each simulated camera has one worker thread that
// renders, encodes, muxes (lib/sim_video's SimVideoStream) and sends, paced by the steady
// clock at the configured frame rate. The model is never touched from it: the model's own
// thread calls update() right after each advance(t) with the camera's view at t - a few
// doubles copied under a mutex - and the worker renders the latest view it finds.
// Compiled into gimbald and gimbal-sim; logs nothing itself (stats() says what happened).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>

#include "sim/camera_view.hpp"
#include "sim_video/sim_video_stream.hpp"

namespace gimbald::video {

struct SimVideoSenderOptions {
    std::string host;  // numeric address (unicast or multicast)
    std::uint16_t port = 0;
    std::optional<int> ttl;
    gimbal::sim_video::SimVideoStreamOptions stream;  // size, fps, bit rate, KLV, objects
    // The moving objects' truth, one JSON line per object per frame (empty: none).
    std::string objects_log;
};

struct SimVideoSenderStats {
    std::uint64_t frames = 0;
    std::uint64_t klv_sets = 0;
    std::uint64_t datagrams = 0;
    std::uint64_t bytes = 0;
    std::uint64_t send_errors = 0;  // datagrams not sent (full buffer, no route, ...)
    std::uint64_t late_frames = 0;  // frames skipped because the worker fell behind
    double cpu_s = 0;               // the worker thread's CPU time (render, encode, mux, send)
    double wall_s = 0;              // since start()
    std::string last_error;
};

class SimVideoSender {
  public:
    // Opens the encoder and the socket; throws std::runtime_error saying why not.
    explicit SimVideoSender(SimVideoSenderOptions options);
    ~SimVideoSender();
    SimVideoSender(const SimVideoSender&) = delete;
    SimVideoSender& operator=(const SimVideoSender&) = delete;

    void start();
    void stop();  // joins the worker (within one frame)

    // The model's thread, right after advance(t): the camera at t.
    void update(const gimbal::sim::CameraView& view);

    SimVideoSenderStats stats() const;
    std::string destination() const;

  private:
    void run();
    void send(std::span<const std::uint8_t> chunk);

    SimVideoSenderOptions options_;
    boost::asio::io_context io_;  // never run: the socket is used synchronously
    boost::asio::ip::udp::socket socket_;
    boost::asio::ip::udp::endpoint destination_;
    std::unique_ptr<gimbal::sim_video::SimVideoStream> stream_;  // worker thread only
    std::ofstream objects_log_;                                  // worker thread only

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<gimbal::sim::CameraView> view_;  // guarded by mutex_
    bool stopping_ = false;                        // guarded by mutex_
    SimVideoSenderStats stats_;                    // guarded by mutex_
    std::thread worker_;
};

// Where a gimbal's simulated video goes for its `video.input` URL text: the input's own
// address, or this machine (127.0.0.1 / ::1) when it binds any address. nullopt (and `why`)
// for an input the simulator cannot feed (rtsp://).
struct SimVideoTarget {
    std::string host;
    std::uint16_t port = 0;
    std::optional<int> ttl;
};
std::optional<SimVideoTarget> sim_video_target(const std::string& input_url, std::string& why);

}  // namespace gimbald::video
