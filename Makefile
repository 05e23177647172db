# Two set-up commands (see README):
#   make study   -> creates .venv if needed, installs the package, runs the main job
#   make test    -> creates .venv if needed, installs the package + test extra, runs pytest
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python
STAMP   = $(VENV)/.installed

.PHONY: study test bench clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test]"
	touch $(STAMP)

study: $(STAMP)
	MPLBACKEND=Agg $(PY) -m studies.hover_control_comparison

# one numba thread per pytest worker: two workers already fill the two CI cores
test: $(STAMP)
	MPLBACKEND=Agg NUMBA_NUM_THREADS=1 $(PY) -m pytest -n 2 -q

bench: $(STAMP)
	MPLBACKEND=Agg $(PY) benchmarks/identification.py
	MPLBACKEND=Agg $(PY) benchmarks/wake.py
	MPLBACKEND=Agg $(PY) benchmarks/dmo.py

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
