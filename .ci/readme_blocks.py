#!/usr/bin/env python3
"""Prints the README's command blocks marked for CI, in order, as one script.

A block is run when the line `<!-- ci: run -->` precedes its ```sh fence
(blank lines allowed between). Blocks that start or install things CI does
itself (building, `robocal serve`, Docker, PostgreSQL) are left unmarked.
"""
import sys

MARK = "<!-- ci: run -->"


def blocks(lines):
    armed = False
    block = None
    for number, line in enumerate(lines, 1):
        text = line.rstrip("\n")
        if block is not None:
            if text.strip() == "```":
                yield block
                block = None
            else:
                block[1].append(text)
        elif text.strip() == MARK:
            armed = True
        elif armed and text.strip().startswith("```"):
            if text.strip() not in ("```sh", "```bash"):
                sys.exit(f"README line {number}: a marked block must be ```sh")
            block = (number, [])
            armed = False
        elif armed and text.strip():
            sys.exit(f"README line {number}: `{MARK}` must directly precede a ```sh block")
    if block is not None:
        sys.exit(f"README line {block[0]}: unterminated block")


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "README.md"
    with open(path, encoding="utf-8") as f:
        found = list(blocks(f.readlines()))
    if not found:
        sys.exit(f"{path}: no block marked `{MARK}`")
    for number, body in found:
        print(f"echo '--- README.md line {number}' >&2")
        print("\n".join(body))


if __name__ == "__main__":
    main()
