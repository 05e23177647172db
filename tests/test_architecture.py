"""docs/architecture.rst states the import graph as it is: checked here, so it cannot drift.

The project's imports are read with :mod:`ast` (nothing is imported). Each module
belongs to one *unit*: ``flightid``, ``aircraft.configs``, ``aircraft.wake``,
``aircraft.inflow``, ``aircraft.helicopter``, ``aircraft.identification``, the
``aircraft`` package face, its private leaf ``aircraft._validation``,
``aircraft.provenance``, ``aircraft.blade`` (real blades, a leaf), ``controllers`` and ``studies``. An import inside a
function (indented) is *lazy*: it runs only when the function does. A name taken
from a package face (``from aircraft.inflow import X``) counts as an import of the
module that defines ``X``.

Checked against the page:

* the unit-level edges, each marked ``(lazy)`` when every import behind it is lazy;
and, independent of the page: no import circle among modules (lazy imports
included) nor among units, no arrow up the layers, ``controllers`` imports no
``aircraft`` module at all, every package face is small (about 30 names), every
library module has its ``__all__``, and the tests and benchmarks import nothing
from ``studies`` but the command line's registry.
"""
import ast
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "architecture.rst"
TOPS = ("flightid", "aircraft", "controllers", "studies")
UNITS = ("flightid", "aircraft._validation", "aircraft.provenance", "aircraft.blade", "aircraft.configs", "aircraft.wake",
         "aircraft.inflow", "aircraft.helicopter", "aircraft.identification", "aircraft", "controllers",
         "studies")


