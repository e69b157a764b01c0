#!/usr/bin/env bash
# Installs the Debian packages qverify needs when any is missing (as root),
# or says which ones to install. Sourced by ./qverify and ./run-tests.
QVERIFY_PACKAGES=(g++ cmake make libeigen3-dev libboost-dev libgmp-dev libmpfr-dev libmpfi-dev libpng-dev libcgal-dev
                  catch2 nlohmann-json3-dev libcli11-dev libfmt-dev libbenchmark-dev)

qverify_install_deps() {
  local missing=() p
  for p in "${QVERIFY_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "qverify: missing Debian packages: ${missing[*]}" >&2
    echo "qverify: run as root, or: sudo apt-get install ${missing[*]}" >&2
    return 1
  fi
  echo "qverify: installing ${missing[*]} ..." >&2
  export DEBIAN_FRONTEND=noninteractive
  { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}"; } >&2
}

# Runs a command with its output kept in a log that is shown (on stderr) only
# when the command fails; returns the command's status.
qverify_quietly() {
  local log status=0
  log="$(mktemp)"
  "$@" >"$log" 2>&1 || status=$?
  if [ "$status" -ne 0 ]; then cat "$log" >&2; fi
  rm -f "$log"
  return "$status"
}

# Configures the release tree if needed and builds the given targets (quietly,
# the log is shown on failure). Build output never reaches stdout.
qverify_build() {
  local root="$1"; shift
  local dir="$root/build/release"
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    qverify_quietly cmake -S "$root" --preset release "${QVERIFY_CMAKE_ARGS[@]}" || return 1
  fi
  qverify_quietly cmake --build "$dir" -j "$(nproc)" "$@"
}
