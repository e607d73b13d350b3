# Sourced by the shell tests: `skip_test REASON` ends a test that cannot run here because a
# tool it needs cannot be had. Normally it says why and exits 77, which ctest reports as
# skipped (scripts/test.sh lists every skipped test at the end of its run). With CI=true in
# the environment it fails instead (exit 1, the reason on stderr): on CI a missing tool is
# lost coverage, never a pass. Not a test itself (no test_ prefix).

skip_test() {
    if [ "${CI:-}" = true ]; then
        echo "FAILED: $* (CI=true: a test whose tools cannot be had fails instead of skipping)" >&2
        exit 1
    fi
    echo "skipped: $*"
    exit 77
}
