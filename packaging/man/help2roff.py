#!/usr/bin/env python3
"""Man page (roff) from a program's own --help and --version output.

Used at build time for gimbald(8), gimbalctl(1), gimbal-sim(1) and any later tool, so the
man pages cannot drift from the programs. Understands the help layouts of this project:

- man-style sections: a line at column 0 in capitals (NAME, SYNOPSIS, OPTIONS, EXIT STATUS)
  followed by indented text;
- CLI11's default layout: "Usage: ..." and "Options:" / "Group name:" headings at column 0
  and option lines such as "  --port UINT=8747   TCP port" (type, check and default are
  turned into words: "PORT ... Default: 8747.").

Help texts share their sentences with the Markdown docs: `code` becomes bold and a link its
text (md2roff.inline), never raw markup on the page.

Inside a section: a line starting with an option or followed by deeper-indented lines is a
tagged paragraph (.TP); "TAG  text" with two spaces after the tag is one too (EXIT STATUS,
FILES); a line at less than the section's text indent is a subsection (.SS); deeper lines
after a line ending in ":" are an example kept as is; other lines are reflowed paragraphs.

usage: help2roff.py --section N [--name-line "prog - what it does"] [--manual TITLE]
                    [--wrapper CMD] PROGRAM > prog.N
"""

import argparse
import datetime
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import md2roff  # noqa: E402  (write(), inline())

HEADING = re.compile(r"^[A-Z][A-Z0-9 /()-]*$")
GAP = re.compile(r"^(\S.*?\S|\S)  +(\S.*)$")
CLI11_TIGHT = re.compile(r"^(-\S+(?: [A-Z]+(?::[A-Z]+|:\{[^}]*\})?(?:=\S+)?)?) (\S.*)$")


def run(command, flag):
    result = subprocess.run(command + [flag], capture_output=True, text=True, timeout=60,
                            check=False)
    if result.returncode != 0:
        sys.exit(f"help2roff: {' '.join(command)} {flag} exited {result.returncode}: "
                 f"{result.stderr.strip()}")
    return result.stdout


def escape(text):
    """Text for roff: backslashes, minus signs (so options copy-paste), leading dot/quote."""
    text = text.replace("\\", "\\e").replace("-", "\\-")
    if text.startswith((".", "'")):
        text = "\\&" + text
    return text


def font_tag(tag):
    """Options in bold, capitalised placeholders (FILE, N, [PROTOCOLS]) in italics."""
    words = []
    for word in tag.split(" "):
        core = word.strip("[]{}|,.")
        if word.startswith("-"):
            words.append("\\fB" + escape(word) + "\\fR")
        elif core and core.upper() == core and re.match(r"^[A-Z_]+(\.\.\.)?$", core):
            words.append("\\fI" + escape(word) + "\\fR")
        else:
            words.append(escape(word))
    return " ".join(words)


CHECK_WORDS = {"NONNEGATIVE": "at least 0", "POSITIVE": "greater than 0"}


def cli11_option(tag, body):
    """'-h,--help' -> '-h, --help'; '--port UINT=8747' -> ('--port UINT', 'Default: 8747.')"""
    names, _, rest = tag.partition(" ")
    names = names.replace(",", ", ")
    if body and not body.endswith("."):
        body += "."
    if not rest:
        return names, body
    argument, extra = rest, []
    default = None
    match = re.match(r"^(.*?)=([^=\]]*)$", argument)
    if match:
        argument, default = match.group(1), match.group(2)
    argument, _, check = argument.partition(":")
    if check:
        if check.startswith("{"):
            extra.append("One of " + ", ".join(check.strip("{}").split(",")) + ".")
        elif check in CHECK_WORDS:
            extra.append("Must be " + CHECK_WORDS[check] + ".")
        else:
            bounds = re.match(r"^\w+ in \[(\S+) - (\S+)\]$", check)
            if bounds:
                extra.append(f"Range {bounds.group(1)} to {bounds.group(2)}.")
    if default is not None:
        extra.append(f"Default: {default}.")
    return f"{names} {argument}", " ".join([body] + extra).strip()


def indent_of(line):
    return len(line) - len(line.lstrip(" "))


def parse_sections(text):
    """[(heading, [lines])]; text before the first heading is DESCRIPTION."""
    sections = [["DESCRIPTION", []]]
    for line in text.splitlines():
        line = line.rstrip()
        if line and indent_of(line) == 0:
            if HEADING.match(line):
                sections.append([line, []])
                continue
            if line.startswith("Usage: "):
                sections.append(["SYNOPSIS (usage)", [line[len("Usage: "):]]])
                continue
            if line.endswith(":"):
                name = line[:-1]
                if name.lower() == "options":
                    sections.append(["OPTIONS", []])
                else:
                    sections.append(["OPTIONS", ["\x00SS " + name]])
                continue
        sections[-1][1].append(line)
    # Merge repeated headings (CLI11 groups) and drop empty ones.
    merged = []
    for heading, lines in sections:
        if merged and merged[-1][0] == heading:
            merged[-1][1].extend([""] + lines)
        elif any(l.strip() for l in lines):
            merged.append([heading, lines])
    return merged


