#!/usr/bin/env python3
"""format/doc-links: every relative link in the repository's Markdown points at a file that exists.

Checks [text](target) links and ![alt](image) references in README.md, docs/*.md and every other
*.md under the source tree (build and output folders left out), outside code blocks and inline
code. A target with a #fragment into a Markdown file must name one of that file's headings (as
GitHub makes anchors of them). Web links (http, https, mailto) are not fetched.

Usage: check_doc_links.py SOURCE_DIR; prints one line per broken link and exits 1 if any.
"""
import os
import re
import sys

SKIP_DIRS = {".git", "build", "out", "node_modules", "third_party", "external"}
LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_CODE = re.compile(r"(`+)(?:(?!\1).)+?\1")


def markdown_files(root):
    for here, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("."))
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(here, name)


def prose_lines(path):
    """(line number, text) of the lines outside fenced code blocks, inline code blanked."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if not fenced:
                yield number, INLINE_CODE.sub(lambda m: " " * len(m.group(0)), line)


def anchor_of(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    found, seen = set(), {}
    for _, line in prose_lines(path):
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        base = anchor_of(m.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        found.add(base if count == 0 else f"{base}-{count}")
    return found


def broken_links(root):
    problems = []
    for path in markdown_files(root):
        shown = os.path.relpath(path, root)
        for number, line in prose_lines(path):
            for m in LINK.finditer(line):
                target = m.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
                    continue  # http:, https:, mailto:
                file_part, _, fragment = target.partition("#")
                resolved = path if not file_part else os.path.normpath(os.path.join(os.path.dirname(path), file_part))
                if not os.path.exists(resolved):
                    problems.append(f"{shown}:{number}: '{target}' names {os.path.relpath(resolved, root)}, which does not exist")
                elif fragment and resolved.endswith(".md") and fragment not in anchors(resolved):
                    problems.append(f"{shown}:{number}: '{target}': {os.path.relpath(resolved, root)} has no heading '#{fragment}'")
    return problems


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        print("usage: check_doc_links.py SOURCE_DIR", file=sys.stderr)
        return 2
    problems = broken_links(os.path.abspath(sys.argv[1]))
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} broken link(s) in the Markdown files")
        return 1
    print("every relative link in the Markdown files resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
