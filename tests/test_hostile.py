"""Hostile input (issue 15): every output path through one guard, damaged archives by
flipped bytes, SIGKILL of writers, collisions, devices, permissions, the sweep journal's
lock and digest, bad option values, files that are not cranefe files, confinement.

Each case runs as a user meets it, through `cranefe.cli.main` (or a subprocess where a
process must die or a file descriptor must fail): exit status 2 (bad input) or 1 (a
failed computation), a message naming the option or entry, never a traceback, and the
files that were there before left as they were.
"""

import json
import os
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time

import pytest

from cranefe.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HOIST = os.path.join(ROOT, "models", "two_mass_hoist.yaml")
ENV = dict(os.environ, PYTHONPATH=ROOT + os.pathsep + os.environ.get("PYTHONPATH", ""))


def cli(capsys, *argv):
    try:
        status = main([str(a) for a in argv])
    except SystemExit as exc:                 # argparse refuses an option's value
        status = exc.code
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    return status, out, err


def bad(capsys, *argv, says=(), status=2):
    got, out, err = cli(capsys, *argv)
    assert got == status, out + err
    for s in (says,) if isinstance(says, str) else says:
        assert s in err, err
    lines = [x for x in err.strip().splitlines() if not x.startswith(("usage:", " "))]
    assert len(lines) == 1, err               # one line (argparse prints its usage first)
    return err


@pytest.fixture
def model(tmp_path):
    """A copy of the two-mass hoist and a scene that names it."""
    m = tmp_path / "m.yaml"
    shutil.copy(HOIST, m)
    s = tmp_path / "s.yaml"
    s.write_text("cranefe: 1\nscene: hoist\nmodel: m.yaml\n")
    return m, s


def snapshot(*paths):
    return {p: open(p, "rb").read() for p in paths}


# ------------------------------------------------------------------ output guard


@pytest.mark.parametrize("args, says", [
    (["--archive", "{m}"], "--archive"),
    (["--vtu", "{m}"], "--vtu"),
    (["--xdmf", "{m}"], "--xdmf"),
    (["--archive", "{s}"], "this run reads"),
], ids=["archive-is-model", "vtu-is-model", "xdmf-is-model", "archive-is-scene"])
def test_an_input_is_never_an_output(model, capsys, args, says):
    m, s = model
    before = snapshot(m, s)
    args = [a.format(m=m, s=s) for a in args]
    bad(capsys, "modes", s, *args, says=(says, "this run reads"))
    assert snapshot(m, s) == before


def test_the_model_named_by_a_scene_is_an_input(model, capsys):
    m, s = model
    before = snapshot(m)
    bad(capsys, "damping", s, "--archive", m, says=("--archive", "this run reads"))
    bad(capsys, "modes", s, "--archive", str(m).replace("m.yaml", "./m.yaml"),
        says="this run reads")           # another spelling of the same file
    hard = m.parent / "hard.yaml"
    os.link(m, hard)                     # a hard link is the same file too
    bad(capsys, "modes", s, "--vtu", hard, says="this run reads")
    assert snapshot(m) == before


def test_a_mesh_file_is_an_input(tmp_path, capsys):
    out = tmp_path / "g.yaml"
    assert cli(capsys, "generate", "tower-crane", "--dofs", "1", "--mesh", "--out", out)[0] == 0
    mesh = tmp_path / "g_mast_chords.vtu"
    before = snapshot(mesh)
    bad(capsys, "modes", out, "--count", "2", "--vtu", mesh,
        says=("--vtu", "this run reads"))
    assert snapshot(mesh) == before


@pytest.mark.parametrize("args, says", [
    (["--archive", "x.h5", "--vtu", "x.h5"], "also the output of --archive"),
    (["--archive", "o.xdmf.h5", "--xdmf", "o.xdmf"], "also the output of --archive"),
    (["--archive", "d", "--images", "d"], "also the output of --archive"),
    (["--archive", ""], "is empty"),
    (["--vtu", ""], "is empty"),
    (["--archive", "./"], "is a folder"),
    (["--archive", "{tmp}"], "is a folder"),
    (["--images", "{m}"], "is a file, not a folder"),
    (["--archive", "missing/x.h5"], "does not exist"),
    (["--image-size", "100000x100000"], "--image-size"),
    (["--animate"], "--animate needs --images"),
], ids=["archive-vtu", "xdmf-heavy-data", "archive-images", "empty", "empty-vtu",
        "dot-slash", "folder", "images-file", "missing-folder", "image-size", "animate"])
