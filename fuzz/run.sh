#!/bin/sh
# Coverage-guided fuzzing of the project's parsers (what `make fuzz` runs).
#
# Seeds each target's corpus (fuzz/corpus/TARGET, not committed) from the repository's own
# files and the thesis scenes, then runs every target for FUZZ_RUNS executions (default
# 1,000,000) with a 10 s per-input timeout and a 2 GB memory limit. A crash, hang or
# out-of-memory stops the run with libFuzzer's report; the input is in fuzz/artifacts/TARGET.
# Prints, per target, executions, execs/s and the corpus after the run.
#
#   FUZZ_RUNS=N        executions per target
#   FUZZ_TARGETS="..." which targets (default: all)
#   RTFPGA_THESIS_SCENES=DIR   the thesis scenes (default ../shared/scenes/thesis)
set -eu

cd "$(dirname "$0")"
RUNS=${FUZZ_RUNS:-1000000}
TARGETS=${FUZZ_TARGETS:-"thesis_sod thesis_ood thesis_geo thesis_objects toml_scene sweep_config"}
THESIS=${RTFPGA_THESIS_SCENES:-../../shared/scenes/thesis}
TOOLCHAIN=${FUZZ_TOOLCHAIN:-+nightly}
# Thesis meshes above this size are left out of the seeds (they would only slow each run).
MAX_SEED=65536

# seed TARGET FILE...: copy each file (if it exists) into the corpus, named by its hash.
seed() {
    target=$1
    shift
    mkdir -p "corpus/$target"
    for f in "$@"; do
        [ -f "$f" ] || continue
        [ "$(wc -c <"$f")" -le "$MAX_SEED" ] || continue
        cp "$f" "corpus/$target/seed-$(sha1sum "$f" | cut -c1-16)"
    done
}

if [ ! -d "$THESIS" ]; then
    echo "note: no thesis scenes at $THESIS (set RTFPGA_THESIS_SCENES): the thesis targets start from an empty corpus" >&2
fi
seed thesis_sod "$THESIS"/*/*.sod
seed thesis_ood "$THESIS"/*/*.ood
seed thesis_geo "$THESIS"/*/*.geo
seed thesis_objects "$THESIS"/*/objects.txt
seed toml_scene ../scenes/*.toml
seed sweep_config ../sweeps/*.toml

mkdir -p artifacts
summary=artifacts/summary.txt
: >"$summary"
for t in $TARGETS; do
    case $t in
    thesis_*) dict=dicts/thesis.dict ;;
    *) dict=dicts/$t.dict ;;
    esac
    case $t in
    toml_scene) max_len=8192 ;;
    *) max_len=4096 ;;
    esac
    features=
    [ "$t" = sweep_config ] && features="--features sweep"
    log=artifacts/$t.log
    mkdir -p "artifacts/$t"
    echo "== $t: $RUNS runs (log: fuzz/$log)"
    start=$(date +%s)
    # -a: overflow checks and debug assertions (an overflow is a crash too).
    # shellcheck disable=SC2086
    if ! cargo $TOOLCHAIN fuzz run -a $features "$t" "corpus/$t" -- \
        -runs="$RUNS" -timeout=10 -rss_limit_mb=2048 -max_len=$max_len \
        -dict="$dict" -print_final_stats=1 -print_pcs=0 >"$log" 2>&1; then
        tail -n 60 "$log"
        echo "FAILED: $t (input in fuzz/artifacts/$t, log fuzz/$log)" >&2
        exit 1
    fi
    secs=$(($(date +%s) - start))
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    files=$(find "corpus/$t" -type f | wc -l)
    bytes=$(find "corpus/$t" -type f -exec cat {} + | wc -c)
    line="$t: $execs execs, $rate execs/s, corpus $files files $bytes bytes, ${secs}s (with build), 0 crashes"
    echo "$line" | tee -a "$summary"
done
echo "== all targets passed; summary in fuzz/$summary"
cat "$summary"
