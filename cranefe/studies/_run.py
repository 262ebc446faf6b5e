"""Run a module (or a script file) as __main__ and report its peak memory on stderr (for
the studies).

    python -m cranefe.studies._run MODULE ARGS...
    python PATH/_run.py PATH/SCRIPT.py ARGS...

The second form imports nothing of cranefe: the reference scripts (`_floor.py`,
`_opensees.py`) are timed without cranefe's package on their path.

The peak is VmHWM from /proc/self/status: unlike getrusage's ru_maxrss (which a child
inherits from its parent at fork), it belongs to this program's own address space.
"""

import runpy
import sys


def _peak_kb():
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    return -1


if __name__ == "__main__":
    module, sys.argv = sys.argv[1], sys.argv[1:]
    try:
        if module.endswith(".py"):
            del sys.path[0]           # this folder: nothing in it may shadow a library
            runpy.run_path(module, run_name="__main__")
        else:
            runpy.run_module(module, run_name="__main__", alter_sys=True)
    finally:
        print(f"PEAK_RSS_KB {_peak_kb()}", file=sys.stderr)
