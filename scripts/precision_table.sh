#!/usr/bin/env bash
# PSNR of model- or traversal-engine renders of the thesis' scenes against their f32 renders,
# per format, engine, spawn policy, scaling, edge test and origin advance (docs/precision.md).
# Prints a Markdown table; one row per combination, one column per scene and the worst.
#
#   scripts/precision_table.sh [FORMATS...]
#
# Environment: RTFPGA (the binary, default target/release/rtfpga), RTFPGA_THESIS_SCENES
# (default ../shared/scenes/thesis), SIZE (default 320x180), OUT (work directory, default a
# temporary one); the lists to combine: ENGINES (default "model"; model and/or traversal),
# SPAWNS (default "thesis format-aware"), SCALES (default "none auto"), EDGES (default
# "exact") and ADVANCES (default "none"; `rtfpga render --edges`, `--advance`). A
# combination the CLI refuses (e.g. `--advance leaf-box` with the model engine) is skipped
# with its error on stderr.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${RTFPGA:-$root/target/release/rtfpga}
scenes_dir=${RTFPGA_THESIS_SCENES:-$root/../shared/scenes/thesis}
size=${SIZE:-320x180}
out=${OUT:-$(mktemp -d)}
w=${size%x*}
h=${size#*x}
formats=("$@")
if [ ${#formats[@]} -eq 0 ]; then
    formats=(fp32 fp24 e8m14 e8m12 bf16 fp16 e5m14 e6m13 fx32_16 'fx<24,12>')
fi
read -r -a engines <<<"${ENGINES:-model}"
read -r -a spawns <<<"${SPAWNS:-thesis format-aware}"
read -r -a scales <<<"${SCALES:-none auto}"
read -r -a edges_list <<<"${EDGES:-exact}"
read -r -a advances <<<"${ADVANCES:-none}"
scenes=(Glass_pen_scene Simple_plane_scene Glasses_scene Glasses_point_scene
    Simple_plane2_scene Utah_teapot_scene All_materials_scene)
psnr() { "$bin" compare "$1" "$2" | tail -1 | sed 's/psnr_db=//'; }
render() { "$bin" render --scene "$scenes_dir/$1" --width "$w" --height "$h" --quiet --out "$2" "${@:3}" >/dev/null; }

for s in "${scenes[@]}"; do
    [ -f "$out/ref_$s.png" ] || render "$s" "$out/ref_$s.png" --engine f32
done
printf '| format | engine | spawn | scale | edges | advance |'
for s in "${scenes[@]}"; do printf ' %s |' "${s%_scene}"; done
printf ' worst |\n|---|---|---|---|---|---|'
for _ in "${scenes[@]}"; do printf -- '---|'; done
printf -- '---|\n'
for f in "${formats[@]}"; do
    for engine in "${engines[@]}"; do
        for spawn in "${spawns[@]}"; do
            for scale in "${scales[@]}"; do
                for edges in "${edges_list[@]}"; do
                    for advance in "${advances[@]}"; do
                        opts=(--engine "$engine" --format "$f" --spawn "$spawn" --scale "$scale"
                            --advance "$advance")
                        # --edges is the model engine's option; the others test exact edges.
                        if [ "$engine" = model ]; then
                            opts+=(--edges "$edges")
                        elif [ "$edges" != exact ]; then
                            continue
                        fi
                        # Skip what the CLI refuses (the first scene's render tells).
                        tag="${f}_${engine}_${spawn}_${scale}_${edges}_${advance}"
                        # A format (fx<24,12>) may be spelled with characters a file name avoids.
                        tag=${tag//[<>,]/_}
                        if ! err=$(render "${scenes[0]}" "$out/${tag}_${scenes[0]}.png" "${opts[@]}" 2>&1); then
                            echo "skipped $tag: $err" >&2
                            continue
                        fi
                        printf '| %s | %s | %s | %s | %s | %s |' "$f" "$engine" "$spawn" "$scale" "$edges" "$advance"
                        worst=inf
                        for s in "${scenes[@]}"; do
                            img="$out/${tag}_$s.png"
                            [ -f "$img" ] || render "$s" "$img" "${opts[@]}"
                            p=$(psnr "$out/ref_$s.png" "$img")
                            printf ' %s |' "$p"
                            worst=$(awk -v a="$worst" -v b="$p" 'BEGIN { if (a == "inf") print b; else if (b == "inf") print a; else print (b + 0 < a + 0) ? b : a }')
                        done
                        printf ' %s |\n' "$worst"
                    done
                done
            done
        done
    done
done