def render_body(lines, keep_lines=False, cli11=False):
    out = []
    text_lines = [l for l in lines if l.strip() and not l.startswith("\x00")]
    if not text_lines:
        return out
    indents = [indent_of(l) for l in text_lines]
    base = max(set(indents), key=lambda i: (indents.count(i), -i)) if not cli11 else min(indents)
    i = 0
    paragraph = []

    def flush():
        if paragraph:
            out.append(".PP")
            if keep_lines:
                out.append(".nf")
                out.extend(escape(p) for p in paragraph)
                out.append(".fi")
            else:
                out.append(md2roff.inline(" ".join(paragraph)))
            paragraph.clear()

    while i < len(lines):
        line = lines[i]
        if line.startswith("\x00SS "):
            flush()
            out.append(".SS " + escape(line[4:]))
            i += 1
            continue
        if not line.strip():
            flush()
            i += 1
            continue
        ind = indent_of(line)
        stripped = line.strip()
        following = []
        j = i + 1
        while j < len(lines) and lines[j].strip() and indent_of(lines[j]) > ind:
            following.append(lines[j])
            j += 1
        # A subsection title: its first deeper line is itself a tag with a body, and it has
        # sibling entries (a tag with a multi-line body or a long tag has neither).
        first = indent_of(following[0]) if following else 0
        siblings = sum(1 for f in following if indent_of(f) == first)
        has_body = len(following) > 1 and indent_of(following[1]) > first
        if following and siblings > 1 and has_body and not stripped.startswith("-"):
            flush()
            out.append(".SS " + escape(stripped))
            i += 1
            continue
        gap = GAP.match(stripped)
        is_option = stripped.startswith("-")
        if cli11 and is_option and not gap and not following:
            # CLI11 leaves one space when the option just fills its column.
            gap = CLI11_TIGHT.match(stripped)
        introduces_example = stripped.endswith((":", "?")) or (
            paragraph and paragraph[-1].endswith(":"))
        if (following or (gap and (is_option or ind <= base))) and not introduces_example:
            if not following and not gap:
                paragraph.append(stripped)
                i += 1
                continue
            if gap and not (following and not is_option and not gap):
                tag, body = gap.group(1), [gap.group(2)]
            else:
                tag, body = stripped, []
            # Lines between the tag and the body's indent continue the tag (long synopses).
            body_indent = max(indent_of(f) for f in following) if following else 0
            for f in following:
                if indent_of(f) < body_indent and not body:
                    tag += " " + f.strip()
                else:
                    body.append(f.strip())
            body_text = " ".join(body)
            if cli11 and tag.startswith("-"):
                tag, body_text = cli11_option(tag, body_text)
            flush()
            out.append(".TP")
            out.append(font_tag(tag))
            out.append(md2roff.inline(body_text) if body_text else "\\&")
            i = j
            continue
        if following and (introduces_example or keep_lines):
            paragraph.append(stripped)
            flush()
            out.append(".PP")
            out.append(".RS 4")
            out.append(".nf")
            deepest = min(indent_of(f) for f in following)
            out.extend(escape(f[deepest:]) for f in following)
            out.append(".fi")
            out.append(".RE")
            i = j
            continue
        paragraph.append(stripped)
        i += 1
    flush()
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program")
    parser.add_argument("--section", required=True)
    parser.add_argument("--name-line", help='used when --help has no NAME: "prog - what"')
    parser.add_argument("--manual", default=None)
    parser.add_argument("--wrapper", default="",
                        help="command that runs PROGRAM (e.g. an emulator when cross-compiling)")
    parser.add_argument("--output", help="write here (gzip -9n when it ends in .gz)")
    args = parser.parse_args()

    command = args.wrapper.split() + [args.program]
    program = os.path.basename(args.program)
    help_text = run(command, "--help")
    version = run(command, "--version").strip().splitlines()[0]

    sections = parse_sections(help_text)
    names = [h for h, _ in sections]
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = (datetime.datetime.fromtimestamp(int(epoch), datetime.timezone.utc) if epoch
            else datetime.datetime.now(datetime.timezone.utc))
    manual = args.manual or ("System Administration" if args.section == "8" else "User Commands")
    out = [f'.\\" Generated by packaging/man/help2roff.py from {program} --help; do not edit.',
           f'.TH {program.upper()} {args.section} "{when:%B %Y}" "{escape(version)}" "{manual}"',
           ".ad l", ".nh"]

    if "NAME" in names:
        name_line = " ".join(l.strip() for l in dict(sections)["NAME"] if l.strip())
    elif args.name_line:
        name_line = args.name_line
    else:
        # CLI11's layout: the app description comes first; its first sentence names it.
        first = " ".join(l.strip() for l in dict(sections).get("DESCRIPTION", []) if l.strip())
        if not first:
            sys.exit(f"help2roff: {program} --help has no NAME or description; give --name-line")
        what = first.split(". ")[0].rstrip(".")
        name_line = f"{program} - {what[0].lower()}{what[1:]}"
    prog, _, what = name_line.partition(" - ")
    out += [".SH NAME", f"{escape(prog.strip())} \\- {escape(what.strip())}"]

    # SYNOPSIS: the program's own, else CLI11's "Usage:" line.
    has_synopsis = "SYNOPSIS" in names
    ordered = []
    for heading, lines in sections:
        if heading == "NAME":
            continue
        if heading == "SYNOPSIS (usage)":
            if has_synopsis:
                continue
            heading = "SYNOPSIS"
        ordered.append((heading, lines))
    # SYNOPSIS first, then the rest in the program's order.
    ordered.sort(key=lambda s: 0 if s[0] == "SYNOPSIS" else 1)
    cli11_layout = "SYNOPSIS (usage)" in names
    for heading, lines in ordered:
        out.append(".SH " + escape(heading))
        if heading == "SYNOPSIS":
            out.append(".nf")
            body = [l for l in lines if l.strip()]
            deepest = min(indent_of(l) for l in body)
            out.extend(font_tag(l[deepest:]) for l in body)
            out.append(".fi")
        else:
            out.extend(render_body(lines, keep_lines=heading == "EXAMPLES",
                                   cli11=cli11_layout and heading == "OPTIONS"))
    md2roff.write("\n".join(out) + "\n", args.output)


if __name__ == "__main__":
    main()