def test_outputs_are_refused_before_anything_is_computed(model, tmp_path, capsys,
                                                          monkeypatch, args, says):
    m, _ = model
    monkeypatch.chdir(tmp_path)
    before = set(os.listdir(tmp_path))
    args = [a.format(m=m, tmp=tmp_path) for a in args]
    err = bad(capsys, "modes", m, *args, says=says)
    assert args[0] in err                                 # names the option
    assert set(os.listdir(tmp_path)) == before            # wrote nothing


def _devices(folder):
    """Private device nodes (twins of /dev/null and /dev/full, as root) and a FIFO in
    `folder`: a regression must never get to replace the machine's own /dev/null."""
    made = []
    for name, minor in (("null", 3), ("full", 7)):
        try:
            os.mknod(folder / name, 0o666 | stat.S_IFCHR, os.makedev(1, minor))
            made.append(folder / name)
        except (OSError, AttributeError):
            pass
    os.mkfifo(folder / "fifo")
    return made + [folder / "fifo"]


def test_a_device_is_never_replaced(model, tmp_path, capsys):
    m, _ = model
    for dev in _devices(tmp_path):
        mode = os.lstat(dev).st_mode
        bad(capsys, "modes", m, "--archive", dev, says="not a regular file")
        bad(capsys, "modes", m, "--vtu", dev,
            says="not a regular file")
        bad(capsys, "generate", "tower-crane", "--out", dev, says="not a regular file")
        assert os.lstat(dev).st_mode == mode and not stat.S_ISREG(mode)


def test_atomic_never_renames_over_a_device(tmp_path):
    """The writer re-checks at the rename: a FIFO that appeared meanwhile stays."""
    from cranefe.errors import ModelError
    from cranefe.outpaths import atomic
    target = tmp_path / "out.csv"
    with pytest.raises(ModelError, match="not a regular file"):
        with atomic(target) as tmp:
            open(tmp, "w").write("x")
            os.mkfifo(target)
    assert stat.S_ISFIFO(os.stat(target).st_mode)
    assert os.listdir(tmp_path) == ["out.csv"]            # no temporary file left


def test_a_symbolic_link_is_written_through(model, tmp_path, capsys):
    m, _ = model
    real = tmp_path / "real.h5"
    real.write_bytes(b"old")
    (tmp_path / "link.h5").symlink_to(real)
    assert cli(capsys, "modes", m, "--archive", tmp_path / "link.h5")[0] == 0
    assert os.path.islink(tmp_path / "link.h5") and real.stat().st_size > 1000


def _read_only_folder():
    """A folder no file can be created in, even as root (a read-only file system), or
    None."""
    for d in ("/sys", "/proc", "/sys/fs"):
        try:
            fd, p = tempfile.mkstemp(dir=d)
        except OSError:
            return d
        os.close(fd)
        os.remove(p)
    return None


def test_an_unwritable_folder_is_one_line(model, tmp_path, capsys):
    m, _ = model
    ro = _read_only_folder()
    if ro is None:
        pytest.skip("no read-only file system here")
    err = bad(capsys, "modes", m, "--archive", os.path.join(ro, "x.h5"),
              says=("--archive", "cannot write in the folder"))
    bad(capsys, "generate", "tower-crane", "--out", os.path.join(ro, "g.yaml"),
        says="cannot write")
    assert err


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into a chmod 500 folder")
def test_a_folder_without_write_permission(model, tmp_path, capsys):
    m, _ = model
    d = tmp_path / "ro"
    d.mkdir()
    d.chmod(0o500)
    try:
        bad(capsys, "modes", m, "--vtu", d / "x.vtu", says="cannot write in the folder")
    finally:
        d.chmod(0o700)


# ------------------------------------------------------------------ stale temporaries


