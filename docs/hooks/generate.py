"""The MkDocs hook (``hooks:`` in ``mkdocs.yml``) that adds the generated pages to the site.

Pages made from the code at build time, never committed, so they cannot fall behind it:

* ``kinds/*.md``, ``reference/config.md``: the kinds' declarations (:mod:`kind_pages`);
* ``reference/cli.md``: the argument parser (:mod:`cli_page`);
* ``reference/archive-layout.md``, ``notebook.md``: module docstrings and the shipped
  notebook (:mod:`source_pages`);
* ``css/pygments.css``: the colours of the code blocks, which Pygments highlights when the
  site is built (the site needs no network to show them).

The nav entry ``Kinds: kinds/index.md`` of ``mkdocs.yml`` gets every kind's page below it
(:func:`on_config`), so a new kind needs no edit here or there.

``mkdocs serve`` imports them once: restart it to see a change to a kind's code.
"""

from __future__ import annotations

import cli_page
import kind_pages
import source_pages
from mkdocs.structure.files import File, Files


def generated_pages() -> dict[str, str]:
    """Site path -> Markdown of every generated page."""
    return {**kind_pages.pages(), **cli_page.pages(), **source_pages.pages()}


def _pygments_css() -> str:
    from pygments.formatters import HtmlFormatter

    return HtmlFormatter(style="default").get_style_defs(".highlight")


def on_config(config):
    """Every kind's page under the nav's ``Kinds`` entry, in ``reportgen kinds`` order."""
    from reportgen.kinds import KINDS

    for i, item in enumerate(config.nav or []):
        if isinstance(item, dict) and item.get("Kinds") == "kinds/index.md":
            config.nav[i] = {"Kinds": ["kinds/index.md",
                                       *({kind: f"kinds/{kind}.md"} for kind in KINDS)]}
    return config


def on_files(files: Files, config) -> Files:
    for path, content in generated_pages().items():
        files.append(File.generated(config, path, content=content))
    files.append(File.generated(config, "css/pygments.css", content=_pygments_css()))
    return files
