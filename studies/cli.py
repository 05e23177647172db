"""The ``rotorwake`` command line: the main job, each study, and the results tools.

::

    rotorwake --help                       list of commands (fast: nothing heavy imported)
    rotorwake main [options]               hover control comparison (``make study``)
    rotorwake <study> [options]            one study; ``rotorwake <study> --help`` for its options
    rotorwake results                      regenerate every committed results folder
    rotorwake check-results                say which committed results are stale
    rotorwake reproduce [folders]          rerun the studies of committed folders and compare within a tolerance
    rotorwake shipped-models [names]       list, check or regenerate the shipped model files

Each study command calls that study's own ``main`` with the remaining options, so
the studies keep their own option parsers; the heavy imports (numba, CasADi,
python-control) happen only after the command line has been parsed. Every run
writes ``manifest.json`` into each results folder it produced (see
:mod:`aircraft.provenance`) and, where it replaced an earlier folder, prints how
its tables compare with the ones it replaced (:mod:`aircraft.result_comparison`).
A run longer than a minute says so, and about how long, before it starts.

Run it from the project's virtual environment: ``.venv/bin/rotorwake`` (after
``make study`` or ``make test``), or ``source .venv/bin/activate`` first.
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import inspect
import os
import platform
import shutil
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["Study", "STUDIES", "main", "hover_study", "REPRODUCIBLE_BLAS_KERNELS"]

#: OpenBLAS kernel family every run uses on an x86-64 processor that has it (AVX2 and FMA: every
#: such processor since 2013). OpenBLAS picks its kernels by processor (AVX-512 ones here, AVX2
#: ones elsewhere), their sums round differently, and the design-margin optimiser's path through
#: unconverged IPOPT iterates turns that round-off into designs 1-2 % apart: with one kernel family
#: the same inputs give the same numbers on every such machine. A value already in the
#: environment (``OPENBLAS_CORETYPE``) is kept; elsewhere (other processors) nothing is set.
REPRODUCIBLE_BLAS_KERNELS = "Haswell"


def _pin_blas_kernels():
    """Set ``OPENBLAS_CORETYPE`` before numpy loads OpenBLAS (it reads it once, at load)."""
    if "OPENBLAS_CORETYPE" in os.environ or platform.machine().lower() not in ("x86_64", "amd64"):
        return
    try:
        flags = set(Path("/proc/cpuinfo").read_text().split())
    except OSError:
        return
    if {"avx2", "fma"} <= flags:
        os.environ["OPENBLAS_CORETYPE"] = REPRODUCIBLE_BLAS_KERNELS


_pin_blas_kernels()

from studies.commands import STUDIES, Study  # noqa: E402  (after the BLAS kernels are chosen)


# identification_demo is written by `main` as its stage 1; `results` does not rerun it
#: What ``rotorwake reproduce`` reruns when no folder is named: the main job's folders.
_MAIN_FOLDERS = ("hover_control_comparison", "identification_demo")


def _minutes(minutes):
    return f"about {minutes:.0f} min" if minutes >= 1 else f"under {max(1, round(minutes * 60, -1)):.0f} s"


def _parser():
    parser = argparse.ArgumentParser(
        prog="rotorwake", description="State-space rotor wake identification and coaxial flight "
                                      "control design (times: wall time on 2 cores).",
        epilog="`rotorwake <command> --help` lists a command's options and defaults. Every run writes "
               "manifest.json (code version, settings hash, date, wall time, cores) into each "
               "results folder. Run from the project's venv: .venv/bin/rotorwake.")
    sub = parser.add_subparsers(dest="command", metavar="command", required=True)
    for name, study in STUDIES.items():
        # add_help=False: `--help` is passed on to the study's own parser
        sub.add_parser(name, add_help=False, help=f"{study.summary} ({_minutes(study.minutes)})")
    res = sub.add_parser("results", help="regenerate every committed results folder with the options its "
                                         "manifest records (about 1 h with the wake cache warm)",
                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    res.add_argument("--only", nargs="+", choices=[n for n, s in STUDIES.items() if s.in_results],
                     help="regenerate only these (default: all)")
    res.add_argument("--stale", action="store_true", help="regenerate only folders check-results calls stale")
    rep = sub.add_parser("reproduce", help="rerun the study of each named results folder with the options its "
                                           "manifest records, into a temporary folder, and compare its tables "
                                           "with the committed ones (default: the main job's two folders, "
                                           f"{_minutes(STUDIES['main'].minutes)})",
                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    rep.add_argument("folders", nargs="*", metavar="FOLDER", default=list(_MAIN_FOLDERS),
                     help="results folders to reproduce: names under --results, or paths")
    rep.add_argument("--results", default="results", help="folder with one sub-folder per study")
    rep.add_argument("--rtol", type=float, default=1e-6, help="relative tolerance of every numeric column")
    rep.add_argument("--atol", type=float, default=1e-9, help="absolute tolerance of every numeric column")
    rep.add_argument("--keep", default=argparse.SUPPRESS, metavar="DIR",
                     help="write the reruns under DIR and keep them (default: a temporary folder, removed "
                          "after the comparison)")
    chk = sub.add_parser("check-results", help="say which committed results are stale",
                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    chk.add_argument("--results", default="results", help="folder with one sub-folder per study")
    chk.add_argument("--upgrade", action="store_true",
                     help="first add code digests to schema-1 manifests whose modules are unchanged, so that "
                          "later documentation-only edits leave them fresh")
    chk.add_argument("--record-kernel-backend", choices=("cpu", "gpu"), default=None,
                     help="first record, in manifests that do not say, which Biot-Savart backend their runs "
                          "used (an attestation by whoever knows where they ran; see "
                          "aircraft.provenance_check.record_kernel_backend)")
    shp = sub.add_parser("shipped-models", help="list, check (--check) or regenerate the identified models "
                                                 "shipped in aircraft/data/models",
                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    shp.add_argument("names", nargs="*", help="models to regenerate (names of their recipes)")
    shp.add_argument("--list", action="store_true", help="list recipes and shipped files")
    shp.add_argument("--published", action="store_true", help="(re)write the printed models' files")
    shp.add_argument("--check", action="store_true", help="report shipped files that no longer match their recipe")
    shp.add_argument("--jobs", type=int, default=2, help="wake worker processes")
    shp.add_argument("--cache", default="default",
                     help="wake run cache folder (default: $ROTORWAKE_CACHE_DIR, else .cache/wake)")
    return parser


def _shipped_models(args):
    """``rotorwake shipped-models``: list, check or regenerate the shipped model files."""
    from aircraft.identification import shipped
    from aircraft.inflow.model_files import shipped_model_path, shipped_models
    from aircraft.provenance_check import record_environment
    if args.list:
        print("recipes:", ", ".join(sorted(shipped.RECIPES)))
        print("published:", ", ".join(sorted(shipped.PUBLISHED_FILES)))
        print("shipped:", ", ".join(shipped_models()))
    status = 0
    if args.check:
        stale = shipped.stale_models()
        print("stale:" if stale else "all shipped models match their recipes and the code",
              *(f"{k}: {'; '.join(reasons)}" for k, reasons in stale.items()), sep="\n  ")
        from aircraft.provenance_check import environment_note
        print("environment of each file's run against this one (reported only):",
              *(f"{k}: {environment_note(shipped_model_path(k))}" for k in shipped_models()), sep="\n  ")
        status = 1 if stale else 0
    names = list(args.names) + (sorted(shipped.PUBLISHED_FILES) if args.published else [])
    t_all = time.perf_counter()
    for k, name in enumerate(names, 1):
        print(f"[{k}/{len(names)}] {name}: regenerating ...", flush=True)
        t0 = time.perf_counter()
        out = shipped.regenerate(name, n_jobs=args.jobs, cache_dir=args.cache)
        # the library's writer is part of every model's code digest: recorded here until it next changes
        if shipped_model_path(name).is_file():
            record_environment(shipped_model_path(name))
        if hasattr(out, "summary"):
            print(out.summary())
        print(f"[{k}/{len(names)}] wrote {shipped_model_path(name)} in {time.perf_counter() - t0:.1f} s",
              flush=True)
    if names:
        print(f"regenerated {len(names)} model file(s) in {time.perf_counter() - t_all:.1f} s")
    return status


def _option(argv, name, default):
    """Value of ``--name value`` / ``--name=value`` in ``argv`` (the last one wins)."""
    value = default
    for k, arg in enumerate(argv):
        if arg == name and k + 1 < len(argv):
            value = argv[k + 1]
        elif arg.startswith(name + "="):
            value = arg.split("=", 1)[1]
    return value


def _without_out(argv):
    """``argv`` without its ``--out`` option(s)."""
    kept, skip = [], False
    for arg in argv:
        if skip:
            skip = False
        elif arg == "--out":
            skip = True
        elif not arg.startswith("--out="):
            kept.append(arg)
    return kept


def _plan(study, argv):
    """(minutes, results folders, cache note) of running ``study`` with ``argv``."""
    minutes, outputs, note = study.minutes, study.outputs, study.cached_note
    for flag, (v_minutes, v_outputs, v_note) in study.variants.items():
        key, _, value = flag.partition("=")
        # "--key=value" variants match that option value; bare "--flag" variants its presence
        if (_option(argv, key, None) == value) if value else (key in argv):
            minutes, outputs, note = v_minutes, v_outputs, v_note
    if "--skip-identification" in argv:
        outputs = tuple(o for o in outputs if not o.endswith("identification_demo"))
    out = _option(argv, "--out", study.default_out)
    return minutes, [Path(o.format(out=out)) for o in outputs], note


class _DefaultsFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Shows the default of every option, also of those declared without help."""

    def _format_action(self, action):
        if not action.help and action.option_strings and action.default not in (None, argparse.SUPPRESS):
            action.help = "default: %(default)s"
        return super()._format_action(action)


