# axiscal: every target sets up what it needs on a fresh machine.
PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed-stamp
OUT    ?= demo-output

.PHONY: setup sysdeps demodeps linuxcnc demo test bench fuzz shots docs clean

setup: $(STAMP)

# Debian packages: WeasyPrint (PDF certificates) needs Pango and HarfBuzz (and Noto CJK so a
# Chinese, Japanese or Korean name on a certificate renders), the tests render PDF
# pages with pdftoppm (poppler-utils), the history tests run on a real throw-away PostgreSQL
# (tools/pgtest.py starts one per test process in a temporary folder), and the workbench's
# browser tests drive Chromium with its driver (Selenium). Installed when missing.
# The demo needs only what its PDF certificates need (DEMO_DEBS: Pango, HarfBuzz and fonts).
DEMO_DEBS := libpango-1.0-0 libpangoft2-1.0-0 libharfbuzz-subset0 fonts-dejavu-core fonts-noto-cjk
DEBS := $(DEMO_DEBS) poppler-utils postgresql chromium chromium-driver
APT := $(if $(filter 0,$(shell id -u)),,sudo) env DEBIAN_FRONTEND=noninteractive apt-get
# $(call apt_missing,PACKAGES): install those of PACKAGES that are missing (Debian only).
define apt_missing
	@command -v dpkg >/dev/null || { echo "not Debian: install $(1) yourself"; exit 0; }; \
	missing=""; for p in $(1); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(APT) update -qq && $(APT) install -y -qq $$missing >/dev/null; \
	fi
endef
sysdeps:
	$(call apt_missing,$(DEBS))
demodeps:
	$(call apt_missing,$(DEMO_DEBS))

# LinuxCNC (issue 32): the real controller the compensation loop is proven on, run headless in
# simulation by the tests (tests/instruments/test_linuxcnc_live.py,
# tests/compensation/test_on_linuxcnc.py). From Debian WITHOUT its
# recommends (they pull a real-time kernel); about 3 minutes and 1.3 GB once. Its Python modules
# (linuxcnc, hal) live in /usr/lib/python3/dist-packages: a .pth file in the venv names a shim
# folder holding links to those modules only, so nothing else of the system's Python leaks in.
LINUXCNC_DEBS := linuxcnc-uspace
LINUXCNC_PY   := /usr/lib/python3/dist-packages
LINUXCNC_SHIM := $(VENV)/linuxcnc-shim
linuxcnc: $(STAMP)
	@command -v dpkg >/dev/null || { echo "not Debian: LinuxCNC tests will say why they did not run"; exit 0; }; \
	dpkg -s $(LINUXCNC_DEBS) >/dev/null 2>&1 || { echo "installing $(LINUXCNC_DEBS) (no recommends)"; \
	  $(APT) update -qq && $(APT) install -y -qq --no-install-recommends $(LINUXCNC_DEBS) >/dev/null; }; \
	mkdir -p $(LINUXCNC_SHIM) && for m in hal.py _hal.cpython-*.so linuxcnc.cpython-*.so; do \
	  for f in $(LINUXCNC_PY)/$$m; do [ -e "$$f" ] && ln -sf "$$f" $(LINUXCNC_SHIM)/; done; done; \
	site=$$($(PY) -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])'); \
	echo "$$(cd $(LINUXCNC_SHIM) && pwd)" > "$$site/axiscal-linuxcnc.pth"

$(STAMP): pyproject.toml | sysdeps
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

# The demo installs axiscal with its [report] extra only (WeasyPrint, for the PDF certificates):
# not the test tools, the workbench, PostgreSQL or Chromium of [dev] and `make test`.
DEMO_STAMP := $(VENV)/.demo-stamp
$(DEMO_STAMP): pyproject.toml | demodeps
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[report]"
	touch $(DEMO_STAMP)

demo: $(DEMO_STAMP)
	$(VENV)/bin/axiscal demo --out $(OUT)

# Three workers: the LinuxCNC tests run on one of them (conftest.py), mostly waiting for
# LinuxCNC; the other two compute the rest (about 9 min instead of 14 with two). Under that load
# LinuxCNC 2.9's task process can end or lose an MDI line: LinuxCNC.mdi starts the session again
# or sends the line again, with a LinuxCNCRecovery warning (listed at the end of the run, -rw).
test: $(STAMP) sysdeps linuxcnc
	$(PY) -m pytest -n 3 --dist loadgroup -q -rw

bench: $(STAMP) sysdeps
	$(PY) benchmarks/run.py

# Every hostile case the CLI fuzz harness derives from the interface (make test runs a seeded
# sample of them); prints the count of cases and commands covered and every fault found.
fuzz: $(STAMP) sysdeps
	$(PY) tests/cli/test_cli_fuzz.py --workers 2

# Render the demo report to PNG with headless Chromium (installed from Debian if missing),
# so a person can look at what a customer would see.
shots: demo sysdeps
	$(PY) tools/screenshot.py $(OUT)

# The documentation site (docs/, Sphinx): the gallery's examples run, the CLI and file-format pages
# are generated from the program; a warning fails the build (-W); every example must have drawn
# its figure. Open docs/_build/html/index.html.
DOCS_STAMP := $(VENV)/.docs-stamp
$(DOCS_STAMP): pyproject.toml | $(STAMP)
	$(PY) -m pip install --quiet -e ".[docs]"
	touch $(DOCS_STAMP)
docs: $(DOCS_STAMP)
	MPLBACKEND=Agg $(PY) -m sphinx -W --keep-going -b html docs docs/_build/html
	$(PY) docs/check_gallery.py docs

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache .hypothesis
