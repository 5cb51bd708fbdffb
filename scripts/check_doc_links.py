#!/usr/bin/env python3
"""scripts/check_doc_links.py [ROOT] — every relative link and image in README.md and docs/*.md
points at a file that exists in the repository, and every #anchor at a heading of its target.

Markdown links `[text](path)`, `[text](path#anchor)`, `[text](#anchor)` and images
`![alt](path)` are checked; links with a scheme (https:, mailto:) are not. Anchors follow
GitHub's rule: the heading lower-cased, punctuation other than '-' and '_' dropped, spaces
turned into '-'. Prints one line per broken link and exits 1 when there is any (the CTest
docs.relative_links).
"""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*```")


def prose_lines(path, keep_code=False):
    """The lines of a Markdown file outside fenced code blocks, inline code removed unless
    keep_code (headings keep theirs: it is part of the anchor)."""
    inside = False
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield number, line if keep_code else re.sub(r"`[^`]*`", "", line)


def slug(heading):
    text = re.sub(r"`", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    found = set()
    for _, line in prose_lines(path, keep_code=True):
        m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if m:
            base = slug(m.group(2))
            name, n = base, 1
            while name in found:
                name, n = f"{base}-{n}", n + 1
            found.add(name)
    return found


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    files = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    files += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    broken = checked = 0
    for path in files:
        for number, line in prose_lines(path):
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):
                    continue
                checked += 1
                file_part, _, anchor = target.partition("#")
                dest = path if not file_part else os.path.normpath(
                    os.path.join(os.path.dirname(path), file_part))
                where = f"{os.path.relpath(path, root)}:{number}"
                if not os.path.exists(dest):
                    print(f"{where}: link to {target}: no such file")
                    broken += 1
                elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                    print(f"{where}: link to {target}: no heading '#{anchor}' there")
                    broken += 1
    print(f"check_doc_links.py: {checked} relative links in {len(files)} files, {broken} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
