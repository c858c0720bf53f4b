#!/bin/bash
# Regenerates the shipped calibrated contact laws (models/contact_laws/*.toml): for each implant
# and each shipped material, `kneesim calibrate-contact` fits the rigid insert's effective
# foundation modulus and exponent to the deformable insert (one deformable gait cycle on the
# reference mesh, models::kContactCalibrationReferenceMesh, and about 200 short rigid ones;
# analysis/run/calibrate_contact_law.h) and the law file
# it writes, with its provenance (command, date, mesh, fitted modulus, held-out errors, stance
# figures), is copied into models/contact_laws/<implant>_<material>.toml.
#   tools/scripts/calibrate_contact_laws.sh [--examples] [--reuse-deformable] [MATERIAL...]
# Default: the built-in implant, every shipped material (uhmwpe peek cfr-peek); --examples also
# the example implants models/examples/dm_stanmore.toml and jw_stanmore.toml (KNEESIM_DATA must
# hold their meshes). Runs are kept in build/contact_laws/; --reuse-deformable fits against the
# deformable run a previous call left there (kneesim calibrate-contact --deformable-from, which
# refuses a run of other settings) instead of running it again. Cost: one deformable cycle per law
# (minutes each on 2 cores); run it with nice on a shared machine.
# CFR-PEEK on the built-in implant is calibrated against a deformable reference on finer surfaces
# (0.25 mm facets, 0.2 mm distance field; the rigid runs keep the default 1 mm and 0.4 mm): its
# small stiff patch follows the default facets' ridges and its peak pressure does not converge on
# them (docs/validation.md, "CFR-PEEK on finely faceted implant surfaces").
set -euo pipefail
cd "$(dirname "$0")/../.."
kneesim=${KNEESIM_BIN:-build/tools/kneesim}
export KNEESIM_DATA="${KNEESIM_DATA:-$(pwd)/../shared/data}"
implants=("generic:")
materials=()
reuse=0
for a in "$@"; do
  case "$a" in
    --reuse-deformable) reuse=1 ;;
    --examples) implants+=("dm:models/examples/dm_stanmore.toml" "jw:models/examples/jw_stanmore.toml") ;;
    *) materials+=("$a") ;;
  esac
done
[ ${#materials[@]} -gt 0 ] || materials=(uhmwpe peek cfr-peek)
mkdir -p build/contact_laws models/contact_laws
for entry in "${implants[@]}"; do
  name=${entry%%:*}
  config=${entry#*:}
  for m in "${materials[@]}"; do
    out=build/contact_laws/${name}_$m
    from=()
    surfaces=()
    if [ "$name" = generic ] && [ "$m" = cfr-peek ]; then
      surfaces=(--reference-edge-mm 0.25 --reference-sdf-mm 0.2)
    fi
    if [ $reuse = 1 ] && [ -f "$out/deformable/summary.json" ]; then
      rm -rf "$out.deformable" && mv "$out/deformable" "$out.deformable"
      from=(--deformable-from "$out.deformable")
    fi
    rm -rf "$out"
    echo "calibrate_contact_laws: $name $m -> $out" >&2
    "$kneesim" calibrate-contact $config --material "$m" --out "$out" --no-plots --quiet \
      "${surfaces[@]}" "${from[@]}"
    if [ ${#from[@]} -gt 0 ]; then mv "$out.deformable" "$out/deformable"; fi
    cp "$out/contact_law.toml" "models/contact_laws/${name}_$m.toml"
  done
done
