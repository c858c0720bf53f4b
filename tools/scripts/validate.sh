#!/bin/bash
# Runs the validation cases of tools/validation/cases against build/tools/kneesim, writes their
# figures to build/validation/<case>.json and regenerates the documentation's tables from them;
# --check compares the documented numbers instead (non-zero exit naming every difference).
#   tools/scripts/validate.sh [--check] [--long | --long-only] [--from-json] [--list] [CASE...]
# How to add a case: tools/validation/README.md.
exec /usr/bin/python3 "$(dirname "$0")/../validation/validate.py" "$@"
