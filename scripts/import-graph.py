#!/usr/bin/env python3
"""The file-level import graph of src/, and its cycles.

An edge A -> B means that file A names an item defined in file B (through `use`, a path in
code, or a child module's name), after following `pub use` re-exports to the file that
defines the item. Declaring a child module (`mod x;`) or re-exporting one of its items
(`pub use x::Item;`) is not an edge. Doc comments and
comments are ignored.

    scripts/import-graph.py            # prints every cycle (strongly connected component)
    scripts/import-graph.py --check    # also exits 1 if there is one (tests/layering.rs)
    scripts/import-graph.py --edges    # prints every edge
"""
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src")


def module_of(path):
    rel = os.path.relpath(path, ROOT)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib", "main"):
        rel = rel[:-1]
    return tuple(rel)


def strip_comments(text):
    # unit-test modules may use anything (and their `super` is the file's own module)
    t = re.search(r"^#\[cfg\(test\)\]\s*\n\s*mod \w+ \{", text, re.M)
    if t:
        text = text[: t.start()]
    out = []
    for line in text.split("\n"):
        s = line.lstrip()
        if s.startswith("//"):
            continue
        # drop trailing line comments (not inside strings: good enough for this code base)
        i = line.find("//")
        if i >= 0 and line[:i].count('"') % 2 == 0:
            line = line[:i]
        out.append(line)
    text = "\n".join(out)
    # string literals name no items
    return re.sub(r'"(?:[^"\\]|\\.)*"', '""', text)


files = {}
for d, _, fs in os.walk(ROOT):
    for f in fs:
        if f.endswith(".rs") and f != "main.rs":
            p = os.path.join(d, f)
            files[module_of(p)] = (os.path.relpath(p, os.path.join(ROOT, "..")), strip_comments(open(p).read()))

ITEM = re.compile(
    r"^\s*(?:pub(?:\([^)]*\))?\s+)?(?:unsafe\s+|const\s+|async\s+)*(?:fn|struct|enum|const|static|type|trait|union)\s+(\w+)",
    re.M,
)
MACRO = re.compile(r"macro_rules!\s*(\w+)")
defined = {m: set(ITEM.findall(t)) | set(MACRO.findall(t)) for m, (_, t) in files.items()}
children = {m: set(re.findall(r"^\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+(\w+)\s*;", t, re.M)) for m, (_, t) in files.items()}


def use_trees(text):
    """Every path of every `use` declaration, with `pub use` marked."""
    out = []
    for m in re.finditer(r"^\s*(pub(?:\([^)]*\))?\s+)?use\s+([^;]+);", text, re.M):
        pub = bool(m.group(1))

        def expand(prefix, tree):
            tree = tree.strip()
            i = tree.find("{")
            if i < 0:
                for part in tree.split(","):
                    part = part.strip()
                    if part:
                        name = part.split(" as ")
                        out.append((pub, prefix + name[0].strip().split("::"), name[-1].strip().split("::")[-1]))
                return
            head = tree[:i].rstrip(":").strip()
            body = tree[i + 1 : tree.rfind("}")]
            depth, cur, parts = 0, "", []
            for ch in body:
                if ch == "{":
                    depth += 1
                elif ch == "}":
                    depth -= 1
                if ch == "," and depth == 0:
                    parts.append(cur)
                    cur = ""
                else:
                    cur += ch
            parts.append(cur)
            pre = prefix + ([p for p in head.split("::") if p] if head else [])
            for p in parts:
                if p.strip():
                    expand(pre, p)

        expand([], m.group(2))
    return out


def absolute(mod, path):
    """The absolute module path of `path` written in module `mod`, or None (std, deps)."""
    if not path:
        return None
    if path[0] == "crate":
        return list(path[1:])
    if path[0] == "self":
        return list(mod) + list(path[1:])
    if path[0] == "super":
        base = list(mod)
        i = 0
        while i < len(path) and path[i] == "super":
            base = base[:-1]
            i += 1
        return base + list(path[i:])
    if path[0] in children.get(mod, ()):
        return list(mod) + list(path)
    return None


reexports = {}  # (module, name) -> absolute path
for m, (_, t) in files.items():
    for pub, path, alias in use_trees(t):
        if pub:
            a = absolute(m, path)
            if a is not None:
                reexports[(m, alias if path[-1] != "self" else path[-2])] = a


def resolve(path, depth=0):
    """The file (module) defining the item at absolute `path`."""
    if depth > 20:
        return None
    path = [p for p in path if p != "self"]
    # longest prefix that is a module
    for k in range(len(path), 0, -1):
        mod = tuple(path[:k])
        if mod in files:
            rest = path[k:]
            if not rest or rest[0] == "*":
                return mod
            name = rest[0]
            if name in defined[mod]:
                return mod
            if (mod, name) in reexports:
                return resolve(reexports[(mod, name)] + rest[1:], depth + 1)
            return mod
    return None


edges = {}
for m, (_, t) in files.items():
    targets = set()
    for pub, path, _ in use_trees(t):
        if pub:
            continue  # a re-export is an alias, resolved through above, not a use
        a = absolute(m, path)
        if a is not None:
            r = resolve(a)
            if r is not None:
                targets.add(r)
    body = re.sub(r"^\s*(pub(?:\([^)]*\))?\s+)?use\s+[^;]+;", "", t, flags=re.M)
    for p in re.findall(r"\b((?:crate|super|self)(?:::\w+)+)", body):
        a = absolute(m, p.split("::"))
        if a is not None:
            r = resolve(a)
            if r is not None:
                targets.add(r)
    for c in children.get(m, ()):
        if re.search(r"(?<![\w:])" + c + r"::", body):
            targets.add(m + (c,))
    targets.discard(m)
    edges[m] = sorted(targets)

# Tarjan's strongly connected components
index, low, stack, on, sccs, counter = {}, {}, [], set(), [], [0]
sys.setrecursionlimit(10000)


def visit(v):
    index[v] = low[v] = counter[0]
    counter[0] += 1
    stack.append(v)
    on.add(v)
    for w in edges.get(v, []):
        if w not in index:
            visit(w)
            low[v] = min(low[v], low[w])
        elif w in on:
            low[v] = min(low[v], index[w])
    if low[v] == index[v]:
        comp = []
        while True:
            w = stack.pop()
            on.discard(w)
            comp.append(w)
            if w == v:
                break
        if len(comp) > 1:
            sccs.append(sorted(comp))


for v in sorted(files):
    if v not in index:
        visit(v)

name = lambda m: files[m][0]
if "--edges" in sys.argv:
    for m in sorted(edges):
        for t in edges[m]:
            print(f"{name(m)} -> {name(t)}")
for c in sccs:
    print("cycle: " + " <-> ".join(name(m) for m in c))
    for m in c:
        for t in edges[m]:
            if t in c:
                print(f"    {name(m)} -> {name(t)}")
if not sccs:
    print(f"no cycles among {len(files)} files")
sys.exit(1 if sccs and "--check" in sys.argv else 0)
