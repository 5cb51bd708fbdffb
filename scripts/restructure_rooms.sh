#!/usr/bin/env bash
# scripts/restructure_rooms.sh — moves the source tree into rooms by responsibility
# (docs/rooms.md describes the target layout and why each file goes where).
#
#   usage: bash scripts/restructure_rooms.sh [--dry-run]
#          bash scripts/restructure_rooms.sh --mentions   (after merging a branch made before the
#            move: rewrites the old paths its files name, moves nothing, stages nothing)
#
# What it does, in one go, on a clean checkout:
#   1. decides every move from patterns (not from a fixed file list, so files it has never
#      seen are placed by their names; a core/ file no rule knows stays in core/, named on
#      stderr):
#        core/*            -> core/base/, core/gl/, core/scene/, core/technique/
#        core/pass_dump.*  -> teach/            figures/lesson.* -> teach/
#        legacy_gl/benchmark.* -> measure/legacy_benchmark.*   legacy_gl/roofline.* -> measure/
#        modern/volumes_bench.*, figures/bench*.*, figures/stability.* -> measure/
#        tests/legacy_gl/roofline_test.cpp, tests/figures/bench_test.cpp -> tests/measure/
#   2. `git mv`s them;
#   3. rewrites every mention of a moved path in every text file git knows (#include lines,
#      CMake, scripts, docs, lesson assets): "core/scene.h" -> "core/scene/scene.h", also as
#      "core/scene.*" or "../core/scene.h";
#   4. edits CMakeLists.txt (core's glob, the sl_teach and sl_measure libraries, links),
#      tests/CMakeLists.txt (tests/measure), tests/layering/include_layers.cmake (the new
#      layers) and the folder maps of docs/design.md and README.md.
# It refuses to run on a tree with uncommitted changes, stops without touching anything when
# the tree is already restructured (exit 0), and on any failure puts the tree back
# (git reset --hard to where it started) and exits 1. It commits nothing: review
# `git status` / `git diff --cached -M --stat`, build, test, then commit.
set -euo pipefail
cd "$(git rev-parse --show-toplevel)"

dry_run=0
mode=move
case "${1:-}" in
  --dry-run) dry_run=1 ;;
  --mentions) mode=mentions ;;
  "") ;;
  *) echo "restructure_rooms.sh: unknown argument '$1' (usage: [--dry-run | --mentions])" >&2; exit 2 ;;
esac

# Done state: the layering test knows the measuring room, and core/ has its parts.
if grep -q 'kLayer_measure' tests/layering/include_layers.cmake 2>/dev/null && [ -d core/technique ]; then
  if [ "$mode" = mentions ]; then
    # After a late merge: rewrite the old paths the merged files still name, move nothing.
    MODE=mentions DRY_RUN=0 python3 - <<'PYTHON'
import os
exec(open(os.path.join("scripts", "restructure_rooms.sh")).read().split("#@PYTHON@\n")[1].split("\nPYTHON\n")[0])
PYTHON
    exit 0
  fi
  echo "restructure_rooms.sh: the tree is already in rooms (tests/layering/include_layers.cmake has kLayer_measure, core/technique/ exists); nothing to do"
  echo "  (after merging a branch made before the move: bash scripts/restructure_rooms.sh --mentions)"
  exit 0
fi
if [ "$mode" = mentions ]; then
  echo "restructure_rooms.sh: --mentions is for a tree already in rooms; this one is not" >&2
  exit 1
fi
if [ -e measure ] || [ -e teach/pass_dump.h ] || [ -d core/technique ] || [ -d core/gl ]; then
  echo "restructure_rooms.sh: the tree is half restructured (measure/, teach/pass_dump.h, core/gl/ or core/technique/ exists but the layering test has no measure layer); refusing" >&2
  exit 1
fi
if [ -n "$(git status --porcelain)" ]; then
  echo "restructure_rooms.sh: the working tree has uncommitted changes or untracked files; commit or stash them first" >&2
  git status --short | head -20 >&2
  exit 1
fi

