"""What a Python test does when a tool it needs cannot be had (tests/integration/skip.sh is
the shell tests' twin). Normally the test case is skipped, saying why (ctest: exit 77 for a
whole file); with CI=true in the environment it fails with the reason instead: on CI a missing
tool is lost coverage, never a pass. scripts/test.sh lists every skip at the end of its run.

Skips that depend on the machine rather than on an installable tool (no root for a network
namespace, no IPv6 loopback, an AddressSanitizer build) stay skips under CI too; they are
still listed."""

import os
import sys
import unittest

SKIP = 77


def on_ci():
    return os.environ.get("CI") == "true"


def need(test, reason):
    """A test case's tool is missing: skip it, or on CI fail it."""
    if on_ci():
        test.fail("%s (CI=true: a test whose tools cannot be had fails instead of skipping)"
                  % reason)
    raise unittest.SkipTest(reason)


def need_for_file(reason):
    """A whole test file cannot run (a binary or tool is missing): exit 77, or on CI 1."""
    if on_ci():
        print("FAILED: %s (CI=true: a test whose tools cannot be had fails instead of "
              "skipping)" % reason, file=sys.stderr)
        sys.exit(1)
    print("skipped: %s" % reason)
    sys.exit(SKIP)


def requires(available, reason):
    """A decorator for a test case or class whose tool may be missing: unittest.skipUnless,
    or on CI a test that fails with the reason."""
    if available:
        return lambda item: item
    if not on_ci():
        return unittest.skipUnless(False, reason)

    def fail_instead(item):
        if isinstance(item, type):
            def setUpClass(cls):
                raise AssertionError("%s (CI=true: a test whose tools cannot be had fails "
                                     "instead of skipping)" % reason)
            item.setUpClass = classmethod(setUpClass)
            return item

        def failing(self, *args, **kwargs):
            self.fail("%s (CI=true: a test whose tools cannot be had fails instead of "
                      "skipping)" % reason)
        failing.__name__ = item.__name__
        return failing
    return fail_instead