def _dead_pid():
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_stale_temporary_files_of_dead_processes_are_removed(model, tmp_path, capsys):
    m, _ = model
    dead = tmp_path / f".a.h5.{_dead_pid()}.tmp"
    old_style = tmp_path / f"a.h5.{_dead_pid()}.tmp"
    other = tmp_path / f".b.h5.{_dead_pid()}.tmp"        # another target's: not ours
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        alive = tmp_path / f".a.h5.{sleeper.pid}.tmp"
        for p in (dead, old_style, other, alive):
            p.write_bytes(b"partial")
        assert cli(capsys, "modes", m, "--archive", tmp_path / "a.h5")[0] == 0
        assert not dead.exists() and not old_style.exists()
        assert alive.exists() and other.exists()
    finally:
        sleeper.kill()
        sleeper.wait()


# a writer stalled in the middle of an archive (the temporary file open, half written)
WRITER = """
import sys, time
from cranefe.outputs import archive
from cranefe.analysis.modal import modes
from cranefe.model import load
m = load(sys.argv[3])
r = modes(m)
def stall(g, obj):
    open(sys.argv[2], "w").close()
    time.sleep(600)
archive._write_dataclass = stall
archive.write(sys.argv[1], m, None, {"modes": r})
"""


def test_sigkill_of_a_writer_leaves_the_old_archive(model, tmp_path, capsys):
    m, _ = model
    target = tmp_path / "a.h5"
    assert cli(capsys, "modes", m, "--archive", target)[0] == 0
    before = target.read_bytes()
    flag = tmp_path / "stalled"
    p = subprocess.Popen([sys.executable, "-c", WRITER, str(target), str(flag), str(m)],
                         env=ENV, stderr=subprocess.PIPE)
    for _ in range(600):
        if flag.exists() or p.poll() is not None:
            break
        time.sleep(0.05)
    assert flag.exists(), p.stderr.read().decode()[-2000:]
    tmps = [f for f in os.listdir(tmp_path) if f.startswith(".a.h5.")]
    assert tmps                                          # killed in the middle of writing
    p.send_signal(signal.SIGKILL)
    p.wait()
    assert target.read_bytes() == before
    assert cli(capsys, "show", target)[0] == 0
    assert cli(capsys, "modes", m, "--archive", target)[0] == 0   # cleans the litter
    assert not [f for f in os.listdir(tmp_path) if f.startswith(".a.h5.")]


# ------------------------------------------------------------------ damaged archives


@pytest.fixture(scope="module")
def archive_bytes(tmp_path_factory):
    d = tmp_path_factory.mktemp("arc")
    path = d / "a.h5"
    assert main(["damping", HOIST, "--archive", str(path)]) == 0
    return path.read_bytes()


@pytest.mark.parametrize("where", [0.02, 0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95, 0.999])
def test_flipped_bytes_are_a_damaged_archive(archive_bytes, tmp_path, capsys, where):
    data = bytearray(archive_bytes)
    k = max(512, int(where * len(data)))                # past the seal itself
    for i in range(k, min(k + 16, len(data))):
        data[i] ^= 0xA5
    path = tmp_path / "d.h5"
    path.write_bytes(bytes(data))
    bad(capsys, "show", path, says="damaged or incomplete archive")


@pytest.mark.parametrize("keep", [0.1, 0.5, 0.99])
def test_truncated_archive_is_incomplete(archive_bytes, tmp_path, capsys, keep):
    path = tmp_path / "t.h5"
    path.write_bytes(archive_bytes[:int(keep * len(archive_bytes))])
    bad(capsys, "show", path, says="damaged or incomplete archive")


