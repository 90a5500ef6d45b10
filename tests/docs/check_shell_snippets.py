#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks the ```sh blocks of the READMEs (the project's and the tool's) and docs/ against the project, so that a command a
page shows keeps working as shown. Running them as written is out of reach of a test (builds,
benchmarks of many minutes, MPI runs), so each command is checked for what can drift:

- `smb ...` (also build/tools/smb/smb) runs on a tiny scene in a temporary folder, its sizes
  (-n, -s) made small and its input files generated; under mpirun, its options are checked
  against `smb <command> --help` instead (an MPI start is slow);
- a script of ours (scripts/, examples/, python/) exists, and each option given to it is one it
  takes: the argparse options of a Python script, the text of a shell script or of the Python
  script it passes its options on to ("[more options of NAME.py]" in its usage line);
- a binary of ours (build*/bench/smb_x, build*/examples/dem/smb_dem) is a target of the project
  built where the path says, and each option given is named in its sources (read, not run);
- cmake: every --target is a target of the project, every -DSMB_... an option of it;
  ctest and pytest: the folders named exist; `python3 -c` runs against the built module.

A command the checker does not know fails the check, unless the block is marked, on the line
just above its fence, `<!-- not run: reason -->`: then such commands are passed over (the
others are still checked). Usage: check_shell_snippets.py --smb SMB --source-dir DIR
--build-dir DIR (standard library only).
"""

import argparse
import ast
import glob
import os
import re
import shlex
import subprocess
import sys
import tempfile

from markdown_blocks import fenced_blocks

SMB_PATHS = {"smb", "build/tools/smb/smb", "./build/tools/smb/smb"}
SEPARATORS = {";", "&&", "||", "|"}
# Sizes a command gets instead of the page's, so that it runs in a moment.
SMALL_BOXES, SMALL_STEPS = 300, 3


def shell_blocks(text):
    """(first line, the reason of a `<!-- not run: reason -->` above its fence or None, lines) of
    every ```sh or ```bash block."""
    found = []
    for start, above, lines in fenced_blocks(text, ["sh", "bash"]):
        marker = re.fullmatch(r"<!--\s*not run:\s*(.+?)\s*-->", above)
        found.append((start, marker.group(1) if marker else None, lines))
    return found


def commands(lines):
    """The simple commands of a block, as token lists, with the variable of each `for` loop set
    to the loop's first value (`for p in 1 2 4; do ... $p` checks p = 1)."""
    simple = []
    for line in "\n".join(lines).replace("\\\n", " ").splitlines():
        lexer = shlex.shlex(line, posix=True, punctuation_chars=";&|")
        lexer.whitespace_split = True
        lexer.commenters = "#"
        current = []
        for token in lexer:
            if token in SEPARATORS:
                simple.append(current)
                current = []
            else:
                current.append(token)
        simple.append(current)
    variables = {}
    result = []
    for command in simple:
        while command and command[0] in ("do", "done", "then", "fi"):
            command = command[1:]
        if not command:
            continue
        if command[0] == "for" and len(command) >= 4 and command[2] == "in":
            variables[command[1]] = command[3]
            continue
        expanded = []
        for token in command:
            for name, value in variables.items():
                token = re.sub(r"\$\{?" + name + r"\b\}?", value, token)
            expanded.append(token)
        result.append(expanded)
    return result


def options_of(arguments):
    """The option names given in a command's arguments: --name (from --name=value) and -x."""
    names = []
    for argument in arguments:
        if re.fullmatch(r"--[A-Za-z][\w-]*(=.*)?", argument):
            names.append(argument.split("=")[0])
        elif re.fullmatch(r"-[A-Za-z]", argument):
            names.append(argument)
    return names


def mentions(text, option):
    return re.search(r"(?<![\w-])" + re.escape(option) + r"(?![\w-])", text) is not None


