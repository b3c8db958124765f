#!/usr/bin/env python3
"""Functions and files that fit on a screen: no function or method past 80 lines and no
room (a .cpp with its same-named .h, or a lone header) past 600 lines in the source.

Function extents come from Universal Ctags (Debian's universal-ctags: --fields=+e gives
each definition's last line). Tests, the generated ColorVideoVDP tables and shaders are
left out. Prints one line per breach and exits 1; with --list prints every function over
--over lines (default 60) and exits 0, as a guide while splitting.

Usage: check_lengths.py REPO_ROOT [--list [--over N]]
"""
import pathlib
import subprocess
import sys

MAX_FUNCTION = 80
MAX_ROOM = 600
FOLDERS = ("camera_paths", "harness", "metrics", "renderer", "reports", "rundir", "settings")


def functions(files):
    """(file, name, lines) for every function and method ctags finds with an end line."""
    out = subprocess.run(["ctags", "--fields=+ne", "--kinds-c++=fm", "--language-force=c++", "-o", "-",
                          *map(str, files)], check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        parts = line.split("\t")
        fields = dict(p.split(":", 1) for p in parts[3:] if ":" in p)
        if "line" in fields and "end" in fields:
            yield parts[1], parts[0], int(fields["end"]) - int(fields["line"]) + 1


def rooms(root, files):
    """{room: lines}: a .cpp with the .h of the same stem, and headers without a .cpp."""
    sizes = {}
    for f in files:
        key = str(f.relative_to(root).with_suffix(""))
        sizes[key] = sizes.get(key, 0) + len(f.read_text(errors="replace").splitlines())
    return sizes


def main(argv):
    root = pathlib.Path(argv[1] if len(argv) > 1 and not argv[1].startswith("-") else ".").resolve()
    listing = "--list" in argv
    over = int(argv[argv.index("--over") + 1]) if "--over" in argv else 60
    files = sorted(p for folder in FOLDERS for p in (root / folder).rglob("*")
                   if p.suffix in (".h", ".cpp") and p.is_file())
    long_functions = sorted(((n, f, name) for f, name, n in functions(files)
                             if n > (over if listing else MAX_FUNCTION)), reverse=True)
    if listing:
        for n, f, name in long_functions:
            print(f"{n:4d}  {pathlib.Path(f).relative_to(root)}  {name}")
        return 0
    problems = [f"{pathlib.Path(f).relative_to(root)}: {name} is {n} lines (at most {MAX_FUNCTION})"
                for n, f, name in long_functions]
    problems += [f"{room}.cpp/.h: {n} lines (at most {MAX_ROOM})"
                 for room, n in sorted(rooms(root, files).items()) if n > MAX_ROOM]
    for p in problems:
        print(p)
    if problems:
        print("split by concern: docs/dev/architecture.md, 'Where a change goes'")
        return 1
    print(f"check_lengths: {len(files)} files, every function at most {MAX_FUNCTION} lines, "
          f"every room at most {MAX_ROOM}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
