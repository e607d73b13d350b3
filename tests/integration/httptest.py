"""HTTP and WebSocket clients for the gimbald HTTP tests, standard library only.

The WebSocket client is written out here (RFC 6455: the opening handshake, masked client
frames, text/binary/close/ping/pong) so a test can also send what a proper library never
would: binary frames, oversized messages, garbage."""

import base64
import hashlib
import http.client
import json
import os
import select
import socket
import struct
import time

WS_GUID = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11"


def request(port, method, path, body=None, headers=None, timeout=5.0, host="127.0.0.1"):
    """One HTTP request on a fresh connection: (status, headers dict (lower-case), body bytes)."""
    conn = http.client.HTTPConnection(host, port, timeout=timeout)
    try:
        conn.request(method, path, body=body, headers=headers or {})
        res = conn.getresponse()
        data = res.read()
        return res.status, {k.lower(): v for k, v in res.getheaders()}, data
    finally:
        conn.close()


def get_json(port, path):
    status, _, body = request(port, "GET", path)
    return status, json.loads(body)


def post_command(port, req):
    status, _, body = request(port, "POST", "/api/command", body=json.dumps(req).encode(),
                              headers={"Content-Type": "application/json"})
    return status, json.loads(body)


def raw_exchange(port, data, timeout=5.0, source=None):
    """Sends raw bytes on a new connection; returns everything the server sent until it
    closed (or `timeout`). `source`: local address to bind (allow-list tests)."""
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        if source:
            s.bind((source, 0))
        s.settimeout(timeout)
        s.connect(("127.0.0.1", port))
        try:
            s.sendall(data)
        except (BrokenPipeError, ConnectionResetError):
            pass
        out = b""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                chunk = s.recv(65536)
            except (ConnectionResetError, socket.timeout):
                break
            if not chunk:
                break
            out += chunk
        return out
    finally:
        s.close()


def status_of(raw):
    """The status code of a raw HTTP response, or None."""
    if not raw.startswith(b"HTTP/1."):
        return None
    return int(raw.split(b" ", 2)[1])


def parse_metrics(text):
    """Prometheus text -> {(name, frozenset(labels.items())): value}."""
    out = {}
    for line in text.splitlines():
        if not line or line.startswith("#"):
            continue
        name_labels, value = line.rsplit(" ", 1)
        labels = {}
        if "{" in name_labels:
            name, rest = name_labels.split("{", 1)
            rest = rest.rstrip("}")
            # Label values in our output hold no commas or quotes except escaped ones.
            for part in filter(None, rest.split('",')):
                k, v = part.split("=", 1)
                labels[k] = v.strip('"')
        else:
            name = name_labels
        out[(name, frozenset(labels.items()))] = float(value)
    return out


def metric(metrics, name, **labels):
    return metrics.get((name, frozenset(labels.items())))


class WebSocket:
    """A minimal RFC 6455 client."""

    def __init__(self, port, path="/api/stream", rcvbuf=None, timeout=5.0, origin=None):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        if rcvbuf:
            # Before connect(): the window the server sees is then small from the start.
            self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)
        self.sock.settimeout(timeout)
        self.sock.connect(("127.0.0.1", port))
        key = base64.b64encode(os.urandom(16)).decode()
        origin_line = "Origin: %s\r\n" % origin if origin else ""
        self.sock.sendall(("GET %s HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nUpgrade: websocket\r\n"
                           "Connection: Upgrade\r\nSec-WebSocket-Key: %s\r\n%s"
                           "Sec-WebSocket-Version: 13\r\n\r\n" % (path, port, key,
                                                                   origin_line)).encode())
        self.buffer = b""
        while b"\r\n\r\n" not in self.buffer:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("closed during the handshake: %r" % self.buffer)
            self.buffer += chunk
        head, self.buffer = self.buffer.split(b"\r\n\r\n", 1)
        self.handshake = head.decode()
        if not head.startswith(b"HTTP/1.1 101"):
            raise ConnectionError("handshake refused: %s" % self.handshake)
        accept = base64.b64encode(hashlib.sha1((key + WS_GUID).encode()).digest()).decode()
        if ("sec-websocket-accept: " + accept.lower()) not in self.handshake.lower():
            raise ConnectionError("bad Sec-WebSocket-Accept: %s" % self.handshake)
        self.close_code = None

    def send_frame(self, opcode, payload, fin=True, mask=True):
        head = bytes([(0x80 if fin else 0) | opcode])
        n = len(payload)
        mbit = 0x80 if mask else 0
        if n < 126:
            head += bytes([mbit | n])
        elif n < 65536:
            head += bytes([mbit | 126]) + struct.pack(">H", n)
        else:
            head += bytes([mbit | 127]) + struct.pack(">Q", n)
        if mask:
            key = os.urandom(4)
            payload = bytes(b ^ key[i % 4] for i, b in enumerate(payload))
            head += key
        self.sock.sendall(head + payload)

    def send_text(self, text):
        self.send_frame(0x1, text.encode())

    def send_json(self, obj):
        self.send_text(json.dumps(obj))

    def _read_exact(self, n, deadline):
        while len(self.buffer) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                raise socket.timeout("no frame in time")
            ready, _, _ = select.select([self.sock], [], [], left)
            if not ready:
                continue
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError("connection closed")
            self.buffer += chunk
        out, self.buffer = self.buffer[:n], self.buffer[n:]
        return out

    def recv_frame(self, timeout=5.0):
        """(opcode, payload) of the next message, its fragments joined; pings are answered
        and skipped."""
        deadline = time.monotonic() + timeout
        message_opcode, parts = None, []
        while True:
            fin, opcode, payload = self._recv_one(deadline)
            if opcode >= 0x8:  # control frames may come between fragments
                if opcode == 0x9:
                    self.send_frame(0xA, payload)
                    continue
                if opcode == 0xA:
                    continue
                self.close_code = (struct.unpack(">H", payload[:2])[0]
                                   if len(payload) >= 2 else None)
                return opcode, payload
            if opcode != 0x0:
                message_opcode = opcode
            parts.append(payload)
            if fin:
                return message_opcode, b"".join(parts)

    def _recv_one(self, deadline):
        while True:
            b0, b1 = self._read_exact(2, deadline)
            opcode = b0 & 0x0F
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read_exact(2, deadline))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read_exact(8, deadline))[0]
            payload = self._read_exact(n, deadline)
            return bool(b0 & 0x80), opcode, payload

    def recv_json(self, timeout=5.0):
        """The next text message as an object; None when the server closed (close_code set)."""
        opcode, payload = self.recv_frame(timeout)
        if opcode == 0x8:
            return None
        return json.loads(payload)

    def wait_json(self, predicate, timeout=5.0):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            msg = self.recv_json(max(0.01, deadline - time.monotonic()))
            if msg is None:
                return None
            if predicate(msg):
                return msg
        return None

    def wait_close(self, timeout=5.0):
        """Reads until the server's close frame; returns its code (None: closed without one)."""
        deadline = time.monotonic() + timeout
        try:
            while time.monotonic() < deadline:
                opcode, _ = self.recv_frame(max(0.01, deadline - time.monotonic()))
                if opcode == 0x8:
                    return self.close_code
        except (ConnectionError, OSError):
            return self.close_code
        return self.close_code

    def close(self):
        try:
            self.send_frame(0x8, struct.pack(">H", 1000))
        except OSError:
            pass
        self.sock.close()