start=$(git rev-parse HEAD)
restore() {
  echo "restructure_rooms.sh: FAILED; putting the tree back to $start (git reset --hard)" >&2
  git reset -q --hard "$start"
  git clean -qfd -- measure teach core tests/measure 2>/dev/null || true
}
if [ "$dry_run" = 0 ]; then trap restore ERR; fi

MODE=move DRY_RUN=$dry_run python3 - <<'PYTHON'
#@PYTHON@
import os, re, shutil, subprocess, sys

dry = os.environ.get("DRY_RUN") == "1"
mentions_only = os.environ.get("MODE") == "mentions"

def run(*args):
    subprocess.run(args, check=True)

def files_under(folder):
    out = subprocess.run(["git", "ls-files", "--", folder], check=True, capture_output=True,
                         text=True).stdout.split()
    return sorted(out)

# ------------------------------------------------------------------ 1. the moves
# core/: the part of each file by its name (the stem before the first dot).
CORE_PARTS = [
    # GL: contexts, the dispatch table and its tracing layer, GL objects, shaders, winding.
    ("gl", re.compile(r"^(context|gl|gl_.*|shaders|winding)$")),
    # scenes: the scene description, the named scenes, meshes and their files, primitives.
    ("scene", re.compile(r"^(scene|scene_.*|mesh_.*|primitives)$")),
    # the technique interface: Technique, PassTimer, the pass table and Passes, capture, plans,
    # frame timing.
    ("technique", re.compile(r"^(technique|technique_.*|pass_table|passes|pass_capture|plan|frame_timing)$")),
    # what everything stands on: errors, numbers, images and PNG, metrics, provenance,
    # all-or-nothing output files, HTML escaping, content hashes.
    ("base", re.compile(r"^(errors|decimal|image|png_text|metrics|provenance|content_hash|output_files|html)$")),
]
moves = []   # (old, new)
unplaced = []
for path in files_under("core"):
    parts = path.split("/")
    if len(parts) != 2:
        continue  # already in a sub-folder
    name = parts[1]
    if name.endswith(".cmake"):
        continue  # build glue stays beside the parts
    stem = name.split(".")[0]
    if stem == "pass_dump" or stem.startswith("pass_dump_"):
        moves.append((path, "teach/" + name))
        continue
    for part, rule in CORE_PARTS:
        if rule.match(stem):
            moves.append((path, "core/%s/%s" % (part, name)))
            break
    else:
        unplaced.append(path)

def move_stems(folder, rule, target, rename=lambda n: n):
    for path in files_under(folder):
        parts = path.split("/")
        if len(parts) != 2:
            continue
        stem = parts[1].split(".")[0]
        if rule.match(stem):
            moves.append((path, target + "/" + rename(parts[1])))

move_stems("legacy_gl", re.compile(r"^benchmark$"), "measure", lambda n: "legacy_" + n)
move_stems("legacy_gl", re.compile(r"^roofline(_.*)?$"), "measure")
move_stems("modern", re.compile(r"^volumes_bench(_.*)?$"), "measure")
move_stems("figures", re.compile(r"^(bench|bench_.*|stability|stability_.*|sweep)$"), "measure")
move_stems("figures", re.compile(r"^(lesson|lesson_.*)$"), "teach")
for old, new in [("tests/legacy_gl/roofline_test.cpp", "tests/measure/roofline_test.cpp"),
                 ("tests/figures/bench_test.cpp", "tests/measure/bench_test.cpp")]:
    if os.path.exists(old):
        moves.append((old, new))

