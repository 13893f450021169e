"""Architecture rules of the package, checked on the source (CONTRIBUTING.md).

* Names starting with ``_`` are not used outside their module: no
  ``from .x import _y`` and no ``x._y`` on an imported module, anywhere in
  ``strapdown.analysis`` and ``strapdown.derivations``.
* Library messages name the Python argument, never a command-line flag: no
  ``--option`` in the text of an exception raised outside the CLI and the
  reports.
* Radians inside the library: no parameter or attribute named ``*_deg`` or
  ``*_deg_per_h``, or documented in degrees, in ``analysis/{core,coning,multistage,gyrocompass,alignment}``
  and ``derivations`` (the printed data of ``published.py`` keep the paper's
  units, with names that say so).
* No import cycle: the graph of imports between the modules of the package
  (imports inside functions included) has no cycle.
* The tool apart from its validation: the reproductions of the papers
  (``analysis/coning/papers``) use the library, and only they, the CLI and the
  reports import them.

The checks walk the syntax trees of the source files, so they see every module,
imported or not.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = {"analysis": "strapdown.analysis", "derivations": "strapdown.derivations"}

#: Modules that may use a private module of their own subpackage, with the reason.
#: ``coning._kernel_template`` and ``vibration._kernel`` are code templates, not APIs: ``kernels`` and
#: ``vibration.monte_carlo`` copy their functions into generated modules (their docstrings say
#: so, and their ``__all__`` is empty).
PRIVATE_MODULE_USERS = {("analysis/coning/kernels.py", "_kernel_template"), ("analysis/vibration/monte_carlo.py", "_kernel")}

#: The one module whose job is the conversion to and from degrees.
UNIT_CONVERSIONS = frozenset({"analysis/core/units.py"})


def _sources(*folders):
    for folder in folders:
        for path in sorted((ROOT / folder).rglob("*.py")):
            rel = path.relative_to(ROOT).as_posix()
            yield rel, ast.parse(path.read_text(encoding="utf-8"), filename=rel)


def _module_name(rel: str) -> str:
    parts = rel[: -len(".py")].split("/")
    parts[0] = PACKAGES[parts[0]]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _target(rel: str, node: ast.ImportFrom) -> str:
    """Absolute name of the module an ``ImportFrom`` reads from."""
    if not node.level:
        return node.module or ""
    base = _module_name(rel).split(".")
    if not rel.endswith("__init__.py"):
        base = base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def private_uses(rel: str, tree: ast.AST) -> list:
    """``from .x import _y`` and ``x._y`` (x an imported module or name) in one source file."""
    found, imported = [], set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            for alias in node.names:
                if _private(alias.name) and (rel, alias.name) not in PRIVATE_MODULE_USERS:
                    found.append(f"{rel}:{node.lineno}: from {'.' * node.level}{node.module or ''} import {alias.name}")
                imported.add(alias.asname or alias.name)
        elif isinstance(node, ast.Import):
            imported.update(alias.asname or alias.name.split(".")[0] for alias in node.names)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _private(node.attr) and isinstance(node.value, ast.Name) and node.value.id in imported:
            found.append(f"{rel}:{node.lineno}: {node.value.id}.{node.attr}")
    return found


def test_no_private_name_is_used_across_modules():
    found = [f for rel, tree in _sources(*PACKAGES) for f in private_uses(rel, tree)]
    assert found == [], "\n".join(found)


@pytest.mark.parametrize("user, module", sorted(PRIVATE_MODULE_USERS))
def test_the_private_module_exception_is_a_documented_template(user, module):
    source = (ROOT / Path(user).parent / f"{module}.py").read_text(encoding="utf-8")
    tree = ast.parse(source)
    assert ast.get_docstring(tree).startswith("Template of the")
    exported = next(n.value for n in tree.body if isinstance(n, ast.AnnAssign) and getattr(n.target, "id", None) == "__all__")
    assert isinstance(exported, ast.List) and exported.elts == []


def test_the_private_check_can_fail():
    tree = ast.parse("from .simulator import _compare\nfrom . import kernels\nkernels._lock\n")
    assert len(private_uses("analysis/coning/x.py", tree)) == 2


# --------------------------------------------------------------------------- messages
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")


def _raised_text(node: ast.Raise) -> str:
    """The string constants (f-string parts included) in the arguments of a raised call."""
    if not isinstance(node.exc, ast.Call):
        return ""
    parts = []
    for arg in node.exc.args:
        for sub in ast.walk(arg):
            if isinstance(sub, ast.Constant) and isinstance(sub.value, str):
                parts.append(sub.value)
    return "".join(parts)


def flag_messages(rel: str, tree: ast.AST) -> list:
    """Raised messages that name a command-line option."""
    return [f"{rel}:{n.lineno}: {FLAG.search(_raised_text(n)).group()}" for n in ast.walk(tree) if isinstance(n, ast.Raise) and FLAG.search(_raised_text(n))]


def _library(rel: str) -> bool:
    return not rel.startswith(("analysis/cli/", "analysis/report/"))


def test_library_messages_name_arguments_not_cli_flags():
    found = [f for rel, tree in _sources(*PACKAGES) if _library(rel) for f in flag_messages(rel, tree)]
    assert found == [], "\n".join(found)


def test_the_flag_check_can_fail():
    tree = ast.parse('def f(x):\n    raise ValueError(f"Expected `x` > 0, got {x} (pass --allow-negative)")\n')
    assert flag_messages("analysis/coning/x.py", tree) == ["analysis/coning/x.py:2: --allow-negative"]


# --------------------------------------------------------------------------- units
UNIT_FOLDERS = ("analysis/core", "analysis/coning", "analysis/multistage", "analysis/gyrocompass", "analysis/alignment", "derivations")
DEGREE_NAME = re.compile(r"(^|_)deg(_per_h)?$")
#: A numpydoc entry "name : type" and its indented description.
DOC_ENTRY = re.compile(r"^(\s*)([A-Za-z_][\w, ]*) : [^\n]*\n((?:\1\s+[^\n]*\n?)*)", re.M)
DEGREE_UNIT = re.compile(r"\[deg(/h)?\]|\bin degrees\b")


def _names(tree: ast.AST):
    """(line, name) of every function parameter and class-level attribute."""
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            for arg in a.posonlyargs + a.args + a.kwonlyargs + [x for x in (a.vararg, a.kwarg) if x]:
                yield arg.lineno, arg.arg
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                    yield item.lineno, item.target.id


def degree_names(rel: str, tree: ast.AST) -> list:
    """Parameters and attributes named in degrees, or documented in degrees, in one source file."""
    found = [f"{rel}:{line}: {name}" for line, name in _names(tree) if DEGREE_NAME.search(name)]
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            doc = ast.get_docstring(node) or ""
            for m in DOC_ENTRY.finditer(doc):
                if DEGREE_UNIT.search(m.group(3)):
                    found.append(f"{rel}:{node.lineno}: {node.name}: {m.group(2).strip()} documented in degrees")
    return found


def _unit_checked(rel: str) -> bool:
    return rel not in UNIT_CONVERSIONS and not rel.endswith("/published.py")


def test_library_parameters_are_in_radians():
    found = [f for rel, tree in _sources(*UNIT_FOLDERS) if _unit_checked(rel) for f in degree_names(rel, tree)]
    assert found == [], "\n".join(found)


def test_the_unit_check_can_fail():
    tree = ast.parse('def f(nutation_deg, rate):\n    """F.\n\n    Parameters\n    ----------\n    rate : float\n        Drift [deg/h].\n    """\n')
    assert degree_names("analysis/coning/x.py", tree) == ["analysis/coning/x.py:1: nutation_deg", "analysis/coning/x.py:1: f: rate documented in degrees"]


def published_degree_fields(rel: str, tree: ast.AST) -> list:
    """Fields of a published data class documented in degrees whose name does not say so.

    A class whose values change unit with their row says it with a ``unit`` field or property.
    """
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            members = {n.target.id for n in node.body if isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name)}
            members |= {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
            for m in DOC_ENTRY.finditer(ast.get_docstring(node) or ""):
                name = m.group(2).strip()
                if re.search(r"\[deg(/h)?\b", m.group(3)) and not DEGREE_NAME.search(name) and "unit" not in members:
                    found.append(f"{rel}: {node.name}.{name}")
    return found


def test_published_data_in_degrees_say_so_in_their_names():
    """Printed values kept in degrees are named ``*_deg`` / ``*_deg_per_h`` (or carry their ``unit``)."""
    found = [f for rel, tree in _sources("derivations") if rel.endswith("/published.py") for f in published_degree_fields(rel, tree)]
    assert found == [], "\n".join(found)


def test_the_published_unit_check_can_fail():
    tree = ast.parse('class Row:\n    """R.\n\n    Attributes\n    ----------\n    u_star : float\n        Drift [deg/h].\n    """\n\n    u_star: float\n')
    assert published_degree_fields("derivations/coning/published.py", tree) == ["derivations/coning/published.py: Row.u_star"]


@pytest.mark.parametrize("folder", sorted(PACKAGES))
def test_the_checks_see_the_package(folder):
    assert sum(1 for _ in _sources(folder)) > 20


# --------------------------------------------------------------------------- import graph
def _modules(*folders) -> dict:
    return {_module_name(rel): (rel, tree) for rel, tree in _sources(*folders)}


def import_graph(modules: dict) -> dict:
    """Module → the modules of ``modules`` it imports (at the top or inside a function)."""
    graph = {name: set() for name in modules}
    for name, (rel, tree) in modules.items():
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = _target(rel, node)
                found = [f"{target}.{a.name}" for a in node.names if f"{target}.{a.name}" in modules]
                graph[name].update(found or ([target] if target in modules else []))
            elif isinstance(node, ast.Import):
                graph[name].update(a.name for a in node.names if a.name in modules)
        graph[name].discard(name)
    return graph


def import_cycles(graph: dict) -> list:
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
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
                cycles.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return cycles


def test_no_import_cycle():
    cycles = import_cycles(import_graph(_modules(*PACKAGES)))
    assert cycles == [], "\n".join(" <-> ".join(c) for c in cycles)


def test_the_cycle_check_can_fail():
    modules = {
        "strapdown.analysis.coning.simulator": ("analysis/coning/simulator.py", ast.parse("from .batch import compiled_series\n")),
        "strapdown.analysis.coning.batch": ("analysis/coning/batch.py", ast.parse("def f():\n    from .simulator import simulate\n")),
        "strapdown.analysis.coning.kernels": ("analysis/coning/kernels.py", ast.parse("from . import streaming\n")),
    }
    assert import_cycles(import_graph(modules)) == [["strapdown.analysis.coning.batch", "strapdown.analysis.coning.simulator"]]


PAPERS = "strapdown.analysis.coning.papers"
#: Who may import the reproductions of the papers: themselves, the command line and the reports.
PAPER_USERS = ("analysis/coning/papers/", "analysis/cli/", "analysis/report/")


def paper_imports(modules: dict) -> list:
    """Modules outside :data:`PAPER_USERS` that import from ``strapdown.analysis.coning.papers``."""
    graph = import_graph(modules)
    return sorted(
        f"{modules[name][0]} imports {target}"
        for name, targets in graph.items()
        if not modules[name][0].startswith(PAPER_USERS)
        for target in targets
        if target == PAPERS or target.startswith(PAPERS + ".")
    )


def test_the_library_does_not_import_the_paper_reproductions():
    modules = _modules(*PACKAGES)
    assert any(name.startswith(PAPERS + ".") for name in modules)
    found = paper_imports(modules)
    assert found == [], "\n".join(found)


def test_the_paper_check_can_fail():
    modules = {
        "strapdown.analysis.coning.simulator": ("analysis/coning/simulator.py", ast.parse("from .papers.budennyi_table3 import simulated_drift\n")),
        "strapdown.analysis.coning.papers.budennyi_table3": ("analysis/coning/papers/budennyi_table3.py", ast.parse("from ..simulator import simulate\n")),
    }
    assert paper_imports(modules) == ["analysis/coning/simulator.py imports strapdown.analysis.coning.papers.budennyi_table3"]
