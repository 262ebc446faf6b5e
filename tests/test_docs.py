"""Every Python block of docs/ runs (issue 14: the docs cannot drift from the code).

The blocks of one page run in order in one namespace, in a scratch folder that holds
the repository's models/ (linked) and every YAML block the page names as a file (a
block right after a line ending in "`NAME.yaml`:"), written before any code runs, so a
tutorial's files exist when its code reads them.
"""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted(p for p in (ROOT / "docs").glob("*.md") if "```python" in p.read_text())
BLOCK = re.compile(r"```(\w*)\n(.*?)```", re.S)
NAMED = re.compile(r"`([\w./-]+\.ya?ml)`:?\s*$")


def blocks(page):
    """(language, code, file name or None) of every fenced block of a page."""
    text = page.read_text()
    for m in BLOCK.finditer(text):
        before = [line for line in text[:m.start()].splitlines() if line.strip()]
        named = NAMED.search(before[-1]) if before else None
        yield m.group(1), m.group(2), named.group(1) if named else None


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_python_blocks_run(page, tmp_path, monkeypatch):
    (tmp_path / "models").symlink_to(ROOT / "models")
    monkeypatch.chdir(tmp_path)
    for lang, code, name in blocks(page):       # the page's files, wherever it shows them
        if lang == "yaml" and name:
            (tmp_path / name).write_text(code)
    namespace = {}
    ran = 0
    for lang, code, _ in blocks(page):
        if lang == "python":
            exec(compile(code, f"{page.name} block {ran + 1}", "exec"), namespace)
            ran += 1
    assert ran > 0


def test_api_page_exists():
    assert (ROOT / "docs" / "api.md").exists()
    assert "docs/api.md" in (ROOT / "README.md").read_text()
