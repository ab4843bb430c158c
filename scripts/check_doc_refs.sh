#!/usr/bin/env bash
# Every citation of docs/theory.md in the code and the docs must name a section or an equation
# that docs/theory.md has, and the code must cite nothing outside this repository for the
# method. Checked in the comments of src/, tests/, perf/, scripts/, inputs/ and CMakeLists.txt,
# and in the text of docs/*.md and README.md:
#   - "docs/theory.md 6.7, 3.4", "theory.md sections 5-12", "docs/theory.md Appendix A":
#     each number must be a heading "## 6.7 ..." ("## 6 ..." for a whole section) of
#     docs/theory.md, each appendix a heading "## Appendix A...";
#   - "section 4.4", "sections 5-12" in code comments: the same (the code's sections are
#     docs/theory.md's);
#   - equation labels "(19)", "(D7)", "(10)" in code comments: the label must be in the
#     equation map of docs/theory.md (Appendix B) and appear in its text;
#   - no "scp-method" anywhere in the code (the method's description lives in docs/theory.md).
# Prints every missing reference as file:line and exits 1 if there is one.
# Usage: scripts/check_doc_refs.sh [REPO_ROOT]
set -euo pipefail
root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
exec /usr/bin/python3 - "$root" <<'PY'
import os
import re
import sys

root = sys.argv[1]
theory_path = os.path.join(root, "docs", "theory.md")
theory = open(theory_path, encoding="utf-8").read()

# sections: "## 6 Title", "### 6.7 Title", "## Appendix A. Title"
sections = set(re.findall(r"^#{2,4} (\d+(?:\.\d+)?)\s", theory, re.M))
appendices = set(re.findall(r"^#{2,4} Appendix ([A-Z])\b", theory, re.M))

# equations: the labels of the equation map (Appendix B), ranges such as (D9)-(D12) expanded
equations = set()
m = re.search(r"^#{2,4} Appendix B\b.*?(?=^#{1,4} |\Z)", theory, re.M | re.S)
if not m:
    print(f"{theory_path}: no Appendix B (equation map)")
    sys.exit(1)
for row in m.group(0).splitlines():
    if not row.startswith("| ("):
        continue
    cell = row.split("|")[1]
    for a, b in re.findall(r"\((D?\d+[ab]?)\)(?:\s*-\s*\((D?\d+)\))?", cell):
        equations.add(a)
        if b:
            pa, pb = re.match(r"(D?)(\d+)", a), re.match(r"(D?)(\d+)", b)
            for k in range(int(pa.group(2)), int(pb.group(2)) + 1):
                equations.add(f"{pa.group(1)}{k}")
body = theory[: m.start()]
for e in sorted(equations):
    if f"({e})" not in body:
        print(f"{theory_path}: equation ({e}) is in the map but not in the text")

CODE_DIRS = ["src", "tests", "perf", "scripts", "inputs"]
CODE_EXT = (".cpp", ".hpp", ".h", ".py", ".sh", ".yaml", ".yml", ".cmake")
SKIP = {os.path.join("scripts", "check_doc_refs.sh")}


def cpp_comments(text):
    """(line, text) of every comment line of a C/C++ file (strings and chars skipped)."""
    out, i, n, line = [], 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append((line, text[i + 2 : j]))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            for k, part in enumerate(text[i + 2 : j - 2].split("\n")):
                out.append((line + k, part))
            line += text[i:j].count("\n")
            i = j
        elif c == '"':
            raw = re.match(r'R"([^(\s]*)\(', text[i - 1 : i + 20]) if i > 0 and text[i - 1] == "R" else None
            if raw:
                end = text.find(")" + raw.group(1) + '"', i)
                end = n if end < 0 else end + len(raw.group(1)) + 2
            else:
                end = i + 1
                while end < n and text[end] not in '"\n':
                    end += 2 if text[end] == "\\" else 1
                end += 1
            line += text[i:end].count("\n")
            i = end
        elif c == "'" and re.match(r"'(\\.|[^\\'\n])'", text[i : i + 4]):
            i += len(re.match(r"'(\\.|[^\\'\n])'", text[i : i + 4]).group(0))
        else:
            i += 1
    return out


