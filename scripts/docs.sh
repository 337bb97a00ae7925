#!/usr/bin/env bash
# Builds the documentation site (mkdocs.yml, pages under docs/) into build/docs/ in strict
# mode: a broken link, a missing image or page fails the build. Installs Debian's mkdocs
# and mkdocs-material when missing, as scripts/build.sh does for the build's packages.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(mkdocs mkdocs-material)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bkquake: installing missing packages: ${missing[*]}" >&2
  sudo=""
  [[ $(id -u) -ne 0 ]] && sudo="sudo"
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y "${missing[@]}"
fi

mkdocs build --strict --clean --config-file mkdocs.yml --site-dir build/docs "$@"
echo "bkquake: documentation built into build/docs/ (open build/docs/index.html)"
