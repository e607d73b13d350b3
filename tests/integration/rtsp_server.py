#!/usr/bin/python3
"""An RTSP server for the video tests, built on GStreamer's RTSP server library through
Debian's python3-gi (run it with /usr/bin/python3; a pyenv python lacks the bindings).

Serves /test: a live test pattern encoded by x264 (or x265 with --codec h265) and packed
with rtph264pay/rtph265pay, over RTP/UDP or RTP/TCP as the client asks. Parameter sets go
only in the SDP (config-interval=0) unless --inband, so a client must insert them itself.
Prints "ready PORT" on stdout once it listens (--port 0 picks a free port), then serves
until killed or until --seconds have passed.

  /usr/bin/python3 rtsp_server.py --port 0 --width 320 --height 240 --fps 15
"""
import argparse
import sys

import gi

gi.require_version("Gst", "1.0")
gi.require_version("GstRtspServer", "1.0")
from gi.repository import GLib, Gst, GstRtspServer  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--port", type=int, default=0)
    ap.add_argument("--codec", choices=["h264", "h265"], default="h264")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--fps", type=int, default=15)
    ap.add_argument("--inband", action="store_true", help="SPS/PPS in band too")
    ap.add_argument("--seconds", type=float, default=0, help="exit after this long (0: never)")
    args = ap.parse_args()

    Gst.init(None)
    interval = -1 if args.inband else 0
    if args.codec == "h264":
        enc = (f"x264enc tune=zerolatency speed-preset=ultrafast key-int-max={args.fps} "
               f"! video/x-h264,profile=baseline ! rtph264pay name=pay0 pt=96 config-interval={interval}")
    else:
        enc = (f"x265enc tune=zerolatency speed-preset=ultrafast key-int-max={args.fps} "
               f"! rtph265pay name=pay0 pt=96 config-interval={interval}")
    launch = (f"( videotestsrc is-live=true pattern=ball "
              f"! video/x-raw,width={args.width},height={args.height},framerate={args.fps}/1 "
              f"! {enc} )")

    server = GstRtspServer.RTSPServer()
    server.set_address("127.0.0.1")
    server.set_service(str(args.port))
    factory = GstRtspServer.RTSPMediaFactory()
    factory.set_launch(launch)
    factory.set_shared(True)  # every client sees the same stream; UDP and TCP both allowed
    server.get_mount_points().add_factory("/test", factory)
    if server.attach(None) == 0:
        print("error: cannot listen", file=sys.stderr)
        return 1
    print(f"ready {server.get_bound_port()}", flush=True)
    loop = GLib.MainLoop()
    if args.seconds > 0:
        GLib.timeout_add(int(args.seconds * 1000), loop.quit)
    loop.run()
    return 0


if __name__ == "__main__":
    sys.exit(main())