@contextlib.contextmanager
def _help_shows_defaults(prog):
    """While a study prints its --help, its parser shows each option's default.

    The studies build their own parsers; rather than asking each to choose a
    formatter, the command line makes ArgumentDefaultsHelpFormatter the default
    for parsers created inside this block (help output only; restored after).
    """
    original, argv0 = argparse.ArgumentParser.__init__, sys.argv[0]

    def init(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", _DefaultsFormatter)
        original(self, *args, **kwargs)

    argparse.ArgumentParser.__init__ = init
    sys.argv[0] = prog     # the usage line then reads "rotorwake <command>"
    try:
        yield
    finally:
        argparse.ArgumentParser.__init__ = original
        sys.argv[0] = argv0


def _snapshot(folders, into):
    """Copy the tables and text files of each existing folder in ``folders`` under ``into``.

    Returns ``{folder: copy}`` for the folders that held any, so that what a run
    replaces can be compared with what it wrote.
    """
    from aircraft.result_comparison import COMPARED_SUFFIXES
    copies = {}
    for k, folder in enumerate(folders):
        files = sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in COMPARED_SUFFIXES) \
            if folder.is_dir() else []
        if files:
            copy = Path(into) / f"{k}_{folder.name}"
            copy.mkdir(parents=True)
            for path in files:
                shutil.copy2(path, copy / path.name)
            copies[folder] = copy
    return copies


