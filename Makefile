# Two commands for a fresh clone (README): `make run` and `make test`.
# Each creates the virtual environment and installs what it needs.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
ROSS_VENV := .venv-ross

.PHONY: run test test-ross lint api bench mutation clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

run: $(STAMP)
	$(BIN)/foilbearing study --out out

# The suite on every core (pytest-xdist), each test file on one worker: its module-scoped
# fixtures run once. On 2 cores it takes about 5 minutes instead of 9.5. Line coverage is
# measured and printed ([tool.coverage] in pyproject.toml); under 90 % the target fails.
test: $(STAMP)
	bash scripts/setup_chromium.sh
	$(BIN)/python -m pytest -q -n auto --dist loadfile --cov --cov-report=term

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

clean:
	rm -rf $(VENV) $(ROSS_VENV) out build mutants .pytest_cache .mypy_cache
