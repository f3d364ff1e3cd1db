# Hamta: `make demo` and `make test` work on a fresh Debian machine (apt-get needs root or sudo).
SHELL := /bin/bash
PYTHON ?= python3
SYSTEM_PYTHON := /usr/bin/python3
VENV := .venv
QVENV := .venv-qgis
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
APT_PACKAGES := qgis python3-qgis qgis-providers python3-numpy python3-scipy python3-opencv python3-rasterio \
	python3-pyproj python3-shapely python3-distributed python3-cryptography python3-pytest python3-hypothesis python3-venv python3-setuptools python3-wheel gdal-bin \
	qttools5-dev-tools pyqt5-dev-tools tesseract-ocr python3-pil fonts-dejavu-core
export PIP_DISABLE_PIP_VERSION_CHECK := 1
# The PyPI-wheels half has the 'learned' extra (its tests run there): torch's CPU build where this machine's
# pip finds one (PyPI's own torch for Linux is a CUDA build of several GB); TORCH=... chooses another.
TORCH ?= torch==2.13.0
# RapidOCR, the second engine that reads a sheet's labels (its models ship in its wheel): installed without its
# dependencies, which name opencv-python, a second OpenCV over opencv-python-headless; its others are listed.
RAPIDOCR := rapidocr_onnxruntime==1.4.4
RAPIDOCR_DEPS := onnxruntime pyclipper pyyaml six tqdm

.PHONY: demo test lint test-wheels test-debian sysdeps i18n bench fuzz package clean

demo: $(VENV)/.ok
	$(VENV)/bin/hamta demo --out demo-output

# The two halves run side by side (each keeps about one of two cores busy); each one's output is
# printed whole when it ends. HAMTA_TEST_HALF shares the cases of tests marked 'split' between them.
test: $(VENV)/.learned $(VENV)/.ocr $(QVENV)/.ok
	$(MAKE) --no-print-directory lint
	$(MAKE) --no-print-directory -j2 --output-sync=target test-wheels test-debian

lint: $(VENV)/.ok
	$(VENV)/bin/ruff check .

# Core suite on current PyPI wheels (numpy 2, OpenCV 5, shapely 2, rasterio with its own GDAL) and the
# 'learned' extra; the labels read by Tesseract (Debian's) and RapidOCR.
test-wheels: $(VENV)/.learned $(VENV)/.ocr
	HAMTA_TEST_HALF=0 $(VENV)/bin/python -P -m pytest tests/core -q -rs --durations=15

# Core and QGIS suites on Debian's packages, in the interpreter QGIS embeds (numpy 1.24, OpenCV 4.6, ...);
# the wheel build, the end-to-end benchmark (make bench runs there), the tests that interrupt, kill or race
# whole processes and the hostile-server matrix (stack-independent) run on the PyPI-wheels half only.
test-debian: $(QVENV)/.ok
	HAMTA_TEST_HALF=1 $(QVENV)/bin/python -P -m pytest tests -q -rs --durations=15 -m "not packaging and not bench and not processes and not hostile"

bench: $(VENV)/.ok
	$(VENV)/bin/hamta bench

# The QGIS plugin zip for Plugins > Manage and Install Plugins > Install from ZIP: dist/hamta-<version>.zip
# (git-tracked plugin files only; see tools/package.py).
package:
	$(PYTHON) tools/package.py

# The long fuzzing profile: 2,000 rasters per method family (and 2,000 parameter sets and reports), two
# families at a time, then 2,000 map-server answers (tests/core/test_fuzz_server.py); outcomes are tallied
# from fuzz-output/*.jsonl at the end (hours on 2 cores).
# FUZZ_EXAMPLES=200 gives a shorter run.
FUZZ_FAMILIES := opencv rilbp sibrif sar structural phase auto inputs
FUZZ_EXAMPLES ?= 2000
fuzz: $(VENV)/.ok
	@mkdir -p fuzz-output && rm -f fuzz-output/*.jsonl
	@printf '%s\n' $(FUZZ_FAMILIES) | xargs -P 2 -I{} sh -c 'HYPOTHESIS_PROFILE=long HAMTA_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) HAMTA_FUZZ_FAMILY={} \
		HAMTA_FUZZ_LOG=fuzz-output/{}.jsonl $(VENV)/bin/python -P -m pytest tests/core/test_fuzz.py -q \
		-k "$$( [ {} = inputs ] && echo "parameter or map_points or georeferencing" || echo any_raster )" > fuzz-output/{}.log 2>&1; \
		echo "fuzz {}: pytest exit $$? (fuzz-output/{}.log)"'
	@HYPOTHESIS_PROFILE=long HAMTA_FUZZ_EXAMPLES=$(FUZZ_EXAMPLES) HAMTA_FUZZ_LOG=fuzz-output/server.jsonl \
		$(VENV)/bin/python -P -m pytest tests/core/test_fuzz_server.py -q > fuzz-output/server.log 2>&1; \
		echo "fuzz server (map-server answers): pytest exit $$? (fuzz-output/server.log)"
	$(VENV)/bin/python tools/fuzz_summary.py fuzz-output/*.jsonl

$(VENV)/.ok: pyproject.toml
	@$(PYTHON) -m venv --help >/dev/null 2>&1 && $(PYTHON) -c "import ensurepip" 2>/dev/null || \
		{ $(SUDO) apt-get update -q && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -q python3-venv python3-pip; }
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install -q -e '.[test]'
	touch $@

$(VENV)/.learned: $(VENV)/.ok
	$(VENV)/bin/pip install -q '$(TORCH)'
	$(VENV)/bin/pip install -q -e '.[test,learned]'
	touch $@

$(VENV)/.ocr: $(VENV)/.ok
	$(VENV)/bin/pip install -q $(RAPIDOCR_DEPS)
	$(VENV)/bin/pip install -q --no-deps $(RAPIDOCR)
	touch $@

sysdeps:
	@dpkg -s $(APT_PACKAGES) >/dev/null 2>&1 || { \
		$(SUDO) apt-get update -q && \
		$(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $(APT_PACKAGES); }

# Debian's interpreter with Debian's packages only: --no-deps keeps pip wheels out of the QGIS process.
$(QVENV)/.ok: pyproject.toml | sysdeps
	$(SYSTEM_PYTHON) -m venv --system-site-packages $(QVENV)
	$(QVENV)/bin/pip install -q --no-deps --no-build-isolation -e .
	mkdir -p $(QVENV)/share && ln -sfn /usr/share/proj $(QVENV)/share/proj
	touch $@

# Collect new strings into the .ts files (existing translations are kept), then compile them.
i18n: sysdeps $(QVENV)/.ok
	$(QVENV)/bin/python -P tools/i18n_strings.py > i18n/core_strings.py
	pylupdate5 processing/*.py plugin/*.py i18n/core_strings.py -ts i18n/hamta_fa.ts i18n/hamta_en.ts
	lrelease -silent i18n/*.ts

clean:
	rm -rf $(VENV) $(QVENV) demo-output bench-output fuzz-output *.egg-info
