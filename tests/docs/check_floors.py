#!/usr/bin/env python3
"""The floors of docs/dev/architecture.md held against the code's includes.

architecture.md has two tables whose first column is a floor number: the libraries
(`| 3 | `renderer/` | ...`) and harness's rooms (`| 6 | `run/` | ...`). A file may include
only files of its own room or of a room on a lower floor; every folder of the source and
every room of harness must stand in a table. Prints one line per breach and exits 1;
exits 0 with a summary when the code matches the drawing.

Usage: check_floors.py REPO_ROOT
"""
import pathlib
import re
import sys

ROW = re.compile(r"^\|\s*(\d+)\s*\|\s*([^|]+)\|")
NAME = re.compile(r"`([^`]+)`")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
SOURCE = (".h", ".cpp", ".inc")


def tables(doc):
    """{'libraries': {room: floor}, 'harness': {room: floor}} from the doc's floor tables."""
    out, current = {"libraries": {}, "harness": {}}, None
    for line in doc.splitlines():
        if line.startswith("#"):
            current = "harness" if "harness" in line.lower() and "floor" in line.lower() else (
                "libraries" if "floor" in line.lower() else None)
            continue
        m = ROW.match(line)
        if current and m:
            for name in NAME.findall(m.group(2)):
                out[current][stem(name.rstrip("/"))] = int(m.group(1))
    return out


def stem(name):
    """A file's room is its name without .h/.cpp: a source and its header are one room."""
    return re.sub(r"\.(h|cpp)$", "", name)


def room_of(rel, rooms, prefix):
    """The room a path belongs to: its folder under prefix, else the file (and its header)."""
    inner = rel[len(prefix):] if prefix else rel
    first = inner.split("/")[0]
    if "/" in inner:
        return first if first in rooms else None
    return stem(inner) if stem(inner) in rooms else None


def main(root):
    root = pathlib.Path(root)
    doc = (root / "docs/dev/architecture.md").read_text()
    t = tables(doc)
    libs, rooms = t["libraries"], t["harness"]
    problems = []
    if not libs or not rooms:
        print("check_floors: docs/dev/architecture.md has no floor tables (a row is | FLOOR | `room` | ...)")
        return 1
    sources = [p for p in root.rglob("*") if p.suffix in SOURCE and p.is_file()]
    top_folders = {p.relative_to(root).parts[0] for p in sources
                   if len(p.relative_to(root).parts) > 1}
    for folder in sorted(top_folders - set(libs) - {"tests", "build", "docs", "scripts", "cmake"}):
        if not folder.startswith(("build", ".")):
            problems.append(f"{folder}/: a source folder with no floor in architecture.md's library table")
    checked = 0
    for p in sources:
        rel = str(p.relative_to(root))
        lib = rel.split("/")[0]
        if lib not in libs:
            continue
        here_room = room_of(rel, rooms, "harness/") if lib == "harness" else None
        if lib == "harness" and here_room is None:
            problems.append(f"{rel}: no room of harness's floor table holds it")
            continue
        for inc in INCLUDE.findall(p.read_text(errors="replace")):
            target_lib = inc.split("/")[0]
            if target_lib not in libs or "/" not in inc:
                continue
            checked += 1
            if target_lib != lib:
                if libs[target_lib] >= libs[lib]:
                    problems.append(f"{rel}: includes {inc}: {target_lib}/ (floor {libs[target_lib]}) "
                                    f"is not below {lib}/ (floor {libs[lib]})")
                continue
            if lib != "harness":
                continue
            there = room_of(inc, rooms, "harness/")
            if there is None:
                problems.append(f"{rel}: includes {inc}, which no room of harness's table holds")
            elif there != here_room and rooms[there] >= rooms[here_room]:
                problems.append(f"{rel}: includes {inc}: {there} (floor {rooms[there]}) is not below "
                                f"{here_room} (floor {rooms[here_room]})")
    for line in problems:
        print(line)
    if problems:
        return 1
    print(f"check_floors: {checked} includes across {len(libs)} libraries and {len(rooms)} harness rooms "
          "point down")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
