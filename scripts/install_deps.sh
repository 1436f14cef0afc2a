#!/usr/bin/env bash
# usage: scripts/install_deps.sh
#
# Installs the Debian packages listed in scripts/deps.txt that are missing (apt-get update, then apt-get
# install --no-install-recommends, with sudo unless run as root); does nothing when all are there.
# Takes no arguments (make deps runs it).
#
#   -h, --help  prints this help and exits
#
# Exit status: 2 for wrong arguments (nothing runs); 0 when every package is installed, else not 0.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/cli.sh"
cli_help "$@"
cli_refuse_options "$@"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mapfile -t wanted < <(grep -v '^\s*#' "$here/deps.txt" | grep -v '^\s*$')
missing=()
for pkg in "${wanted[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)"
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done
if ((${#missing[@]} == 0)); then
  exit 0
fi
echo "installing: ${missing[*]}"
sudo_cmd=()
[[ "$(id -u)" == 0 ]] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