@pytest.mark.parametrize("where", [0.06, 0.12, 0.3, 0.5, 0.7, 0.9, 0.99])
def test_damaged_unsealed_archive_gives_a_message_not_a_traceback(archive_bytes, tmp_path,
                                                                   capsys, where):
    """An archive without a seal (an older cranefe, or the seal itself damaged) is read
    in a child process with a time limit: exit 0 with a table if HDF5 reads it, else
    status 2 "damaged or incomplete"."""
    # without its 512-byte user block the archive is a plain HDF5 file (HDF5 addresses
    # are relative to the block's end), as an older cranefe wrote it
    data = bytearray(archive_bytes[512:])
    intact = tmp_path / "intact.h5"
    intact.write_bytes(bytes(data))
    assert cli(capsys, "show", intact)[0] == 0
    k = int(where * len(data))
    for i in range(k, min(k + 64, len(data))):
        data[i] ^= 0xFF
    path = tmp_path / "u.h5"
    path.write_bytes(bytes(data))
    status, out, err = cli(capsys, "show", path)
    assert status in (0, 2)
    if status == 2:
        assert "damaged or incomplete archive" in err or "not a cranefe archive" in err \
            or "not an HDF5 file" in err


def _hang(path):
    time.sleep(600)


def test_a_reader_that_hangs_is_stopped():
    from cranefe.outputs import archive
    from cranefe.errors import ModelError
    with pytest.raises(ModelError, match="did not finish"):
        archive._in_child(_hang, __file__, (), "archive", 0.5)


