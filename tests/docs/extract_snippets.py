#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the ```cpp blocks of a Markdown page into one C++ file, so that the build compiles them
and a snippet that drifts from the API fails the build.

Each block becomes the body of a function of its own (its #include lines go to the top of the
file), after doc_snippet_context.hpp, which declares the names the snippets use without
defining them (the world, the boxes, the caller's callbacks). A block that names smb::bullet or
Bullet's world is compiled only where SMB_SNIPPETS_BULLET is set, one that names smb::mpi only
where SMB_SNIPPETS_MPI is. Usage: extract_snippets.py PAGE.md OUT.cpp (standard library only).
"""

import os
import re
import sys

from markdown_blocks import fenced_blocks


def guard(lines):
    joined = "\n".join(lines)
    if "smb::mpi" in joined:
        return "SMB_SNIPPETS_MPI"
    if "smb::bullet" in joined or "btDiscreteDynamicsWorld" in joined:
        return "SMB_SNIPPETS_BULLET"
    return None


def main():
    page, out = sys.argv[1], sys.argv[2]
    with open(page, encoding="utf-8") as f:
        text = f.read()
    includes = ['#include "doc_snippet_context.hpp"']
    bodies = []
    for index, (start, _, lines) in enumerate(fenced_blocks(text, ["cpp"])):
        body = []
        for line in lines:
            if re.match(r"\s*#include\s", line):
                include = line.split("//")[0].strip()
                if guard(lines):
                    include = f"#if {guard(lines)}\n{include}\n#endif"
                if include not in includes:
                    includes.append(include)
                body.append("")  # keeps the lines where #line puts them
            else:
                body.append(line)
        condition = guard(lines)
        function = [f"// {page}, block {index + 1} (line {start})"]
        if condition:
            function.append(f"#if {condition}")
        function.append(f"[[maybe_unused]] void snippet_{index + 1}() {{")
        function.append(f'#line {start} "{page}"')
        function.extend(body)
        function.append("}")
        if condition:
            function.append("#endif")
        bodies.append("\n".join(function))
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, "w", encoding="utf-8") as f:
        f.write(f"// Generated from {page} by tests/docs/extract_snippets.py: do not edit.\n")
        f.write("\n".join(includes) + "\n\n")
        f.write("namespace smb_doc_snippets {\n\n")
        f.write("\n\n".join(bodies) + "\n\n")
        f.write("}  // namespace smb_doc_snippets\n")


if __name__ == "__main__":
    main()
