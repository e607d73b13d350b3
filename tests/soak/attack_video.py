"""Attacks on the UDP video input (MPEG-TS, KLV): issue 25 items 1, 2 and 10, and the held
ones (junk TS, every PID, a 16 MiB PES, hostile SPS, hostile KLV sets)."""

import json
import random
import time

import attack_streams as S
from attack_rig import Client

KLV_JSON_LIMIT = 8192  # contract section 14 v4: STATE video.klv holds at most 8 KiB of JSON


def video_state(rig, timeout=2.0):
    """STATE `video` of the Orion (None when unanswered or refused)."""
    r = rig.client.request({"cmd": "state", "gimbal": "orion", "keys": ["video"]}, timeout)
    if not r or not r.get("ok"):
        return None
    return r["state"].get("video")


def note_video_counters(rig, f):
    v = video_state(rig)
    if v is None:
        f.note("STATE video unanswered after the attack")
        return None
    f.note("STATE video: klv_sets %s, klv_bad_checksums %s" % (v.get("klv_sets"),
                                                               v.get("klv_bad_checksums")))
    return v


def paced_bursts(rig, psi, grams, bursts, period_s, counter):
    """Traffic: the PSI, then `grams` in `bursts` bursts 10 ms apart, once every `period_s`;
    each whole pass counted as `counter`."""
    def send(stop):
        sender = S.UdpSender(rig.video_port, rig=rig)
        per_burst = len(grams) // bursts + 1
        while not stop.is_set():
            began = time.monotonic()
            sender.send_all(psi)
            for i in range(0, len(grams), per_burst):
                if stop.is_set():
                    break
                sender.send_all(grams[i:i + per_burst])
                time.sleep(0.01)
            else:
                rig.count(counter)
            time.sleep(max(0.0, began + period_s - time.monotonic()))
        sender.close()
    return send


def klv_huge(suite, f, bad_checksum):
    """Item 1: one 8 MB ST 0601 set of 2 M distinct unknown tags, every second."""
    data = suite.cached("klv-huge-%s" % bad_checksum,
                        lambda: S.huge_set_for_packets(2_000_000, bad_checksum))
    with suite.rig(f, video="udp") as rig:
        ts = S.Ts()
        psi = S.datagrams(ts.psi())
        grams = S.datagrams(ts.pes(S.KLV_PID, 0xBD, data, 90000, bounded=False))

        huge_sets = paced_bursts(rig, psi, grams, 70, 1.0, "sets")
        rig.measure([huge_sets])
        v = note_video_counters(rig, f)
        if v is not None and not bad_checksum and v.get("klv") is not None:
            size = len(json.dumps(v["klv"]))
            f.check(size <= KLV_JSON_LIMIT, "STATE video.klv is %d bytes of JSON (limit 8 KiB)"
                    % size)


def klv_sync_middle(suite, f):
    """Item 2: ST 1402 synchronous KLV, one "first" cell then "middle" cells without end."""
    rate_mb_s = 40.0
    with suite.rig(f, video="udp") as rig:
        ts = S.Ts(sync_klv=True)
        psi = S.datagrams(ts.psi())
        first = S.datagrams(ts.pes(S.KLV_PID, 0xFC, S.sync_cell(2, b"\x5A" * 1000), 90000))
        middle = S.datagrams(S.sync_middle_pes(ts))
        pes_bytes = len(middle) * S.DATAGRAM

        def middles(stop):
            sender = S.UdpSender(rig.video_port, rig=rig)
            sender.send_all(psi + first)
            last_psi = time.monotonic()

            def produce(n):
                nonlocal last_psi
                if time.monotonic() - last_psi > 0.25:
                    sender.send_all(psi)
                    last_psi = time.monotonic()
                for _ in range(n):
                    sender.send_all(middle)
                rig.count("middle cells", n)

            S.paced(stop, rate_mb_s * 1e6 / pes_bytes, produce)
            sender.close()

        rig.measure([middles])


