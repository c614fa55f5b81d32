"""Command-line code waiting to be wired into the CLI package (``vines.cli``): each module
has ``add_parser(subparsers)`` and ``run(args) -> dict``; the .md files describe flag
changes of existing commands. Nothing imports this package."""
