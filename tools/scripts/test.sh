#!/usr/bin/env bash
# Quick start 2: set up, build and run the default test suite (long validations excluded:
# run them with `ctest --test-dir build -L long`).
set -euo pipefail
cd "$(dirname "$0")/../.."
bash tools/scripts/setup.sh
ctest --test-dir build --output-on-failure -LE long -j"$(nproc)"