def _study_tolerances(module):
    """A study's per-column tolerances, ``RESULT_TOLERANCES`` (none if it states none)."""
    return dict(getattr(module, "RESULT_TOLERANCES", None) or {})


def _print_replaced(copies, module):
    """How each folder a run wrote compares with the files it replaced (a report only)."""
    if not copies:
        return
    from aircraft.result_comparison import compare_folders
    for folder, copy in copies.items():
        if not folder.is_dir():
            continue
        try:
            result = compare_folders(copy, folder, tolerances=_study_tolerances(module))
        except (OSError, ValueError) as exc:      # the comparison informs; it never fails a run
            print(f"\n[rotorwake] {folder}: not compared with the files this run replaced ({exc})")
            continue
        print(f"\n[rotorwake] {folder}: compared with the files this run replaced")
        print(result.report(max_rows=10), flush=True)


def _out_under(study, root):
    """The ``--out`` value that puts ``study``'s folders under the results root ``root``."""
    return str(root) if study.default_out == "results" else str(Path(root) / Path(study.default_out).name)


def run_study(name, argv, *, stream=sys.stderr):
    """Run one study through its ``main`` and write the manifests of its folders.

    Where a folder it writes existed before, its tables and text files are copied
    aside first and, after the run, compared with what the run wrote
    (:func:`aircraft.result_comparison.compare_folders`, with the study's
    ``RESULT_TOLERANCES``); the report is printed under "compared with the files
    this run replaced". It never changes the outcome of the run.

    Parameters
    ----------
    name : str
        Command name, a key of :data:`STUDIES`.
    argv : list of str
        Options passed on to the study.
    stream : file-like
        Where the long-run notice goes.

    Returns
    -------
    float
        Wall time [s].
    """
    study = STUDIES[name]
    minutes, folders, note = _plan(study, argv)
    asks_help = any(a in ("-h", "--help") for a in argv)
    if minutes >= 1 and not asks_help:
        print(f"[rotorwake] {name}: a long run, {_minutes(minutes)} on 2 cores"
              + (f"; {note}" if note else "") + ".", file=stream, flush=True)
    if asks_help:
        print(f"rotorwake {name}: {study.summary}\n  {_minutes(minutes)} on 2 cores; writes "
              + ", ".join(str(f) for f in folders) + " with manifest.json\n")
    before = tempfile.mkdtemp(prefix="rotorwake-replaced-")
    try:
        copies = {} if asks_help else _snapshot(folders, before)
        module, wall = _run_and_record(name, study, argv, folders, asks_help)
        _print_replaced(copies, module)
    finally:
        shutil.rmtree(before, ignore_errors=True)
    return wall


