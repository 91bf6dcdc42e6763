# The two set-up commands of the README (`make demo`, `make test`) and the developer targets.
# Each bootstraps .venv with the project and its dev extras when it is missing or stale.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.rosaadl-installed
DEMO_OUT ?= demo-out

.PHONY: demo test bench lint venv clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

venv: $(STAMP)

demo: $(STAMP)
	$(BIN)/rosaadl demo -o $(DEMO_OUT)

test: $(STAMP)
	$(BIN)/python -m pytest -q

bench: $(STAMP)
	$(BIN)/python -m benchmarks $(BENCH)

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/python tests/layers.py
	$(BIN)/ruff format --check --diff . || true

clean:
	rm -rf $(VENV) $(DEMO_OUT) build *.egg-info
