#!/usr/bin/env python3
# DocsExamples: runs every command block marked `<!-- doc-test -->` (the line before its
# fence) in the given Markdown files, so the quick start and the tutorial cannot go stale.
# Usage: run_doc_blocks.py CBRBENCH WORK_DIR FILE.md...
#
# Each file's blocks run in order in one bash (set -euo pipefail), in a fresh WORK_DIR/<file>
# sandbox holding stand-ins for what the blocks call:
#   build/harness/cbrbench  the real binary, with `--res 64x48 --frames 3 --repeat 2 --warmup 0`
#                           in place of the block's own values for run, sweep, plan and
#                           calibrate (what CI can afford); on PATH as `cbrbench` too;
#   scripts/bench           that cbrbench (`run` without arguments): the build is done already;
#   scripts/test            says it is not re-entered (it is the suite running this test).
# A marker may name files the block must leave behind: <!-- doc-test expect: out/*/report.html -->
# Each file's blocks run twice in the same sandbox, as a reader trying them again would: an
# example that only works once (an --out that exists the second time) fails the test.
import glob
import re
import shutil
import subprocess
import sys
from pathlib import Path

SMALL = "--res 64x48 --frames 3 --repeat 2 --warmup 0"
WRAPPER = """#!/usr/bin/env bash
# doc-test stand-in: the real cbrbench at small settings.
real=%(real)s
case "${1:-}" in
  run|sweep|calibrate|plan) ;;
  *) exec "$real" "$@" ;;
esac
args=() skip=0
for a in "$@"; do
  if ((skip)); then skip=0; continue; fi
  case $a in
    --res|--frames|--repeat|--warmup) skip=1; continue ;;
    --res=*|--frames=*|--repeat=*|--warmup=*) continue ;;
  esac
  args+=("$a")
done
quiet=(); [[ $1 != plan ]] && quiet=(--quiet)
exec "$real" "${args[@]}" %(small)s "${quiet[@]}"
"""
BENCH = """#!/usr/bin/env bash
# doc-test stand-in for scripts/bench: the build is done; runs cbrbench ARGS (default: run).
(($#)) || set -- run
exec "$(dirname "$0")/../build/harness/cbrbench" "$@"
"""
TEST = """#!/usr/bin/env bash
echo "doc-test: ./scripts/test is the suite running this test; not re-entered"
"""


def blocks(path):
    """[(line number, expected globs, code)] of the marked blocks."""
    out, lines = [], Path(path).read_text().splitlines()
    i = 0
    while i < len(lines):
        m = re.match(r"\s*<!--\s*doc-test\b(.*?)-->", lines[i])
        if m:
            expect = re.findall(r"expect:\s*(\S+)", m.group(1))
            j = i + 1
            if j >= len(lines) or not re.match(r"\s*```(sh|bash)\s*$", lines[j]):
                sys.exit(f"{path}:{i + 1}: a doc-test marker must sit on the line before a ```sh fence")
            k = j + 1
            while k < len(lines) and not lines[k].strip().startswith("```"):
                k += 1
            out.append((j + 2, expect, "\n".join(lines[j + 1:k])))
            i = k
        i += 1
    return out


def sandbox(root, real):
    shutil.rmtree(root, ignore_errors=True)
    for rel, text in [("build/harness/cbrbench", WRAPPER % {"real": real, "small": SMALL}),
                      ("scripts/bench", BENCH), ("scripts/test", TEST)]:
        p = root / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
        p.chmod(0o755)


def run_file(md, real, work):
    found = blocks(md)
    if not found:
        sys.exit(f"{md}: no <!-- doc-test --> block")
    box = work / Path(md).name.replace(".", "_")
    sandbox(box, real)
    script = ["set -euo pipefail", f'export PATH="{box}/build/harness:$PATH"',
              "trap 'echo \"doc-test: a command failed in the block at $DOC_BLOCK\" >&2' ERR"]
    for attempt in ("first", "second"):
        for line, expect, code in found:
            where = f"{md}:{line} ({attempt} time)"
            script += [f"DOC_BLOCK='{where}'", f"echo '== {where}'", "set -x", code, "{ set +x; } 2>/dev/null"]
            for pattern in expect:
                script.append(f"compgen -G '{pattern}' >/dev/null || {{ echo 'doc-test: {where}: "
                              f"no {pattern} after the block' >&2; false; }}")
    r = subprocess.run(["bash", "-c", "\n".join(script)], cwd=box)
    if r.returncode != 0:
        sys.exit(f"run_doc_blocks: {md} failed (exit {r.returncode}); its sandbox is {box}")
    print(f"run_doc_blocks: {md}: {len(found)} blocks ran, twice each")
    shutil.rmtree(box, ignore_errors=True)


def main():
    real = str(Path(sys.argv[1]).resolve())
    work = Path(sys.argv[2]).resolve()
    for md in sys.argv[3:]:
        run_file(md, real, work)


if __name__ == "__main__":
    main()
