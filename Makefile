# Two entry points, each sets itself up from nothing:
#   make run   - create .venv, install reportgen, run the lecture pack configs/ -> output/
#   make test  - create .venv with the test extras (+ chromium and poppler for the
#                browser/PDF checks), lint, and run the test suite
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
SUDO   := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: run test setup setup-test system-test-deps lint clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip

# The package is installed editable, which compiles none of its modules; compiling them
# once here spares every reportgen command about 0.1 s of compiling them again (this
# matters where PYTHONDONTWRITEBYTECODE is set: Python then never writes them itself).
setup: $(BIN)/python
	$(BIN)/pip install --quiet -e .
	$(BIN)/python -m compileall -q reportgen

setup-test: $(BIN)/python system-test-deps
	$(BIN)/pip install --quiet -e ".[test]"
	$(BIN)/python -m compileall -q reportgen

# Debian's chromium (real-browser report test) and poppler-utils (PDF rasterizing test).
system-test-deps:
	@if ! command -v chromium >/dev/null || ! command -v pdftoppm >/dev/null; then \
	  if command -v apt-get >/dev/null; then \
	    $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq chromium poppler-utils >/dev/null; \
	  else echo "note: no apt-get; the browser and PDF-raster tests will be skipped"; fi; \
	fi

run: setup
	$(BIN)/reportgen run configs/ --out output

lint: setup-test
	$(BIN)/ruff check reportgen tests benchmarks docs

test: setup-test lint
	$(BIN)/python -m pytest -q --durations=25

clean:
	rm -rf $(VENV) output/*/ output/index.html
