"""Markdown links from a page of the site to files of the repository outside ``docs/``.

A page such as ``docs/algorithm-files.md`` is read on the repository host as
well as in the site, and may link to ``../reports/algorithms.md`` or
``../README.md``. Those files are not part of the site, so MyST cannot resolve
the link and warns (which fails a ``-W`` build). This post-transform runs just
before MyST's resolver and replaces such a link, when its target exists in the
repository, by its words followed by the repository path in monospace — what a
reader of the site can act on. A link to a file that exists nowhere is left to MyST, which warns.
"""

from __future__ import annotations

from pathlib import Path

from docutils import nodes
from sphinx import addnodes
from sphinx.transforms.post_transforms import SphinxPostTransform
from sphinx.util import logging

logger = logging.getLogger(__name__)


class RepositoryLinks(SphinxPostTransform):
    default_priority = 8  # before MyST's reference resolver (9)

    def run(self, **kwargs) -> None:
        srcdir = Path(self.env.srcdir).resolve()
        repository = srcdir.parent
        for node in list(self.document.findall(addnodes.pending_xref)):
            if node.get("reftype") != "myst" or node.get("refdomain") != "doc":
                continue
            target = str(node["reftarget"])
            base = Path(target) if Path(target).is_absolute() else srcdir / target
            base = base.resolve()
            if base.is_relative_to(srcdir) or not base.is_relative_to(repository):
                continue
            found = next((p for p in (base, base.with_name(base.name + ".md"), base.with_name(base.name + ".rst")) if p.is_file()), None)
            if found is None:
                continue
            shown = found.relative_to(repository).as_posix()
            logger.info(f"{self.env.docname}: link to {shown}, a file of the repository outside the site, shown as its path")
            text = node.astext().strip().strip("`")
            if text in (shown, found.name, target):
                node.replace_self(nodes.literal(shown, shown))
            else:  # keep the words of the link, with the path beside them
                node.replace_self(nodes.inline("", "", *[c.deepcopy() for c in node.children], nodes.Text(" ("), nodes.literal(shown, shown), nodes.Text(")")))


def setup(app):
    app.add_post_transform(RepositoryLinks)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
