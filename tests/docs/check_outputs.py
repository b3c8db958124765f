#!/usr/bin/env python3
# DocsOutputColumns: every CSV column and run.json key real runs write is documented in
# docs/reference/outputs.md, and everything that page documents is still written.
# Usage: check_outputs.py CBRBENCH DOC_MD WORK_DIR
import csv
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

SMALL = ["--res", "64x48", "--frames", "3", "--repeat", "1", "--warmup", "0", "--quiet"]
# Small runs that together write every column and key the page documents: forward with the
# fused passes and an ssaa reference; deferred atrium with separate passes (gbuffer, lighting,
# cfb, upscale, cbr_resolve, taau_resolve); the blocks scene (culled passes have a reason, an
# orbit is placed on a grid); a sweep (sweep.csv); compare of a run with itself (compare.csv).
RUNS = {
    "forward": ["run", "--reference", "ssaa", "--ssaa", "2"],
    "deferred": ["run", "--pipeline", "deferred", "--resolve-impl", "separate"],
    "blocks": ["run", "--scene", "blocks", "--path", "orbit", "--variants", "cbr-aso"],
    "sweep": ["sweep", "--variants", "cbr-cso", "--param", "cso-tolerance=0.01,0.1"],
}
CHECKED = ["frames.csv", "summary.csv", "run.json", "compare.csv", "sweep.csv"]


def parse_doc(path):
    """{(h2 file name, h3 title or None): [first-cell names]} from the page's tables."""
    tables, h2, h3 = {}, None, None
    for line in Path(path).read_text().splitlines():
        if line.startswith("## "):
            m = re.search(r"`([^`]+)`", line)
            h2, h3 = (m.group(1) if m else line[3:].strip()), None
        elif line.startswith("### "):
            h3 = line[4:].strip()
        elif line.startswith("|") and not re.match(r"^\|[-| ]+\|$", line):
            first = line.split("|")[1]
            names = re.findall(r"`([^`]+)`", first)
            if names:
                tables.setdefault((h2, h3), []).extend(names)
    return tables


def pattern(name, placeholders):
    parts = re.split(r"(<[a-z_]+>)", name)
    rx = ""
    for p in parts:
        if p.startswith("<") and p.endswith(">"):
            alts = placeholders.get(p[1:-1])
            rx += "(?:" + "|".join(map(re.escape, alts)) + ")" if alts else r"[A-Za-z0-9_.-]+"
        else:
            rx += re.escape(p)
    return re.compile(rx + r"\Z")


def flatten(value, prefix, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(v, f"{prefix}.{k}" if prefix else k, out)
    elif isinstance(value, list):
        out.add(prefix + "[]")
        for v in value:
            flatten(v, prefix + "[]", out)
    else:
        out.add(prefix)


def run(exe, args, cwd, ok=(0,)):
    r = subprocess.run([exe] + args, cwd=cwd, capture_output=True, text=True)
    if r.returncode not in ok:
        sys.exit(f"check_outputs: `cbrbench {' '.join(args)}` exited {r.returncode}:\n{r.stderr}")


def collect(exe, work):
    """{file: {name: [runs that wrote it]}} from the small runs."""
    seen = {f: {} for f in CHECKED}
    for name, args in RUNS.items():
        run(exe, args + SMALL + ["--out", name], work)
    # One repetition per side decides nothing: compare exits 2 (inconclusive) and writes compare.csv.
    run(exe, ["compare", "forward", "forward"], work, ok=(2,))
    for name in RUNS:
        d = work / name
        for f in ["frames.csv", "summary.csv", "sweep.csv", "compare.csv"]:
            if (d / f).exists():
                with open(d / f) as fh:
                    for col in next(csv.reader(fh)):
                        seen[f].setdefault(col, []).append(name)
        keys = set()
        flatten(json.loads((d / "run.json").read_text()), "", keys)
        for k in keys:
            seen["run.json"].setdefault(k, []).append(name)
    with open(work / "forward" / "compare.csv") as fh:
        settings = next(csv.DictReader(fh))["settings"]
    cell_key = [kv.split("=", 1)[0] for kv in settings.split(";")]
    return seen, cell_key


def check(doc, seen, cell_key):
    tables = parse_doc(doc)
    placeholders = {"pass": tables.get(("frames.csv", "Pass names"), []),
                    "class": tables.get(("frames.csv", "Pixel classes"), [])}
    errors = []
    for f in CHECKED:
        documented = tables.get((f, None), [])
        if not documented:
            errors.append(f"{doc}: no table of `{f}` (a '## `{f}`' section with one row per column)")
            continue
        pats = [(n, pattern(n, placeholders)) for n in documented]
        for name, runs in sorted(seen[f].items()):
            if not any(p.match(name) for _, p in pats):
                errors.append(f"{f}: `{name}` (written by the {runs[0]} run) is not documented: add a row to "
                              f"the `{f}` table of {doc}")
        for n, p in pats:
            if not any(p.match(name) for name in seen[f]):
                errors.append(f"{f}: {doc} documents `{n}`, but no test run wrote it: fix or remove the row")
    for kind, prefix in [("pass", "gpu_ms_"), ("class", "px_")]:
        for v in placeholders[kind]:
            if prefix + v not in seen["frames.csv"]:
                errors.append(f"frames.csv: {doc} lists the {kind} `{v}`, but no run wrote `{prefix}{v}`")
    documented_key = tables.get(("compare.csv", "The cell key"), [])
    documented_key = [n for n in documented_key if not n.startswith(("settings.", "metrics."))]
    if documented_key != cell_key:
        errors.append(f"compare.csv: the cell key is {';'.join(cell_key)}, {doc} says {';'.join(documented_key)}")
    return errors


def main():
    exe, doc, work = str(Path(sys.argv[1]).resolve()), sys.argv[2], Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    seen, cell_key = collect(exe, work)
    errors = check(doc, seen, cell_key)
    for e in errors:
        print(e)
    if errors:
        sys.exit(1)
    total = sum(len(v) for v in seen.values())
    print(f"check_outputs: {total} columns and keys of {', '.join(CHECKED)} match {doc}")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
