# Entry points. `make demo` and `make test` work on a fresh Debian machine with Rust:
# both install the system tools first (scripts/setup.sh, apt-get).

CARGO ?= cargo
RTFPGA := target/release/rtfpga
DEMO_SCENE ?= utah_teapot
DEMO_SIZE ?= --width 320 --height 180
OUT ?= out

.PHONY: setup build demo test golden verilog bench sweep clean fuzz

setup:
	@./scripts/setup.sh

build: setup
	$(CARGO) build --release

$(RTFPGA): build

# Render the built-in Utah teapot (6,322 triangles) in software and through the Verilated fp32
# accelerator (the first run builds the model, about half a minute), write software | hardware |
# difference side by side in $(OUT)/demo.png, print its absolute path and the PSNR (last line).
demo: build
	@mkdir -p $(OUT)
	$(RTFPGA) render --scene $(DEMO_SCENE) $(DEMO_SIZE) --engine f32 --out $(OUT)/demo_sw.png
	$(RTFPGA) cosim --scene $(DEMO_SCENE) $(DEMO_SIZE) --format fp32 --depth 5 --lanes 1 --out $(OUT)/demo_hw.png
	$(RTFPGA) compare $(OUT)/demo_sw.png $(OUT)/demo_hw.png --diff $(OUT)/demo_diff.png \
		--side-by-side $(OUT)/demo.png --labels "software f32,accelerator fp32 d5 l1"

# Formatting, lints, every test of the workspace and the checks of the Vivado scripts (what
# CI runs). Tests that need the thesis' scenes take them from RTFPGA_THESIS_SCENES, else
# ../shared/scenes/thesis, else print a SKIPPED line.
test: setup
	$(CARGO) fmt --all --check
	$(CARGO) clippy --workspace --all-targets -- -D warnings
	$(CARGO) test --workspace --release
	VERILOG_DIR=generated-verilog/fp32_d5_l1 sh constraints/check.sh

# Regenerate the golden images of scenes/ (a test checks they are current).
golden: build
	$(RTFPGA) golden --out golden

# Regenerate generated-verilog/ (a test checks it is current): the accelerator's default
# configurations and the traversal unit's C driver and config.json.
verilog: build
	$(RTFPGA) verilog --defaults --out generated-verilog

# Design-space sweep of sweeps/default.toml into sweep-out/ (about 37 min on 2 cores, most
# of it yosys; a re-run reuses the cached syntheses, 4 min):
# results.md/csv/json, quality.csv, plots/, grids/. docs/sweep.md reports it.
sweep: build
	$(RTFPGA) sweep --config sweeps/default.toml --out sweep-out

bench: build
	$(CARGO) bench -p sw-renderer

clean:
	$(CARGO) clean
	rm -rf $(OUT)

# Coverage-guided fuzzing of the scene and sweep-config parsers (fuzz/, cargo fuzz on the
# nightly toolchain; not part of `make test`): each target FUZZ_RUNS executions (default 1 M),
# seeded from scenes/, sweeps/ and the thesis scenes. About 80 min on 2 cores (BENCHMARKS.md).
FUZZ_RUNS ?= 1000000
fuzz:
	@rustup run nightly rustc --version >/dev/null 2>&1 || rustup toolchain install nightly --profile minimal
	@$(CARGO) fuzz --version >/dev/null 2>&1 || $(CARGO) install cargo-fuzz
	FUZZ_RUNS=$(FUZZ_RUNS) fuzz/run.sh
