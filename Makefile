# The two commands of the README, and a few more. Every target installs what is missing first.
BUILD ?= build
JOBS  ?= 2

.PHONY: all deps configure build demo test refresh bench asan fuzz study corpus corpus-run blender-addon blender-screenshot clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release > $(BUILD).configure.log 2>&1 || (cat $(BUILD).configure.log; exit 1)

# Everything: the command, the tests, the benchmarks.
build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The demo needs the `shatter` command alone (about half of the objects `build` compiles).
demo: configure
	@cmake --build $(BUILD) -j $(JOBS) --target shatter
	@bash scripts/install-node-tools.sh $(BUILD)
	@bash scripts/demo.sh $(BUILD)

test: build
	@bash scripts/install-node-tools.sh $(BUILD)
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# After a change of behaviour: re-makes the pins, the pinned figures, the goldens, the scenes'
# sweeps and the generated pages, and says what moved and by how much (scripts/refresh.py).
refresh: build
	@/usr/bin/python3 scripts/refresh.py $(BUILD)

bench: build
	@bash scripts/bench.sh $(BUILD)

# The Blender add-on's .zip alone, BUILD/shatter_blender.zip (`build` makes it too; docs/blender.md).
blender-addon: configure
	@cmake --build $(BUILD) --target blender_addon

# The screenshot in docs/blender.md, made again: the add-on run in Blender's window on a virtual
# display (xvfb-run), the window saved to docs/images/blender-bunny.png.
blender-screenshot: blender-addon
	@cmake --build $(BUILD) -j $(JOBS) --target shatter
	@/usr/bin/python3 scripts/blender_screenshot.py $(BUILD) docs/images/blender-bunny.png

# Reliability (docs/reliability.md). asan: every test under AddressSanitizer + UBSan (gcc, -O1)
# in build-asan. fuzz: each libFuzzer target (clang) for FUZZ_SECONDS on its seed corpus.
FUZZ_SECONDS ?= 60
asan: deps
	@bash scripts/asan.sh build-asan $(JOBS)

fuzz: deps
	@bash scripts/fuzz.sh $(FUZZ_SECONDS) build-fuzz $(JOBS)

# The accuracy and cost study (docs/accuracy.md): CSV into bench/results/study, charts into docs/images.
# Then the continuum reference's checks against theory (fem_checks.md) and the rigid method against
# it on every scene (section 8; fem_SCENE.csv and the printed tables in fem_SCENE.md). Last, the
# results page docs/results/study.md from those files (scripts/study_tables.py; ctest
# Docs.StudyResults keeps it equal to them).
FEM_SCENES ?= beam chain plate bunny corpus
study: build
	@cmake --build $(BUILD) --target study study_float fem_compare fem_checks -j $(JOBS)
	@$(BUILD)/bench/study --out bench/results/study --refs $(BUILD)/study-refs
	@$(BUILD)/bench/study_float --out bench/results/study --refs $(BUILD)/study-refs
	@$(BUILD)/bench/fem_checks > bench/results/study/fem_checks.md
	@for s in $(FEM_SCENES); do \
	  $(BUILD)/bench/fem_compare --scene $$s --out bench/results/study > bench/results/study/fem_$$s.md || exit 1; \
	done
	@/usr/bin/python3 scripts/study_charts.py bench/results/study docs/images
	@/usr/bin/python3 scripts/study_tables.py bench/results/study docs/results/study.md

# Every mesh of the corpus (CGAL's data set, glmark2-data, assimp-testmodels) pre-scored with the
# defaults; the page goes to docs/results/corpus.md, made from its record docs/results/corpus.tsv.
# A fixed sample of it runs in `make test`.
corpus: build
	@/usr/bin/python3 scripts/corpus.py $(BUILD)/bin/shatter $(BUILD)/corpus --all --table docs/results/corpus.md

# `shatter run MESH` (the default shot, movie and all) on every mesh of the corpus:
# docs/results/corpus-run.md, made from its record docs/results/corpus-run.tsv.
corpus-run: build
	@/usr/bin/python3 scripts/corpus.py $(BUILD)/bin/shatter $(BUILD)/corpus --all --run --workers 1 --table docs/results/corpus-run.md

clean:
	rm -rf $(BUILD) $(BUILD).configure.log out build-asan build-asan.configure.log build-fuzz build-fuzz.configure.log