def test_damaged_sweep_table(tmp_path, capsys):
    spec = tmp_path / "w.yaml"
    spec.write_text(f"cranefe: 1\nbase: {HOIST}\nparameters:\n  masses.H: "
                    "{values: [3000, 6000]}\noutputs: [frequency_hz.1]\n")
    assert cli(capsys, "sweep", spec, "--workers", "0")[0] == 0
    table = tmp_path / "w.h5"
    data = bytearray(table.read_bytes())
    data[len(data) // 2] ^= 0xFF
    table.write_bytes(bytes(data))
    bad(capsys, "show", table, says="damaged or incomplete")


# ------------------------------------------------------------------ sweeps


def sweep_spec(tmp_path, values="[3000, 6000]", output=None, base=None, name="w",
               outputs="[frequency_hz.1]"):
    path = tmp_path / f"{name}.yaml"
    path.write_text(f"cranefe: 1\nbase: {base or HOIST}\nparameters:\n  masses.H: "
                    f"{{values: {values}}}\noutputs: {outputs}\n"
                    + (f"output: {output}\n" if output else ""))
    return path


def test_sweep_output_may_not_be_its_base_or_leave_its_folder(tmp_path, capsys):
    m = tmp_path / "m.yaml"
    shutil.copy(HOIST, m)
    before = snapshot(m)
    bad(capsys, "sweep", sweep_spec(tmp_path, base="m.yaml", output="m.yaml"),
        "--workers", "0", says=("output", "this run reads"))
    bad(capsys, "sweep", sweep_spec(tmp_path, base="m.yaml", output="w.yaml"),
        "--workers", "0", says="the sweep file")
    assert snapshot(m) == before
    sub = tmp_path / "sub"
    sub.mkdir()
    shutil.copy(m, sub / "m.yaml")
    bad(capsys, "sweep", sweep_spec(sub, base="m.yaml", output="../x.h5"),
        "--workers", "0", says=("output", "outside the sweep file's folder"))
    bad(capsys, "sweep", sweep_spec(sub, base="m.yaml", output=str(tmp_path / "y.h5")),
        "--workers", "0", says="outside the sweep file's folder")
    assert not (tmp_path / "x.h5").exists() and not (tmp_path / "y.h5").exists()
    bad(capsys, "sweep", sweep_spec(sub, base="m.yaml"), "--workers", "0",
        "--plots", sub / "m.yaml", says=("--plots", "is a file"))


F2 = "[frequency_hz.2]"         # the hoist (rope) mode: it depends on EA


def test_sweep_journal_is_keyed_to_the_spec_and_its_files(tmp_path, capsys):
    m = tmp_path / "m.yaml"
    shutil.copy(HOIST, m)
    from cranefe.sweeps.table import read_table
    spec = sweep_spec(tmp_path, base="m.yaml", outputs=F2)
    assert cli(capsys, "sweep", spec, "--workers", "0", "--json")[0] == 0
    first = read_table(tmp_path / "w.h5").results[:, 0]
    # another parameter table on the same output: refused, not "resumed"
    spec = sweep_spec(tmp_path, base="m.yaml", values="[1000, 2000, 4000]",
                      outputs=F2)
    err = bad(capsys, "sweep", spec, "--workers", "0", says=("another sweep", "w.yaml",
                                                             "--restart"))
    # the spec as before, but the base model edited
    spec = sweep_spec(tmp_path, base="m.yaml", outputs=F2)
    m.write_text(m.read_text().replace("EA: 1.7e7", "EA: 2.7e7"))
    err = bad(capsys, "sweep", spec, "--workers", "0", says="m.yaml")
    assert "w.yaml" not in err.split("changed since:")[1].split(";")[0]
    # --restart starts afresh and the table then has the new results only
    status, out, _ = cli(capsys, "sweep", spec, "--workers", "0", "--restart", "--json")
    assert status == 0 and json.loads(out)["variants"] == 2
    t = read_table(tmp_path / "w.h5")
    # the stiffer rope's hoist mode, not the first run's (EA x 27/17 raises it)
    assert t.index.tolist() == [0, 1] and (t.results[:, 0] > first).all()
    assert cli(capsys, "sweep", spec, "--workers", "0")[0] == 0        # same: resumes


def test_a_journal_without_a_digest_is_refused(tmp_path, capsys):
    spec = sweep_spec(tmp_path)
    (tmp_path / "w.h5.journal").write_text(json.dumps(
        {"index": 0, "values": [3000.0], "outputs": [1.0], "status": "ok", "error": "",
         "seconds": 0.0}) + "\n")
    bad(capsys, "sweep", spec, "--workers", "0", says="records no digest")


def test_two_sweeps_on_one_output_the_second_is_refused(tmp_path, capsys):
    from cranefe.sweeps.spec import load_sweep
    from cranefe.sweeps.table import Journal
    spec = sweep_spec(tmp_path)
    sweep = load_sweep(spec)
    holder = Journal(sweep.output, sweep.digest)          # as a running sweep holds it
    try:
        err = bad(capsys, "sweep", spec, "--workers", "0",
                  says=("another sweep is writing", f"process {os.getpid()}"))
    finally:
        holder.close()
    assert err
    assert cli(capsys, "sweep", spec, "--workers", "0")[0] == 0


def test_a_missing_mode_is_an_error_of_the_variant(tmp_path, capsys):
    spec = sweep_spec(tmp_path, outputs="[frequency_hz.1, frequency_hz.99]")
    status, out, _ = cli(capsys, "sweep", spec, "--workers", "0", "--json")
    doc = json.loads(out)
    assert status == 0 and doc["failed"] == 2
    assert "frequency_hz.99" in doc["errors"][0]["error"]
    assert "elastic mode" in doc["errors"][0]["error"]


@pytest.mark.parametrize("args, says", [
    (["--workers", "-1"], "--workers"),
    (["--workers", "x"], "--workers"),
    (["--scheduler", "notaurl"], "--scheduler"),
    (["--scheduler", "tcp://host:99999"], "--scheduler"),
    (["--scheduler", "tcp://127.0.0.1:1", "--scheduler-timeout", "1"],
     "cannot reach the scheduler"),
], ids=["workers-negative", "workers-text", "scheduler-not-url", "scheduler-port",
        "scheduler-unreachable"])
def test_sweep_options(tmp_path, capsys, args, says):
    if "unreachable" in says or "cannot reach" in says:
        pytest.importorskip("distributed")
    bad(capsys, "sweep", sweep_spec(tmp_path), *args, says=says)


# ------------------------------------------------------------------ option values


@pytest.mark.parametrize("argv, says", [
    (["modes", HOIST, "--count", "-1"], "--count"),
    (["modes", HOIST, "--count", "0"], "--count"),
    (["damping", HOIST, "--count", "0"], "--count"),
    (["generate", "tower-crane", "--tie-every", "0", "--out", "g.yaml"], "--tie-every"),
    (["generate", "tower-crane", "--dofs", "-5", "--out", "g.yaml"], "--dofs"),
    (["generate", "tower-crane", "--panels", "0", "--out", "g.yaml"], "--panels"),
    (["generate", "tower-crane", "--dofs", "100000000000", "--out", "g.yaml"], "--dofs"),
    (["generate", "tower-crane", "--out", "missing/g.yaml"], "does not exist"),
    (["generate", "tower-crane", "--out", ""], "is empty"),
], ids=["count-negative", "count-zero", "damping-count", "tie-every", "dofs", "panels",
        "dofs-huge", "out-missing-folder", "out-empty"])
def test_bad_option_values(tmp_path, capsys, monkeypatch, argv, says):
    monkeypatch.chdir(tmp_path)
    bad(capsys, *argv, says=says)
    assert not os.path.exists(tmp_path / "g.yaml")


def test_generate_writes_atomically(tmp_path, capsys):
    """A new file is renamed over the old name: another (hard) link to the old file
    keeps the old content, which an in-place write would have changed."""
    out = tmp_path / "g.yaml"
    out.write_text("old")
    os.link(out, tmp_path / "keep.yaml")
    assert cli(capsys, "generate", "tower-crane", "--dofs", "1", "--out", out)[0] == 0
    assert out.read_text().startswith("# Lattice")
    assert (tmp_path / "keep.yaml").read_text() == "old"
    assert sorted(os.listdir(tmp_path)) == ["g.yaml", "keep.yaml"]


def test_a_full_disk_on_stdout_is_one_line(tmp_path):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    with open("/dev/full", "w") as full:
        p = subprocess.run([sys.executable, "-m", "cranefe", "modes", HOIST, "--json"],
                           stdout=full, stderr=subprocess.PIPE, env=ENV, text=True)
    assert p.returncode != 0
    assert p.stderr.strip().splitlines() == [
        "cranefe: error: cannot write to standard output (No space left on device)"]


def _edit(tmp_path, old, new, name="m.yaml"):
    text = open(HOIST).read()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new, 1))
    return path


