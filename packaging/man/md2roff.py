#!/usr/bin/env python3
"""gimbald.json(5) from docs/configuration.md, at build time, so the man page cannot drift.

Handles the Markdown that page uses: # headings (## -> .SH, ### -> .SS), paragraphs,
"- " lists (with indented continuation lines and code blocks), ``` code blocks, tables
(each row becomes a tagged paragraph: the first column is the tag, the middle columns
"type: ...; default: ..." and the last column the text), `code`, **bold** and links.

usage: md2roff.py --version VERSION docs/configuration.md > gimbald.json.5
"""

import argparse
import datetime
import gzip
import os
import re
import sys

HEADER = [
    ".SH NAME",
    "gimbald.json \\- configuration file of gimbald(8)",
    ".SH SYNOPSIS",
    "\\fI/etc/gimbald/gimbald.json\\fR",
]
FOOTER = [
    ".SH FILES",
    ".TP",
    "\\fI/etc/gimbald/gimbald.json\\fR",
    "The configuration the systemd unit uses; as packaged it lists no gimbals.",
    ".TP",
    "\\fI/usr/share/doc/gimbald/examples/gimbald.json\\fR",
    "Every key at its default, with two example gimbals.",
    ".TP",
    "\\fI/usr/share/doc/gimbald/examples/sim.json\\fR",
    "One Orion at 127.0.0.1:8747, what \\fBgimbal\\-sim\\fR(1) serves.",
    ".SH SEE ALSO",
    "\\fBgimbald\\fR(8), \\fBgimbalctl\\fR(1), \\fBgimbal\\-sim\\fR(1), \\fBgimbal\\-replay\\fR(1),",
    "\\fBgimbal\\-export\\fR(1),",
    "\\fI/usr/share/doc/gimbald/configuration.md\\fR",
]


def escape(text):
    text = text.replace("\\", "\\e").replace("-", "\\-")
    if text.startswith((".", "'")):
        text = "\\&" + text
    return text


# A link, keeping its text; the text may hold `code` with brackets ([`gimbals[].video`](#...)).
LINK = re.compile(r"\[((?:`[^`]*`|[^\]`])+)\]\([^)\s]*\)")
COMMENT = re.compile(r"<!--.*?-->")


def inline(text):
    """Markdown inline markup to roff fonts; everything else escaped."""
    text = LINK.sub(r"\1", COMMENT.sub("", text))
    out = []
    for part in re.split(r"(`[^`]+`|\*\*[^*]+\*\*)", text):
        if part.startswith("`") and part.endswith("`") and len(part) > 1:
            out.append("\\fB" + escape(part[1:-1]) + "\\fR")
        elif part.startswith("**") and part.endswith("**") and len(part) > 3:
            out.append("\\fB" + escape(part[2:-2].replace("`", "")) + "\\fR")
        else:
            out.append(escape(part))
    line = "".join(out)
    return "\\&" + line if line.startswith("\\fB.") else line


def cells(row):
    row = row.strip()
    if row.startswith("|"):
        row = row[1:]
    if row.endswith("|"):
        row = row[:-1]
    # A "|" inside `code` (a "type" such as "a | b") is not a column separator.
    parts, current, in_code = [], "", False
    for ch in row:
        if ch == "`":
            in_code = not in_code
        if ch == "|" and not in_code:
            parts.append(current.strip())
            current = ""
        else:
            current += ch
    parts.append(current.strip())
    return parts


def table(rows):
    header = [h.lower() for h in cells(rows[0])]
    out = []
    for row in rows[2:]:
        values = cells(row)
        if len(values) < 2:
            continue
        out.append(".TP")
        out.append(inline(values[0]))
        middle = [f"{header[k]}: {values[k]}" for k in range(1, len(values) - 1)
                  if k < len(header) and values[k]]
        text = ""
        if middle:
            text = inline("; ".join(middle)) + "\n.br\n"
        out.append(text + inline(values[-1]))
    return out