def _run_and_record(name, study, argv, folders, asks_help):
    """Run the study's ``main`` and write the manifests: (study module, wall time [s])."""
    t0 = time.perf_counter()
    loaded_before = set(sys.modules)
    module = importlib.import_module(study.module)
    params = list(inspect.signature(module.main).parameters)
    if params and params[0] == "argv" and asks_help:
        with _help_shows_defaults(f"rotorwake {name}"):
            module.main(list(argv))
    elif params and params[0] == "argv":
        module.main(list(argv))
    else:
        # studies whose main takes keyword options: the command line offers --out
        parser = argparse.ArgumentParser(prog=f"rotorwake {name}", description=study.summary,
                                         formatter_class=argparse.ArgumentDefaultsHelpFormatter)
        parser.add_argument("--out", default=study.default_out, help="results folder")
        module.main(out_dir=parser.parse_args(argv).out)
    wall = time.perf_counter() - t0
    from aircraft.provenance import import_closure, imported_sources, write_manifest
    # where the results go does not change them: --out stays out of the settings hash
    settings = {"command": name, "options": _without_out(argv)}
    # the code this study can have run: its static import closure and what it newly
    # imported (dynamic imports), not whatever earlier studies of `rotorwake results`
    # left in sys.modules
    used = set(import_closure(study.module)) | (set(sys.modules) - loaded_before)
    sources = imported_sources(modules=sorted(used))
    for folder in folders:
        if folder.is_dir():
            write_manifest(folder, command=f"rotorwake {name} " + " ".join(argv), settings=settings,
                           wall_time_s=wall, sources=sources)
    return module, wall


