#!/usr/bin/env python3
"""gzip -9n IN > OUT (no name, no time stamp), for the package's changelog.gz."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import md2roff  # noqa: E402

with open(sys.argv[1], encoding="utf-8") as f:
    md2roff.write(f.read(), sys.argv[2])
