"""Write docs/studies.rst from the committed results (called by conf.py at each build).

Each study gets its purpose (the study module's docstring, read without importing
it), its comparison tables against the dissertation (the CSVs in its results
folder, numbers to 4 significant digits), its figures, and the manifest of the
run that produced them. A missing folder or file is said so on the page.
"""
import ast
import csv
import io
import json
import math
import os

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))

# (title, study module, results folder, comparison tables shown, command)
STUDIES = [
    ("Main job: hover control comparison (§7.5)", "hover_control_comparison", "hover_control_comparison",
     ["table_7_5_characteristics.csv", "table_7_4_gains.csv"], "rotorwake main"),
    ("Identification pipeline on an embedded truth", "identification_demo", "identification_demo",
     ["parameters.csv", "verification.csv"], "rotorwake identification-demo"),
    ("Single rotor: identification from our free wake (Ch. 4)", "wake_identification", "wake_identification",
     ["coefficients.csv", "cost_table.csv", "verification.csv"], "rotorwake wake-identification"),
    ("Coaxial rotor: 6- and 12-state identification from our free wake (Ch. 5-6)", "coaxial_wake_identification",
     "coaxial_wake_identification", ["same_responses.csv", "parameters_6state.csv", "parameters_12state.csv",
                                     "verification_6state.csv", "verification_12state.csv"],
     "rotorwake coaxial-wake-identification"),
    ("Coaxial rotor: quasi-steady check of the shipped models (held steps of the wake)", "coaxial_quasi_steady",
     "coaxial_quasi_steady", ["table.csv", "settling.csv"], "rotorwake coaxial-quasi-steady"),
    ("Coaxial rotor: constrained 12-state models on one data set (trust per constraint)", "twelve_state_variants",
     "twelve_state_variants", ["table.csv"], "rotorwake twelve-state-variants"),
    ("Coaxial rotor: design space of rotor spacing and thrust (recommendation 2)", "coaxial_design_space",
     "coaxial_design_space", ["summary.csv"], "rotorwake coaxial-design-space"),
    ("Single rotor in forward flight and wake distortion K_R (§4.4, §4.7)", "forward_flight_identification",
     "forward_flight_identification", ["cost_table.csv", "coefficients.csv", "kr_constants.csv", "wall_times.csv"],
     "rotorwake forward-flight-identification"),
    ("Off-rotor induced velocity: tail and wing (§4.6, Eqs. 2.39-2.40)", "off_rotor_models", "off_rotor_models",
     ["gains_delays.csv", "verification.csv", "exposure.csv"], "rotorwake off-rotor-models"),
    ("Coaxial at 200 kt: Eq. 6.5 model and the isolated-rotor check (§6.6, Figs. 7.7-7.10)",
     "coaxial_forward_flight", "coaxial_forward_flight", ["cost_table.csv", "verdicts.csv", "differences.csv"],
     "rotorwake coaxial-forward-flight"),
    ("Coaxial aircraft: hover poles (Tables 7.1/7.2)", "coaxial_hover_poles", "coaxial_hover_poles",
     ["poles_clr.csv", "poles_id6.csv"], "rotorwake coaxial-hover-poles"),
    ("Pitt-Peters check (Tables 4.1-4.2, Eqs. 4.7-4.8)", "pitt_peters_hover_check", "pitt_peters_hover_check",
     ["matrices.csv", "forward_flight.csv"], "rotorwake pitt-peters-hover-check"),
]
MAX_ROWS = 30


def _docstring(module):
    path = os.path.join(ROOT, "studies", module + ".py")
    if not os.path.exists(path):
        return None
    with open(path) as fh:
        return ast.get_docstring(ast.parse(fh.read()))


def _fmt(cell):
    try:
        value = float(cell)
    except ValueError:
        return cell
    if math.isnan(value) or cell.strip().lower() in ("true", "false"):
        return cell
    return f"{value:.4g}"


def _table(path, title):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        return []
    header, body = rows[0], rows[1:]
    more = len(body) - MAX_ROWS
    body = body[:MAX_ROWS]
    buf = io.StringIO()
    writer = csv.writer(buf, quoting=csv.QUOTE_ALL, lineterminator="\n")
    writer.writerow([h or " " for h in header])
    for row in body:
        writer.writerow([_fmt(c) or " " for c in row])
    lines = [f".. csv-table:: {title}", "   :header-rows: 1", ""]
    lines += ["   " + line for line in buf.getvalue().splitlines()]
    lines.append("")
    if more > 0:
        lines += [f"({more} more rows in ``{os.path.relpath(path, ROOT)}``)", ""]
    return lines


def write(path):
    lines = ["Studies", "=======", "",
             "Each study is a thin script over the library; it writes tables (CSV) and figures",
             "(PNG) to ``results/<study>/`` with a ``manifest.json`` (:doc:`reproducibility`).",
             "This page is generated from the committed results at each build: the numbers",
             "are ours, and the dissertation's appear only in columns that say so.", ""]
    for title, module, folder, tables, command in STUDIES:
        lines += [title, "-" * len(title), ""]
        doc = _docstring(module)
        if doc:
            lines += ["::", ""] + ["    " + line for line in doc.splitlines()] + [""]
        lines += [f"Run: ``{command}`` (see ``{command} --help``).", ""]
        where = os.path.join(ROOT, "results", folder)
        if not os.path.isdir(where):
            lines += [f"*No committed results in* ``results/{folder}/`` *yet.*", ""]
            continue
        manifest = os.path.join(where, "manifest.json")
        if os.path.exists(manifest):
            with open(manifest) as fh:
                m = json.load(fh)
            lines += [f"Computed {m['date']} with code ``{m['code']['git']}`` in {m['wall_time_s']:.0f} s "
                      f"on {m['machine']['cores']} cores.", ""]
        else:
            lines += ["*These results carry no manifest yet (written before* ``rotorwake`` *existed).*", ""]
        for name in tables:
            table = os.path.join(where, name)
            if os.path.exists(table):
                lines += _table(table, f"``{name}``")
        for name in sorted(os.listdir(where)):
            if name.endswith(".png"):
                lines += [f".. figure:: ../results/{folder}/{name}", "   :width: 100%", "",
                          f"   ``results/{folder}/{name}``", ""]
    text = "\n".join(lines) + "\n"
    if not os.path.exists(path) or open(path).read() != text:
        with open(path, "w") as fh:
            fh.write(text)