if mentions_only:
    # The moves as they were, read back from the new places (the same rules, reversed). Files a
    # late merge added at an old place are named: move them by hand (git mv) and run again.
    for old, new in moves:
        print("restructure_rooms.sh: %s is at an old place; move it by hand: git mv %s %s" % (old, old, new),
              file=sys.stderr)
    moves = []
    back = [(r"^core/(base|gl|scene|technique)/([^/]+)$", r"core/\2"),
            (r"^teach/(pass_dump[^/]*)$", r"core/\1"),
            (r"^teach/(lesson[^/]*)$", r"figures/\1"),
            (r"^measure/legacy_(benchmark[^/]*)$", r"legacy_gl/\1"),
            (r"^measure/(roofline[^/]*)$", r"legacy_gl/\1"),
            (r"^measure/(volumes_bench[^/]*)$", r"modern/\1"),
            (r"^measure/((bench|stability|sweep)[^/]*)$", r"figures/\1"),
            (r"^tests/measure/(roofline_test\.cpp)$", r"tests/legacy_gl/\1"),
            (r"^tests/measure/(bench_test\.cpp)$", r"tests/figures/\1")]
    for folder in ["core", "teach", "measure", "tests/measure"]:
        for path in files_under(folder):
            for rule, old in back:
                if re.match(rule, path):
                    moves.append((re.sub(rule, old, path), path))
                    break
for path in unplaced:
    print("restructure_rooms.sh: no rule places %s; it stays in core/ (layer 0)" % path,
          file=sys.stderr)
for old, new in ([] if mentions_only else moves):
    if os.path.exists(new):
        sys.exit("restructure_rooms.sh: %s exists already (would be the new place of %s)" % (new, old))
if not mentions_only:
    print("restructure_rooms.sh: %d files move" % len(moves))
    for old, new in moves:
        print("  %-42s -> %s" % (old, new))
if dry:
    sys.exit(0)

for old, new in ([] if mentions_only else moves):
    os.makedirs(os.path.dirname(new), exist_ok=True)
    run("git", "mv", old, new)

# ------------------------------------------------------------------ 2. every mention
# A moved file's path without its extension, followed by .h, .cpp, .inc, .* or .{ ("core/scene.h",
# "core/scene.*", "core/scene.{h,cpp}"; not "figures/bench.csv"), in one regular expression
# over all of them so that nothing is rewritten twice. A mention is a path when it is not glued
# to a longer name on the left ("tests/core/x.h" is not "core/x.h"; "../core/x.h" and
# "${CMAKE_SOURCE_DIR}/core/x.h" are).
stems = {}
for old, new in moves:
    o, n = old.split(".")[0], new.split(".")[0]
    stems[o] = n
alternatives = sorted(stems, key=len, reverse=True)
mention = re.compile(r"(?<![\w\-.])(?<!tests/)(" + "|".join(re.escape(a) for a in alternatives) +
                     r")(?=\.(?:(?:h|cpp|inc)(?!\w)|\*|\{))")

def rewrite_mention(m):
    return stems[m.group(1)]

# Test names that moved with their files (ctest prefixes are the test folder).
test_names = [(re.compile(r"\blegacy_gl\.Roofline\b"), "measure.Roofline"),
              (re.compile(r"\bfigures\.Bench"), "measure.Bench")]

# A // comment line that the longer paths pushed past the 100 columns of .clang-format is
# broken at its last space before them, and the words that did not fit are carried into the
# next line of the same comment paragraph (same prefix), which is broken in turn if it then
# is too long; after the paragraph's last line they make a new line.
COLUMNS = 100
def rewrap(text, new):
    before = set(text.split("\n"))
    lines = new.split("\n")
    out = []
    i = 0
    while i < len(lines):
        line = lines[i]
        m = re.match(r"^(\s*//+\s*)\S", line)
        if line in before or len(line) <= COLUMNS or not m:
            out.append(line)
            i += 1
            continue
        prefix = m.group(1)
        while True:
            cut = line.rfind(" ", len(prefix), COLUMNS + 1)
            if len(line) <= COLUMNS or cut <= len(prefix):
                out.append(line)
                i += 1
                break
            out.append(line[:cut])
            carry = line[cut + 1:]
            nxt = lines[i + 1] if i + 1 < len(lines) else None
            if nxt is not None and nxt.startswith(prefix) and nxt[len(prefix):len(prefix) + 1].strip():
                line = prefix + carry + " " + nxt[len(prefix):]
                i += 1
            else:
                line = prefix + carry
                lines.insert(i + 1, line)
                i += 1
    return "\n".join(out)