def _modules():
    mods = {}
    for top in TOPS:
        for path in sorted((ROOT / top).rglob("*.py")):
            parts = list(path.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            mods[".".join(parts)] = path
    return mods


def unit_of(module):
    return next(u for u in UNITS if module == u or module.startswith(u + "."))


def _imports(module, path):
    """``[(dotted target, lazy)]`` of one module, relative imports resolved."""
    is_package = path.name == "__init__.py"
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        lazy = node.col_offset > 0 if isinstance(node, (ast.Import, ast.ImportFrom)) else None
        if isinstance(node, ast.Import):
            found += [(alias.name, lazy) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = module.split(".") if is_package else module.split(".")[:-1]
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            found += [(f"{target}.{alias.name}", lazy) for alias in node.names] + [(target, lazy)]
    return found


def module_graph():
    """``{module: {(imported module, lazy)}}`` over the project's modules."""
    mods = _modules()
    faces = {}
    for name, path in mods.items():
        if path.name == "__init__.py":
            for node in ast.parse(path.read_text()).body:
                if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
                    for alias in node.names:
                        faces.setdefault(name, {})[alias.asname or alias.name] = f"{name}.{node.module}"
    graph = {}
    for name, path in mods.items():
        for target, lazy in _imports(name, path):
            parts = target.split(".")
            while parts and ".".join(parts) not in mods:
                parts.pop()
            if not parts:
                continue                                   # not the project's
            resolved = ".".join(parts)
            if mods[resolved].name == "__init__.py" and target != resolved:
                resolved = faces.get(resolved, {}).get(target[len(resolved) + 1:].split(".")[0], resolved)
            if resolved != name:
                graph.setdefault(name, set()).add((resolved, lazy))
    return graph, mods


def unit_edges(graph):
    """``{(unit, unit): lazy}``: lazy when every import behind the edge is lazy."""
    edges = {}
    for source, targets in graph.items():
        for target, lazy in targets:
            a, b = unit_of(source), unit_of(target)
            if a != b:
                edges[(a, b)] = edges.get((a, b), True) and lazy
    return edges


def circles(adjacency):
    """Strongly connected components with more than one node (Tarjan), each sorted."""
    sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in adjacency.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(adjacency):
        if v not in index:
            visit(v)
    return sorted(found)


def module_circles(graph, mods, lazy=True):
    # package faces are left out: importing a name from a face is an import of the
    # module that defines it (resolved above); what remains are the modules' own circles
    adjacency = {m: {t for t, lz in ts if (lazy or not lz) and mods[t].name != "__init__.py"}
                 for m, ts in graph.items()}
    return circles(adjacency)


def _page_block(name):
    text = PAGE.read_text()
    match = re.search(rf"\.\. {name}-start\n(.*?)\.\. {name}-end", text, re.S)
    assert match, f"docs/architecture.rst has no '.. {name}-start' ... '.. {name}-end' block"
    return [line.strip() for line in match.group(1).splitlines()
            if line.strip() and not line.strip().startswith(("..", "::"))]


def _edge_lines(edges):
    return sorted(f"{a} -> {b}" + (" (lazy)" if lazy else "") for (a, b), lazy in edges.items())


@pytest.mark.slow
def test_page_states_the_unit_import_graph():
    graph, _ = module_graph()
    expected = _edge_lines(unit_edges(graph))
    assert sorted(_page_block("import-graph")) == expected, (
        "docs/architecture.rst's import graph differs from the code; the block should read:\n"
        + "\n".join("   " + line for line in expected))


@pytest.mark.slow
def test_no_module_circle_even_through_lazy_imports():
    graph, mods = module_graph()
    found = [" <-> ".join(c) for c in module_circles(graph, mods)]
    assert found == [], "import circles among modules:\n" + "\n".join(found)


#: The layers, lowest first: a unit imports only units of a lower layer (or its own).
LAYERS = {"flightid": 0, "aircraft._validation": 1, "aircraft.provenance": 1, "aircraft.blade": 1,
          "aircraft.configs": 2,
          "aircraft.inflow": 3, "controllers": 3, "aircraft.wake": 4, "aircraft.helicopter": 4,
          "aircraft.identification": 5, "aircraft": 6, "studies": 7}


@pytest.mark.slow
def test_no_arrow_runs_up_the_layers():
    graph, _ = module_graph()
    assert set(LAYERS) == set(UNITS)
    upward = sorted(f"{a} -> {b}" for (a, b) in unit_edges(graph) if LAYERS[b] >= LAYERS[a])
    assert upward == [], "imports against the layers (lazy ones included):\n" + "\n".join(upward)


@pytest.mark.slow
def test_controllers_need_no_aircraft_at_all():
    graph, _ = module_graph()
    found = sorted(b for (a, b) in unit_edges(graph) if a == "controllers" and b.startswith("aircraft"))
    assert found == []


@pytest.mark.parametrize("package", ["flightid", "aircraft", "aircraft.wake", "aircraft.inflow",
                                     "aircraft.helicopter", "aircraft.identification",
                                     "aircraft.identification.structures", "aircraft.identification.off_rotor",
                                     "controllers", "controllers.hq"])
def test_package_faces_are_small(package):
    # a face is what `from package import *` and the docs show: a user's first names, not all of them
    path = ROOT / package.replace(".", "/") / "__init__.py"
    names = None
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "__all__" for t in node.targets):
            names = ast.literal_eval(node.value)
    assert names is not None, f"{package} has no __all__"
    assert len(names) <= 32, f"{package} exports {len(names)} names"


def test_every_module_says_what_it_exports():
    missing = []
    for name, path in _modules().items():
        if name.startswith("studies") and not name.startswith("studies.analysis.") or ".tests." in name:
            continue                       # study scripts and test modules are programs, not libraries
        if name.rsplit(".", 1)[-1].startswith("_"):
            continue                       # private helpers of their package
        tree = ast.parse(path.read_text())
        if path.name != "__init__.py" and not any(
                (isinstance(n, ast.Assign) and any(getattr(t, "id", None) == "__all__" for t in n.targets))
                or (isinstance(n, ast.AnnAssign) and getattr(n.target, "id", None) == "__all__")
                for n in tree.body):
            missing.append(name)
    assert missing == [], f"modules without __all__: {missing}"


def test_tests_and_benchmarks_never_import_studies():
    # the research analyses (studies.analysis) carry their own tests beside them; only the command
    # line's registry of study names (studies.cli) is read by the docs tests
    allowed = ("studies.cli",)
    found = []
    for folder in ("tests", "benchmarks"):
        for path in (ROOT / folder).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                         [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else [])
                found += [f"{path.relative_to(ROOT)}: {n}" for n in names
                          if (n == "studies" or n.startswith("studies.")) and not n.startswith(allowed)]
    assert found == []


@pytest.mark.slow
def test_no_circle_at_import_time():
    graph, mods = module_graph()
    assert module_circles(graph, mods, lazy=False) == []
    eager = {}
    for (a, b), lazy in unit_edges(graph).items():
        if not lazy:
            eager.setdefault(a, set()).add(b)
    assert circles(eager) == []


@pytest.mark.slow
def test_the_checker_finds_circles_and_units():
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert circles({"a": {"b"}, "b": set()}) == []
    _, mods = module_graph()
    assert {unit_of(m) for m in mods} == set(UNITS)
