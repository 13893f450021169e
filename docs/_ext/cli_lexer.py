"""A Pygments lexer for command lines, ``cli``: options and comments highlighted, nothing else.

The default lexer (Python) reads ``strapdown drift --algorithm panov-4s-3`` as
arithmetic, colouring the hyphens of ``panov-4s-3`` as operators and the digits
as numbers; bash's lexer does much the same with ``-4``.  Here a command line is
words: a token that starts with ``--`` (or ``-`` and a letter) is an option,
``#`` starts a comment, a ``$`` at the start of a line is a prompt, quoted text
is a string, and every other word, hyphens and digits included, is plain text.
Shell blocks of the site are written as ``cli`` blocks.
"""

from __future__ import annotations

from pygments.lexer import RegexLexer
from pygments.token import Comment, Generic, Name, String, Text, Whitespace

__all__ = ["CommandLineLexer", "setup"]


class CommandLineLexer(RegexLexer):
    """Command lines: prompts, options, quoted strings and comments; every other word plain."""

    name = "Command line"
    aliases = ["cli"]
    filenames: list = []

    tokens = {
        "root": [
            (r"\n", Whitespace),
            (r"^\$ ", Generic.Prompt),
            (r"[ \t]+", Whitespace),
            (r"#.*", Comment.Single),
            (r"'[^']*'|\"[^\"]*\"", String),
            (r"--?[A-Za-z][\w-]*(=\S*)?(?=\s|$)", Name.Attribute),
            (r"[^\s'\"#]+", Text),
        ],
    }


def setup(app):
    """Register the ``cli`` lexer with Sphinx."""
    app.add_lexer("cli", CommandLineLexer)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
