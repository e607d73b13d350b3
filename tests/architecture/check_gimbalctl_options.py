#!/usr/bin/env python3
"""gimbalctl's options are the command catalogue's parameters (docs/architecture.md,
"A request parsed once").

The catalogue (lib/command/catalogue.cpp) declares each command's parameters once; the daemon
checks requests against it and gen-api-docs writes docs/json-api.md's tables from it.
gimbalctl declares its own command line (positional arguments and options, each naming the
JSON key it fills). This check reads both - `gen-api-docs --params` and every sub-command's
`gimbalctl NAME --help` - and fails when

  - a catalogue command has no gimbalctl sub-command (other than the ones listed below, which
    gimbalctl sends in other ways);
  - a sub-command fills a key its command does not have (a typo, or a parameter the catalogue
    dropped), or leaves out one it has (a parameter gimbalctl cannot send).

Usage: check_gimbalctl_options.py --gen-api-docs PATH --gimbalctl PATH
"""

import argparse
import re
import subprocess
import sys

# Catalogue commands without a sub-command of their own, and how gimbalctl sends them.
SENT_OTHERWISE = {
    "unsubscribe": "gimbalctl watch sends it when it stops",
}

# Keys of a sub-command's help that are the envelope's, not the command's parameters.
ENVELOPE_KEYS = {"cmd", "id", "gimbal", "token"}

# Sub-commands that send no catalogue command of their own.
NOT_A_COMMAND = {"send", "keygen"}


def run(*argv):
    result = subprocess.run(argv, capture_output=True, text=True, timeout=30)
    if result.returncode != 0:
        sys.exit("%s exited %d: %s" % (" ".join(argv), result.returncode, result.stderr))
    return result.stdout


def catalogue(gen_api_docs):
    """{command: set of parameter keys} from gen-api-docs --params."""
    commands = {}
    for line in run(gen_api_docs, "--params").splitlines():
        words = line.split()
        if words:
            commands[words[0]] = set(words[1:])
    return commands


def sub_commands(gimbalctl):
    """The sub-command names listed under COMMANDS in gimbalctl --help."""
    text = run(gimbalctl, "--help")
    section = text.split("\nCOMMANDS\n", 1)[1]
    section = re.split(r"\n[A-Z][A-Z ]+\n", section, 1)[0]
    return [m.group(1) for m in re.finditer(r"^ {7}([a-z][a-z0-9-]*)\b", section, re.M)]


def help_of(gimbalctl, name):
    """(cmd sent, set of JSON keys named) from gimbalctl NAME --help."""
    text = re.sub(r"\s+", " ", run(gimbalctl, name, "--help"))
    sent = re.search(r'Sends \{"cmd": "([a-z_0-9]+)"', text)
    keys = set()
    for named in re.findall(r"\(JSON ([^)]*)\)", text):  # (JSON "x"), (JSON "px" and "py" ...)
        keys.update(re.findall(r'"([a-z_0-9]+)"', named))
    keys -= ENVELOPE_KEYS
    return (sent.group(1) if sent else None), keys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gen-api-docs", required=True)
    parser.add_argument("--gimbalctl", required=True)
    args = parser.parse_args()

    commands = catalogue(args.gen_api_docs)
    if not commands:
        sys.exit("gen-api-docs --params listed no command")
    names = sub_commands(args.gimbalctl)
    if not names:
        sys.exit("gimbalctl --help listed no sub-command")

    problems = []
    covered = {}
    for name in names:
        if name in NOT_A_COMMAND:
            continue
        cmd, keys = help_of(args.gimbalctl, name)
        if cmd is None:
            problems.append("gimbalctl %s: its help names no request it sends" % name)
            continue
        if cmd not in commands:
            problems.append("gimbalctl %s sends %r, which the catalogue lacks" % (name, cmd))
            continue
        covered.setdefault(cmd, set()).update(keys)
        extra = keys - commands[cmd]
        if extra:
            problems.append("gimbalctl %s fills %s, not parameters of %s in the catalogue"
                            % (name, ", ".join(sorted(extra)), cmd))
    for cmd, params in commands.items():
        if cmd in SENT_OTHERWISE:
            continue
        if cmd not in covered:
            problems.append("catalogue command %s has no gimbalctl sub-command" % cmd)
            continue
        missing = params - covered[cmd]
        if missing:
            problems.append("gimbalctl cannot send %s's %s" % (cmd, ", ".join(sorted(missing))))

    for problem in problems:
        print(problem, file=sys.stderr)
    print("%d catalogue commands, %d gimbalctl sub-commands checked: %s"
          % (len(commands), len(names), "ok" if not problems else "%d problems" % len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
