import textwrap

import pytest

from cranefe.model import load


@pytest.fixture
def model_from(tmp_path):
    """Write YAML text to a file and load it: model_from(text, name='m.yaml')."""
    def make(text, name="m.yaml"):
        path = tmp_path / name
        path.write_text(textwrap.dedent(text))
        return load(path)
    return make


@pytest.fixture
def looped(monkeypatch):
    """simulate() through the compiled loop's code (loop.run; as plain Python without
    numba: `fast.available` answers True); returns the list of its calls."""
    from cranefe.analysis.operation import fast, loop
    from cranefe.analysis.operation import integrate as integ
    calls = []
    run = loop.run
    monkeypatch.setattr(fast, "available", lambda: True)

    def spy(*a, **k):
        calls.append(a[2])
        return run(*a, **k)
    monkeypatch.setattr(integ._loop, "run", spy)
    return calls
