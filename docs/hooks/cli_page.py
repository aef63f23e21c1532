"""The command-line reference, generated from ``reportgen``'s argparse parser
(:func:`reportgen.commands.cli.build_parser`) when the site is built: every command in the
parser's order, its usage line and each argument with its default and help."""

from __future__ import annotations

import argparse
import functools

from mdtext import code, table, text

from reportgen.commands import cli

#: width of the usage lines (the terminal's width is not the page's)
WIDTH = 92

#: where the guide says more about a command (site paths from reference/)
GUIDE = {
    "run": "../usage.md", "watch": "../watch.md", "report": "../archive.md",
    "figures": "../figures.md", "animate": "../figures.md", "inspect": "../archive.md",
    "verify": "../archive.md", "kinds": "../scenes.md", "validate": "../scenes.md",
    "audit": "../accuracy.md", "cache": "../usage.md", "bench": "../benchmarks.md",
}


def _subcommands(parser: argparse.ArgumentParser):
    """(name, help, parser) of each subcommand, in the order they were added."""
    (action,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    helps = {choice.dest: choice.help or "" for choice in action._choices_actions}
    return [(name, helps.get(name, ""), sub) for name, sub in action.choices.items()]


def _usage(parser: argparse.ArgumentParser) -> str:
    parser.formatter_class = functools.partial(argparse.HelpFormatter, width=WIDTH)
    return parser.format_usage().removeprefix("usage: ").strip()


def _argument(action: argparse.Action) -> list[str]:
    if action.option_strings:
        name = ", ".join(action.option_strings)
        if action.nargs != 0:
            name += " " + (action.metavar or action.dest.upper())
    else:
        name = action.metavar or action.dest
        name += " ..." if action.nargs in ("+", "*") else ""
    default = action.default
    shown = ("" if default in (None, False, [], argparse.SUPPRESS) or action.nargs == 0
             else code(",".join(default) if isinstance(default, tuple) else str(default)))
    words = action.help or ""
    if action.choices and not words:
        words = "one of " + ", ".join(map(str, action.choices))
    return [code(name), shown, text(words)]


def cli_reference() -> str:
    parser = cli.build_parser()
    doc = " ".join((cli.__doc__ or "").split("\n\n", 1)[-1].split())
    out = ["# Command line", "",
           "*Generated from the argument parser (`reportgen/commands/cli.py`) when the site "
           "is built; `reportgen COMMAND --help` prints the same.*", "",
           text(parser.description or ""), "", text(doc), "",
           "`reportgen --version` prints the version.", ""]
    for name, help_text, sub in _subcommands(parser):
        arguments = [a for a in sub._actions if not isinstance(a, argparse._HelpAction)]
        out += [f"## reportgen {name}", "", text(help_text[:1].upper() + help_text[1:]) + ".",
                "", "```text", _usage(sub), "```", ""]
        if arguments:
            out += [table(["argument", "default", "meaning"],
                          [_argument(a) for a in arguments]), ""]
        if name in GUIDE:
            out += [f"More in [the guide]({GUIDE[name]}).", ""]
    return "\n".join(out)


def pages() -> dict[str, str]:
    return {"reference/cli.md": cli_reference()}
