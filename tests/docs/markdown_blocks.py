# SPDX-License-Identifier: MIT
"""The fenced code blocks of a Markdown page, for the scripts of tests/docs/ that compile, run or
check the snippets of the README and docs/ (standard library only)."""


def fenced_blocks(text, languages):
    """(first line number, line above the fence, lines) of every block fenced ```LANGUAGE, for
    each LANGUAGE in `languages`; line numbers count from 1."""
    found, current, start, above = [], None, 0, ""
    lines = text.splitlines()
    for number, line in enumerate(lines, 1):
        if current is None and line.strip() in {"```" + language for language in languages}:
            current, start = [], number + 1
            above = lines[number - 2].strip() if number >= 2 else ""
        elif current is not None and line.strip() == "```":
            found.append((start, above, current))
            current = None
        elif current is not None:
            current.append(line)
    return found
