"""Write the study pages, ``docs/studies/``, from the CLI's registry (called by conf.py).

One page per command of :data:`studies.commands.STUDIES`, so a new study gets its page
without editing the docs. Each page holds

* the hand-written notes ``docs/studies/_notes/<command>.rst``: what the study
  asks and how to read its tables and figures (no numbers: the numbers are in
  the tables, which come from the files);
* the study module's docstring (read without importing the study);
* the command and its variants (from the registry);
* per results folder the study writes: the manifest of the committed run, every
  CSV as a ``csv-table`` read from the file at build time (``:file:``; a table too
  long or too wide to read on a page is offered as a download instead), and every
  figure.

A folder not committed yet is said so on the page. Results folders that no
command writes are listed on the index page.
"""
import ast
import csv
import json
import os
import re

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
RESULTS = os.path.join(ROOT, "results")
PAGES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "studies")
NOTES = os.path.join(PAGES, "_notes")
#: a CSV with more data rows or columns than this is offered as a download
MAX_ROWS = 60
MAX_COLUMNS = 32
# text that reST would read as markup inside a table cell (emphasis, substitution,
# interpreted text, a reference ``name_``, a footnote ``[1]_``)
_MARKUP = re.compile(r"[*|`]|_(\s|$)|^_|\]_")


def summary(study):
    """The study's one-line summary, without a pointer into the issue tracker."""
    return re.sub(r"\s*\([Ii]ssue[ #]*\d+[^)]*\)", "", study.summary)


def registry():
    """The CLI's registry ``{command: Study}`` (importing ``studies.cli`` is cheap)."""
    import sys
    if ROOT not in sys.path:
        sys.path.insert(0, ROOT)
    from studies.cli import STUDIES
    return STUDIES


def study_folders(study):
    """``[(folder name under results/, option that writes it or None)]`` of one study."""
    found = []

    def add(outputs, option):
        for out in outputs:
            path = out.format(out=study.default_out).replace("\\", "/")
            if path.startswith("results/") and path.count("/") == 1:
                name = path.split("/", 1)[1]
                if name not in [f for f, _ in found]:
                    found.append((name, option))

    add(study.outputs, None)
    for option, (_, outputs, _) in study.variants.items():
        add(outputs, option)
    return found


def _docstring(module):
    path = os.path.join(ROOT, *module.split(".")) + ".py"
    if not os.path.exists(path):
        return None
    with open(path) as fh:
        return ast.get_docstring(ast.parse(fh.read()))


def _read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.reader(fh))


def _table(folder, name):
    """reST for one CSV of ``results/<folder>/``."""
    path = os.path.join(RESULTS, folder, name)
    rel = f"../../results/{folder}/{name}"
    rows = _read_csv(path)
    if not rows:
        return [f"``{name}`` is empty.", ""]
    header, body = rows[0], rows[1:]
    size = f"{len(body)} rows x {len(header)} columns"
    if (len(body) > MAX_ROWS or len(header) > MAX_COLUMNS or not body
            or any(len(row) != len(header) for row in body)):
        return [f"``{name}`` ({size}): :download:`download <{rel}>`", ""]
    lines = [f".. csv-table:: ``{name}``", "   :header-rows: 1", "   :class: longtable"]
    if not any(_MARKUP.search(cell) for row in rows for cell in row) and all(h.strip() for h in header):
        # the file itself, read at build time
        return lines + [f"   :file: {rel}", ""]
    # a cell reST would read as markup: the same file, its cells escaped (still read at build time)
    lines.append("")
    for row in rows:
        cells = []
        for cell in row:
            text = cell.replace("\\", "\\\\")
            text = re.sub(r"([*|`_\[\]])", r"\\\1", text) if text.strip() else "\\ "
            cells.append('"' + text.replace('"', '""') + '"')
        lines.append("   " + ", ".join(cells))
    return lines + [""]