def convert(lines):
    out = []
    i = 0
    paragraph = []

    def flush():
        if paragraph:
            out.append(".PP")
            out.append(inline(" ".join(paragraph)))
            paragraph.clear()

    def code_block(start, indent):
        """Lines of a ``` block starting after line `start`; returns (roff, next index)."""
        block = [".PP", ".RS 4", ".nf"]
        j = start + 1
        while j < len(lines) and not lines[j].strip().startswith("```"):
            block.append(escape(lines[j][indent:] if lines[j][:indent].strip() == ""
                                else lines[j].lstrip()))
            j += 1
        block += [".fi", ".RE"]
        return block, j + 1

    while i < len(lines):
        line = lines[i].rstrip("\n")
        stripped = line.strip()
        if not stripped:
            flush()
            i += 1
        elif COMMENT.fullmatch(stripped):
            i += 1  # markers for the docs' tests (<!-- example -->), not text
        elif stripped.startswith("```"):
            flush()
            block, i = code_block(i, len(line) - len(line.lstrip()))
            out += block
        elif line.startswith("# "):
            i += 1  # the page title: the man page has its own NAME
        elif line.startswith("## "):
            flush()
            out.append(".SH " + inline(line[3:].strip().upper()))
            i += 1
        elif line.startswith("### ") or line.startswith("#### "):
            flush()
            out.append(".SS " + inline(line.lstrip("#").strip()))
            i += 1
        elif stripped.startswith("|"):
            flush()
            rows = []
            while i < len(lines) and lines[i].strip().startswith("|"):
                rows.append(lines[i])
                i += 1
            out += table(rows)
        elif re.match(r"^(- |\* |\d+\. )", line):
            flush()
            bullet = "\\(bu" if line[0] in "-*" else line.split(".")[0] + "."
            item = [re.sub(r"^(- |\* |\d+\. )", "", line).strip()]
            i += 1
            nested = []
            while i < len(lines) and (lines[i].startswith("  ") or not lines[i].strip()):
                if not lines[i].strip():
                    # A blank line ends the item unless indented content follows.
                    if i + 1 < len(lines) and lines[i + 1].startswith("  "):
                        i += 1
                        continue
                    break
                if lines[i].strip().startswith("```"):
                    block, i = code_block(i, len(lines[i]) - len(lines[i].lstrip()))
                    nested += block
                    continue
                if nested:
                    nested.append(inline(lines[i].strip()))
                else:
                    item.append(lines[i].strip())
                i += 1
            out.append(f".IP {bullet} 4")
            out.append(inline(" ".join(item)))
            if nested:
                out.append(".RS 4")
                out += [n for n in nested if n != ".PP"]
                out.append(".RE")
        else:
            paragraph.append(stripped)
            i += 1
    flush()
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("markdown")
    parser.add_argument("--version", required=True)
    parser.add_argument("--output", help="write here (gzip -9n when it ends in .gz)")
    args = parser.parse_args()
    with open(args.markdown, encoding="utf-8") as f:
        lines = f.read().splitlines()
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    when = (datetime.datetime.fromtimestamp(int(epoch), datetime.timezone.utc) if epoch
            else datetime.datetime.now(datetime.timezone.utc))
    out = [f'.\\" Generated by packaging/man/md2roff.py from docs/configuration.md; do not edit.',
           f'.TH GIMBALD.JSON 5 "{when:%B %Y}" "gimbald {args.version}" "File Formats"',
           ".ad l", ".nh"]
    out += HEADER
    body = convert(lines)
    # The page's introduction is the DESCRIPTION.
    out.append(".SH DESCRIPTION")
    out += body
    out += FOOTER
    write("\n".join(out) + "\n", args.output)


def write(text, path):
    """stdout, a file, or a reproducible .gz (no name, no time stamp: gzip -9n)."""
    if not path:
        sys.stdout.write(text)
    elif path.endswith(".gz"):
        with open(path, "wb") as raw, gzip.GzipFile(filename="", mode="wb", fileobj=raw,
                                                   compresslevel=9, mtime=0) as f:
            f.write(text.encode("utf-8"))
    else:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)


if __name__ == "__main__":
    sys.exit(main())