def klv_state_size(suite, f):
    """Item 1: a valid 46.5 KB set (2,440 distinct unknown tags) makes STATE too large for a
    datagram; `state` and subscriptions must still get a reply (or `too_large`), never
    silence."""
    big = suite.cached("klv-46k", lambda: S.unknown_tags_set(2440, 1000, 16))
    f.note("set %d bytes" % len(big))
    with suite.rig(f, video="udp") as rig:
        ts = S.Ts()
        watcher = Client(rig.command_port)
        subscriber = Client(rig.command_port)
        asked = []  # request ids of `state`
        began = {}

        def big_sets(stop):
            sender = S.UdpSender(rig.video_port, rig=rig)
            while not stop.is_set():
                sender.send_all(S.datagrams(ts.psi() + ts.klv(big, 90000)))
                began.setdefault("first", time.monotonic())
                rig.count("sets")
                stop.wait(0.5)
            began["end"] = time.monotonic()
            sender.close()

        def ask(elapsed):
            if began and elapsed > 0.3 and (not asked or time.monotonic() - asked[-1][0] > 0.25):
                asked.append((time.monotonic(),
                              watcher.send({"cmd": "state", "gimbal": "orion"})))

        subscribed = subscriber.request({"cmd": "subscribe", "gimbal": "orion", "rate_hz": 4,
                                         "ttl_s": 60}, timeout=2.0)
        f.check(subscribed is not None and subscribed.get("ok"),
                "subscribe unanswered: %s" % subscribed)
        rig.measure([big_sets], during=ask)
        time.sleep(0.5)
        silent = too_large = ok = 0
        for _, rid in asked:
            r = watcher.reply(rid, 0.01)
            if r is None:
                silent += 1
            elif r.get("ok"):
                ok += 1
            elif r.get("error", {}).get("code") == "too_large":
                too_large += 1
        f.note("state: %d ok, %d too_large, %d silent" % (ok, too_large, silent))
        f.check(asked, "no state request was sent")
        f.check(silent == 0, "%d of %d state requests got no reply" % (silent, len(asked)))
        if "end" in began:
            # Pushes at 4 Hz from 1 s after the first set to the attack's end: at least half.
            window = began["end"] - began["first"] - 1.0
            after = [t for t, _ in subscriber.pushes
                     if began["first"] + 1.0 < t <= began["end"]]
            f.note("subscription pushes in the %.1f s after the set: %d (4 Hz)"
                   % (window, len(after)))
            f.check(len(after) >= 2 * window, "the subscription went silent after the large "
                    "set (%d pushes in %.1f s at 4 Hz)" % (len(after), window))
        watcher.close()
        subscriber.close()


def klv_foreign(suite, f):
    """Item 10: KLV from a foreign address must not become STATE klv nor be relayed."""
    units = suite.h264_units()
    out_port = S.free_udp_port()
    with suite.rig(f, video="udp", video_extra={"outputs": ["klv-udp://127.0.0.1:%d"
                                                           % out_port]}) as rig:
        relay = S.UdpCollector(out_port)
        seen = {"LEGIT": 0, "FOREIGN": 0, "polls": 0}

        def camera(stop):
            sender = S.UdpSender(rig.video_port, rig=rig, key="camera datagrams")
            S.LegitStream(units, sender, mission="LEGIT").run(stop)
            sender.close()

        def foreigner(stop):
            stop.wait(0.3)
            sender = S.UdpSender(rig.video_port, source="127.0.0.7", rig=rig,
                                 key="foreign datagrams")
            ts = S.Ts()
            n = 0
            while not stop.is_set():
                if n % 10 == 0:
                    sender.send_all(S.datagrams(ts.psi()))
                sender.send_all(S.datagrams(ts.klv(S.legit_set("FOREIGN", 10.0, 10.0),
                                                   90000 + n * 1800)))
                n += 1
                stop.wait(0.02)
            sender.close()

        def poll(elapsed):
            v = video_state(rig, timeout=0.3)
            seen["polls"] += 1
            text = json.dumps((v or {}).get("klv"))
            for who in ("LEGIT", "FOREIGN"):
                if who in text:
                    seen[who] += 1

        rig.measure([camera, foreigner], during=poll)
        relayed = relay.data()
        relay.close()
        foreign_out = sum(1 for d in relayed if b"FOREIGN" in d)
        legit_out = sum(1 for d in relayed if b"LEGIT" in d)
        f.note("STATE polls %d: LEGIT %d, FOREIGN %d; relayed LEGIT %d, FOREIGN %d" % (
            seen["polls"], seen["LEGIT"], seen["FOREIGN"], legit_out, foreign_out))
        f.check(seen["FOREIGN"] == 0, "foreign KLV became STATE klv (%d of %d polls)"
                % (seen["FOREIGN"], seen["polls"]))
        f.check(foreign_out == 0, "foreign KLV relayed (%d sets)" % foreign_out)
        f.check(seen["LEGIT"] > 0, "the camera's own KLV never reached STATE")


# --- the attacks that held (keep them holding) -----------------------------------------------

def ts_junk(suite, f):
    """30,300 junk TS datagrams (about 3,000 a second): noise, and 0x47-synced packets with
    random headers."""
    rng = random.Random(1)
    junk = [bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 1500))) for _ in range(150)]
    synced = [b"".join(b"\x47" + bytes(rng.getrandbits(8) for _ in range(187))
                       for _ in range(7)) for _ in range(150)]
    pool = junk + synced
    with suite.rig(f, video="udp") as rig:
        def flood(stop):
            sender = S.UdpSender(rig.video_port, rig=rig)
            S.paced(stop, 3030, lambda n: sender.send_all(rng.choice(pool) for _ in range(n)))
            sender.close()

        rig.measure([flood])


