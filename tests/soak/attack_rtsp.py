"""A malicious RTSP camera (issue 25 items 6, 7 and 11), written here over plain sockets
(RFC 2326, RFC 6184 for the H.264 payload): a DESCRIBE with `Content-Length: 2000000000`, an
endless fragmented frame, a redirect to another host after taking the credentials, and a
redirect loop."""

import base64
import json
import socket
import struct
import threading
import time

import attack_streams as S

LOOP_RATE_LIMIT = 10.0  # connections a second, averaged over the attack (the old code: 256)


class EvilRtsp:
    """An RTSP server on `host` in one of the modes: content_length, endless_frame, redirect
    (401 Basic until credentials come, then 302 to `redirect_to`), phish (401 Basic to all,
    Authorization headers recorded), loop (302 to itself)."""

    def __init__(self, mode, host="127.0.0.1", cap_bytes=0, sdp=None, redirect_to=None):
        self.mode, self.host, self.cap, self.sdp = mode, host, cap_bytes, sdp
        self.redirect_to = redirect_to
        self.listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.listener.bind((host, 0))
        self.listener.listen(256)
        self.port = self.listener.getsockname()[1]
        self.connections = []  # arrival times
        self.auth = []  # Authorization headers received
        self.methods = []
        self.sent = 0
        self.lock = threading.Lock()
        self.stop = threading.Event()
        # DESCRIBE waits until the suite arms the server, so gimbald's memory at the start of
        # the measure is its own (it connects as it starts, before the measure begins).
        self.armed = threading.Event()
        self.armed_at = None
        self.thread = threading.Thread(target=self._accept, daemon=True)
        self.thread.start()

    def url(self, path="stream", credentials=""):
        return "rtsp://%s%s:%d/%s" % (credentials + "@" if credentials else "", self.host,
                                      self.port, path)

    def arm(self, stop):
        """The attack's traffic: serve the attack from now until `stop`."""
        self.armed_at = time.monotonic()
        self.armed.set()
        stop.wait()

    def connections_armed(self):
        with self.lock:
            return [t for t in self.connections if self.armed_at and t >= self.armed_at]

    def close(self):
        self.stop.set()
        self.listener.close()
        self.thread.join(timeout=3)

    def _accept(self):
        self.listener.settimeout(0.1)
        while not self.stop.is_set():
            try:
                conn, _ = self.listener.accept()
            except socket.timeout:
                continue
            except OSError:
                return
            with self.lock:
                self.connections.append(time.monotonic())
            threading.Thread(target=self._serve, args=(conn,), daemon=True).start()

    def _serve(self, conn):
        conn.settimeout(0.5)
        buf = b""
        try:
            while not self.stop.is_set():
                while b"\r\n\r\n" not in buf:
                    try:
                        chunk = conn.recv(65536)
                    except socket.timeout:
                        if self.stop.is_set():
                            return
                        continue
                    if not chunk:
                        return
                    buf += chunk
                    if len(buf) > 1 << 20:
                        return
                head, buf = buf.split(b"\r\n\r\n", 1)
                lines = head.decode(errors="replace").split("\r\n")
                method = lines[0].split(" ")[0]
                headers = {}
                for line in lines[1:]:
                    if ":" in line:
                        k, v = line.split(":", 1)
                        headers[k.strip().lower()] = v.strip()
                with self.lock:
                    self.methods.append(method)
                    if "authorization" in headers:
                        self.auth.append(headers["authorization"])
                if not self._answer(conn, method, headers):
                    return
        except OSError:
            return
        finally:
            conn.close()

    def _reply(self, conn, cseq, status="200 OK", headers=(), body=b""):
        text = "RTSP/1.0 %s\r\nCSeq: %s\r\n" % (status, cseq)
        for h in headers:
            text += h + "\r\n"
        if body:
            text += "Content-Length: %d\r\n" % len(body)
        conn.sendall(text.encode() + b"\r\n" + body)

    def _answer(self, conn, method, headers):
        """Answers one request; False ends the connection."""
        cseq = headers.get("cseq", "0")
        base = "Content-Base: rtsp://%s:%d/stream/" % (self.host, self.port)
        if method == "DESCRIBE":
            while not self.armed.wait(0.1):
                if self.stop.is_set():
                    return False
        if self.mode in ("redirect", "phish") and "authorization" not in headers:
            self._reply(conn, cseq, "401 Unauthorized", ['WWW-Authenticate: Basic realm="cam"'])
            return True
        if method == "OPTIONS":
            self._reply(conn, cseq, headers=["Public: OPTIONS, DESCRIBE, SETUP, PLAY, TEARDOWN, "
                                             "GET_PARAMETER"])
            return True
        if self.mode == "phish":
            self._reply(conn, cseq, "401 Unauthorized", ['WWW-Authenticate: Basic realm="cam"'])
            return True
        if method == "DESCRIBE" and self.mode in ("redirect", "loop"):
            target = self.redirect_to or self.url("loop")
            self._reply(conn, cseq, "302 Moved Temporarily", ["Location: " + target])
            return True
        if method == "DESCRIBE" and self.mode == "content_length":
            conn.sendall(("RTSP/1.0 200 OK\r\nCSeq: %s\r\n%s\r\nContent-Type: application/sdp\r\n"
                          "Content-Length: 2000000000\r\n\r\nv=0\r\n" % (cseq, base)).encode())
            self._blast(conn, lambda: b"a=x-attack:" + b"A" * (1 << 20) + b"\r\n")
            return False
        if method == "DESCRIBE":
            self._reply(conn, cseq, headers=[base, "Content-Type: application/sdp"],
                        body=self.sdp.encode())
            return True
        if method == "SETUP":
            self._reply(conn, cseq, headers=["Transport: RTP/AVP/TCP;unicast;interleaved=0-1",
                                             "Session: 12345678;timeout=60"])
            return True
        if method == "PLAY":
            self._reply(conn, cseq, headers=["Session: 12345678",
                                             "RTP-Info: url=rtsp://%s:%d/stream/track1;seq=0;"
                                             "rtptime=0" % (self.host, self.port)])
            threading.Thread(target=self._discard, args=(conn,), daemon=True).start()
            self._blast(conn, self._fragments())
            return False
        self._reply(conn, cseq)
        return True

    def _discard(self, conn):
        """Reads whatever the client sends while the server streams (keep-alives, RTCP)."""
        try:
            while not self.stop.is_set():
                try:
                    if not conn.recv(65536):
                        return
                except socket.timeout:
                    continue
        except OSError:
            return

    def _fragments(self):
        """FU-A fragments of one IDR slice: a start, then middles forever, never an end, never
        the marker bit; 64 RTP packets over interleaved channel 0 per call."""
        state = {"seq": 0}
        payload = b"\xAB" * 1400

        def chunk():
            out = bytearray()
            for _ in range(64):
                seq = state["seq"]
                state["seq"] = (seq + 1) & 0xFFFF
                fu = b"\x7C" + (b"\x85" if seq == 0 else b"\x05")
                rtp = struct.pack(">BBHII", 0x80, 96, seq, 0, 0x1234) + fu + payload
                out += b"$\x00" + struct.pack(">H", len(rtp)) + rtp
            return bytes(out)
        return chunk

    def _blast(self, conn, produce):
        """Sends produce()'s bytes as fast as the client takes them, until the suite's cap;
        then holds the connection open, silent."""
        conn.settimeout(2.0)
        while not self.stop.is_set():
            with self.lock:
                room = self.cap - self.sent
            if room <= 0:
                self.stop.wait(0.2)
                continue
            data = produce()[:room]
            try:
                conn.sendall(data)
            except socket.timeout:
                continue
            except OSError:
                return
            with self.lock:
                self.sent += len(data)