TEXT = (".h", ".cpp", ".inc", ".c", ".glsl", ".cmake", ".txt", ".md", ".sh", ".py", ".json",
        ".mjs", ".js", ".html", ".css", ".cff", ".yml", ".yaml", ".map", "")
tracked = subprocess.run(["git", "ls-files"], check=True, capture_output=True,
                         text=True).stdout.splitlines()
changed = 0
reformat = {}
for path in tracked:
    if path == "scripts/restructure_rooms.sh" or path == "docs/rooms.md":
        continue  # these name the old places on purpose
    if not path.endswith(TEXT) or not os.path.isfile(path) or os.path.islink(path):
        continue
    if os.path.splitext(path)[1] == "" and not path.startswith((".ci/", "scripts/")):
        continue
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except UnicodeDecodeError:
        continue
    new = mention.sub(rewrite_mention, text)
    for rule, replacement in test_names:
        new = rule.sub(replacement, new)
    if new != text and path.endswith((".h", ".cpp", ".inc", ".glsl")):
        new = rewrap(text, new)
    if new != text:
        with open(path, "w", encoding="utf-8") as f:
            f.write(new)
        changed += 1
        if path.endswith((".h", ".cpp")):
            before = set(text.split("\n"))
            lines = [i + 1 for i, b in enumerate(new.split("\n"))
                     if b.lstrip().startswith("#") and b not in before]
            if lines:
                reformat[path] = lines
print("restructure_rooms.sh: rewrote mentions of moved paths in %d files" % changed)
# The rewritten #include lines only, through clang-format (.clang-format), so that each include
# block is sorted again. Nothing else of a file changes (a comment that grew past 100 columns
# stays as it is: clang-format would break the code line it trails instead).
if reformat and shutil.which("clang-format"):
    for path, lines in sorted(reformat.items()):
        run("clang-format", "-i", *["--lines=%d:%d" % (n, n) for n in lines], path)
    print("restructure_rooms.sh: clang-format on the rewritten #include lines of %d C++ files" % len(reformat))
elif reformat:
    print("restructure_rooms.sh: clang-format not found: rewritten #include blocks are not re-sorted",
          file=sys.stderr)

if mentions_only:
    sys.exit(0)  # the build files and docs were edited by the move itself

# ------------------------------------------------------------------ 3. build files
def edit(path, steps):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for what, pattern, replacement, flags in steps:
        new, n = re.subn(pattern, replacement, text, count=1, flags=flags)
        if n != 1:
            sys.exit("restructure_rooms.sh: %s: did not find %s" % (path, what))
        text = new
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)

ROOMS_CMAKE = r"""# ---------------------------------------------------------------- teach (layer 4)
# The inspection and teaching room: pass dumps (index.html, passes.json) and lessons.
file(GLOB_RECURSE SL_TEACH_SOURCES CONFIGURE_DEPENDS teach/*.cpp)
add_library(sl_teach STATIC ${SL_TEACH_SOURCES})
target_link_libraries(sl_teach PUBLIC sl_registry PRIVATE CLI11::CLI11)

# ---------------------------------------------------------------- measure (layer 4)
# The measuring room: the bench, its claims and report section, the stability suite, the legacy
# timings and their roofline floors, the shadow-volume timings (the tools' libraries).
file(GLOB_RECURSE SL_MEASURE_SOURCES CONFIGURE_DEPENDS measure/*.cpp)
add_library(sl_measure STATIC ${SL_MEASURE_SOURCES})
target_link_libraries(sl_measure PUBLIC sl_registry PRIVATE CLI11::CLI11)

"""
edit("CMakeLists.txt", [
    ("core's source glob 'file(GLOB SL_CORE_SOURCES CONFIGURE_DEPENDS core/*.cpp)'",
     r"file\(GLOB SL_CORE_SOURCES CONFIGURE_DEPENDS core/\*\.cpp\)",
     "file(GLOB_RECURSE SL_CORE_SOURCES CONFIGURE_DEPENDS core/*.cpp)", 0),
    ("the figures block '# ---...--- figures'",
     r"# -+ figures\n", ROOMS_CMAKE + "# ---------------------------------------------------------------- figures\n", 0),
    ("sl_figures' link line",
     r"target_link_libraries\(sl_figures PUBLIC sl_registry",
     "target_link_libraries(sl_figures PUBLIC sl_teach sl_measure sl_registry", 0),
    ("sl_lab's link line",
     r"target_link_libraries\(sl_lab PUBLIC sl_registry",
     "target_link_libraries(sl_lab PUBLIC sl_teach sl_registry", 0),
    ("legacy_bench's link line",
     r"target_link_libraries\(legacy_bench PRIVATE sl_registry",
     "target_link_libraries(legacy_bench PRIVATE sl_measure", 0),
    ("volumes_bench's link line",
     r"target_link_libraries\(volumes_bench PRIVATE sl_registry",
     "target_link_libraries(volumes_bench PRIVATE sl_measure", 0),
    ("the header comment on module dependencies",
     r"# Module dependencies run one way:[^\n]*\n",
     "# Module dependencies run one way, downwards (docs/design.md \"Layout and layering\"):\n"
     "# apps, tools -> figures, lab -> teach, measure -> registry -> legacy_gl, modern, reference\n"
     "# -> imaging -> core.\n", 0),
])

