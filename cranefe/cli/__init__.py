"""Command line: ``cranefe modes|check ...``. Thin: parse, call the pipeline, present.

Exit status: 0 success, 2 bad input (ModelError, with file and entry), 1 a failed
computation (AnalysisError). No traceback unless ``--debug``.
"""

import argparse
import sys

from .. import __version__
from ..errors import AnalysisError, ModelError

COMMANDS = ("modes", "damping", "simulate", "check", "show", "study", "generate",
            "sweep", "luff", "loads")


def _parser():
    p = argparse.ArgumentParser(prog="cranefe",
                                description="Dynamics of cranes and rope systems.")
    p.add_argument("--version", action="version", version=f"cranefe {__version__}")
    p.add_argument("--debug", action="store_true", help="show tracebacks")
    p.add_argument("--confine", action="store_true",
                   help="every path a scene, model or sweep file names must lie in or "
                   "below that file's folder (for files from others; also "
                   "CRANEFE_CONFINE=1; docs/security.md)")
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
    args = parser.parse_args(argv)      # a bad option value: usage, SystemExit(2)
    args.argv = list(argv) if argv is not None else sys.argv[1:]
    if not args.command:
        parser.print_help()
        return 2
    from ..outpaths import reset_reads, set_confine
    reset_reads()
    set_confine(args.confine)
    try:
        status = _module(args.command).run(args) or 0
        sys.stdout.flush()               # a full disk or closed stdout shows here
        return status
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
        _drop_stdout()
        return 0
    except OSError as exc:
        if args.debug or not _is_stdout_error(exc):
            raise
        _drop_stdout()
        print(f"cranefe: error: cannot write to standard output ({exc.strerror})",
              file=sys.stderr)
        return 1
    finally:
        set_confine(False)


def _is_stdout_error(exc):
    """An OSError from writing stdout (a full disk, an I/O error), not from a file."""
    import errno
    return exc.filename is None and exc.errno in (errno.ENOSPC, errno.EIO, errno.EDQUOT,
                                                  errno.EFBIG, errno.EBADF)


def _drop_stdout():
    """Point stdout at /dev/null so that the interpreter's final flush stays quiet."""
    import os
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):
        pass


if __name__ == "__main__":
    sys.exit(main())
