#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs the ```python blocks of Markdown pages against the built module, so that a snippet that
drifts from the API (a name, an argument, a dtype) fails.

Each block runs on its own, in a fresh namespace that holds the names of
doc_snippet_context.py (what a fragment takes from the reader's program around it). An
exception in a block fails the run, with the page and the line of the block.
Usage: run_python_snippets.py PAGE.md... (smb importable, e.g. PYTHONPATH=<build>/python).
"""

import os
import sys
import traceback

from markdown_blocks import fenced_blocks


def context_names():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "doc_snippet_context.py")
    with open(path, encoding="utf-8") as f:
        names = {"__name__": "doc_snippet_context"}
        exec(compile(f.read(), path, "exec"), names)
    return {name: value for name, value in names.items() if not name.startswith("__")}


def main():
    pages = sys.argv[1:]
    if not pages:
        sys.exit("usage: run_python_snippets.py PAGE.md...")
    context = context_names()
    ran, failed = 0, 0
    for page in pages:
        with open(page, encoding="utf-8") as f:
            text = f.read()
        for start, _, lines in fenced_blocks(text, ["python"]):
            source = "\n".join(lines) + "\n"
            # Blank lines before the block keep its line numbers those of the page in a traceback.
            code = compile("\n" * (start - 1) + source, page, "exec")
            namespace = dict(context, __name__="__main__")
            try:
                exec(code, namespace)
                ran += 1
            except Exception:  # noqa: BLE001: every failure of a snippet is reported the same way
                failed += 1
                print(f"{page}:{start}: the block failed", file=sys.stderr)
                traceback.print_exc()
    print(f"{ran} Python snippet(s) ran, {failed} failed")
    if ran + failed == 0:
        sys.exit("no ```python block found: are these the right pages?")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