edit("tests/CMakeLists.txt", [
    ("SL_TEST_DIRS' 'figures'", r"(set\(SL_TEST_DIRS [^)]*?)\bfigures\b", r"\1measure figures", re.S),
    ("the conflict-marker test's folder list 'registry figures'",
     r"(no_conflict_markers\s+COMMAND[^\n]*?)registry figures", r"\1registry teach measure figures", 0),
])

# The layering test: teach and measure at 4, everything above registry one higher.
path = "tests/layering/include_layers.cmake"
with open(path, encoding="utf-8") as f:
    text = f.read()
layer_rule = re.compile(r"^set\(kLayer_(\w+) (\d+)\)$", re.M)
layers = {m.group(1): int(m.group(2)) for m in layer_rule.finditer(text)}
if layers.get("registry") != 3 or "measure" in layers:
    sys.exit("restructure_rooms.sh: %s: expected registry at layer 3 and no measure layer" % path)
def relayer(m):
    n = int(m.group(2))
    return "set(kLayer_%s %d)" % (m.group(1), n + 1 if n >= 4 else n)
text = layer_rule.sub(relayer, text)
text, n = re.subn(r"^(set\(kLayer_registry 3\)\n)", r"\1set(kLayer_teach 4)\nset(kLayer_measure 4)\n",
                  text, count=1, flags=re.M)
if n != 1:
    sys.exit("restructure_rooms.sh: %s: no 'set(kLayer_registry 3)' line" % path)
text, n = re.subn(r"^(set\(kModules [^)]*?\bregistry\b)", r"\1 teach measure", text, count=1, flags=re.M)
if n != 1:
    sys.exit("restructure_rooms.sh: %s: no kModules list with registry" % path)
layers = {m.group(1): int(m.group(2)) for m in layer_rule.finditer(text)}
by_layer = {}
for module, n in layers.items():
    by_layer.setdefault(n, []).append(module + "/")
rows = []
for n in sorted(by_layer):
    names = " ".join(by_layer[n])
    note = " (never each other)" if len(by_layer[n]) > 1 else ""
    rows.append("#   %d %s%s" % (n, names, note))
comment = ("# The layers, lowest first (docs/design.md \"Layout and layering\"):\n" + "\n".join(rows) +
           "\n# core/'s parts (core/base, core/gl, core/scene, core/technique) are one layer: the check\n"
           "# keys on the first folder of a path, and files in sub-folders are checked too.\n")
text, n = re.subn(r"^# The layers, lowest first.*?\n(?=# A source file may include)", lambda m: comment,
                  text, count=1, flags=re.M | re.S)
if n != 1:
    sys.exit("restructure_rooms.sh: %s: no '# The layers, lowest first' comment" % path)
with open(path, "w", encoding="utf-8") as f:
    f.write(text)