def sdp_for(units):
    sps, pps = S.parameter_sets(units)
    sets = ",".join(base64.b64encode(x).decode() for x in (sps, pps))
    return ("v=0\r\no=- 0 0 IN IP4 127.0.0.1\r\ns=attack\r\nc=IN IP4 127.0.0.1\r\nt=0 0\r\n"
            "a=control:*\r\nm=video 0 RTP/AVP 96\r\na=rtpmap:96 H264/90000\r\n"
            "a=fmtp:96 packetization-mode=1;profile-level-id=%s;sprop-parameter-sets=%s\r\n"
            "a=control:track1\r\n" % (sps[1:4].hex().upper(), sets))


def rtsp_rig(suite, f, url):
    return suite.rig(f, video=url + "?transport=tcp")


def content_length(suite, f):
    """Item 6: DESCRIBE answered with Content-Length: 2000000000 and bytes as fast as gimbald
    reads them (capped by the suite)."""
    server = EvilRtsp("content_length", cap_bytes=suite.volume(300e6, 1.5e9))
    try:
        with rtsp_rig(suite, f, server.url()) as rig:
            rig.measure([server.arm])
            f.note("connections %d, %.0f MB served" % (len(server.connections),
                                                       server.sent / 1e6))
            f.check(server.connections, "gimbald never connected to the camera")
    finally:
        server.close()


