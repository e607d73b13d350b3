"""What the dissector tests share: finding tshark (a missing one fails under CI=true and skips,
exit 77, elsewhere) and reading tshark -T json with its repeated keys kept."""
import os
import shutil


def find_tshark():
    """(path, None) when tshark is installed, else (None, the exit status to return)."""
    tshark = shutil.which("tshark")
    if tshark:
        return tshark, None
    # On CI (CI=true) a missing tool fails the test; elsewhere it is skipped (77), and
    # scripts/test.sh lists it (tests/integration/skipping.py).
    if os.environ.get("CI") == "true":
        print("FAILED: tshark not installed (scripts/install-deps.sh; CI=true: a test "
              "whose tools cannot be had fails instead of skipping)")
        return None, 1
    print("skipped: tshark not installed (scripts/install-deps.sh)")
    return None, 77


def pairs_keep_duplicates(pairs):
    """json.loads object_pairs_hook: tshark -T json repeats a key for repeated fields."""
    out = {}
    for k, v in pairs:
        out.setdefault(k, []).append(v)
    return out
