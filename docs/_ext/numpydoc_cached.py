"""numpydoc with its docstring template loaded once per build instead of once per object.

numpydoc's ``get_doc_object`` builds a Jinja environment and compiles
``numpydoc_docstring.rst`` on every call, about three times per documented
object; over the API reference that is a third of the build.  numpydoc's own
``setup(app, get_doc_object_=...)`` hook takes a replacement, which is this
function: the same call with the compiled template cached per builder.
"""

from __future__ import annotations

import functools
import os

from jinja2 import FileSystemLoader
from jinja2.sandbox import SandboxedEnvironment
from numpydoc import docscrape_sphinx
from numpydoc import numpydoc as _numpydoc
from sphinx.jinja2glue import BuiltinTemplateLoader

_TEMPLATE_DIRS = [os.path.join(os.path.dirname(docscrape_sphinx.__file__), "templates")]


@functools.cache
def _template(builder):
    if builder is not None:
        loader = BuiltinTemplateLoader()
        loader.init(builder, dirs=_TEMPLATE_DIRS)
    else:
        loader = FileSystemLoader(_TEMPLATE_DIRS)
    return SandboxedEnvironment(loader=loader).get_template("numpydoc_docstring.rst")


def get_doc_object(obj, what=None, doc=None, config=None, builder=None):
    """``numpydoc.docscrape_sphinx.get_doc_object`` with the template compiled once."""
    config = {} if config is None else config
    config["template"] = _template(builder)
    return docscrape_sphinx.get_doc_object_orig(
        obj,
        what=what,
        doc=doc,
        config=config,
        class_doc=docscrape_sphinx.SphinxClassDoc,
        func_doc=docscrape_sphinx.SphinxFunctionDoc,
        obj_doc=docscrape_sphinx.SphinxObjDoc,
    )


def setup(app):
    metadata = _numpydoc.setup(app, get_doc_object_=get_doc_object)
    return {**metadata, "parallel_read_safe": True}
