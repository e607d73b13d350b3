"""Attacks through HTTP: 50 video viewers that never read (held), and a flood of viewers
joining and leaving (issue 25 item 9: `video_viewer` lines rolled up)."""

import socket

import attack_streams as S

ROLLUP_PER_S = 12  # contract section 14 v4: at most 10 a second, then one roll-up line


def open_viewer(port, source, gimbal="orion", rcvbuf=None, timeout=3.0):
    """A WebSocket /api/video/{gimbal} from `source`; the socket once upgraded (101), else
    None. With `rcvbuf` the socket's receive buffer is that small."""
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    if rcvbuf:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)
    s.settimeout(timeout)
    try:
        s.bind((source, 0))
        s.connect(("127.0.0.1", port))
        s.sendall(("GET /api/video/%s HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nUpgrade: websocket\r\n"
                   "Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                   "Sec-WebSocket-Version: 13\r\n\r\n" % (gimbal, port)).encode())
        head = b""
        while b"\r\n\r\n" not in head and len(head) < 8192:
            chunk = s.recv(1024)
            if not chunk:
                break
            head += chunk
        if head.startswith(b"HTTP/1.1 101"):
            return s
    except OSError:
        pass
    s.close()
    return None


def stalled_viewers(suite, f):
    """50 viewers of /api/video (13 or 12 from each of 4 addresses: the per-client cap is 16)
    that never read, while the camera streams H.264 at 30 frames/s."""
    units = suite.h264_units()
    with suite.rig(f, video="udp", http=True) as rig:
        viewers = []

        def camera(stop):
            sender = S.UdpSender(rig.video_port, rig=rig, key="camera datagrams")
            S.LegitStream(units, sender).run(stop)
            sender.close()

        def stallers(stop):
            stop.wait(0.2)  # the stream's first key frame
            for i in range(50):
                if stop.is_set():
                    break
                v = open_viewer(rig.http_port, "127.0.0.%d" % (10 + i % 4), rcvbuf=4096)
                if v is not None:
                    viewers.append(v)
            rig.count("viewers upgraded", len(viewers))
            stop.wait()

        rig.measure([camera, stallers])
        f.check(len(viewers) == 50, "only %d of 50 viewers were upgraded" % len(viewers))
        for v in viewers:
            v.close()


def viewer_flood(suite, f):
    """Viewers joining and leaving as fast as one address can (one `video_viewer` line each
    on the old code); the lines must be rolled up and the laser's lines all present."""
    with suite.rig(f, video="udp", http=True) as rig:
        def flood(stop):
            n = 0
            while not stop.is_set():
                v = open_viewer(rig.http_port, "127.0.0.20", timeout=1.0)
                if v is not None:
                    n += 1
                    v.close()
            rig.count("viewers joined", n)

        rig.measure([flood, flood])
        total, worst, rate = rig.log_rate("video_viewer")
        f.note("video_viewer lines: %d, at most %d in one second (%.0f/s)" % (total, worst,
                                                                              rate))
        f.check(rig.stats.get("viewers joined", 0) > 0, "no viewer could join")
        f.check(worst <= ROLLUP_PER_S, "video_viewer not rolled up: %d lines in one second"
                % worst)
        rig.check_safety_lines()
