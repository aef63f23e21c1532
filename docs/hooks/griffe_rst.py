"""A griffe extension for the API reference: docstrings' reStructuredText as Markdown
(:func:`rst.to_markdown`) before mkdocstrings renders them.  Named in ``mkdocs.yml``
under the python handler's ``extensions``."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import griffe

sys.path.insert(0, str(Path(__file__).resolve().parent))
from rst import to_markdown  # noqa: E402  (a sibling module: this file is loaded by path)


class RstToMarkdown(griffe.Extension):
    """Rewrites each object's docstring once, when griffe has read it."""

    def on_instance(self, *, node: Any, obj: griffe.Object, agent: Any, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = to_markdown(obj.docstring.value)
