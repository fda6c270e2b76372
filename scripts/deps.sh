#!/bin/sh
# Install the Debian packages s42 needs to build and test, when missing.
# As root (or with password-less sudo) it installs them with apt-get;
# otherwise it prints the exact command and fails.
#   sh scripts/deps.sh           install what is missing
#   sh scripts/deps.sh --check   only say what is missing (exit 1 if any)
#   sh scripts/deps.sh --oracle  also LinuxCNC's rs274 (linuxcnc-uspace), the
#                                outside oracle of tests/oracle (CI installs it;
#                                without it that test says it is skipped)
PKGS="build-essential pkg-config check libncurses-dev libmodbus-dev libopencv-dev libcairo2-dev tmux python3 valgrind mbpoll groff-base man-db"
if [ "$1" = "--oracle" ]; then
  PKGS="$PKGS linuxcnc-uspace"
  shift
fi

missing=""
if command -v dpkg-query >/dev/null 2>&1; then
  for p in $PKGS; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing="$missing $p"
    fi
  done
else
  # Not Debian: check what the build itself uses.
  command -v pkg-config >/dev/null 2>&1 || missing="$missing pkg-config"
  command -v python3 >/dev/null 2>&1 || missing="$missing python3"
  pkg-config --exists check 2>/dev/null || missing="$missing check"
  if [ -n "$missing" ]; then
    echo "s42: missing:$missing -- install them with your system's package manager" >&2
    exit 1
  fi
  exit 0
fi

[ -z "$missing" ] && exit 0
if [ "$1" = "--check" ]; then
  echo "s42: missing Debian packages:$missing" >&2
  exit 1
fi

if [ "$(id -u)" = 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO="sudo"
else
  echo "s42: these Debian packages are missing:$missing" >&2
  echo "s42: install them with:  sudo apt-get install -y$missing" >&2
  exit 1
fi

echo "s42: installing$missing" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || { echo "s42: apt-get update failed" >&2; exit 1; }
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq --no-install-recommends $missing >&2 || {
  echo "s42: apt-get install failed; run:  sudo apt-get install -y$missing" >&2
  exit 1
}