def endless_frame(suite, f):
    """Item 6: after PLAY, one H.264 frame in FU-A fragments that never ends."""
    server = EvilRtsp("endless_frame", cap_bytes=suite.volume(300e6, 1.5e9),
                      sdp=sdp_for(suite.h264_units()))
    try:
        with rtsp_rig(suite, f, server.url()) as rig:
            rig.measure([server.arm])
            f.note("connections %d, %.0f MB of fragments served, requests %s" % (
                len(server.connections), server.sent / 1e6, ",".join(server.methods[:6])))
            f.check("PLAY" in server.methods, "gimbald never reached PLAY (attack not exercised)")
    finally:
        server.close()


def redirect_credentials(suite, f):
    """Item 7: the camera (127.0.0.1) takes the credentials, then redirects to 127.0.0.2,
    which asks for them too: none may reach it; the redirect is logged."""
    phish = EvilRtsp("phish", host="127.0.0.2")
    camera = EvilRtsp("redirect", redirect_to=phish.url("stolen"))
    try:
        with rtsp_rig(suite, f, camera.url(credentials="operator:s3cret")) as rig:
            rig.measure([camera.arm])
            logs = rig.logs()
        f.note("camera: %d connections, %d with credentials; other host: %d connections, %d "
               "Authorization headers" % (len(camera.connections), len(camera.auth),
                                          len(phish.connections), len(phish.auth)))
        f.check(camera.auth, "the camera never received the credentials (attack not exercised)")
        f.check(not phish.auth, "credentials sent to the host of the redirect (%d times: %s)"
                % (len(phish.auth), phish.auth[0] if phish.auth else ""))
        f.check(any("redirect" in json.dumps(e).lower() for e in logs),
                "the redirect to another host was not logged")
    finally:
        camera.close()
        phish.close()


def redirect_loop(suite, f):
    """Item 11: DESCRIBE redirected to itself forever; gimbald must log the failure and back
    off (the old code: 10,237 connections in 40 s)."""
    server = EvilRtsp("loop")
    try:
        with rtsp_rig(suite, f, server.url()) as rig:
            rig.measure([server.arm])
            span = time.monotonic() - server.armed_at if server.armed_at else 0.0
            n = len(server.connections_armed())
            logs = rig.logs()
        rate = n / max(span, 0.001)
        f.note("%d connections in %.1f s (%.1f/s)" % (n, span, rate))
        f.check(n > 0, "gimbald never connected to the camera")
        f.check(rate <= LOOP_RATE_LIMIT, "no back-off: %.0f connections a second (limit %.0f)"
                % (rate, LOOP_RATE_LIMIT))
        failures = [e for e in logs if e.get("level") in ("warn", "warning", "error") and
                    ("video" in str(e.get("event")) or "rtsp" in str(e.get("event")))]
        f.check(failures, "the RTSP failure was never logged")
    finally:
        server.close()
