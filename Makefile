# Two set-up commands (see README):
#   make study   -> creates .venv if needed, installs the package, runs the main job
#   make test    -> creates .venv if needed, installs the package + test extra, runs pytest
# Others:
#   make results        regenerate every committed results/ folder with its recorded options (~1 h warm cache)
#   make check-results  say which committed results the current code no longer produces
#   make docs           the Sphinx site in docs/_build/html (warnings are errors)
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python
STAMP   = $(VENV)/.installed
DOCS_STAMP = $(VENV)/.installed-docs

.PHONY: study test bench results check-results docs clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test]"
	touch $(STAMP)

$(DOCS_STAMP): $(STAMP)
	$(PY) -m pip install --quiet -e ".[test,docs]"
	touch $(DOCS_STAMP)

study: $(STAMP)
	MPLBACKEND=Agg $(PY) -m studies.cli main

# one numba thread per pytest worker: two workers already fill the two CI cores; work stealing
# keeps both busy to the end (a few minute-long design tests otherwise leave one idle: 550 -> 419 s)
test: $(STAMP)
	MPLBACKEND=Agg NUMBA_NUM_THREADS=1 $(PY) -m pytest -n 2 --dist worksteal -q

bench: $(STAMP)
	MPLBACKEND=Agg $(PY) benchmarks/identification.py
	MPLBACKEND=Agg $(PY) benchmarks/wake.py
	MPLBACKEND=Agg $(PY) benchmarks/dmo.py
	MPLBACKEND=Agg $(PY) benchmarks/coaxial_forward_refit.py

results: $(STAMP)
	MPLBACKEND=Agg $(PY) -m studies.cli results

check-results: $(STAMP)
	$(PY) -m studies.cli check-results

docs: $(DOCS_STAMP)
	MPLBACKEND=Agg $(PY) -m sphinx -W --keep-going -q -b html docs docs/_build/html

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache docs/_build
