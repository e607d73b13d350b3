#!/usr/bin/env python3
"""One home per protocol (docs/architecture.md, "The protocol registry").

Everything vendor-specific about a gimbal protocol lives in lib/protocols/<p>/ (its codec
may be a library of its own beneath it); the rest of the code reaches it only through the
registry's neutral headers (lib/protocols/*.hpp). This check fails when

  - a file under lib/ named after a protocol (orion/, orion_state.cpp, viewpro_sim.hpp ...)
    lives outside that protocol's home;
  - a C++ file under lib/, daemon/ or tools/ includes a header of a protocol's home (or a
    header named after a protocol) without being in that home itself. Allowed: the
    registry's list of entries (lib/protocols/registry.cpp includes each <p>_entry.hpp) and
    the tools that are a protocol's own (OWN_TOOLS). tests/ may include anything;
  - a library declared with gimbal_lib() in lib/CMakeLists.txt that is not a protocol's
    links a protocol's library (the registry library `protocols` links them all), or a
    target in daemon/ or tools/ links one directly (except a protocol's own tool).

A protocol is a folder of lib/protocols/ that holds its registry entry (<p>_entry.cpp).

Usage: check_homes.py [SOURCE_DIR]   (default: the repository this script is in)
"""

import os
import re
import sys

# Tools that belong to one protocol: gen-dissector generates the Orion part of the
# Wireshark dissector from the Orion codec's packet declarations.
OWN_TOOLS = {"tools/gen-dissector": "orion"}
OWN_TARGETS = {"gen-dissector": "orion"}

CXX = (".cpp", ".hpp", ".h", ".cc", ".c")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def protocols_of(lib):
    folder = os.path.join(lib, "protocols")
    found = []
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if os.path.isdir(path) and os.path.exists(os.path.join(path, name + "_entry.cpp")):
            found.append(name)
    return found


def named_for(path, protocols):
    """The protocol a path (relative to lib/) belongs to by its location or its name."""
    parts = path.split("/")
    if parts[0] == "protocols" and len(parts) > 2 and parts[1] in protocols:
        return parts[1]
    for part in parts:
        stem = part.split(".")[0]
        for p in protocols:
            if stem == p or stem.startswith(p + "_"):
                return p
    return None


def home_of(path, protocols):
    """The protocol whose home a path (relative to the source dir) is in, or None."""
    parts = path.split("/")
    if len(parts) > 3 and parts[0] == "lib" and parts[1] == "protocols" and parts[2] in protocols:
        return parts[2]
    for tool, p in OWN_TOOLS.items():
        if path.startswith(tool + "/"):
            return p
    return None


def files_under(root, top):
    for folder, dirs, files in os.walk(os.path.join(root, top)):
        dirs.sort()
        for name in sorted(files):
            yield os.path.relpath(os.path.join(folder, name), root).replace(os.sep, "/")


def check_homes(root, protocols, problems):
    for path in files_under(root, "lib"):
        owner = named_for(path[len("lib/"):], protocols)
        if owner and home_of(path, protocols) != owner:
            problems.append(f"{path}: belongs to {owner}, outside lib/protocols/{owner}/")


def check_includes(root, protocols, problems):
    lib = os.path.join(root, "lib")
    checked = 0
    for top in ("lib", "daemon", "tools"):
        for path in files_under(root, top):
            if not path.endswith(CXX):
                continue
            checked += 1
            home = home_of(path, protocols)
            if home is None and path.startswith("lib/"):
                home = named_for(path[len("lib/"):], protocols)  # misplaced: reported above
            with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
                text = f.read()
            for header in INCLUDE.findall(text):
                if not os.path.isfile(os.path.join(lib, header)):
                    continue  # not a lib/ header (the daemon's own, a tool's own)
                owner = named_for(header, protocols)
                if owner is None or owner == home:
                    continue
                if path == "lib/protocols/registry.cpp" and \
                        header == f"protocols/{owner}/{owner}_entry.hpp":
                    continue
                problems.append(f"{path}: includes {owner}'s \"{header}\"")
    return checked


def cmake_calls(text, command):
    """The argument lists of every call of `command` (comments removed, ${var} expanded)."""
    text = re.sub(r"#[^\n]*", "", text)
    variables = {}
    for name, value in re.findall(r"\bset\(\s*(\w+)\s+([^)]*)\)", text):
        variables[name] = value.split()
    calls = []
    for args in re.findall(r"\b" + command + r"\(([^)]*)\)", text):
        words = []
        for word in args.split():
            m = re.fullmatch(r"\$\{(\w+)\}", word)
            words.extend(variables.get(m.group(1), []) if m else [word])
        calls.append(words)
    return calls


def check_libraries(root, protocols, problems):
    with open(os.path.join(root, "lib", "CMakeLists.txt"), encoding="utf-8") as f:
        text = f.read()
    owner_of = {}  # gimbal::<name> -> its protocol, or None
    deps_of = {}
    for words in cmake_calls(text, "gimbal_lib"):
        name, rest = words[0], words[1:]
        folder, deps, key = name, [], None
        for word in rest:
            if word in ("DIR", "DEPS", "SYSTEM_INCLUDES"):
                key = word
            elif key == "DIR":
                folder = word
            elif key == "DEPS":
                deps.append(word)
        owner_of["gimbal::" + name] = named_for(folder, protocols)
        deps_of["gimbal::" + name] = deps
    for lib, deps in deps_of.items():
        if lib == "gimbal::protocols":
            continue  # the registry: every protocol's entry
        for dep in deps:
            owner = owner_of.get(dep)
            if owner and owner != owner_of[lib]:
                what = f"{owner_of[lib]}'s library" if owner_of[lib] else "neutral library"
                problems.append(f"lib/CMakeLists.txt: {what} {lib} links {owner}'s {dep}")
    for top in ("daemon", "tools"):
        path = os.path.join(root, top, "CMakeLists.txt")
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for words in cmake_calls(text, "target_link_libraries"):
            target = words[0]
            for dep in words[1:]:
                owner = owner_of.get(dep)
                if owner and OWN_TARGETS.get(target) != owner:
                    problems.append(f"{top}/CMakeLists.txt: {target} links {owner}'s {dep}")
    return len(deps_of)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..")
    protocols = protocols_of(os.path.join(root, "lib"))
    if not protocols:
        print("no protocol found in lib/protocols/ (a folder with <name>_entry.cpp)")
        return 1
    problems = []
    check_homes(root, protocols, problems)
    files = check_includes(root, protocols, problems)
    libraries = check_libraries(root, protocols, problems)
    for problem in problems:
        print(problem)
    summary = (f"protocols {', '.join(protocols)}: {files} C++ files under lib/, daemon/, "
               f"tools/ and {libraries} libraries checked")
    if problems:
        print(f"{len(problems)} problems ({summary})")
        return 1
    print(f"ok: every protocol in its home ({summary})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
