#!/usr/bin/env bash
# Installs, with apt-get, those of the given Debian packages that are missing.
# Usage: install-debian-packages.sh LABEL PACKAGE...   (LABEL prefixes the messages)
# Idempotent: packages already installed are not touched; nothing is downloaded
# from anywhere but the Debian archive. Used by setup-deps.sh and setup-test-deps.sh.
set -euo pipefail
label=$1
shift
missing=()
for pkg in "$@"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "$label: all $# packages present"
  exit 0
fi

echo "$label: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
