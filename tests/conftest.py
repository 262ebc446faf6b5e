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
