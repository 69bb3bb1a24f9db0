# axiscal: every target sets up what it needs on a fresh machine.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed-stamp
OUT    ?= demo-output

.PHONY: setup sysdeps demo test bench shots clean

setup: $(STAMP)

# WeasyPrint (PDF certificates) needs Pango and HarfBuzz from the system, the tests render PDF
# pages with pdftoppm (poppler-utils); installed from Debian when missing.
DEBS := libpango-1.0-0 libpangoft2-1.0-0 libharfbuzz-subset0 fonts-dejavu-core poppler-utils
sysdeps:
	@command -v dpkg >/dev/null || { echo "not Debian: install Pango and poppler-utils yourself"; exit 0; }; \
	missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	fi

$(STAMP): pyproject.toml | sysdeps
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/axiscal demo --out $(OUT)

test: $(STAMP)
	$(PY) -m pytest -n 2 -q

bench: $(STAMP)
	$(PY) benchmarks/run.py

# Render the demo report to PNG with headless Chromium (installed from Debian if missing),
# so a person can look at what a customer would see.
shots: demo
	command -v chromium >/dev/null || (apt-get update -qq && apt-get install -y -qq chromium)
	$(PY) tools/screenshot.py $(OUT)

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache .hypothesis
