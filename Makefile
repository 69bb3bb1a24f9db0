# axiscal: every target sets up what it needs on a fresh machine.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed-stamp
OUT    ?= demo-output

.PHONY: setup sysdeps demo test bench shots clean

setup: $(STAMP)

# Debian packages: WeasyPrint (PDF certificates) needs Pango and HarfBuzz (and Noto CJK so a
# Chinese, Japanese or Korean name on a certificate renders), the tests render PDF
# pages with pdftoppm (poppler-utils), the history tests run on a real throw-away PostgreSQL
# (tools/pgtest.py starts one per test process in a temporary folder), and the workbench's
# browser tests drive Chromium with its driver (Selenium). Installed when missing.
DEBS := libpango-1.0-0 libpangoft2-1.0-0 libharfbuzz-subset0 fonts-dejavu-core fonts-noto-cjk \
        poppler-utils postgresql chromium chromium-driver
APT := $(if $(filter 0,$(shell id -u)),,sudo) env DEBIAN_FRONTEND=noninteractive apt-get
sysdeps:
	@command -v dpkg >/dev/null || { echo "not Debian: install $(DEBS) yourself"; exit 0; }; \
	missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(APT) update -qq && $(APT) install -y -qq $$missing >/dev/null; \
	fi

$(STAMP): pyproject.toml | sysdeps
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/axiscal demo --out $(OUT)

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
