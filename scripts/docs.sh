#!/usr/bin/env bash
# Builds the documentation site (mkdocs.yml, pages under docs/) into build/docs/ in strict
# mode: a broken link, a missing image or page fails the build. Installs Debian's mkdocs
# and mkdocs-material when missing, as scripts/build.sh does for the build's packages.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(mkdocs mkdocs-material)
scripts/ensure_packages.sh "${packages[@]}"

mkdocs build --strict --clean --config-file mkdocs.yml --site-dir build/docs "$@"
echo "bkquake: documentation built into build/docs/ (open build/docs/index.html)"