@pytest.mark.parametrize("old, new, entry", [
    ("EA: 1.7e7", "EA: 1" + "0" * 400, "ropes.hoist_rope.EA"),
    ("EA: 1.7e7", "EA: -1" + "0" * 400, "ropes.hoist_rope.EA"),
    ("EA: 1.7e7", "EA: 1.0e-300", "ropes.hoist_rope.EA"),
    ("cranefe: 1\n", "cranefe: 1\ngravity: [0, 0, -1.0e308]\n", "gravity[2]"),
], ids=["EA-400-digits", "EA-minus-400-digits", "EA-subnormal-scale", "gravity-1e308"])
def test_numbers_beyond_double_precision(tmp_path, capsys, old, new, entry):
    bad(capsys, "modes", _edit(tmp_path, old, new), says=(entry, "finite number of "
                                                          "magnitude"))


def test_scene_name_must_be_text(model, capsys):
    m, s = model
    s.write_text("cranefe: 1\nscene: [x]\nmodel: m.yaml\n")
    bad(capsys, "modes", s, says=("scene", "must be the scene's name"))


def test_transient_overflow_names_the_time(model, tmp_path, capsys):
    m, _ = model
    scene = tmp_path / "t.yaml"
    scene.write_text("cranefe: 1\nmodel: m.yaml\neffects: {sway: false}\nanalysis:\n"
                     "  type: transient\n  duration: 1.0e59\n  method: direct\n"
                     "  max_steps: 200\n  drums:\n    hoist: {torque: 1.0e59}\n")
    p = subprocess.run([sys.executable, "-W", "default", "-m", "cranefe", "simulate",
                        str(scene)], capture_output=True, text=True, env=ENV)
    assert p.returncode == 1, p.stderr
    assert "overflows" in p.stderr and "t = " in p.stderr
    assert "RuntimeWarning" not in p.stderr and "Traceback" not in p.stderr


# ------------------------------------------------------------------ leaks, confinement


