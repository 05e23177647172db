"""The docs' study pages follow the command line's registry and read the committed results.

``docs/_studies.py`` writes one page per command of ``studies.commands.STUDIES`` at each
build; here the pages are generated into a temporary folder (no Sphinx needed) and
checked: every command has a page and hand-written notes, every table and figure
points to a file that exists, and the notes quote no result numbers (those change
with every regeneration and are read from the CSV files instead).
"""
import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def generator():
    spec = importlib.util.spec_from_file_location("_studies", DOCS / "_studies.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def pages(generator, tmp_path_factory):
    folder = tmp_path_factory.mktemp("studies")
    generator.write(folder)
    return folder


def test_every_command_of_the_registry_has_a_page_and_notes(generator, pages):
    from studies.cli import STUDIES
    assert sorted(p.stem for p in pages.glob("*.rst")) == sorted(list(STUDIES) + ["index"])
    index = (pages / "index.rst").read_text()
    for command in STUDIES:
        assert f"   {command}\n" in index                      # in the toctree
        assert (DOCS / "studies" / "_notes" / f"{command}.rst").is_file(), command
        assert f".. include:: _notes/{command}.rst" in (pages / f"{command}.rst").read_text()
    assert not set(p.stem for p in (DOCS / "studies" / "_notes").glob("*.rst")) - set(STUDIES)


def test_tables_and_figures_point_to_committed_files(pages):
    targets = []
    for page in pages.glob("*.rst"):
        text = page.read_text()
        targets += re.findall(r":file: (\S+)", text)
        targets += re.findall(r"\.\. figure:: (\S+)", text)
        targets += re.findall(r":download:`[^<]*<([^>]+)>`", text)
    assert any(t.endswith(".csv") for t in targets)
    for target in targets:
        assert (DOCS / "studies" / target).resolve().is_file(), target


def test_every_committed_study_folder_is_on_a_page(generator):
    from studies.cli import STUDIES
    claimed = {folder for study in STUDIES.values() for folder, _ in generator.study_folders(study)}
    committed = {p.name for p in (ROOT / "results").iterdir() if (p / "manifest.json").is_file()}
    # hq_spec_library is written by its own script (results/hq_spec_library/make_table.py)
    assert committed - claimed <= {"hq_spec_library"}


_REFERENCE = re.compile(r"(Eqs?\.|§|Tables?|Figs?\.|Chapters?|conclusion|mu =)\s*[\d.,\- /]+")


def _decimals(text):
    """Decimal numbers in a text, section/equation/table/figure references left out."""
    return re.findall(r"\b\d+\.\d+\b", _REFERENCE.sub("", text))


def test_the_notes_quote_no_result_numbers():
    # a decimal number in prose would go stale at the next regeneration; the notes
    # name files and columns instead (section and equation numbers are not decimals
    # of results, e.g. "Eq. 5.3", "§7.5", "Table 7.1", "Figs. 7.3-7.11")
    for notes in (DOCS / "studies" / "_notes").glob("*.rst"):
        assert not _decimals(notes.read_text()), notes.name


def test_every_results_folder_has_a_readme_that_says_how_to_rerun_it(generator):
    from studies.cli import STUDIES
    for command, study in STUDIES.items():
        for folder, _ in generator.study_folders(study):
            where = ROOT / "results" / folder
            if not (where / "manifest.json").is_file():
                continue                                   # not committed (yet)
            text = (where / "README.md").read_text()
            assert "rotorwake " in text and "docs/studies/" in text, folder
            assert not _decimals(text), folder   # no result numbers
