#!/usr/bin/env python3
"""Every link and picture in README.md and docs/*.md points inside the repository, at a file
that exists (issue 26: the README linked ../shared/DESIGN.md, outside the repository).

  doc_links_check.py ROOT [EXTRA.md …]   exit 0 when every link resolves, 1 listing those
                                         that do not (EXTRA files are checked as if in docs/)
"""
import os
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def problems_in(path, root):
    found = []
    text = open(path, encoding="utf-8").read()
    # Code spans and blocks hold commands, not links.
    text = re.sub(r"```.*?```", "", text, flags=re.S)
    text = re.sub(r"`[^`\n]*`", "", text)
    for target in LINK.findall(text):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):
            found.append(f"{path}: link leaves the repository: {target}")
            continue
        if target.startswith("#"):
            continue
        resolved = os.path.realpath(os.path.join(os.path.dirname(path), target.split("#")[0]))
        if os.path.commonpath([resolved, root]) != root:
            found.append(f"{path}: link leaves the repository: {target}")
        elif not os.path.exists(resolved):
            found.append(f"{path}: link to a file that does not exist: {target}")
    return found


def main():
    root = os.path.realpath(sys.argv[1])
    files = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    files += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    files += sys.argv[2:]
    found = [p for f in files for p in problems_in(f, root)]
    for p in found:
        print(p)
    print(f"{len(files)} files, {len(found)} bad links")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