def argparse_options(path):
    """The option strings of every add_argument call of a Python script, or None if it has none."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    found, calls = set(), 0
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "attr", None) == "add_argument":
            calls += 1
            for argument in node.args:
                if isinstance(argument, ast.Constant) and str(argument.value).startswith("-"):
                    found.add(argument.value)
    return found | {"-h", "--help"} if calls else None


class Checker:
    def __init__(self, smb, source_dir, build_dir):
        self.smb, self.source, self.build = smb, source_dir, build_dir
        self.failures, self.notes, self.counts = [], [], {}
        self.executables, self.targets, self.options = {}, set(), set()
        for lists in glob.glob(os.path.join(source_dir, "**", "CMakeLists.txt"), recursive=True) + glob.glob(
                os.path.join(source_dir, "**", "*.cmake"), recursive=True):
            if os.path.relpath(lists, source_dir).split(os.sep)[0].startswith(("build", "_deps", ".")):
                continue  # build folders inside the source folder hold copies of other projects
            with open(lists, encoding="utf-8") as f:
                text = f.read()
            folder = os.path.relpath(os.path.dirname(lists), source_dir)
            for kind, name, listed in re.findall(
                    r"\b(add_executable|add_library|add_custom_target|pybind11_add_module)\(\s*(\w+)([^)]*)", text):
                self.targets.add(name)
                if kind == "add_executable":
                    sources = [os.path.join(folder, source) for source in re.findall(r"[\w/.-]+\.cpp", listed)]
                    self.executables[name] = (folder, sources)
            self.options.update(re.findall(r"\boption\(\s*(\w+)", text))
            self.options.update(re.findall(r"\bset\(\s*(\w+)\s[^)]*\bCACHE\b", text))
        self.help_cache = {}

    def fail(self, where, message):
        self.failures.append(f"{where}: {message}")

    def count(self, kind):
        self.counts[kind] = self.counts.get(kind, 0) + 1

    def help_text(self, command):
        key = tuple(command)
        if key not in self.help_cache:
            done = subprocess.run(command + ["--help"], capture_output=True, text=True, timeout=30)
            self.help_cache[key] = done.stdout + done.stderr
        return self.help_cache[key]

    # -- smb --------------------------------------------------------------------------------
    def smb_command(self, where, arguments, under_mpi, workdir):
        if not arguments:
            return self.fail(where, "smb without a command")
        name = arguments[0]
        help_text = self.help_text([self.smb, name])
        if "--distributed" in arguments and not mentions(help_text, "--distributed"):
            self.notes.append(f"{where}: smb {name} --distributed: this build has no MPI, not checked")
            return
        if under_mpi:
            for option in options_of(arguments[1:]):
                if not mentions(help_text, option):
                    self.fail(where, f"smb {name} takes no option {option}")
            return self.count("smb options checked against --help (MPI)")
        arguments = self.small(arguments)
        self.make_inputs(arguments, workdir)
        done = subprocess.run([self.smb] + arguments, cwd=workdir, capture_output=True, text=True, timeout=60)
        if done.returncode != 0:
            self.fail(where, f"`smb {' '.join(arguments)}` exited {done.returncode}: {done.stderr.strip()[:400]}")
        self.count("smb commands run")

    @staticmethod
    def small(arguments):
        """The arguments with the sizes that make a run long (-n, -s) cut down."""
        out = list(arguments)
        for index, option in enumerate(out[:-1]):
            value = out[index + 1]
            if option in ("-n", "--boxes") and re.fullmatch(r"[\d.e+]+", value):
                out[index + 1] = str(min(int(float(value)), SMALL_BOXES))
            if option in ("-s", "--steps") and value.isdigit():
                out[index + 1] = str(min(int(value), SMALL_STEPS))
        if out[0] == "run":
            if "-n" not in out and "--boxes" not in out:
                out += ["-n", str(SMALL_BOXES)]
            if "-s" not in out and "--steps" not in out:
                out += ["-s", str(SMALL_STEPS)]
        return out

    def make_inputs(self, arguments, workdir):
        """Generates, with smb itself, each scene the command reads and the folder has not."""
        dim = "3"
        if "--periodic" in arguments:
            dim = str(arguments[arguments.index("--periodic") + 1].count(",") + 1)
        for index, option in enumerate(arguments[:-1]):
            if option in ("-i", "--input", "-l", "--left", "-r", "--right"):
                path = os.path.join(workdir, arguments[index + 1])
                if arguments[index + 1] != "-" and not os.path.exists(path):
                    os.makedirs(os.path.dirname(path), exist_ok=True)
                    # Boxes of side up to 1 in a cube of side 8: inside a periodic domain of 10.
                    subprocess.run([self.smb, "generate", "--dim", dim, "-n", "200", "--side", "8", "-s", "2",
                                    "-o", path], check=True, capture_output=True, timeout=30)

    # -- scripts and binaries ---------------------------------------------------------------
    def script(self, where, path, arguments, direct):
        full = os.path.join(self.source, path)
        if not os.path.isfile(full):
            return self.fail(where, f"{path} does not exist")
        if direct and not os.access(full, os.X_OK):
            self.fail(where, f"{path} is run directly but is not executable")
        given = options_of(arguments)
        if path.endswith(".py"):
            accepted = argparse_options(full)
            if accepted is None and given:
                self.fail(where, f"{path} takes no options, given {' '.join(given)}")
            for option in given:
                if accepted is not None and option not in accepted:
                    self.fail(where, f"{path} takes no option {option}")
        else:
            with open(full, encoding="utf-8") as f:
                text = f.read()
            passed_on = re.search(r"\[more options of ([\w./-]+\.py)\]", text)
            if passed_on:
                target = os.path.join(os.path.dirname(path), os.path.basename(passed_on.group(1)))
                text += "\n".join(argparse_options(os.path.join(self.source, target)) or [])
            for option in given:
                if not mentions(text, option):
                    self.fail(where, f"{path} takes no option {option}")
        self.count("scripts checked")

    def binary(self, where, path, arguments):
        """A binary of ours: a target built where the path says, and the options given to it named in
        its sources (read, not run: a benchmark that took --help for a size would run for minutes)."""
        parts = os.path.normpath(path).split(os.sep)
        name, inside = parts[-1], "/".join(parts[1:-1])
        if name not in self.executables:
            return self.fail(where, f"{path}: {name} is not a target of the project")
        folder, sources = self.executables[name]
        if folder != inside:
            built, named = os.path.join("<build>", folder), os.path.join("<build>", inside)
            return self.fail(where, f"{path}: {name} is built in {built}, not {named}")
        text = ""
        for source in sources:
            with open(os.path.join(self.source, source), encoding="utf-8") as f:
                text += f.read()
        for option in options_of(arguments):
            if not mentions(text, option):
                self.fail(where, f"{name} takes no option {option} (not in {', '.join(sources)})")
        self.count("binaries checked against their sources")

    def cmake(self, where, arguments):
        for index, argument in enumerate(arguments):
            match = re.fullmatch(r"-D(\w+)(:\w+)?=.*", argument)
            if match and not match.group(1).startswith("CMAKE_") and match.group(1) not in self.options:
                self.fail(where, f"cmake: the project has no option {match.group(1)}")
            if argument == "--target":
                for target in arguments[index + 1:]:
                    if target.startswith("-"):
                        break
                    if target not in self.targets:
                        self.fail(where, f"cmake: the project has no target {target}")
        self.count("cmake lines checked")

    def python(self, where, interpreter, arguments, workdir):
        """Checks a command of the Python interpreter; False for one this check does not know."""
        if arguments[:1] == ["-c"]:
            module = glob.glob(os.path.join(self.build, "python", "smb", "_smb*.so"))
            if not module:
                self.notes.append(f"{where}: python3 -c: the module is not built here, not run")
                return True
            env = dict(os.environ, PYTHONPATH=os.path.join(self.build, "python"))
            # The page's interpreter where it names one that is here (Debian's, with NumPy).
            program = interpreter if os.path.isabs(interpreter) and os.access(interpreter, os.X_OK) else sys.executable
            done = subprocess.run([program] + arguments, cwd=workdir, env=env, capture_output=True, text=True,
                                  timeout=60)
            if done.returncode != 0:
                self.fail(where, f"python3 -c exited {done.returncode}: {done.stderr.strip()[-400:]}")
            self.count("python3 -c run")
            return True
        if arguments[:2] == ["-m", "pytest"]:
            for path in arguments[2:]:
                if not path.startswith("-") and not os.path.exists(os.path.join(self.source, path)):
                    self.fail(where, f"pytest: {path} does not exist")
            self.count("pytest lines checked")
            return True
        if arguments and arguments[0].endswith(".py"):
            self.script(where, arguments[0], arguments[1:], direct=False)
            return True
        return False

    # -- one command --------------------------------------------------------------------------
    def check(self, where, command, workdir):
        """Returns False for a command the checker does not know."""
        while command and re.fullmatch(r"\w+=.*", command[0]):
            command = command[1:]  # VAR=value before the command
        if command[:1] == ["nice"]:
            command = command[3:] if command[1:2] == ["-n"] else command[1:]
        under_mpi = command[:1] == ["mpirun"]
        if under_mpi:
            index = 1
            while index < len(command) and command[index].startswith("-"):
                index += 2 if command[index] in ("-np", "-n") else 1
            command = command[index:]
        if not command:
            return True
        program, arguments = command[0], command[1:]
        # Paths and names in a page are the reader's: a scratch folder stands in for /tmp.
        arguments = [re.sub(r"^/tmp/", "", argument) for argument in arguments]
        for argument in arguments:
            if "/" in argument and not argument.startswith(("-", "/")):
                folder = os.path.dirname(os.path.join(workdir, argument))
                if not os.path.isdir(folder) and not os.path.exists(os.path.join(self.source, argument)):
                    os.makedirs(folder, exist_ok=True)  # a folder the page's reader has made
        if program in SMB_PATHS:
            self.smb_command(where, arguments, under_mpi, workdir)
        elif program in ("bash", "sh") and arguments:
            self.script(where, arguments[0], arguments[1:], direct=False)
        elif program in ("/usr/bin/python3", "python3"):
            return self.python(where, program, arguments, workdir)
        elif program == "cmake":
            self.cmake(where, arguments)
        elif program == "ctest":
            self.count("ctest lines")
        elif re.match(r"(\./)?build[\w-]*/", program):
            self.binary(where, program, arguments)
        elif re.match(r"(\./)?(scripts|examples|python)/", program):
            self.script(where, program.removeprefix("./"), arguments, direct=True)
        else:
            return False
        return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smb", required=True, help="the built smb tool")
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--build-dir", required=True)
    parser.add_argument("--verbose", action="store_true", help="print every command as it is checked")
    arguments = parser.parse_args()
    source = os.path.abspath(arguments.source_dir)
    checker = Checker(os.path.abspath(arguments.smb), source, os.path.abspath(arguments.build_dir))
    pages = [os.path.join(source, "README.md"), os.path.join(source, "tools", "smb", "README.md")] + sorted(
        glob.glob(os.path.join(source, "docs", "*.md")))
    blocks = passed_over = 0
    with tempfile.TemporaryDirectory(prefix="smb-doc-shell-") as workdir:
        for page in pages:
            with open(page, encoding="utf-8") as f:
                text = f.read()
            relative = os.path.relpath(page, source)
            for start, marker, lines in shell_blocks(text):
                blocks += 1
                # Each block in a folder of its own: its commands share their files, as a reader's do.
                folder = os.path.join(workdir, f"block-{blocks}")
                os.makedirs(folder)
                for command in commands(lines):
                    where = f"{relative}:{start} `{' '.join(command)[:70]}`"
                    if arguments.verbose:
                        print(where)
                    if not checker.check(where, command, folder):
                        if marker:
                            passed_over += 1
                            checker.notes.append(f"{where}: not run ({marker})")
                        else:
                            checker.fail(where, "a command this check does not know: check it here, or mark "
                                         "the block <!-- not run: reason --> on the line above its fence")
    for note in checker.notes:
        print("note:", note)
    summary = ", ".join(f"{count} {kind}" for kind, count in sorted(checker.counts.items()))
    print(f"{blocks} shell blocks: {summary}; {passed_over} passed over in blocks marked not run, "
          f"{len(checker.notes) - passed_over} other(s) not checked here")
    for failure in checker.failures:
        print("FAIL", failure, file=sys.stderr)
    if blocks == 0:
        sys.exit("no ```sh block found: is this the right source folder?")
    sys.exit(1 if checker.failures else 0)


if __name__ == "__main__":
    main()
