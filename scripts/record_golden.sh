#!/usr/bin/env bash
# usage: scripts/record_golden.sh [TOW_SIM_BATCH]
#
# Records the golden outputs of every shipped scenario (scenarios/*.yaml but the bathymetry_* grids:
# timeseries.csv and shapes.csv) into test/golden/, which Batch.ShippedScenariosReproduceTheGoldenOutputs
# compares each run against (1e-9 of each column's scale). Run it only when a change is meant to move the
# results, and say in the commit which and why.
#
#   TOW_SIM_BATCH  the tow_sim_batch binary to run (default: the workspace beside the repository,
#                  ../tow_sim_ws/devel/lib/tow_sim/tow_sim_batch)
#   -h, --help     prints this help and exits
#
# Exit status: 2 for wrong arguments (nothing runs); 1 when a scenario's run fails (its log is printed).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/cli.sh"
cli_help "$@"
cli_refuse_options "$@"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
batch="${1:-$repo/../tow_sim_ws/devel/lib/tow_sim/tow_sim_batch}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for scenario in "$repo"/scenarios/*.yaml; do
  name="$(basename "$scenario" .yaml)"
  [[ "$name" == bathymetry_* ]] && continue  # grids, not scenarios
  "$batch" --scenario "$scenario" --out "$tmp/$name" > /dev/null 2> "$tmp/$name.log" || { cat "$tmp/$name.log"; exit 1; }
  mkdir -p "$repo/test/golden/$name"
  cp "$tmp/$name/timeseries.csv" "$tmp/$name/shapes.csv" "$repo/test/golden/$name/"
  echo "recorded $name"
done
