"""The README is a short front page that stays true: its command table is the CLI's
registry, its links resolve, its tour's imports exist."""
import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()


def test_readme_is_short_and_keeps_the_two_set_up_commands():
    assert len(README.splitlines()) <= 160
    assert "make study   # the main job: hover control comparison (results/ + printed summary)" in README
    assert "make test    # the test suite (pytest, 2 workers)" in README
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^study:", makefile, re.M) and re.search(r"^test:", makefile, re.M)


def test_command_table_is_the_cli_registry():
    from studies.cli import STUDIES
    rows = re.findall(r"^\| `rotorwake ([a-z0-9-]+)` \|", README, re.M)
    assert len(rows) == len(set(rows))
    assert set(rows) == set(STUDIES) | {"results", "check-results", "shipped-models"}


def test_links_resolve():
    for target in re.findall(r"\]\(([^)#]+)\)", README):
        if "://" not in target:
            assert (ROOT / target).exists(), target


def test_tour_snippet_imports_exist():
    (code,) = re.findall(r"```python\n(.*?)```", README, re.S)
    tree = ast.parse(code)
    imports = [node for node in tree.body if isinstance(node, (ast.Import, ast.ImportFrom))]
    assert imports
    exec(compile(ast.Module(body=imports, type_ignores=[]), "README.md", "exec"), {})