# ------------------------------------------------------------------ 4. folder maps in the docs
FOLDERS = {
    "core": ("core/        the foundations, in four parts (one layer):\n"
             "  base/      errors and exit statuses, decimal parsing, images and PNG, mask metrics,\n"
             "             provenance, all-or-nothing output files, HTML escaping\n"
             "  gl/        GL contexts (OSMesa, the reference Mesa 7.8.2, EGL), the GL dispatch table\n"
             "             and its tracing layer, GL objects, shader embedding, winding\n"
             "  scene/     scenes, named scenes, meshes and scene files, primitives\n"
             "  technique/ the Technique interface, PassTimer, pass tables and Passes, pass capture,\n"
             "             plans, frame timing\n"),
    "teach": ("teach/       the inspection and teaching room: pass dumps (index.html, passes.json) and\n"
              "             lessons\n"),
    "measure": ("measure/     the measuring room: the bench, its claims and report section, the\n"
                "             stability suite, the legacy timings and their roofline floors, the\n"
                "             shadow-volume timings\n"),
    "figures": ("figures/     one declarative entry per paper figure or table, the report, the plan\n"
                "             command, charts\n"),
}
def entry_span(lines, i):
    j = i + 1
    while j < len(lines) and lines[j].startswith(" ") and lines[j].strip():
        j += 1
    return j
def edit_folder_map(path):
    if not os.path.exists(path):
        return
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    starts = [i for i, l in enumerate(lines) if re.match(r"^core/ +\S", l)]
    if len(starts) != 1:
        print("restructure_rooms.sh: %s: no folder map found; edit it by hand" % path, file=sys.stderr)
        return
    i = starts[0]
    lines[i:entry_span(lines, i)] = FOLDERS["core"].rstrip("\n").split("\n")
    fig = [k for k in range(i, len(lines)) if re.match(r"^figures/ +\S", lines[k])]
    if fig:
        k = fig[0]
        lines[k:entry_span(lines, k)] = (FOLDERS["teach"] + FOLDERS["measure"] +
                                         FOLDERS["figures"]).rstrip("\n").split("\n")
    else:
        print("restructure_rooms.sh: %s: no figures/ entry in the folder map" % path, file=sys.stderr)
    text = "\n".join(lines)
    # The layer table of docs/design.md: rows "| N | `folder/` ... |".
    row = re.compile(r"^\| (\d+) \| (.*) \|$", re.M)
    if path == "docs/design.md" and row.search(text):
        def renumber(m):
            n = int(m.group(1))
            return "| %d | %s |" % (n + 1 if n >= 4 else n, m.group(2))
        text = row.sub(renumber, text)
        text, n = re.subn(r"^(\| 3 \| `registry/` \|\n)",
                          r"\1| 4 | `teach/`, `measure/` (never each other) |\n", text, count=1, flags=re.M)
        if n != 1:
            print("restructure_rooms.sh: docs/design.md: no registry row in the layer table", file=sys.stderr)
        note = ("\ncore/'s four parts are one layer and may include each other. The GL tracing layer\n"
                "(core/gl/gl_trace.h) and pass capture (core/technique/pass_capture.h) stay in core/,\n"
                "below the techniques, because Passes and PassTimer call them while a technique runs;\n"
                "teach/ only shows what they recorded. HTML escaping (core/base/html.h) is shared by\n"
                "teach/, measure/ and figures/. Which file went where and why: [rooms.md](rooms.md).\n")
        text, n = re.subn(r"(points up, and `layering\.include_layers_refuses_upward_include` proves the check can fail\.\n)",
                          lambda m: m.group(1) + note, text, count=1)
        if n != 1:
            print("restructure_rooms.sh: docs/design.md: no place for the note on core's parts", file=sys.stderr)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
edit_folder_map("docs/design.md")
edit_folder_map("README.md")
run("git", "add", "-A", "--", ".")
PYTHON

if [ "$dry_run" = 1 ]; then exit 0; fi
trap - ERR
echo "restructure_rooms.sh: done; review with 'git status' and 'git diff --cached -M --stat', then build"
echo "  (cmake --preset release && cmake --build build -j2), run ctest -R layering, and commit."