def _check(results):
    from aircraft.provenance_check import check_results
    table = check_results(results)
    if table.empty:
        print(f"no results folders under {results}/")
        return 1
    import pandas as pd
    with pd.option_context("display.max_colwidth", 90, "display.width", 200):
        print(table.to_string(index=False))
    print("(versions: the numerical packages of each run against those installed now; reported only, "
          "a difference does not make a folder stale)")
    bad = table[table.status != "fresh"]
    if len(bad):
        print(f"\n{len(bad)} of {len(table)} results folders are not fresh: run `make results` "
              "(or `rotorwake results --stale`) and commit them.")
        return 1
    print(f"\nall {len(table)} results folders are what the current code produces")
    return 0


def main(argv=None):
    """Entry point of the ``rotorwake`` console script.

    Parameters
    ----------
    argv : list of str, optional
        Command line without the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status (0: success).
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    args, rest = _parser().parse_known_args(argv)
    if args.command in STUDIES:
        run_study(args.command, rest)
        return 0
    if rest:
        _parser().error(f"unrecognised arguments: {' '.join(rest)}")
    if args.command == "shipped-models":
        return _shipped_models(args)
    if args.command == "reproduce":
        return _reproduce(args)
    if args.command == "check-results":
        if args.upgrade:
            from aircraft.provenance_check import upgrade_manifests
            upgraded = upgrade_manifests(args.results)
            print(f"upgraded {len(upgraded)} manifest(s) to code digests: {', '.join(upgraded) or 'none'}")
        if args.record_kernel_backend:
            from aircraft.provenance_check import record_kernel_backend
            marked = record_kernel_backend(args.results, args.record_kernel_backend)
            print(f"recorded kernel backend {args.record_kernel_backend!r} in {len(marked)} manifest(s): "
                  f"{', '.join(marked) or 'none'}")
        return _check(args.results)
    # results: regenerate every committed folder with the options it was computed with
    names = args.only or [n for n, s in STUDIES.items() if s.in_results]
    if args.stale:
        from aircraft.provenance_check import check_results
        table = check_results("results")
        stale = {row.folder for row in table.itertuples() if row.status != "fresh"}
        names = [n for n in names if any(f.name in stale for f in _plan(STUDIES[n], [])[1])]
    options = {n: committed_options(n) for n in names}
    total = sum(_plan(STUDIES[n], options[n])[0] for n in names)
    print("[rotorwake] results: " + (", ".join(f"{n} {' '.join(options[n])}".strip() for n in names)
                                     or "nothing to do") + f" ({_minutes(total)} on 2 cores)",
          file=sys.stderr, flush=True)
    for name in names:
        run_study(name, options[name])
    return 0


def hover_study(argv=None):
    """Entry point of the older ``rotorwake-hover-study`` console script: ``rotorwake main``.

    It runs through the command line like every study, so it takes the same BLAS
    kernels, writes the same manifests and prints the same comparison.

    Parameters
    ----------
    argv : list of str, optional
        Options of ``rotorwake main`` (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status (0: success).
    """
    return main(["main", *(sys.argv[1:] if argv is None else argv)])


def committed_options(name, results="results"):
    """The options the committed results of study ``name`` were computed with.

    Read from the ``manifest.json`` of the study's first results folder under
    ``results`` (``settings.options``), so ``rotorwake results`` reproduces what is
    committed -- e.g. ``off-rotor-models --coarse`` -- rather than the study's
    defaults. ``[]`` (the defaults) when there is no readable manifest yet.

    Parameters
    ----------
    name : str
        Command name, a key of :data:`STUDIES`.
    results : str or pathlib.Path
        Folder with one sub-folder per study (what ``--out`` the study's outputs
        are relative to).
    """
    from aircraft.provenance import ResultsManifestError, read_manifest
    study = STUDIES[name]
    folder = Path(study.outputs[0].format(out=_out_under(study, results)))
    try:
        options = read_manifest(folder)["settings"]["options"]
    except (ResultsManifestError, KeyError, TypeError):
        return []
    if not (isinstance(options, list) and all(isinstance(o, str) for o in options)):
        return []
    return list(options)


def _rerun_of(reference):
    """``((command, options), None)`` of the run that wrote folder ``reference``, or
    ``(None, why not)``."""
    from aircraft.provenance import ResultsManifestError, read_manifest
    try:
        manifest = read_manifest(reference)
    except ResultsManifestError as exc:
        return None, str(exc)
    settings = manifest.get("settings") or {}
    command, options = settings.get("command"), settings.get("options", [])
    if command not in STUDIES:
        return None, (f"{reference} was not written by a rotorwake study (its manifest records "
                      f"{manifest.get('command')!r}); rerun it as that says")
    if not (isinstance(options, list) and all(isinstance(o, str) for o in options)):
        return None, f"{reference}/manifest.json records no readable options: {options!r}"
    planned = sorted(f.name for f in _plan(STUDIES[command], options)[1])
    if reference.name not in planned:
        return None, (f"{reference}: `rotorwake {command} {' '.join(options)}` writes "
                      f"{', '.join(planned)}, not {reference.name}")
    return (command, tuple(options)), None


def _inside(path, folder):
    path, folder = Path(path).resolve(), Path(folder).resolve()
    return path == folder or folder in path.parents


def _reproduce(args):
    """``rotorwake reproduce``: rerun the study of each folder and compare it with the rerun."""
    from aircraft.result_comparison import Tolerance, compare_folders
    try:
        default = Tolerance(args.rtol, args.atol)
    except ValueError as exc:
        _parser().error(str(exc))
    runs, problems = {}, []
    for name in dict.fromkeys(args.folders):
        reference = Path(args.results) / name
        reference = reference if reference.is_dir() else Path(name)
        if not reference.is_dir():
            problems.append(f"no results folder {name!r} under {args.results}/ (nor at that path)")
            continue
        run, why = _rerun_of(reference)
        if why:
            problems.append(why)
        else:
            runs.setdefault(run, []).append(reference)
    if problems:
        print("rotorwake reproduce: " + "\n  ".join(problems), file=sys.stderr)
        return 2
    keep = getattr(args, "keep", None)
    committed = {Path(args.results)} | {ref.parent for refs in runs.values() for ref in refs}
    if keep and any(_inside(keep, folder) for folder in committed):
        _parser().error(f"--keep {keep} lies inside the committed results: reproduce never writes there")
    root = Path(keep) if keep else Path(tempfile.mkdtemp(prefix="rotorwake-reproduce-"))
    minutes = sum(_plan(STUDIES[command], list(options))[0] for command, options in runs)
    print("[rotorwake] reproduce: " + ", ".join(f"rotorwake {c} {' '.join(o)}".strip() for c, o in runs)
          + f" into {root} ({_minutes(minutes)} on 2 cores)", file=sys.stderr, flush=True)
    failed = []
    try:
        for (command, options), references in runs.items():
            study = STUDIES[command]
            argv = list(options) + ["--out", _out_under(study, root)]
            run_study(command, argv)
            reruns = {f.name: f for f in _plan(study, argv)[1]}
            tolerances = _study_tolerances(sys.modules[study.module])
            for reference in references:
                rerun = reruns[reference.name]
                print(f"\n[rotorwake] reproduce {reference}: against a rerun of "
                      f"`{' '.join(['rotorwake', command, *options])}`")
                if not rerun.is_dir():
                    print(f"the rerun wrote no folder {rerun}")
                    failed.append(str(reference))
                    continue
                result = compare_folders(reference, rerun, tolerances=tolerances, default=default)
                print(result.report(max_rows=20), flush=True)
                if not result.passes:
                    failed.append(str(reference))
    finally:
        if not keep:
            shutil.rmtree(root, ignore_errors=True)
    done = sum(len(refs) for refs in runs.values())
    print(f"\n[rotorwake] reproduce: {done - len(failed)} of {done} folder(s) reproduced within tolerance"
          + (f"; moved or missing in: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
