#!/usr/bin/env python3
"""The concurrent `ping` of the attack suite, in a process of its own so that the attack's
traffic (Python threads in the suite) never delays a ping or its timing.

    attack_pinger.py PORT SOURCE_ADDRESS INTERVAL_S

Sends {"cmd": "ping", "id": N} to 127.0.0.1:PORT from SOURCE_ADDRESS every INTERVAL_S until a
line arrives on standard input (or it closes), waits one more second for late replies, then
prints one JSON object: {"sent": N, "rtts_ms": [...], "lost": N}. A ping answered late is
counted with its round-trip time; one never answered is lost.
"""

import json
import os
import select
import socket
import sys
import time

GRACE_S = 1.0


def main():
    port, source, interval = int(sys.argv[1]), sys.argv[2], float(sys.argv[3])
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind((source, 0))
    sock.setblocking(False)
    sent = {}
    rtts = {}
    n = 0
    next_send = time.monotonic()
    stop_at = None
    stdin = sys.stdin.fileno()
    while True:
        now = time.monotonic()
        if stop_at is not None and (now >= stop_at or len(rtts) == len(sent)):
            break
        if stop_at is None and now >= next_send:
            n += 1
            sent[n] = time.monotonic()
            try:
                sock.sendto(b'{"cmd":"ping","id":%d}' % n, ("127.0.0.1", port))
            except OSError:
                pass
            next_send += interval
            if next_send < now:
                next_send = now + interval
        wait = (stop_at if stop_at is not None else next_send) - time.monotonic()
        watch = [sock] if stop_at is not None else [sock, stdin]
        ready, _, _ = select.select(watch, [], [], max(0.0, wait))
        if stdin in ready:
            os.read(stdin, 4096)
            stop_at = time.monotonic() + GRACE_S
        if sock in ready:
            while True:
                try:
                    data = sock.recv(65536)
                except (BlockingIOError, ConnectionRefusedError):
                    break
                arrived = time.monotonic()
                try:
                    reply_id = json.loads(data).get("id")
                except ValueError:
                    continue
                if reply_id in sent and reply_id not in rtts:
                    rtts[reply_id] = (arrived - sent[reply_id]) * 1000.0
    print(json.dumps({"sent": len(sent), "rtts_ms": [rtts[i] for i in sorted(rtts)],
                      "lost": len(sent) - len(rtts)}), flush=True)


if __name__ == "__main__":
    main()
