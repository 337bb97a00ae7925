#!/usr/bin/env bash
# Installs the Debian packages named on the command line that are not installed yet
# (apt-get update first, sudo when not root); options before the packages, such as
# --no-install-recommends, go to apt-get install. Used by scripts/build.sh and scripts/docs.sh.
set -euo pipefail
options=()
while (($#)) && [[ $1 == -* ]]; do options+=("$1"); shift; done
missing=()
for p in "$@"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bkquake: installing missing packages: ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y "${options[@]}" "${missing[@]}"
fi