def test_a_file_that_is_not_a_cranefe_file_is_never_echoed(tmp_path, capsys):
    secret = tmp_path / "shadow"
    secret.write_text("root:$6$SECRETHASH:19000:0:99999:7:::\ndaemon:*:19000::\n")
    s = tmp_path / "s.yaml"
    s.write_text(f"cranefe: 1\nmodel: {secret}\n")
    err = bad(capsys, "modes", s, says="not a cranefe model file")
    assert "SECRET" not in err and "19000" not in err
    secret.write_text("root: [SECRET\n")                 # a YAML syntax error too
    err = bad(capsys, "modes", s, says="not a cranefe model file")
    assert "SECRET" not in err
    spec = tmp_path / "w.yaml"
    spec.write_text(f"cranefe: 1\nbase: {secret}\nparameters: {{a: {{values: [1]}}}}\n"
                    "outputs: [dofs]\n")
    err = bad(capsys, "sweep", spec, says="not a cranefe model file")
    assert "SECRET" not in err


def test_confine_keeps_named_paths_in_the_folder(tmp_path, capsys, monkeypatch):
    outside = tmp_path / "m.yaml"
    shutil.copy(HOIST, outside)
    inner = tmp_path / "in"
    inner.mkdir()
    (inner / "up.yaml").write_text("cranefe: 1\nmodel: ../m.yaml\n")
    (inner / "abs.yaml").write_text(f"cranefe: 1\nmodel: {outside}\n")
    (inner / "link.yaml").symlink_to(outside)
    (inner / "via-link.yaml").write_text("cranefe: 1\nmodel: link.yaml\n")
    shutil.copy(HOIST, inner / "m.yaml")
    (inner / "ok.yaml").write_text("cranefe: 1\nmodel: m.yaml\n")
    for name in ("up.yaml", "abs.yaml", "via-link.yaml", "ok.yaml"):
        assert cli(capsys, "check", inner / name)[0] == 0           # not confined
    for name in ("up.yaml", "abs.yaml", "via-link.yaml"):
        bad(capsys, "--confine", "check", inner / name, says=("model", "outside the folder"))
    assert cli(capsys, "--confine", "check", inner / "ok.yaml")[0] == 0
    monkeypatch.setenv("CRANEFE_CONFINE", "1")
    bad(capsys, "check", inner / "up.yaml", says="outside the folder")
    spec = inner / "w.yaml"
    spec.write_text("cranefe: 1\nbase: ../m.yaml\nparameters:\n  masses.H: {values: [1]}\n"
                    "outputs: [dofs]\n")
    bad(capsys, "sweep", spec, "--workers", "0", says=("base", "outside the folder"))


def test_confine_covers_mesh_files(tmp_path, capsys):
    assert cli(capsys, "generate", "tower-crane", "--dofs", "1", "--mesh", "--out",
               tmp_path / "g.yaml")[0] == 0
    inner = tmp_path / "in"
    inner.mkdir()
    text = (tmp_path / "g.yaml").read_text().replace("mesh: g_", "mesh: ../g_")
    (inner / "g.yaml").write_text(text)
    assert cli(capsys, "check", inner / "g.yaml")[0] == 0
    bad(capsys, "--confine", "check", inner / "g.yaml", says=("mesh", "outside the folder"))


@pytest.mark.parametrize("value", ['"' + "x" * 5000 + '"', "[" + ", ".join(["1"] * 3000) + "]"])
def test_a_huge_wrong_value_is_not_echoed_whole(tmp_path, capsys, value):
    path = tmp_path / "big.yaml"
    path.write_text(f"cranefe: 1\nnodes: {{A: [0, 0, 0], B: [0, 0, {value}]}}\n")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "nodes.B[2]" in err and "characters" in err and len(err) < 400


def test_a_full_disk_inside_an_output_file_is_exit_1_and_keeps_the_old_file(
        tmp_path, capsys, monkeypatch):
    # the computation was right and the input too: the machine could not keep the result
    # (errno ENOSPC at the rename); the file named keeps its old content
    import errno
    from cranefe import outpaths
    out = tmp_path / "modes.h5"
    out.write_bytes(b"old")

    def full(*a, **k):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(outpaths.os, "replace", full)
    assert main(["modes", HOIST, "--archive", str(out)]) == 1
    err = capsys.readouterr().err
    assert "No space left on device" in err and "Traceback" not in err
    assert out.read_bytes() == b"old"
    assert sorted(os.listdir(tmp_path)) == ["modes.h5"]
