#!/usr/bin/env python3
"""DESIGN.md stays a map a newcomer reads in minutes, and every path it names exists.

Its recipes ("A new ...") name every file a change of that kind touches, so a file that moves without
the map following fails here. Checked: at most 25 kB, no line over 200 characters, and each path in
backquotes that starts at a top-level folder of the repository exists (a path holding a placeholder
such as <kind> names a pattern, not a file, and is not checked).

    design_map.py SOURCE_DIR
"""
import re
import sys
from pathlib import Path

MAX_BYTES = 25 * 1024
MAX_LINE = 200
TOP = "generator|runtime|templates|tests|docs|cmake|scripts|python|support|benchmarks|examples|embedded|fuzz"
PATH = re.compile(rf"^(?:{TOP})/[A-Za-z0-9_./+-]*$")


def main():
    root = Path(sys.argv[1])
    design = root / "DESIGN.md"
    text = design.read_bytes()
    problems = []
    if len(text) > MAX_BYTES:
        problems.append(f"DESIGN.md: {len(text)} bytes, the map holds at most {MAX_BYTES}")
    checked = 0
    for number, line in enumerate(text.decode("utf-8").splitlines(), start=1):
        if len(line) > MAX_LINE:
            problems.append(f"DESIGN.md:{number}: {len(line)} characters, at most {MAX_LINE}")
        for span in re.findall(r"`([^`]+)`", line):
            if not PATH.match(span):
                continue
            checked += 1
            if not (root / span.rstrip("/")).exists():
                problems.append(f"DESIGN.md:{number}: `{span}` does not exist")
    if checked < 20:
        problems.append(f"DESIGN.md names only {checked} paths; its recipes name every file they touch")
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        return 1
    print(f"DESIGN.md: {len(text)} bytes, {checked} paths named, all present")
    return 0


if __name__ == "__main__":
    sys.exit(main())
