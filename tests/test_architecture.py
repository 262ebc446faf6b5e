"""The layout is the architecture (issue 14; style.md 14): the package's folders are the
pipeline's stages, and every import (at module level or inside a function) goes from a
stage to the same or an earlier one, without cycles between modules.
"""

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "cranefe"

# the pipeline in order (docs/theory.md, "Pipeline"); a module may import only from its
# own stage or earlier ones
STAGES = ("errors", "cases", "outpaths", "elements", "model", "coordinates", "assembly", "statics",
          "system", "condense", "analysis", "outputs", "sweeps", "api", "studies", "cli",
          "__main__")
BASE = {"errors", "cases", "outpaths"}   # leaves anyone may use (outpaths: safe I/O)
MAX_LINES = 80                      # a longer function gives its reason in its docstring
REASON = "Length:"                  # ... in a line starting with this word


def modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        is_pkg = parts[-1] == "__init__"
        yield ".".join(parts[:-1] if is_pkg else parts), is_pkg, path


def imports(name, is_pkg, path):
    """Every cranefe module imported anywhere in the file (absolute names)."""
    tree = ast.parse(path.read_text())
    here = name.split(".") if is_pkg else name.split(".")[:-1]
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            base = here[:len(here) - node.level + 1] if node.level else []
            mod = ".".join(base + ([node.module] if node.module else []))
            for alias in node.names:
                yield mod, f"{mod}.{alias.name}"
        elif isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, alias.name


def stage(module):
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None     # None: the package itself (the API)


def graph():
    mods = {name: (is_pkg, path) for name, is_pkg, path in modules()}
    edges = {}
    for name, (is_pkg, path) in mods.items():
        targets = set()
        for mod, full in imports(name, is_pkg, path):
            if full in mods:
                targets.add(full)
            elif mod in mods:
                targets.add(mod)
        edges[name] = targets - {name}
    return edges


def test_stages_import_only_earlier_stages():
    bad = []
    for src, targets in graph().items():
        s = stage(src)
        if s is None:
            continue
        assert s.split(".")[0] in STAGES, f"{src}: a folder that is not a pipeline stage"
        for dst in targets:
            d = stage(dst)
            if d is None or d in BASE or d == s:
                continue
            if STAGES.index(d) > STAGES.index(s):
                bad.append(f"{src} imports {dst} (stage {d} comes after {s})")
    assert not bad, "\n".join(bad)


def test_elements_see_no_model():
    """Element kernels receive arrays; nothing in elements/ imports a later stage or the
    model (style.md 3, 13)."""
    for src, targets in graph().items():
        if stage(src) == "elements":
            assert all(stage(d) in ("elements", "errors") for d in targets), (src, targets)


def test_no_import_cycles():
    """The package's root is left out: it holds the version and re-exports the API
    lazily (on first attribute access), so modules that read `__version__` make no cycle."""
    edges = {k: v - {"cranefe"} for k, v in graph().items() if k != "cranefe"}
    state, stack, cycles = {}, [], []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in edges.get(n, ()):
            if m not in edges:
                continue
            if state.get(m) == 1:
                cycles.append(" -> ".join(stack[stack.index(m):] + [m]))
            elif m not in state:
                visit(m)
        stack.pop()
        state[n] = 2

    for n in edges:
        if n not in state:
            visit(n)
    assert not cycles, "\n".join(cycles)


def test_functions_are_short_or_say_why():
    long = []
    for name, _, path in modules():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = node.end_lineno - node.lineno + 1
                doc = ast.get_docstring(node) or ""
                if n > MAX_LINES and REASON not in doc:
                    long.append(f"{name}.{node.name}: {n} lines")
    assert not long, "\n".join(long)
