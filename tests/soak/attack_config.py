"""Hostile configuration files (issue 25 item 12): /dev/zero, a FIFO, text after a NUL, a
5 MB unclosed array. `gimbald --check-config -c FILE` and `gimbald -c FILE` must both refuse
(exit 1) within 2 s, with a message, and stay under 128 MB while doing so (contract section
14 v4: regular files only, at most 1 MiB, no NUL)."""

import os

from attack_process import run_measured
from attack_rig import free_port

LIMIT_S = 2.0
RSS_LIMIT_MB = 128.0


def refuse(suite, f, path):
    """Runs both commands; the verdict on each."""
    f.runtime = False
    timeout = 3.0 if suite.brief else 10.0
    peak = 0
    shown = os.path.basename(path) if path.startswith(suite.workdir) else path
    for args in (["--check-config", "-c", path], ["-c", path]):
        what = "gimbald " + " ".join(a if a != path else shown for a in args)
        code, seconds, rss_kb, text = run_measured([suite.gimbald] + args, timeout)
        peak = max(peak, rss_kb)
        f.note("%s: %s in %.2f s, peak RSS %.0f MB: %s" % (
            what, "killed (hung)" if code is None else "exit %d" % code, seconds,
            rss_kb / 1024.0, " ".join(text.split())[:140]))
        if code is None:
            started = '"event":"start"' in text.replace(" ", "")
            f.fail("%s %s (killed after %.0f s)" % (what, "started and ran with it" if started
                                                    else "hung", timeout))
            continue
        f.check(code == 1, "%s: exit %s, not 1" % (what, code))
        f.check(seconds <= LIMIT_S, "%s took %.1f s (limit %.0f)" % (what, seconds, LIMIT_S))
        f.check(rss_kb / 1024.0 < RSS_LIMIT_MB, "%s peaked at %.0f MB" % (what, rss_kb / 1024.0))
        f.check(text.strip(), "%s said nothing" % what)
    f.rss_peak_kb = peak


def dev_zero(suite, f):
    refuse(suite, f, "/dev/zero")


def fifo(suite, f):
    path = os.path.join(suite.attack_dir(f.name), "gimbald.json")
    if not os.path.exists(path):
        os.mkfifo(path)
    refuse(suite, f, path)


def text_after_nul(suite, f):
    """A valid configuration, a NUL, then more text (the port is free: if it is accepted and
    started, it binds nothing anyone else uses)."""
    path = os.path.join(suite.attack_dir(f.name), "nul.json")
    with open(path, "wb") as out:
        out.write(b'{"gimbals": [], "command": {"port": %d}}\x00{"laser": {"allow_fire": true}}'
                  % free_port())
    refuse(suite, f, path)


def unclosed_array(suite, f):
    """5 MB of '[' after the gimbals key: never closed."""
    path = os.path.join(suite.attack_dir(f.name), "unclosed.json")
    with open(path, "wb") as out:
        out.write(b'{"gimbals": ' + b"[" * 5_000_000)
    refuse(suite, f, path)

