#!/usr/bin/env python3
"""scripts/check_doc_history.py [ROOT] | --self-test — README.md and docs/*.md say what holds
now: no hand-written paragraph quotes a load average or tells the development history.

Measured numbers, with the date, machine and load average of their run, live only in generated
blocks, which are skipped here:
  <!-- perf-table ID --> ... <!-- /perf-table ID -->     (scripts/perf_tables.sh)
  <!-- generated:ID --> ... <!-- /generated:ID -->       (scripts/user_guide.sh)
  <!-- NAME:begin --> ... <!-- NAME:end -->              (scripts/error_tables.sh,
                                                          scripts/bench_tables.py)
Everywhere else a paragraph fails when it quotes a load (`load 8-9`, `load average 0.6`,
`/proc/loadavg 9.2`) or uses one of the history phrases below (an earlier run or binary, what
was "not kept", "this round", a commit hash, a date, "before the merge", ...), also where the
phrase wraps across lines; the finding names the line it starts on. Naming the load average
as a concept ("each table states its load average") is allowed. A block opened and not closed
is an error too (it would hide the rest of the file). Prints one line per finding and exits 1
when there is any (the CTest docs.no_history); --self-test checks the checker on a made-up tree
(the CTest docs.no_history_selftest).
"""
import os
import re
import sys
import tempfile

BEGIN = re.compile(r"^<!-- (?:perf-table (\S+)|generated:(\S+)|(\S+):begin) -->$")
END = re.compile(r"^<!-- (?:/perf-table (\S+)|/generated:(\S+)|(\S+):end) -->$")

# A load quoted with a number: "load 8-9", "load average 7.0-7.5", "load average about 15",
# "/proc/loadavg 9.20".
LOAD = re.compile(r"\bload(?:\s+averages?)?(?:\s+(?:of|about|under|around|near|was|is|at)){0,2}"
                  r"\s+~?[0-9]|loadavg\s*[0-9]", re.IGNORECASE)
# How the code came to be, rather than what it is now.
HISTORY = [
    r"\bearlier (?:run|runs|binary|build|commit|version|code|round|pair|measurement)s?\b",
    r"\bprevious (?:run|round|binary|commit|version|code)s?\b",
    r"\bthis round\b", r"\bnot kept\b", r"\(kept\)", r"\ba helper\b",
    r"\bbefore the merge\b", r"\bback to back with the\b",
    r"\bcommit [0-9a-f]{7,40}\b", r"\bcommits [0-9a-f]{7,40}\b",
    r"\bwe (?:changed|tried|removed|replaced)\b", r"\bwhat was tried\b",
    r"\bused to (?:be|take|run|cost)\b", r"\bno longer\b", r"\bpreviously\b",
    r"\bearlier (?:default|setup|foliage|form|table)s?\b", r"\bprevious setup\b",
    r"\bfresh-clone run\b", r"\bchanged since\b", r"\buntil this change\b",
    r"\bthe old (?:table|axis|code|binary)\b", r"\ban older run\b",
    r"\b20[0-9]{2}-[01][0-9]-[0-3][0-9]\b",  # a date: runs are dated in generated blocks only
]
HISTORY_RE = re.compile("|".join(HISTORY), re.IGNORECASE)


def block_name(m):
    return next(g for g in m.groups() if g is not None)


def paragraphs(path):
    """(first line, [lines]) for each hand-written paragraph of PATH (blank-line separated, the
    generated blocks left out), and the line of a block never closed (or None)."""
    out, current, first, open_block = [], [], 0, None
    def flush():
        nonlocal current
        if current:
            out.append((first, current))
        current = []
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        text = line.rstrip("\n")
        if open_block is None:
            m = BEGIN.match(text)
            if m:
                flush()
                open_block = (block_name(m), number)
                continue
        else:
            m = END.match(text)
            if m and block_name(m) == open_block[0]:
                open_block = None
            continue
        if not text.strip():
            flush()
            continue
        if not current:
            first = number
        current.append(text)
    flush()
    return out, open_block


def findings(path, shown):
    """Lines of PATH whose paragraph quotes a load or tells history (a phrase may wrap)."""
    out = []
    paras, open_block = paragraphs(path)
    for first, lines in paras:
        joined = " ".join(lines)
        starts = [0]
        for line in lines[:-1]:
            starts.append(starts[-1] + len(line) + 1)
        for regex, what in ((LOAD, "quotes a load"), (HISTORY_RE, "tells history")):
            for hit in regex.finditer(joined):
                line = first + max(i for i, s in enumerate(starts) if s <= hit.start())
                out.append((line, f"{what} ('{hit.group(0)}'): move the number into a "
                            "generated table or say what holds now"))
    if open_block is not None:
        out.append((open_block[1], f"generated block '{open_block[0]}' is never closed"))
    return [f"{shown}:{n}: {msg}" for n, msg in sorted(out)]


def check(root):
    files = [os.path.join(root, "README.md")]
    docs = os.path.join(root, "docs")
    files += sorted(os.path.join(docs, f) for f in os.listdir(docs) if f.endswith(".md"))
    lines = []
    for path in files:
        if os.path.exists(path):
            lines += findings(path, os.path.relpath(path, root))
    return files, lines


def self_test():
    """The checker passes a clean tree and names each planted fault, once."""
    clean = ("# Speed\n\nEach table states its load average.\n\n"
             "<!-- perf-table t -->\nrun at load average 9.1 before, commit abc1234\n"
             "<!-- /perf-table t -->\n\n<!-- generated:help -->\nload 3\n<!-- /generated:help -->\n"
             "<!-- bench-quick:begin -->\nan earlier run, load 5\n<!-- bench-quick:end -->\n")
    planted = {
        "4x faster at load 0.6-2.3.": "quotes a load",
        "The /proc/loadavg 9.20 was high.": "quotes a load",
        "An earlier run gave 3x.": "tells history",
        "The blur form was not kept.": "tells history",
        "Fixed in commit 1e0f175.": "tells history",
        "Measured on 2026-12-02.": "tells history",
        "These numbers are no\nlonger shown.": "tells history",
        "<!-- perf-table u -->\nload 1\n": "never closed",
    }
    failures = 0
    with tempfile.TemporaryDirectory() as root:
        os.mkdir(os.path.join(root, "docs"))
        with open(os.path.join(root, "README.md"), "w") as f:
            f.write(clean)
        _, lines = check(root)
        if lines:
            print("self-test: clean tree flagged:", *lines, sep="\n  ")
            failures += 1
        for sentence, expected in planted.items():
            with open(os.path.join(root, "docs", "x.md"), "w") as f:
                f.write(clean + "\n" + sentence + "\n")
            _, lines = check(root)
            if len(lines) != 1 or expected not in lines[0]:
                print(f"self-test: {sentence!r}: expected one '{expected}' finding, got {lines}")
                failures += 1
    print(f"check_doc_history.py --self-test: {len(planted) + 1} cases, {failures} failed")
    return 1 if failures else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), ".."))
    files, lines = check(root)
    for line in lines:
        print(line)
    print(f"check_doc_history.py: {len(files)} files, {len(lines)} findings (a load quoted or "
          "history told outside generated blocks)")
    return 1 if lines else 0


if __name__ == "__main__":
    sys.exit(main())
