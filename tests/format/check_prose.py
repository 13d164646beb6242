#!/usr/bin/env python3
"""format/prose: the repository's prose reads without its history.

- README.md holds at most 250 lines (the rest belongs in docs/).
- No "seed 000" naming a paper (it reads like --seed; docs/references.md names each paper, and
  its file in ../shared/seeds/ by path) and no "issue 15" (a tracker a reader cannot see), in
  Markdown files or in the comments and strings of the sources, shaders, scripts and CMake files.

Usage: check_prose.py SOURCE_DIR; prints one line per finding and exits 1 if any.
"""
import os
import re
import sys

SKIP_DIRS = {".git", "build", "out", "node_modules", "third_party", "external"}
CHECKED = (".md", ".cpp", ".hpp", ".h", ".glsl", ".comp", ".vert", ".frag", ".py", ".sh", ".cmake", ".txt")
README_MAX_LINES = 250
FORBIDDEN = [(re.compile(r"\bseeds? 0\d\d\b", re.IGNORECASE), "names a paper by its seed number"),
             (re.compile(r"\bissues? #?\d+\b", re.IGNORECASE), "points to an issue number")]


def checked_files(root):
    for here, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith(".") and not d.startswith("build-"))
        for name in sorted(files):
            if name.endswith(CHECKED) and name != os.path.basename(__file__):
                yield os.path.join(here, name)


def main():
    if len(sys.argv) != 2:
        print("usage: check_prose.py SOURCE_DIR", file=sys.stderr)
        return 2
    root = sys.argv[1]
    findings = []
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        lines = sum(1 for _ in f)
    if lines > README_MAX_LINES:
        findings.append(f"README.md: {lines} lines, more than {README_MAX_LINES}: move detail to docs/")
    for path in checked_files(root):
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except UnicodeDecodeError:
            continue  # not text
        for number, line in enumerate(text.splitlines(), 1):
            for pattern, problem in FORBIDDEN:
                match = pattern.search(line)
                if match:
                    findings.append(f"{os.path.relpath(path, root)}:{number}: '{match.group(0)}' {problem}")
    for finding in findings:
        print(finding)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
