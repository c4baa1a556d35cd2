#!/usr/bin/env bash
# Installs the Debian packages libpool's build, tools and tests need, once.
# Run by both README commands; does nothing when everything is already there.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libode-dev libbullet-dev libgsl-dev libeigen3-dev
  liblcm-dev liblcm-bin libglib2.0-dev
  libcmocka-dev libjansson-dev
  python3 python3-matplotlib python3-numpy python3-venv python3-pip
  chromium
  iproute2 util-linux
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Python side (pool-plot, LCM subscriber, end-to-end tests): Debian's python3 with matplotlib,
# plus the PyPI `lcm` bindings in a project-local venv (Debian ships no python3-lcm).
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"
if [ ! -x "$VENV/bin/python" ]; then
  /usr/bin/python3 -m venv --system-site-packages "$VENV"
fi
if ! "$VENV/bin/python" -c "import lcm" 2>/dev/null; then
  "$VENV/bin/pip" install -q --disable-pip-version-check "lcm==1.5.3"
fi
# websockets for pool-view --live (the bridge from LCM to the page) and the browser tests' DevTools
# client.
if ! "$VENV/bin/python" -c "import websockets; assert websockets.__version__ == '15.0.1'" 2>/dev/null; then
  "$VENV/bin/pip" install -q --disable-pip-version-check "websockets==15.0.1"
fi
# Dask for libpool.dask and its test (tests/python_dask), with a NumPy from PyPI: 1.x, because the
# venv also sees Debian's matplotlib (--system-site-packages), built against NumPy 1.x.
if ! "$VENV/bin/python" -c "import dask.distributed, numpy; assert numpy.__version__ == '1.26.4'" 2>/dev/null; then
  "$VENV/bin/pip" install -q --disable-pip-version-check "numpy==1.26.4" "dask[distributed]==2026.8.0"
fi
# Gymnasium for libpool.gym and its tests (tests/games/test_gym.py); also the extra [gym] of
# pip install ./python.
if ! "$VENV/bin/python" -c "import gymnasium; assert gymnasium.__version__ == '1.4.0'" 2>/dev/null; then
  "$VENV/bin/pip" install -q --disable-pip-version-check "gymnasium==1.4.0"
fi
