#!/usr/bin/env python3
"""scripts/check_identity_lookups.py [ROOT] | --self-test — no code path finds a technique's
family or a pass's role by reading a display string.

A technique's family (legacy, modern, reference) is Technique::family, set by the registry from
the module that declares it (registry/registry.cpp); a pass's role (light, camera, projective,
copy, lighting, ...) is PassSpec::role, declared in its pass table and carried by PassTime::role.
Neither is parsed from a name. This check fails on a source line that does it anyway:
  - a technique name tested for a family prefix: `name.rfind("legacy.", 0)`, `find("reference.")`,
    `starts_with("modern.")`, `compare(0, 7, "legacy.")`;
  - a pass's display name cut at its colon or read word by word to find what the pass does:
    `name.substr(0, name.find(':'))`, `std::istringstream words(pass.name...)`;
  - a pass found again, or numbered, by its display name: `passes[i].name == ...`,
    `name.compare(0, passPrefix.size(), passPrefix)`, `passNumberOf(name)` (the pass-table id and part
    are its identity: core/technique/pass_run_key.h).
Scanned: the C++ sources of every room (tests/ are exempt: they may build names to ask the
registry). Prints one line per finding (file:line: what) and exits 1 when there is any (the CTest
layering.no_identity_lookups); --self-test plants each kind in a made-up tree and expects each to
be named (the CTest layering.no_identity_lookups_selftest).
"""
import os
import re
import sys
import tempfile

ROOMS = ["core", "imaging", "legacy_gl", "modern", "reference", "registry", "teach", "measure",
         "figures", "lab", "apps", "tools", "python", "interpose"]

FAMILY = re.compile(r"\b(?:r?find|starts_with|compare)\s*\([^;]*\"(?:legacy|modern|reference)\.\"")
ROLE = re.compile(r"\bname\s*\.\s*substr\s*\(\s*0\s*,\s*[\w.>-]*name\s*\.\s*find\s*\(\s*':'"
                  r"|\bistringstream\s+\w+\s*\(\s*[\w.>-]*\bname\b")
PASS = re.compile(r"\bpasses\s*\[[^\]]*\]\s*\.\s*name\s*==|\bname\s*\.\s*compare\s*\(\s*0\s*,"
                  r"\s*[\w.>-]*[pP]refix|\b(?:passNumberOf|afterPassNumber)\s*\(")
CHECKS = ((FAMILY, "a technique's family read from its name (use Technique::family)"),
          (ROLE, "a pass's role read from its display name (use PassSpec::role / PassTime::role)"),
          (PASS, "a pass found or numbered by its display name (use PassTime::id and part: "
                 "core/technique/pass_run_key.h)"))


def findings(root):
    out = []
    for room in ROOMS:
        top = os.path.join(root, room)
        for base, _, files in os.walk(top):
            for f in sorted(files):
                if not f.endswith((".cpp", ".h", ".inc")):
                    continue
                path = os.path.join(base, f)
                with open(path, encoding="utf-8", errors="replace") as text:
                    for number, line in enumerate(text, 1):
                        code = line.split("//", 1)[0]
                        for regex, what in CHECKS:
                            if regex.search(code):
                                out.append(f"{os.path.relpath(path, root)}:{number}: {what}: "
                                           f"{line.strip()}")
    return out


def self_test():
    planted = {
        'if (t.name.rfind("reference.", 0) == 0) return "";': "family",
        'return name.starts_with("legacy.");': "family",
        'bool m = name.compare(0, 7, "modern.") == 0;': "family",
        'std::string role = name.substr(0, name.find(\':\'));': "role",
        'std::istringstream words(pass.name);': "role",
        'if (f.passes[i].name == first.passes[i].name) times.push_back(ms);': "pass found",
        'met = name.compare(0, prefix.size(), prefix) == 0;': "pass found",
        'const int n = passNumberOf(p.name);': "pass found",
    }
    clean = ('// a comment may say rfind("legacy.", 0)\n'
             'const bool legacy = t.family == TechniqueFamily::kLegacy;\n'
             'const std::string n = "legacy." + rest;\n')
    failures = 0
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "measure"))
        with open(os.path.join(root, "measure", "clean.cpp"), "w") as f:
            f.write(clean)
        if findings(root):
            print("self-test: clean file flagged:", *findings(root), sep="\n  ")
            failures += 1
        for line, kind in planted.items():
            path = os.path.join(root, "measure", "planted.cpp")
            with open(path, "w") as f:
                f.write(clean + line + "\n")
            found = findings(root)
            if len(found) != 1 or kind not in found[0]:
                print(f"self-test: planted {kind} lookup '{line}' gave {found}")
                failures += 1
            os.remove(path)
    print("self-test:", "ok" if failures == 0 else f"{failures} failure(s)")
    return 1 if failures else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    found = findings(root)
    for line in found:
        print(line)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
