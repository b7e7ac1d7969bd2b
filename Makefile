# Two commands for a fresh clone (README): `make run` and `make test`.
# Each creates the virtual environment and installs what it needs.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
ROSS_VENV := .venv-ross
# The versions CI passed: every install takes its packages from these lock files (`make lock`).
LOCK := constraints.txt
LOCK_VENV := build/lock-venv

.PHONY: run test test-ross lint api bench mutation lock clean

$(STAMP): pyproject.toml $(LOCK)
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c $(LOCK) -e '.[dev]'
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/foilbearing study --out out

# The suite on every core (pytest-xdist), each test file on one worker: its module-scoped
# fixtures run once. On 2 cores it takes about 5 minutes instead of 9.5. Line coverage is
# measured and printed ([tool.coverage] in pyproject.toml); under 90 % the target fails.
test: $(STAMP)
	bash scripts/setup_chromium.sh
	$(BIN)/python -m pytest -q -n auto --dist loadfile --durations=15 --cov --cov-report=term

# The ROSS export needs ROSS >= 3.0, hence Python >= 3.13: a second venv (scripts/setup_ross_env.sh).
# Its coverage data goes to build/: CI runs it beside the main suite, whose data is .coverage.
test-ross:
	bash scripts/setup_ross_env.sh
	mkdir -p build
	COVERAGE_FILE=build/.coverage-ross $(ROSS_VENV)/bin/python -m pytest -q -p no:cacheprovider tests/test_ross.py --cov=foilbearing.export \
		--cov-config=scripts/coverage-ross.toml --cov-report=term-missing

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks scripts examples
	$(BIN)/ruff format --check src tests benchmarks scripts examples
	$(BIN)/mypy

# The HTML API reference, generated from the docstrings (numpydoc) by pdoc, into build/api.
api: $(STAMP)
	rm -rf build/api
	$(BIN)/pdoc -d numpy --no-show-source -o build/api foilbearing \
		$$(cd src && ls -d foilbearing/*/ foilbearing/*.py | grep -v '__\|cases\|data' \
		| sed 's#/$$##; s#\.py$$##; s#/#.#g')
	@echo "API reference: build/api/index.html"

bench: $(STAMP)
	for f in benchmarks/bench_*.py; do $(BIN)/python $$f || exit 1; done

# Mutation testing of the physics in Python, on demand (minutes; not part of CI).
mutation: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[dev,mutation]'
	rm -rf mutants  # mutmut caches which tests reach which function: start afresh
	$(BIN)/mutmut run --max-children 2
	$(BIN)/mutmut export-cicd-stats
	$(BIN)/python scripts/mutation_report.py

# Refresh the lock files from pyproject's ranges: the newest versions the registry offers, in a
# fresh venv for each (the ROSS one on Python 3.13). Then run .ci/run before committing them.
lock:
	rm -rf $(LOCK_VENV)
	$(PYTHON) -m venv $(LOCK_VENV)
	$(LOCK_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(LOCK_VENV)/bin/python -m pip install --quiet -e '.[dev]'
	{ echo "# The versions CI passed, for $$($(LOCK_VENV)/bin/python -V). Refresh: make lock, then .ci/run."; \
	  $(LOCK_VENV)/bin/python -m pip freeze --exclude-editable; } > $(LOCK)
	rm -rf $(LOCK_VENV)
	bash scripts/setup_ross_env.sh --lock
	touch $(STAMP) 2>/dev/null || true

clean:
	rm -rf $(VENV) $(ROSS_VENV) out build mutants .pytest_cache .mypy_cache