def ts_pid_flood(suite, f):
    """Every PID of the 8,192 flooded with random packets, and the program changing 20 times
    a second (PAT/PMT of ever new programs and PIDs)."""
    rng = random.Random(2)
    noise = [bytes(rng.getrandbits(8) for _ in range(184)) for _ in range(64)]
    with suite.rig(f, video="udp") as rig:
        def flood(stop):
            sender = S.UdpSender(rig.video_port, rig=rig)
            state = {"pid": 0, "n": 0, "psi_at": 0.0}

            def produce(n):
                for _ in range(n):
                    packets = []
                    for _ in range(7):
                        pid = state["pid"]
                        state["pid"] = (pid + 1) % 8192
                        head = bytes([0x47, (0x40 if rng.random() < 0.3 else 0) | (pid >> 8),
                                      pid & 0xFF, 0x10 | rng.randrange(16)])
                        packets.append(head + noise[rng.randrange(64)])
                    sender.send(b"".join(packets))
                if time.monotonic() - state["psi_at"] > 0.05:
                    state["n"] += 1
                    k = state["n"]
                    w = S.vt.TsWriter(video_pid=0x30 + (k * 7) % 8000,
                                      klv_pid=0x31 + (k * 11) % 8000,
                                      pmt_pid=0x20 + (k * 13) % 8000, program=1 + k % 65000,
                                      version=k % 32)
                    sender.send(w.psi())
                    state["psi_at"] = time.monotonic()

            S.paced(stop, 4000, produce)
            sender.close()

        rig.measure([flood])


def pes_16mib(suite, f):
    """A video PES of 16 MiB + 100 KiB (over the demultiplexer's bound) every 2 s."""
    with suite.rig(f, video="udp") as rig:
        ts = S.Ts()
        au = b"\x00\x00\x00\x01\x09\xF0\x00\x00\x00\x01\x65" + b"\xAB" * ((16 << 20) + 100 * 1024)
        grams = S.datagrams(ts.video(au, 90000))
        psi = S.datagrams(ts.psi())

        big_pes = paced_bursts(rig, psi, grams, 180, 2.0, "PES")
        rig.measure([big_pes])


def sps_hostile(suite, f):
    """5,000 hostile H.264 SPS (500 a second): overflowing exp-Golomb codes, absurd sizes,
    crops, scaling lists, POC cycles, VUI/HRD, truncation, noise."""
    units = suite.cached("hostile-sps", lambda: S.hostile_sps_units(suite.count(500, 5000)))
    with suite.rig(f, video="udp") as rig:
        def flood(stop):
            sender = S.UdpSender(rig.video_port, rig=rig)
            ts = S.Ts(klv=False)
            state = {"i": 0, "psi_at": 0.0}

            def produce(n):
                if time.monotonic() - state["psi_at"] > 0.25:
                    sender.send_all(S.datagrams(ts.psi()))
                    state["psi_at"] = time.monotonic()
                for _ in range(n):
                    i = state["i"]
                    state["i"] += 1
                    sender.send_all(S.datagrams(ts.video(units[i % len(units)],
                                                         (90000 + i * 3000) % (1 << 33))))
                rig.count("SPS", n)

            S.paced(stop, 500, produce)
            sender.close()

        rig.measure([flood])


def klv_hostile(suite, f):
    """~2,800 hostile ST 0601 sets (280 a second): absurd BER lengths, endless tags, items past
    the end, wrong lengths with good checksums, nested garbage, mutations, keys cut across
    PES packets."""
    sets = suite.cached("hostile-klv", lambda: S.hostile_klv_sets(suite.count(280, 2800)))
    with suite.rig(f, video="udp") as rig:
        def flood(stop):
            sender = S.UdpSender(rig.video_port, rig=rig)
            ts = S.Ts()
            state = {"i": 0, "psi_at": 0.0}

            def produce(n):
                if time.monotonic() - state["psi_at"] > 0.25:
                    sender.send_all(S.datagrams(ts.psi()))
                    state["psi_at"] = time.monotonic()
                for _ in range(n):
                    i = state["i"]
                    state["i"] += 1
                    data = sets[i % len(sets)]
                    if i % 7 == 0:  # a set cut across two PES packets
                        half = len(data) // 2
                        out = ts.klv(data[:half], 90000 + i * 300) + \
                            ts.klv(data[half:], 90000 + i * 300 + 1)
                    else:
                        out = ts.klv(data, 90000 + i * 300)
                    sender.send_all(S.datagrams(out))
                rig.count("sets", n)

            S.paced(stop, 280, produce)
            sender.close()

        rig.measure([flood])
