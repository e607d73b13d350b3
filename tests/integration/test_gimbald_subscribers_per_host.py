#!/usr/bin/env python3
"""command.max_subscribers_per_host (contract section 14): one source address holds at most
that many UDP subscriptions (default 16); past it `subscribe` answers `busy` to that host
only, while other hosts still subscribe and get their STATE."""

import json
import os
import socket

import gimbaltest as gt


def client_from(daemon, address):
    """A command-socket client bound to `address` (any 127.0.0.0/8 address is local)."""
    c = gt.Client(daemon.port)
    c.sock.close()
    c.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    c.sock.bind((address, 0))
    return c


class SubscribersPerHost(gt.GimbaldTestCase):
    def clients_from(self, daemon, address, n):
        out = [client_from(daemon, address) for _ in range(n)]
        for c in out:
            self.addCleanup(c.close)
        return out

    def test_default_sixteen_per_host_then_busy_for_that_host_only(self):
        daemon = self.start_daemon({}, ("--sim",))
        first = self.clients_from(daemon, "127.0.0.1", 17)
        for c in first[:16]:
            self.assertOk(c.request("subscribe", rate_hz=1, ttl_s=30, events=False))
        for c in first[16:]:
            reply = c.request("subscribe", rate_hz=1, ttl_s=30)
            self.assertError(reply, "busy")
            self.assertIn("max_subscribers_per_host = 16", reply["error"]["message"])
            self.assertIn("127.0.0.1", reply["error"]["message"])
        # Renewing one that is held is not a new subscription.
        self.assertOk(first[3].request("subscribe", rate_hz=2, ttl_s=30, events=False))
        # Another host is not affected, and gets its STATE.
        other = self.clients_from(daemon, "127.0.0.2", 1)[0]
        self.assertOk(other.request("subscribe", rate_hz=5, ttl_s=30, events=False))
        self.assertTrue(other.wait_message(gt.is_state, 3.0))
        # A slot given up is the host's again.
        self.assertOk(first[0].request("unsubscribe"))
        self.assertOk(first[16].request("subscribe", rate_hz=1, ttl_s=30, events=False))
        state = first[16].request("state")["state"]
        self.assertEqual(state["protocol"], "orion")

    def test_configured_limit(self):
        daemon = self.start_daemon({"command": {"max_subscribers_per_host": 2}}, ("--sim",))
        a = self.clients_from(daemon, "127.0.0.1", 3)
        self.assertOk(a[0].request("subscribe", ttl_s=5))
        self.assertOk(a[1].request("subscribe", ttl_s=5))
        reply = a[2].request("subscribe", ttl_s=5)
        self.assertError(reply, "busy")
        self.assertIn("max_subscribers_per_host = 2", reply["error"]["message"])
        b = self.clients_from(daemon, "127.0.0.3", 2)
        self.assertOk(b[0].request("subscribe", ttl_s=5))
        self.assertOk(b[1].request("subscribe", ttl_s=5))

    def test_bad_limit_is_a_configuration_error(self):
        path = os.path.join(self.workdir, "bad.json")
        with open(path, "w") as f:
            json.dump({"command": {"max_subscribers_per_host": 0}}, f)
        result = gt.run([gt.GIMBALD, "--check-config", "-c", path])
        self.assertEqual(result.returncode, 1)
        self.assertIn("command.max_subscribers_per_host: must be between 1 and 1024",
                      result.stdout + result.stderr)

if __name__ == "__main__":
    gt.main()