def _folder_section(folder, option, command):
    where = os.path.join(RESULTS, folder)
    title = f"``results/{folder}/``"
    lines = [title, "~" * len(title), ""]
    if option:
        lines += [f"Written by ``rotorwake {command} {option}``.", ""]
    if not os.path.isdir(where):
        return lines + [f"*No committed results in* ``results/{folder}/`` *yet.*", ""]
    manifest = os.path.join(where, "manifest.json")
    if os.path.exists(manifest):
        with open(manifest) as fh:
            m = json.load(fh)
        lines += [f"The committed run: ``{m.get('command', '?')}``, {m.get('date', '?')}, code "
                  f"``{m.get('code', {}).get('git', '?')}`` (``results/{folder}/manifest.json``).", ""]
    else:
        lines += ["*This folder carries no manifest.*", ""]
    if os.path.exists(os.path.join(where, "README.md")):
        lines += [f"``results/{folder}/README.md`` says what each file holds.", ""]
    names = sorted(os.listdir(where))
    for name in names:
        if name.endswith(".csv"):
            lines += _table(folder, name)
    for name in names:
        if name.endswith(".png"):
            lines += [f".. figure:: ../../results/{folder}/{name}", "   :width: 100%", "",
                      f"   ``results/{folder}/{name}``", ""]
    others = [n for n in names if not n.endswith((".csv", ".png")) and n not in ("manifest.json", "README.md")]
    for name in others:
        lines += [f"``{name}``: :download:`download <../../results/{folder}/{name}>`", ""]
    return lines


def page(command, study):
    """The reST of one study's page."""
    title = f"``rotorwake {command}``"
    lines = [f".. _study-{command}:", "", title, "=" * len(title), "", f"*{summary(study)}*", ""]
    notes = os.path.join(NOTES, command + ".rst")
    if os.path.exists(notes):
        lines += [f".. include:: _notes/{command}.rst", ""]
    lines += ["How to run it", "-------------", "", ".. code-block:: text", "",
              f"    rotorwake {command}    # rotorwake {command} --help lists its options"]
    for option, (_, _, note) in study.variants.items():
        lines += [f"    rotorwake {command} {option}    # {note}"]
    lines += [""]
    if study.cached_note:
        lines += [f"A second run is faster: {study.cached_note}.", ""]
    if not study.in_results:
        lines += ["``rotorwake results`` does not rerun it.", ""]
    doc = _docstring(study.module)
    if doc:
        lines += ["The study module", "----------------", "", f"``{study.module}``:", "", "::", ""]
        lines += ["    " + line if line else "" for line in doc.splitlines()] + [""]
    lines += ["Results", "-------", ""]
    for folder, option in study_folders(study):
        lines += _folder_section(folder, option, command)
    return "\n".join(lines) + "\n"


def index(studies):
    """The reST of ``docs/studies/index.rst``."""
    lines = ["Studies", "=======", "",
             "Each study is a thin script over the library, run by one command of the",
             "``rotorwake`` command line (:doc:`../cli`). It writes tables (CSV) and figures",
             "(PNG) to ``results/<study>/`` with a ``manifest.json`` (:doc:`../reproducibility`),",
             "and each folder's ``README.md`` says what its files hold.",
             "",
             "These pages are generated from the command line's registry",
             "(``studies.commands.STUDIES``) and from the committed results at each build: every",
             "table is read from its CSV file, so the numbers on a page are those of the",
             "committed run. The dissertation's numbers appear only in columns that say so.",
             "What the models and the studies cannot do yet is on one page, :doc:`../limits`.",
             "", ".. toctree::", "   :maxdepth: 1", ""]
    lines += [f"   {command}" for command in studies] + [""]
    lines += [".. list-table::", "   :header-rows: 1", "", "   * - command", "     - what it does",
              "     - results folders"]
    claimed = set()
    for command, study in studies.items():
        folders = [f for f, _ in study_folders(study)]
        claimed |= set(folders)
        lines += [f"   * - :doc:`{command}`", f"     - {summary(study)}",
                  "     - " + ", ".join(f"``{f}``" for f in folders)]
    lines.append("")
    other = sorted(n for n in os.listdir(RESULTS) if os.path.isdir(os.path.join(RESULTS, n))) \
        if os.path.isdir(RESULTS) else []
    other = [n for n in other if n not in claimed]
    if other:
        lines += ["Results folders that no command writes (each has its own ``README.md``):", ""]
        lines += [f"* ``results/{n}/``" for n in other] + [""]
    return "\n".join(lines) + "\n"


def _write(path, text):
    if not os.path.exists(path) or open(path).read() != text:
        with open(path, "w") as fh:
            fh.write(text)


def write(pages=PAGES):
    """Write ``index.rst`` and one page per study into ``pages``; remove pages of removed studies."""
    studies = registry()
    os.makedirs(pages, exist_ok=True)
    wanted = {"index.rst"} | {f"{command}.rst" for command in studies}
    for name in os.listdir(pages):
        if name.endswith(".rst") and name not in wanted:
            os.remove(os.path.join(pages, name))
    _write(os.path.join(pages, "index.rst"), index(studies))
    for command, study in studies.items():
        _write(os.path.join(pages, f"{command}.rst"), page(command, study))
