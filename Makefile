# axiscal: every target sets up what it needs on a fresh machine.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed-stamp
OUT    ?= demo-output

.PHONY: setup sysdeps demo test bench shots clean

setup: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/axiscal demo --out $(OUT)

# Debian packages the tests use: PostgreSQL, so the history tests run on a real throw-away server
# (tools/pgtest.py starts one per test process in a temporary folder and removes it), and
# Chromium with its driver for the workbench's browser tests (Selenium).
APT := $(if $(filter 0,$(shell id -u)),,sudo) env DEBIAN_FRONTEND=noninteractive apt-get
sysdeps:
	@if ! ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 || ! [ -x /usr/bin/chromium ] \
	    || ! [ -x /usr/bin/chromedriver ]; then \
	  echo "installing Debian's postgresql, chromium and chromium-driver (tests)"; \
	  $(APT) update -qq && $(APT) install -y -qq postgresql chromium chromium-driver >/dev/null; fi

test: $(STAMP) sysdeps
	$(PY) -m pytest -n 2 -q

bench: $(STAMP) sysdeps
	$(PY) benchmarks/run.py

# Render the demo report to PNG with headless Chromium (installed from Debian if missing),
# so a person can look at what a customer would see.
shots: demo sysdeps
	$(PY) tools/screenshot.py $(OUT)

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache .hypothesis
