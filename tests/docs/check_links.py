#!/usr/bin/env python3
# DocsLinks: every relative link and anchor in README.md and docs/ resolves inside the
# repository; no page outside docs/history and the records under docs/results points out of
# the repository (../shared) or carries work-log numbers ("issue 17", "session 12").
# Usage: check_links.py REPO_ROOT
import re
import sys
from pathlib import Path

LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
WORKLOG = re.compile(r"\b(issue|session)s?\s+#?\d+", re.IGNORECASE)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`|\*\*|__", "", heading.strip()).lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def prose_lines(path):
    """(line number, text) outside fenced code blocks, with inline code spans blanked."""
    fenced = False
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if line.lstrip().startswith(("```", "~~~")):
            fenced = not fenced
            continue
        if not fenced:
            yield n, re.sub(r"`[^`]*`", "``", line)


def anchors(path, cache={}):
    if path not in cache:
        seen, found, fenced = {}, set(), False
        for line in path.read_text().splitlines():
            if line.lstrip().startswith(("```", "~~~")):
                fenced = not fenced
                continue
            m = None if fenced else re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
            if m:
                s = slug(m.group(1))
                found.add(s if s not in seen else f"{s}-{seen[s]}")
                seen[s] = seen.get(s, 0) + 1
        found |= set(re.findall(r"<a\s+(?:id|name)=\"([^\"]+)\"", path.read_text()))
        cache[path] = found
    return cache[path]


def is_record(root, path):
    rel = path.relative_to(root).parts
    return rel[:2] == ("docs", "history") or (rel[:2] == ("docs", "results") and len(rel) > 3)


def check_file(root, path):
    errors = []
    if not is_record(root, path):
        for n, raw in enumerate(path.read_text().splitlines(), 1):
            if "../shared" in raw:
                errors.append(f"{path.relative_to(root)}:{n}: points outside the repository (../shared)")
    for n, line in prose_lines(path):
        where = f"{path.relative_to(root)}:{n}"
        if not is_record(root, path):
            if m := WORKLOG.search(line):
                errors.append(f"{where}: work-log number '{m.group(0)}' outside docs/history")
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                continue  # https:, mailto: and the like
            file_part, _, anchor = target.partition("#")
            dest = (path.parent / file_part).resolve() if file_part else path
            if root not in dest.parents and dest != root:
                errors.append(f"{where}: link '{target}' leaves the repository")
                continue
            if not dest.exists():
                errors.append(f"{where}: link '{target}': {dest.relative_to(root)} does not exist")
                continue
            if anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                errors.append(f"{where}: link '{target}': no heading with anchor #{anchor} in "
                              f"{dest.relative_to(root)}")
    return errors


def main():
    root = Path(sys.argv[1]).resolve()
    pages = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    errors = [e for p in pages for e in check_file(root, p)]
    for e in errors:
        print(e)
    if errors:
        sys.exit(1)
    print(f"check_links: {len(pages)} pages, every relative link and anchor resolves")


if __name__ == "__main__":
    main()
