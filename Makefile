# Two set-up commands (see README):
#   make study   -> creates .venv if needed, installs the package, runs the main job
#   make test    -> creates .venv if needed, installs the package + test extra, runs pytest
# Both install the exact versions pinned in constraints.txt (CPython >= 3.11).
# Others:
#   make results        regenerate every committed results/ folder with its recorded options (~1 h warm cache)
#   make check-results  say which committed results the current code no longer produces
#   make docs           the Sphinx site in docs/_build/html (warnings are errors)
#   make test-quick     the tests not marked slow (under 2 min on 2 cores): a developer's inner loop
#   make reproduce      rerun the main job into a temporary folder and compare it with the committed tables
#   make test-latest    the test suite against the newest releases, unpinned, in a fresh .venv-latest
#   make lock           re-resolve the newest releases into constraints.txt (a deliberate upgrade)
PYTHON ?= python3
VENV   ?= .venv
LATEST_VENV ?= .venv-latest
PY      = $(VENV)/bin/python
STAMP   = $(VENV)/.installed
DOCS_STAMP = $(VENV)/.installed-docs

# constraints.txt is resolved on this Python minor version: its pins are known to install there
# (and, wheels permitting, on newer ones), not on older ones, so the pinned targets refuse those
LOCK_PYTHON = 3.11
LOCK_TUPLE  = tuple(map(int, "$(LOCK_PYTHON)".split(".")))
CHECK_PYTHON = $(PYTHON) -c 'import sys; sys.exit(sys.version_info[:2] < $(LOCK_TUPLE) and "$(PYTHON) is Python %d.%d, but constraints.txt pins versions for CPython >= $(LOCK_PYTHON): use make PYTHON=python$(LOCK_PYTHON) ..., or make test-latest to test the newest versions on this Python" % sys.version_info[:2])'

# one numba thread per pytest worker: two workers already fill the two CI cores; work stealing
# keeps both busy to the end (a few minute-long design tests otherwise leave one idle: 550 -> 419 s)
TEST_ENV  = MPLBACKEND=Agg NUMBA_NUM_THREADS=1
TEST_ARGS = -m pytest -n 2 --dist worksteal -q

# the comment block `make lock` writes above the pins (the line saying where they were resolved follows it)
define LOCK_HEADER
# constraints.txt: the exact version of every distribution that
#     pip install -e ".[test,docs,cluster]"
# installs (the project itself left out), and of pip. pyproject.toml states what the code
# needs (lower bounds); this file records the one set of versions the tests and the committed
# results are checked with, so that a fresh machine gets the same environment.
# `make test`, `make study`, `make docs` and CI install exactly these (pip install -c
# constraints.txt) and stop on a Python older than $(LOCK_PYTHON).
# Newest versions instead: `make test-latest` runs the test suite against them in .venv-latest
# and lists the versions that differ from these.
# Regenerate (a deliberate upgrade: review the diff, then run `make test`): `make lock`.
endef
export LOCK_HEADER

.PHONY: study test test-quick test-latest lock bench results check-results reproduce docs clean

# a venv that also holds the docs extra gets it re-pinned too: the test that the environment is the
# pinned one looks at every pinned distribution installed, so stale docs versions would fail make test
comma := ,
$(STAMP): pyproject.toml constraints.txt
	@$(CHECK_PYTHON)
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet -c constraints.txt --upgrade pip
	$(PY) -m pip install --quiet -c constraints.txt -e ".[test$(if $(wildcard $(DOCS_STAMP)),$(comma)docs)]"
	touch $(STAMP)

$(DOCS_STAMP): $(STAMP) pyproject.toml constraints.txt
	$(PY) -m pip install --quiet -c constraints.txt -e ".[test,docs]"
	touch $(DOCS_STAMP)

study: $(STAMP)
	MPLBACKEND=Agg $(PY) -m studies.cli main

test: $(STAMP)
	$(TEST_ENV) $(PY) $(TEST_ARGS)

# the tests marked slow (each over about 3 s: designs, end-to-end studies, wake runs) left out
test-quick: $(STAMP)
	$(TEST_ENV) $(PY) $(TEST_ARGS) -m "not slow"

# what a user who upgrades would meet: a venv made afresh each time (so it really holds the newest
# releases), no constraints; it lists the versions that differ from the pins, then runs the same
# tests, with the check that the environment is the pinned one skipped
test-latest:
	rm -rf $(LATEST_VENV)
	$(PYTHON) -m venv $(LATEST_VENV)
	$(LATEST_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(LATEST_VENV)/bin/python -m pip install --quiet --upgrade -e ".[test]"
	$(LATEST_VENV)/bin/python tests/test_constraints.py
	ROTORWAKE_UNPINNED=1 $(TEST_ENV) $(LATEST_VENV)/bin/python $(TEST_ARGS)

# resolved on exactly $(LOCK_PYTHON), the oldest Python the lock serves, so that every pin installs on it;
# pip freeze leaves pip out, and pip is pinned too (the stamp installs it from the lock);
# written to a temporary file first, so a failed resolution leaves constraints.txt as it was
lock:
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info[:2] != $(LOCK_TUPLE) and "make lock resolves on CPython $(LOCK_PYTHON), the oldest Python the lock serves; $(PYTHON) is %d.%d: use make lock PYTHON=python$(LOCK_PYTHON)" % sys.version_info[:2])'
	set -e; tmp=$$(mktemp -d); trap 'rm -rf "$$tmp"' EXIT; \
	$(PYTHON) -m venv "$$tmp/venv"; \
	"$$tmp/venv/bin/python" -m pip install --quiet --upgrade pip; \
	"$$tmp/venv/bin/python" -m pip install --quiet -e ".[test,docs,cluster]"; \
	{ printf '%s\n' "$$LOCK_HEADER"; \
	  "$$tmp/venv/bin/python" -c 'import platform, pip; print(f"# Resolved on {platform.python_implementation()} {platform.python_version()}, {platform.system()} {platform.machine()}, with pip {pip.__version__}.")'; \
	  { "$$tmp/venv/bin/python" -m pip freeze --exclude-editable; "$$tmp/venv/bin/python" -m pip freeze --all | grep -i '^pip=='; } \
	  | "$$tmp/venv/bin/python" -c 'import sys; print(*sorted(sys.stdin.read().split(), key=lambda pin: pin.split("==")[0].lower()), sep="\n")'; \
	} > "$$tmp/constraints.txt"; \
	cp "$$tmp/constraints.txt" constraints.txt

bench: $(STAMP)
	MPLBACKEND=Agg $(PY) benchmarks/identification.py
	MPLBACKEND=Agg $(PY) benchmarks/wake.py
	MPLBACKEND=Agg $(PY) benchmarks/dmo.py
	MPLBACKEND=Agg $(PY) benchmarks/coaxial_forward_refit.py

results: $(STAMP)
	MPLBACKEND=Agg $(PY) -m studies.cli results

reproduce: $(STAMP)
	MPLBACKEND=Agg $(PY) -m studies.cli reproduce

check-results: $(STAMP)
	$(PY) -m studies.cli check-results

docs: $(DOCS_STAMP)
	MPLBACKEND=Agg $(PY) -m sphinx -W --keep-going -q -b html docs docs/_build/html

clean:
	rm -rf $(VENV) $(LATEST_VENV) build *.egg-info .pytest_cache docs/_build
