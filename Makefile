# Two commands for a fresh clone (README): `make run` and `make test`.
# Each creates the virtual environment and installs what it needs: one venv on Python >= 3.13
# with foilbearing[dev,ross,docs] (scripts/setup_venv.sh finds the interpreter; PYTHON=... names one).
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
# The versions CI passed: every install takes its packages from this lock file (`make lock`).
LOCK := constraints.txt

.PHONY: run test docs-check lint api docs bench mutation lock clean

$(STAMP): pyproject.toml $(LOCK)
	bash scripts/setup_venv.sh

run: $(STAMP)
	$(BIN)/foilbearing study --out out

# The suite on every core (pytest-xdist), each test file on one worker: its module-scoped
# fixtures run once. On 2 cores it takes about 5 minutes instead of 9.5. Line coverage is
# measured and printed ([tool.coverage] in pyproject.toml); under 90 % the target fails.
test: $(STAMP)
	bash scripts/setup_chromium.sh
	$(BIN)/python -m pytest -q -n auto --dist loadfile --durations=15 --cov --cov-report=term -m "not browser"

# The docs site loaded page by page in headless Chromium (tests/test_docs.py, marker
# browser), alone on the machine: CI runs it after `make test`, on the site that one built
# (FOILBEARING_DOCS_SITE, set by .ci/run).
docs-check: $(STAMP)
	bash scripts/setup_chromium.sh
	$(BIN)/python -m pytest -q -p no:cacheprovider -m browser tests/test_docs.py

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks scripts examples docs
	$(BIN)/ruff format --check src tests benchmarks scripts examples docs
	$(BIN)/mypy

# The HTML API reference, generated from the docstrings (numpydoc) by pdoc, into build/api.
api: $(STAMP)
	rm -rf build/api
	$(BIN)/pdoc -d numpy --no-show-source -o build/api foilbearing \
		$$(cd src && ls -d foilbearing/*/ foilbearing/*.py | grep -v '__\|cases\|data' \
		| sed 's#/$$##; s#\.py$$##; s#/#.#g')
	@echo "API reference: build/api/index.html"

# The documentation site (docs/, Sphinx + MyST + sphinx-gallery) into build/docs, warnings as
# errors; the tutorials and the gallery run during the build (coarse grids: about a minute).
docs: $(STAMP)
	rm -rf build/docs build/docs-doctrees docs/generated docs/api/generated
	$(BIN)/sphinx-build -b html -W --keep-going -q -d build/docs-doctrees docs build/docs
	@echo "Documentation: build/docs/index.html"

bench: $(STAMP)
	for f in benchmarks/bench_*.py; do $(BIN)/python $$f || exit 1; done

# Mutation testing of the physics in Python, on demand (minutes; not part of CI).
mutation: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[dev,mutation]'
	rm -rf mutants  # mutmut caches which tests reach which function: start afresh
	$(BIN)/mutmut run --max-children 2
	$(BIN)/mutmut export-cicd-stats
	$(BIN)/python scripts/mutation_report.py

# Refresh the lock file from pyproject's ranges: the newest versions the registry offers, in a
# fresh venv (Python >= 3.13). Then run .ci/run before committing it.
lock:
	bash scripts/setup_venv.sh --lock

clean:
	rm -rf $(VENV) out build mutants .pytest_cache .mypy_cache docs/generated docs/api/generated
