"""`cranefe modes` stays light: no plotting, file-format or units library is imported for
a file without units."""

import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEAVY = ("pyvista", "vtk", "h5py", "meshio", "matplotlib", "pint")   # pint: only for units


def test_modes_imports_nothing_heavy():
    code = ("import sys, contextlib, io\n"
            "from cranefe.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    rc = main(['modes', {os.path.join(ROOT, 'models', 'hammerhead_tower_crane.yaml')!r}])\n"
            f"print(rc, sorted(m for m in {HEAVY!r} if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "0 []"


def test_help_and_version(capsys):
    from cranefe import __version__
    from cranefe.cli import main
    assert main([]) == 2
    assert "usage: cranefe" in capsys.readouterr().out      # help on stdout, status 2
    with pytest.raises(SystemExit) as exc:          # argparse's version action exits
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"cranefe {__version__}"
