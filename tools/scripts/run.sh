#!/usr/bin/env bash
# Quick start 1: set up, build and run `kneesim run` on the built-in default implant.
set -euo pipefail
cd "$(dirname "$0")/../.."
bash tools/scripts/setup.sh
./build/tools/kneesim run --out kneesim-run "$@"