def hash_comments(text, python):
    """(line, text) of # comments (and, for Python, docstring lines)."""
    out, in_doc, quote = [], False, None
    for k, l in enumerate(text.split("\n"), 1):
        if python:
            if in_doc:
                out.append((k, l))
                in_doc = quote not in l
                continue
            d = re.match(r'\s*[rbuRBU]?("""|\'\'\')', l)
            if d:
                quote = d.group(1)
                out.append((k, l))
                in_doc = l.count(quote) == 1
                continue
        q = None
        for p, ch in enumerate(l):
            if q:
                q = None if ch == q else q
            elif ch in "\"'":
                q = ch
            elif ch == "#":
                out.append((k, l[p + 1 :]))
                break
    return out


def blocks(lines):
    """Join comment lines that follow each other, so a citation may wrap: (first line, text)."""
    out, start, prev, buf = [], None, None, []
    for ln, t in lines:
        t = re.sub(r"^\s*(///?<?|\*+|#+)?\s?", "", t)
        if prev is not None and ln == prev + 1:
            buf.append(t)
        else:
            if buf:
                out.append((start, " ".join(buf)))
            start, buf = ln, [t]
        prev = ln
    if buf:
        out.append((start, " ".join(buf)))
    return out


REF = r"(?:Appendix\s+[A-Z]|\d+(?:\.\d+)?(?:\s*-\s*\d+(?:\.\d+)?)?)"
REF_LIST = rf"(?:(?:sections?|§)\s*)?{REF}(?:(?:\s*,\s*|\s+and\s+|\s*/\s*)(?:(?:sections?|§)\s*)?{REF})*"
THEORY_CITE = re.compile(rf"theory\.md,?\s+({REF_LIST})")
SECTION_CITE = re.compile(rf"(?<![\w-])(?:[Ss]ections?|§)\s*({REF}(?:(?:\s*,\s*|\s+and\s+){REF})*)")
EQUATION = re.compile(r"(?<![\w)\]])\((D?\d{1,2}[ab]?)\)")

missing = []


def check_refs(where, refs):
    for r in re.findall(REF, refs):
        if r.startswith("Appendix"):
            if r.split()[-1] not in appendices:
                missing.append(f"{where}: {r} is not in docs/theory.md")
            continue
        ends = [x.strip() for x in r.split("-")]
        if len(ends) == 2 and "." not in ends[0] and "." not in ends[1]:
            ends = [str(k) for k in range(int(ends[0]), int(ends[1]) + 1)]
        for s in ends:
            if s not in sections:
                missing.append(f"{where}: section {s} is not in docs/theory.md")


def check_code(path, rel):
    text = open(path, encoding="utf-8", errors="replace").read()
    for k, l in enumerate(text.split("\n"), 1):
        if "scp-method" in l:
            missing.append(f"{rel}:{k}: cites scp-method (cite docs/theory.md)")
    if path.endswith((".cpp", ".hpp", ".h")):
        lines = cpp_comments(text)
    else:
        lines = hash_comments(text, path.endswith(".py"))
    for ln, t in blocks(lines):
        where = f"{rel}:{ln}"
        for refs in THEORY_CITE.findall(t):
            check_refs(where, refs)
        for refs in SECTION_CITE.findall(t):
            check_refs(where, refs)
        for e in EQUATION.findall(t):
            if e not in equations:
                missing.append(f"{where}: equation ({e}) is not in docs/theory.md")


for d in CODE_DIRS:
    for dp, dn, fn in os.walk(os.path.join(root, d)):
        dn[:] = sorted(x for x in dn if not x.startswith(".") and x != "results")
        for f in sorted(fn):
            p = os.path.join(dp, f)
            rel = os.path.relpath(p, root)
            if rel in SKIP or not (f.endswith(CODE_EXT) or f == "CMakeLists.txt"):
                continue
            check_code(p, rel)
if os.path.exists(os.path.join(root, "CMakeLists.txt")):
    check_code(os.path.join(root, "CMakeLists.txt"), "CMakeLists.txt")

docs = [os.path.join("docs", f) for f in sorted(os.listdir(os.path.join(root, "docs"))) if f.endswith(".md")]
for rel in docs + ["README.md", os.path.join("perf", "README.md")]:
    p = os.path.join(root, rel)
    if not os.path.exists(p):
        continue
    for k, l in enumerate(open(p, encoding="utf-8").read().split("\n"), 1):
        for refs in THEORY_CITE.findall(l):
            check_refs(f"{rel}:{k}", refs)

for x in missing:
    print(x)
if missing:
    print(f"{len(missing)} reference(s) to docs/theory.md missing or pointing outside the repository")
    sys.exit(1)
print(f"docs/theory.md references: all found ({len(sections)} sections, {len(equations)} equations)")
PY
