"""Every public callable documents each of its parameters in numpydoc form.

Like python-control's docstring test: for every public function and class of
the installed package (the module's ``__all__``, or its public definitions
when it has none), and every public method defined on such a class, each
parameter of the signature must appear under *Parameters* (or *Other
Parameters*; for classes also *Attributes*).  Command modules of
``strapdown.analysis.cli`` and report modules count as public too.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import warnings

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

import strapdown.analysis
import strapdown.derivations


def _module_names():
    for package in (strapdown.analysis, strapdown.derivations):
        yield package.__name__
        for info in pkgutil.walk_packages(package.__path__, prefix=package.__name__ + "."):
            if not info.name.endswith("__main__"):
                yield info.name


def _public_objects(module):
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n in vars(module) if not n.startswith("_")]
    for name in names:
        obj = getattr(module, name)
        if (inspect.isfunction(obj) or inspect.isclass(obj)) and getattr(obj, "__module__", None) == module.__name__:
            yield name, obj
            if inspect.isclass(obj):
                for attr, member in vars(obj).items():
                    if attr.startswith("_"):
                        continue
                    func = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
                    if inspect.isfunction(func):
                        yield f"{name}.{attr}", func


def _documented(doc, sections) -> set:
    out = set()
    for section in sections:
        for param in doc[section]:
            for part in param.name.split(","):
                out.add(part.strip().lstrip("*"))
    return out


def missing_parameters(obj) -> list:
    """Signature parameters of ``obj`` that its docstring does not document (``["<no docstring>"]`` if none)."""
    if not inspect.getdoc(obj):
        return ["<no docstring>"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if inspect.isclass(obj):
            doc = ClassDoc(obj, config={"show_class_members": False})
            documented = _documented(doc, ("Parameters", "Other Parameters", "Attributes"))
        else:
            doc = FunctionDoc(obj)
            documented = _documented(doc, ("Parameters", "Other Parameters"))
    try:
        signature = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    skip = (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)
    params = [p.name for p in signature.parameters.values() if p.name not in ("self", "cls") and p.kind not in skip]
    return [p for p in params if p not in documented]


MODULES = sorted(_module_names())


@pytest.mark.parametrize("name", MODULES)
def test_public_callables_document_their_parameters(name):
    module = importlib.import_module(name)
    problems = {qual: miss for qual, obj in _public_objects(module) if (miss := missing_parameters(obj))}
    assert not problems, f"{name}: undocumented parameters {problems}"


def test_the_check_can_fail():
    def undocumented(a, b):
        """Add.

        Parameters
        ----------
        a : float
            First.
        """

    assert missing_parameters(undocumented) == ["b"]
