"""Command-line interface: ``vines <command> ...`` (also ``python -m vines``).

Contract (see the README and the project specification, section 7):

* ``--json`` prints exactly one JSON object on stdout (NaN and infinities become null).
* Bad input of any kind (a non-number, a value out of range, an unknown flag, a missing
  required flag, a bad choice) exits with status 2 after printing exactly one line
  ``vines <command>: error: <message>`` on stderr, naming the parameter, the value given and
  what is allowed. No traceback, no output file.
* Unexpected internal errors are not caught: they keep their traceback.

One module per command (``simulate``, ``periodic``, ``continue_``, ``boundaries``,
``attractors``, ``lyapunov``); what they share (the argument parser, the model arguments, the error
messages, the JSON-or-text output) is in ``common``.

Adding a command: a module ``vines/cli/<name>.py`` defining ``NAME``,
``add_parser(subparsers) -> VinesArgumentParser`` (reusing ``common.add_model_args``) and
``run(args) -> int`` (ending in ``common.emit``), and its module name in ``COMMANDS``.
"""
from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from importlib import import_module

from .. import __version__
from ..core.params import ParameterError
from .common import PROG, VinesArgumentParser, flag_for

#: the commands' modules, in the order of ``vines --help``
COMMANDS = ("simulate", "periodic", "continue_", "boundaries", "attractors", "lyapunov")

__all__ = ["main", "build_parser", "COMMANDS", "VinesArgumentParser"]


def _value_flags(subparsers_map: dict) -> set[str]:
    flags = set()
    for sub in subparsers_map.values():
        for action in sub._actions:
            if action.option_strings and action.nargs is None and not isinstance(
                    action, (argparse._StoreTrueAction, argparse._StoreFalseAction)):
                flags.update(action.option_strings)
    return flags


def _join_negative_values(argv: list[str], value_flags: set[str]) -> list[str]:
    """Turn ``--phi -1e-3`` into ``--phi=-1e-3``.

    argparse only recognises plain negative numbers such as -1 or -0.5 as option values;
    exponent forms like -1e-3 would otherwise be rejected as an unknown option.
    """
    out, i = [], 0
    while i < len(argv):
        tok = argv[i]
        if tok == "--":
            out.extend(argv[i:])
            break
        if tok in value_flags and i + 1 < len(argv) and argv[i + 1].startswith("-"):
            try:
                float(argv[i + 1])
            except ValueError:
                pass
            else:
                out.append(f"{tok}={argv[i + 1]}")
                i += 2
                continue
        out.append(tok)
        i += 1
    return out


def build_parser() -> tuple[VinesArgumentParser, dict]:
    """The ``vines`` parser and its sub-parsers by command name."""
    parser = VinesArgumentParser(
        prog=PROG,
        description="Exact simulation and map-based analysis of the vibro-impact nonlinear "
                    "energy sink (VI NES).",
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="command",
                                       parser_class=VinesArgumentParser)
    commands = {}
    for name in COMMANDS:
        module = import_module(f".{name}", __name__)
        sub = module.add_parser(subparsers)
        sub.set_defaults(handler=module.run)
        commands[module.NAME] = sub
    return parser, commands


def main(argv: Sequence[str] | None = None) -> int:
    parser, commands = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    argv = _join_negative_values(argv, _value_flags(commands))
    args, extras = parser.parse_known_args(argv)
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    sub = commands[args.command]
    if extras:
        known = sorted(f for a in sub._actions for f in a.option_strings)
        sub.error(f"unrecognized argument {extras[0]!r} (allowed options: {', '.join(known)})")
    try:
        return args.handler(args)
    except ParameterError as err:
        flag = flag_for(err.name)
        if any(flag in a.option_strings for a in sub._actions):
            sub.error(f"argument {flag}: {err}")
        sub.error(str(err))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
