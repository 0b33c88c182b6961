"""The README's Python blocks marked `<!-- ci: python -->`, in order, as
one script (they are written to run so, from an empty directory).

usage: python tests/readme_blocks.py [README.md] > example.py
"""

from __future__ import annotations

import sys
from pathlib import Path

MARK = "<!-- ci: python -->"
README = Path(__file__).resolve().parent.parent / "README.md"


def python_blocks(text: str) -> list[str]:
    """The marked blocks; a mark not directly followed by a ```python
    fence is an error, so a block cannot silently drop out of the test."""
    blocks: list[str] = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        if lines[index].strip() == MARK:
            index += 1
            while index < len(lines) and not lines[index].strip():
                index += 1
            if index >= len(lines) or lines[index].strip() != "```python":
                raise ValueError(f"README line {index + 1}: {MARK} must precede a ```python block")
            body: list[str] = []
            index += 1
            while index < len(lines) and lines[index].strip() != "```":
                body.append(lines[index])
                index += 1
            if index >= len(lines):
                raise ValueError("README: unterminated block")
            blocks.append("\n".join(body))
        index += 1
    return blocks


def script(path: Path = README) -> str:
    blocks = python_blocks(path.read_text(encoding="utf-8"))
    if not blocks:
        raise ValueError(f"{path}: no block marked {MARK}")
    return "\n\n".join(blocks) + "\n"


if __name__ == "__main__":
    sys.stdout.write(script(Path(sys.argv[1]) if len(sys.argv) > 1 else README))
