"""Generate the API reference: one page per module of the installed packages.

At ``builder-inited`` the packages named in ``api_packages`` are walked
(:func:`pkgutil.walk_packages`), and each module gets a page
``api/generated/<module>.rst``: the module docstring, a summary table (unless
the docstring holds its own ``autosummary`` of the module's API) and the full
documentation of every public name.  Nothing is kept by hand: a module
added to the package appears in the reference at the next build.

A module's public names are its ``__all__``; a module without ``__all__``
(a package ``__init__``, a command or report module) contributes the public
functions and classes it defines and the public names it assigns at module
level.  Modules whose name has a part starting with ``_`` (``__main__``, the
kernel template) are private and skipped.

Pages are rewritten only when their text changes, so an incremental build
re-reads only what changed.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
from pathlib import Path

from sphinx.errors import PycodeError
from sphinx.pycode import ModuleAnalyzer
from sphinx.util import logging

logger = logging.getLogger(__name__)

OUTPUT = Path("api") / "generated"


def module_names(package_names) -> list:
    """Every public module of the packages, the packages included, sorted."""
    out = []
    for name in package_names:
        package = importlib.import_module(name)
        out.append(name)
        for info in pkgutil.walk_packages(package.__path__, prefix=name + "."):
            if not any(part.startswith("_") for part in info.name.split(".")):
                out.append(info.name)
    return sorted(out)


def _assigned_names(module) -> list:
    """Names bound by module-level assignments in the module's source, in order."""
    try:
        tree = ast.parse(inspect.getsource(module))
    except (OSError, TypeError):
        return []
    names = []
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        for target in targets:
            for leaf in ast.walk(target):
                if isinstance(leaf, ast.Name) and leaf.id not in names:
                    names.append(leaf.id)
    return names


def public_api(module) -> dict:
    """``{"classes", "functions", "data"}``: the module's public names, each list in source order."""
    explicit = getattr(module, "__all__", None)
    if explicit is not None:
        names = list(explicit)
    else:
        defined = [n for n, v in vars(module).items() if (inspect.isclass(v) or inspect.isfunction(v)) and v.__module__ == module.__name__]
        names = defined + [n for n in _assigned_names(module) if n not in defined]
        names = [n for n in names if not n.startswith("_") and hasattr(module, n) and not inspect.ismodule(getattr(module, n))]
    api = {"classes": [], "functions": [], "data": []}
    for name in names:
        obj = getattr(module, name)
        if inspect.isclass(obj):
            api["classes"].append(name)
        elif inspect.isfunction(obj) or (callable(obj) and inspect.isfunction(inspect.unwrap(obj))):
            api["functions"].append(name)
        else:
            api["data"].append(name)
    return api


#: Longest value written out beside a data name without a doc comment.
VALUE_WIDTH = 72


def _documented_attributes(name: str) -> set:
    """Module-level names with a doc comment (``#:``) or a docstring below the assignment."""
    try:
        return {attr for (scope, attr) in ModuleAnalyzer.for_module(name).find_attr_docs() if not scope}
    except PycodeError:
        return set()


def _data_entry(module, name: str, documented: set) -> list:
    """An ``autodata`` entry for a documented name; a bare ``py:data`` entry (short value shown) otherwise.

    ``autodata`` of an undocumented object would show the docstring of its type
    (a SymPy expression shows SymPy's ``Mul``), which says nothing of the name.
    """
    if name in documented:
        return [f".. autodata:: {name}", "   :no-value:", ""]
    text = repr(getattr(module, name))
    entry = [f".. py:data:: {name}"]
    if len(text) <= VALUE_WIDTH and "\n" not in text:
        entry.append(f"   :value: {text}")
    return entry + [""]


def _title(text: str, char: str = "=") -> str:
    return f"{text}\n{char * len(text)}\n"


def module_page(name: str, submodules: list) -> str:
    """reStructuredText of the page of module ``name``."""
    module = importlib.import_module(name)
    api = public_api(module)
    lines = [_title(f"``{name}``"), f".. automodule:: {name}", "   :no-members:", "", f".. currentmodule:: {name}", ""]
    documented = _documented_attributes(name) if api["data"] else set()
    # the summary takes a name's first docstring line: undocumented data would show its type's
    listed = api["classes"] + api["functions"] + [n for n in api["data"] if n in documented]
    if listed and ".. autosummary::" not in (module.__doc__ or ""):  # a docstring that lists its API needs no second table
        lines += [".. rubric:: Summary", "", ".. autosummary::", "   :nosignatures:", ""]
        lines += [f"   {n}" for n in listed]
        lines.append("")
    for n in api["classes"]:
        lines += [f".. autoclass:: {n}", "   :members:", ""]
    for n in api["functions"]:
        lines += [f".. autofunction:: {n}", ""]
    for n in api["data"]:
        lines += _data_entry(module, n, documented)
    if submodules:
        lines += [".. rubric:: Modules", "", ".. autosummary::", "   :nosignatures:", ""]
        lines += [f"   {s[len(name) + 1:]}" for s in submodules]
        lines += ["", ".. toctree::", "   :hidden:", ""]
        lines += [f"   {s}" for s in submodules]
        lines.append("")
    return "\n".join(lines)


def _children(name: str, names: list) -> list:
    depth = name.count(".") + 1
    return [n for n in names if n.startswith(name + ".") and n.count(".") == depth]


def _write_if_changed(path: Path, text: str) -> None:
    if not path.is_file() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def generate(app) -> None:
    names = module_names(app.config.api_packages)
    out = Path(app.srcdir) / OUTPUT
    out.mkdir(parents=True, exist_ok=True)
    wanted = set()
    for name in names:
        path = out / f"{name}.rst"
        _write_if_changed(path, module_page(name, _children(name, names)))
        wanted.add(path.name)
    for stale in out.glob("*.rst"):  # a module removed from the package loses its page
        if stale.name not in wanted:
            stale.unlink()
    top = [n for n in names if n in app.config.api_packages]
    index = ["API reference", "=============", "", app.config.api_intro.strip(), ""]
    for package in top:
        module = importlib.import_module(package)
        summary = (inspect.getdoc(module) or "").split("\n\n")[0].replace("\n", " ")
        index += [f":mod:`{package}` — {summary}", "", ".. autosummary::", "   :nosignatures:", ""]
        index += [f"   {n}" for n in names if n == package or n.startswith(package + ".")]
        index.append("")
    index += [".. toctree::", "   :hidden:", ""] + [f"   generated/{p}" for p in top] + [""]
    _write_if_changed(Path(app.srcdir) / "api" / "index.rst", "\n".join(index))
    logger.info(f"api_pages: {len(names)} module pages in {OUTPUT}")


def setup(app):
    app.add_config_value("api_packages", (), "env")
    app.add_config_value("api_intro", "", "env")
    app.connect("builder-inited", generate)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
