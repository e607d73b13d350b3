#!/usr/bin/env bash
# Hostile input on the MQTT command topic (contract section 14) against a real mosquitto.
# paho-mqtt comes from Debian (python3-paho-mqtt) and imports only under /usr/bin/python3.
here="$(cd "$(dirname "$0")" && pwd)"
# shellcheck source=skip.sh
. "$here/skip.sh"
if ! command -v mosquitto >/dev/null 2>&1 && [ ! -x /usr/sbin/mosquitto ]; then
  skip_test "mosquitto not installed (scripts/install-deps.sh)"
fi
if ! /usr/bin/python3 -c "import paho.mqtt.client" 2>/dev/null; then
  skip_test "python3-paho-mqtt not installed (scripts/install-deps.sh)"
fi
export PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}"
exec /usr/bin/python3 "$here/mqtt_limits_tests.py" "$@"
