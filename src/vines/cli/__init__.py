"""Command-line interface: ``vines <command> ...`` (also ``python -m vines``).

Contract (see docs/cli.md and the project specification, section 7):

* ``--json`` prints exactly one JSON object on stdout (NaN and infinities become null).
* Bad input of any kind (a non-number, a value out of range, an unknown flag, a missing
  required flag, a bad choice) exits with status 2 after printing exactly one line
  ``vines <command>: error: <message>`` on stderr, naming the parameter, the value given and
  what is allowed. No traceback, no output file.
* Ctrl-C (SIGINT) ends any command within about a second with one line
  ``vines <command>: interrupted (Ctrl-C); no output written`` on stderr and exit status
  130; nothing is written on stdout (the output is printed only once complete).
* stderr carries progress bars (on a terminal) and log messages (``vines.cli.reporting``;
  ``-q/--quiet``, ``-v/--verbose``); stdout carries the answer only.
* Unexpected internal errors are not caught: they keep their traceback.

One module per command (``simulate``, ``periodic``, ``continue_``, ``boundaries``,
``attractors``, ``lyapunov``, ``design``, ``design_map``, ``shock``, ``slowflow``, ``model``); what they share (the argument parser, the model
arguments, the error messages, the JSON-or-text output) is in ``common``, the messages and
progress on stderr in ``reporting``.

Adding a command: a module ``vines/cli/<name>.py`` defining ``NAME``,
``add_parser(subparsers) -> VinesArgumentParser`` (reusing ``common.add_model_args``) and
``run(args) -> int`` (ending in ``common.emit``), and its module name in ``COMMANDS``
(optionally ``FLAG_OF``: the flag of each ParameterError name that is not ``--<name>``).
"""
from __future__ import annotations

import argparse
import logging
import os
import sys
import threading
import time
from collections.abc import Sequence
from importlib import import_module

from .. import __version__, progress
from ..core.params import ParameterError
from . import reporting
from .common import PROG, VinesArgumentParser, flag_for

#: the commands' modules, in the order of ``vines --help``
COMMANDS = ("simulate", "periodic", "continue_", "boundaries", "attractors", "lyapunov",
            "design", "design_map", "shock", "slowflow", "model")

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


def build_parser(with_modules: bool = False) -> tuple:
    """The ``vines`` parser and its sub-parsers by command name (and the command modules by
    name with ``with_modules``)."""
    parser = VinesArgumentParser(
        prog=PROG,
        description="Exact simulation and map-based analysis of the vibro-impact nonlinear "
                    "energy sink (VI NES).",
        epilog="Every command's options: docs/cli.md; worked examples and the JSON keys: "
               "docs/usage.md.",
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    subparsers = parser.add_subparsers(dest="command", metavar="command",
                                       parser_class=VinesArgumentParser)
    commands, modules = {}, {}
    for name in COMMANDS:
        module = import_module(f".{name}", __name__)
        sub = module.add_parser(subparsers)
        reporting.add_flags(sub)
        sub.set_defaults(handler=module.run)
        commands[module.NAME] = sub
        modules[module.NAME] = module
    return (parser, commands, modules) if with_modules else (parser, commands)


#: exit status after Ctrl-C (128 + SIGINT, as shells report it)
EXIT_INTERRUPTED = 130
#: seconds a cancelled command may take to stop between two items of its loop before the
#: process ends without waiting for it (a compiled run in progress cannot be stopped)
GRACE_S = 0.5


class _Interrupted(Exception):
    """Ctrl-C while a command ran: the reporter whose bar must be cleared."""

    def __init__(self, reporter: progress.Reporter):
        super().__init__("interrupted")
        self.reporter = reporter


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``vines`` on ``argv`` (default: the command line); the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    command = next((a for a in argv if not a.startswith("-")), None)
    reporting.setup_logging(command)
    try:
        return _main(argv)
    except (KeyboardInterrupt, _Interrupted) as err:
        reporting.close(getattr(err, "reporter", None))
        reporting.LOG.error("interrupted (Ctrl-C); no output written")
        if isinstance(err, _Interrupted):
            # a compiled run still in progress cannot be stopped and its thread pool would
            # be joined at exit; the interpreter's teardown (numba, LLVM) takes a second or
            # more on a loaded machine: leave now, nothing is left to write
            logging.shutdown()
            sys.stderr.flush()
            os._exit(EXIT_INTERRUPTED)
        return EXIT_INTERRUPTED


def _interruptible(handler, args: argparse.Namespace, reporter: progress.Reporter) -> int:
    """``handler(args)`` in a worker thread (reporting progress to ``reporter``) while the
    main thread waits in short slices.

    Ctrl-C is delivered to the main thread; blocked without a timeout (e.g. on the results
    of a thread pool) it would never see it. Waking every 0.1 s it does: it cancels the
    reporter, so the command's loops stop at their next item and drop their pending work,
    waits up to GRACE_S for that and raises ``_Interrupted``. Exceptions of the handler
    (SystemExit of a parser error included) are raised again here. (The end of the worker
    is an Event: ``Thread.join`` interrupted by Ctrl-C may mark a running thread as ended.)
    """
    out: dict = {}
    ended = threading.Event()

    def target():
        try:
            with progress.reporting(reporter):
                out["status"] = handler(args)
        except BaseException as err:    # noqa: BLE001 - handed to the main thread
            out["error"] = err
        finally:
            ended.set()

    threading.Thread(target=target, name=f"{PROG}-{args.command}", daemon=True).start()
    try:
        while not ended.wait(0.1):
            pass
    except KeyboardInterrupt:
        reporter.cancel()
        try:
            ended.wait(GRACE_S)
            reporting.LOG.debug("after Ctrl-C the command %s", f"stopped: {out.get('error')!r}"
                                if ended.is_set() else f"still runs after {GRACE_S:g} s: left")
        finally:
            raise _Interrupted(reporter) from None
    if "error" in out:
        raise out["error"]
    return out["status"]


def _main(argv: list[str]) -> int:
    parser, commands, modules = build_parser(with_modules=True)
    argv = _join_negative_values(argv, _value_flags(commands))
    args, extras = parser.parse_known_args(argv)
    if args.command is None:
        parser.print_help(sys.stderr)
        return 2
    sub = commands[args.command]
    reporting.setup_logging(args.command, args.verbose, args.quiet)
    if extras:
        known = sorted(f for a in sub._actions for f in a.option_strings)
        sub.error(f"unrecognized argument {extras[0]!r} (allowed options: {', '.join(known)})")
    reporter = reporting.reporter_for(args)
    t0 = time.perf_counter()
    try:
        status = _interruptible(args.handler, args, reporter)
    except ParameterError as err:
        flag = getattr(modules[args.command], "FLAG_OF", {}).get(err.name) or flag_for(err.name)
        if any(flag in a.option_strings for a in sub._actions):
            if err.value is None:       # an option the call needs was not given
                sub.error(f"missing required option {flag}: {err.allowed}")
            sub.error(f"argument {flag}: {err}")
        sub.error(str(err))
    reporting.LOG.info("done in %.1f s", time.perf_counter() - t0)
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
