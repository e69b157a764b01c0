#!/usr/bin/env bash
# Installs the Debian packages qverify needs when any is missing (as root),
# or says which ones to install. Sourced by ./qverify and ./run-tests.
QVERIFY_PACKAGES=(g++ cmake ninja-build make libeigen3-dev libboost-dev libgmp-dev libmpfr-dev libmpfi-dev libpng-dev libcgal-dev
                  catch2 nlohmann-json3-dev libcli11-dev libfmt-dev libbenchmark-dev)

qverify_install_deps() {
  local missing=() p
  for p in "${QVERIFY_PACKAGES[@]}" "$@"; do
    [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" = "install ok installed" ] || missing+=("$p")
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

# Whether the build tree DIR was configured for Ninja (the presets' generator).
qverify_tree_is_ninja() { grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$1/CMakeCache.txt" 2>/dev/null; }

# Configures the tree of a preset quietly (the log is shown if it fails): cmake -S ROOT --preset PRESET
# [ARGS...]. The presets use Ninja (it compiles a library's objects while the library it links against
# is still being built, where make waits for it). A tree configured before with another generator (make,
# before 2026-12) cannot be configured again in place: its cache is removed first (so are the -D settings
# it held), it is said on stderr, and everything in it is built again.
qverify_configure() {
  local root="$1" preset="$2"; shift 2
  local dir="$root/build/$preset"
  if [ -f "$dir/CMakeCache.txt" ] && ! qverify_tree_is_ninja "$dir"; then
    echo "qverify: build/$preset was configured for make: configuring it again for Ninja (its -D settings are" \
         "not kept; give them again: cmake --preset $preset -D...)" >&2
    rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
  fi
  qverify_quietly cmake -S "$root" --preset "$preset" "$@"
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

# Prints why the release tree of the checkout $1 must be built for the given targets (none: all),
# or nothing when it is up to date: "unconfigured", "missing" (a product is not built yet), or
# "changed" (a source or build file is newer than the last build: the oldest product, or the
# stamp of the last qverify_build of these targets if newer, so that a change the products do not
# depend on is announced once, not on every run). Only decides whether to announce a build: Ninja
# decides what to build. A tree made by make before counts as unconfigured (qverify_configure).
qverify_build_reason() {
  local root="$1"; shift
  local dir="$root/build/release" p ref=""
  local products=("$dir/apps/qverify") prune=(build .git examples bench python tests/fuzz)
  local stamp="$dir/qverify-built-all.stamp"
  if [ "$*" = "--target qverify" ]; then
    prune+=(tests)
    stamp="$dir/qverify-built-cli.stamp"
  else
    products+=("$dir/tests/qverify_tests")
  fi
  if ! qverify_tree_is_ninja "$dir"; then  # no tree yet, or one made by make
    echo unconfigured
    return
  fi
  for p in "${products[@]}"; do
    if [ ! -e "$p" ]; then echo missing; return; fi
    if [ -z "$ref" ] || [ "$p" -ot "$ref" ]; then ref="$p"; fi
  done
  if [ "$stamp" -nt "$ref" ]; then ref="$stamp"; fi
  local skip=()
  for p in "${prune[@]}"; do skip+=(-path "$root/$p" -o); done
  if [ -n "$(find "$root" \( "${skip[@]}" -false \) -prune -o -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \
               -o -name 'CMakeLists.txt' -o -name '*.cmake' -o -name '*.cmake.in' -o -name 'CMakePresets.json' \) \
               -newer "$ref" -print -quit)" ]; then
    echo changed
  fi
}

# Configures the release tree if needed and builds the given targets (quietly,
# the log is shown on failure). Build output never reaches stdout. When there is
# something to build, stderr says so first, and roughly how long it takes.
qverify_build() {
  local root="$1"; shift
  local dir="$root/build/release" reason what minutes start="" stamp=all
  reason="$(qverify_build_reason "$root" "$@")"
  # measured from scratch on 2 cores: the CLI 4 min 26 s (a clean clone of fe48cb2, `./qverify --help`), with the
  # test suite about 8 (unity build, CI logs); the machine's speed varies by a third between days
  if [ "$*" = "--target qverify" ]; then what="the release tree"; minutes=5; stamp=cli; else what="the release tree and its tests"; minutes=8; fi
  case "$reason" in
    unconfigured) echo "qverify: building $what (first build: about $minutes minutes on 2 cores; later runs start at once) ..." >&2 ;;
    missing) echo "qverify: building $what (up to $minutes minutes on 2 cores) ..." >&2 ;;
    changed) echo "qverify: rebuilding $what (sources changed; up to $minutes minutes on 2 cores) ..." >&2 ;;
  esac
  if [ -n "$reason" ]; then start=$SECONDS; fi
  if [ "$reason" = unconfigured ]; then
    qverify_configure "$root" release "${QVERIFY_CMAKE_ARGS[@]}" || return 1
  fi
  # the stamp carries the time the build started: a source changed during the build stays newer
  local next="$dir/qverify-built-$stamp.stamp.$$"
  touch "$next"
  if ! qverify_quietly cmake --build "$dir" -j "$(nproc)" "$@"; then
    rm -f "$next"
    return 1
  fi
  mv -f "$next" "$dir/qverify-built-$stamp.stamp"
  if [ -n "$start" ]; then
    echo "qverify: built in $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s" >&2
  fi
}
