"""Command line: ``cranefe modes|check ...``. Thin: parse, call the pipeline, present.

Exit status: 0 success, 2 bad input (ModelError, with file and entry), 1 a failed
computation (AnalysisError). No traceback unless ``--debug``.
"""

import argparse
import sys

from .. import __version__
from ..errors import AnalysisError, ModelError

COMMANDS = ("modes", "damping", "simulate", "check", "show", "study", "generate",
            "sweep", "luff")


def _parser():
    p = argparse.ArgumentParser(prog="cranefe",
                                description="Dynamics of cranes and rope systems.")
    p.add_argument("--version", action="version", version=f"cranefe {__version__}")
    p.add_argument("--debug", action="store_true", help="show tracebacks")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMANDS:
        mod = _module(name)
        sp = sub.add_parser(name, help=mod.HELP, description=mod.__doc__)
        mod.add_arguments(sp)
    return p


def _module(name):
    from importlib import import_module
    return import_module(f".{name}", __name__)


def main(argv=None):
    parser = _parser()
    args = parser.parse_args(argv)
    args.argv = list(argv) if argv is not None else sys.argv[1:]
    if not args.command:
        parser.print_help()
        return 2
    try:
        return _module(args.command).run(args) or 0
    except ModelError as exc:
        if args.debug:
            raise
        print(f"cranefe: error: {exc}", file=sys.stderr)
        return 2
    except AnalysisError as exc:
        if args.debug:
            raise
        print(f"cranefe: analysis failed: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:          # e.g. `cranefe modes x --json | head`: stop quietly
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(main())
