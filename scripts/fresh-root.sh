#!/usr/bin/env bash
# The clean-machine check: do the README's commands work on a Debian 12 machine
# that has never had any of strahl's packages?
#
# It builds a minimal Debian 12 (bookworm) root with debootstrap from the Debian
# mirror the host's apt sources name, puts a fresh `git clone` of the commit into
# it and, inside it (chroot, as root, with /proc, /sys and /dev mounted):
#   1. runs README command 1 verbatim (read from README.md, so the two cannot drift);
#   2. checks that out/default.exr and out/default.png exist;
#   3. runs scripts/test.sh --quick (the Release ctest suite), or with
#      --command2 README command 2 verbatim (the whole suite: Release,
#      sanitizers, fuzzing), which is what CI does (.ci/run).
# Every step prints how long it took; a failing step prints its whole output and
# the script exits non-zero. The host's packages are never touched: debootstrap
# itself, when the host lacks it, is unpacked from its .deb into the cache.
# An unreachable package registry is a failure, never a skip.
#
# The bare root is cached as a tarball under /var/cache/strahl/ (outside the
# repository), so later runs only unpack it (a few seconds); downloaded .debs are
# cached beside it, which speeds up later runs on the same machine without
# changing what gets installed into the root.
#
# Usage: scripts/fresh-root.sh [--command2] [--shared DIR] [--ref REF] [--refresh] [--keep]
#   --command2  step 3 runs README command 2 instead of scripts/test.sh --quick
#   --shared DIR  mount DIR read-only where the clone's ../shared is (the shared
#               test data set; without it, the tests that need it skip, as in a
#               user's clone)
#   --ref REF   clone this commit/branch instead of HEAD (e.g. a throwaway branch
#               with a package removed from scripts/packages.txt, to see it fail)
#   --refresh   rebuild the cached bare root
#   --keep      leave the root in place afterwards (its path is printed)
# Environment: STRAHL_CACHE (default /var/cache/strahl).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ref=HEAD refresh=0 keep=0 run_command2=0 shared=""
usage="usage: scripts/fresh-root.sh [--command2] [--shared DIR] [--ref REF] [--refresh] [--keep]"
while (($#)); do
  case "$1" in
    --command2) run_command2=1; shift ;;
    --shared)
      shared="${2:?--shared needs a folder}"
      [ -d "$shared" ] || { echo "fresh-root: --shared: '$shared' is not a folder" >&2; exit 2; }
      shared="$(cd "$shared" && pwd)"
      shift 2
      ;;
    --ref) ref="${2:?--ref needs a commit or branch}"; shift 2 ;;
    --refresh) refresh=1; shift ;;
    --keep) keep=1; shift ;;
    *) echo "fresh-root: unknown argument '$1' ($usage)" >&2; exit 2 ;;
  esac
done
[ "$(id -u)" -eq 0 ] || { echo "fresh-root: needs root (debootstrap, chroot and mount); run it with sudo" >&2; exit 2; }

cache="${STRAHL_CACHE:-/var/cache/strahl}"
suite=bookworm
mkdir -p "$cache/apt-archives/partial"
logs="$(mktemp -d /var/tmp/strahl-fresh-root-logs.XXXXXX)"
total_start=$SECONDS

fail() { echo "fresh-root: FAILED: $*" >&2; exit 1; }

# step <id> <description> <command...>: runs the command with its output in
# $logs/<id>.log; prints its time, or its whole output and fails.
step() {
  local id="$1" what="$2" start=$SECONDS
  shift 2
  echo "fresh-root: $what ..."
  if "$@" >"$logs/$id.log" 2>&1; then
    echo "fresh-root: $what: ok in $((SECONDS - start)) s"
  else
    local status=$?
    echo "fresh-root: ---- output of '$what' ----" >&2
    cat "$logs/$id.log" >&2
    echo "fresh-root: ---- end of '$what' ----" >&2
    fail "$what (exit $status, after $((SECONDS - start)) s; log kept in $logs/$id.log)"
  fi
}

# --- The Debian mirrors the host uses -------------------------------------------
# URIs of the host's apt sources (one-line sources.list and deb822 .sources) whose
# suite is "$suite" (the main archive) or "$suite-security".
host_sources() {
  local f
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] && sed -n 's/^[[:space:]]*deb[[:space:]]\+\(\[[^]]*\][[:space:]]\+\)\{0,1\}\([^[:space:]]\+\)[[:space:]]\+\([^[:space:]]\+\).*/\2 \3/p' "$f"
  done
  for f in /etc/apt/sources.list.d/*.sources; do
    # deb822: paragraphs of "Key: value" lines; print "uri suite" for every pair.
    [ -f "$f" ] && awk '
      function flush() { if (types ~ /(^| )deb( |$)/ && enabled != "no") { n = split(uris, u, " "); m = split(suites, s, " ");
                         for (i = 1; i <= n; i++) for (j = 1; j <= m; j++) print u[i], s[j] } types = uris = suites = ""; enabled = "" }
      /^[[:space:]]*$/ { flush(); next }
      /^#/ { next }
      tolower($1) == "types:" { $1 = ""; types = $0 }
      tolower($1) == "uris:" { $1 = ""; uris = $0 }
      tolower($1) == "suites:" { $1 = ""; suites = $0 }
      tolower($1) == "enabled:" { enabled = tolower($2) }
      END { flush() }' "$f"
  done
}
mirror="$(host_sources | awk -v s="$suite" '$2 == s { print $1; exit }')"
security="$(host_sources | awk -v s="$suite-security" '$2 == s { print $1; exit }')"
[ -n "$mirror" ] || fail "the host's apt sources name no Debian mirror for '$suite' (looked in /etc/apt/sources.list and /etc/apt/sources.list.d/)"
echo "fresh-root: Debian mirror $mirror${security:+, security $security}"

# --- debootstrap, without installing it on the host ------------------------------
debootstrap_cmd=()
if command -v debootstrap >/dev/null; then
  debootstrap_cmd=(debootstrap)
else
  tool="$cache/debootstrap-tool"
  if [ ! -x "$tool/usr/sbin/debootstrap" ]; then
    fetch_debootstrap() {
      local tmp
      tmp="$(mktemp -d)"
      chmod 755 "$tmp"  # apt downloads as its own user (_apt)
      (cd "$tmp" && { apt-get download debootstrap || { apt-get update && apt-get download debootstrap; }; }) &&
        rm -rf "$tool" && dpkg-deb -x "$tmp"/debootstrap_*.deb "$tool" && rm -rf "$tmp"
    }
    step fetch-debootstrap "fetch debootstrap" fetch_debootstrap
  fi
  debootstrap_cmd=(env DEBOOTSTRAP_DIR="$tool/usr/share/debootstrap" "$tool/usr/sbin/debootstrap")
fi

# --- The cached bare root ----------------------------------------------------------
# One tarball per mirror (a different mirror is a different root).
key="$(printf '%s' "$suite $mirror" | md5sum | cut -c1-12)"
tarball="$cache/$suite-minbase-$key.tar"
if ((refresh)) || [ ! -f "$tarball" ]; then
  make_bare_root() {
    local tmp
    tmp="$(mktemp -d /var/tmp/strahl-debootstrap.XXXXXX)"
    "${debootstrap_cmd[@]}" --variant=minbase --keyring=/usr/share/keyrings/debian-archive-keyring.gpg \
      "$suite" "$tmp" "$mirror" &&
      tar -C "$tmp" -cf "$tarball.partial" . && mv "$tarball.partial" "$tarball"
    local status=$?
    rm -rf --one-file-system "$tmp"
    return $status
  }
  step debootstrap "debootstrap $suite (minbase)" make_bare_root
fi

# --- A fresh root with a fresh clone -------------------------------------------------
work="$(mktemp -d /var/tmp/strahl-fresh-root.XXXXXX)"
rootfs="$work/root"
mounts=()

cleanup() {
  local status=$? pid m i
  # Processes still running inside the root (a daemon a test left behind) would
  # keep the mounts busy.
  for pid in /proc/[0-9]*; do
    [ "$(readlink "$pid/root" 2>/dev/null)" = "$rootfs" ] && kill -9 "${pid#/proc/}" 2>/dev/null
  done
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do
    m="${mounts[i]}"
    umount "$m" 2>/dev/null || umount -l "$m" 2>/dev/null || echo "fresh-root: could not unmount $m" >&2
  done
  if grep -q " $work/" /proc/self/mountinfo; then
    echo "fresh-root: mounts remain under $work; not deleting it" >&2
    status=1
  elif ((keep)); then
    echo "fresh-root: root kept in $rootfs"
  else
    rm -rf --one-file-system "$work"
  fi
  # The logs stay only when something failed (their path was printed).
  ((status != 0)) || rm -rf "$logs"
  echo "fresh-root: total $((SECONDS - total_start)) s"
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM

mount_into() { # mount_into <target below the root> <mount arguments...>
  local target="$rootfs/$1"
  shift
  mkdir -p "$target"
  mount "$@" "$target"
  mounts+=("$target")
}

prepare_root() {
  mkdir -p "$rootfs" && tar -C "$rootfs" -xf "$tarball" || return 1
  cp /etc/resolv.conf "$rootfs/etc/resolv.conf"
  # The same registry as the host: the main archive, its updates and security.
  rm -f "$rootfs/etc/apt/sources.list"
  {
    echo "Types: deb"
    echo "URIs: $mirror"
    echo "Suites: $suite $suite-updates"
    echo "Components: main"
    echo "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg"
    if [ -n "$security" ]; then
      echo
      echo "Types: deb"
      echo "URIs: $security"
      echo "Suites: $suite-security"
      echo "Components: main"
      echo "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg"
    fi
  } >"$rootfs/etc/apt/sources.list.d/debian.sources"
  git clone --quiet --no-local "$repo" "$rootfs/src/strahl" &&
    git -C "$rootfs/src/strahl" checkout --quiet --detach "$(git -C "$repo" rev-parse --verify "$ref^{commit}")"
}
step prepare "unpack root and clone $ref ($(git -C "$repo" rev-parse --short "$ref"))" prepare_root

mount_into proc -t proc proc
mount_into sys -t sysfs sysfs
mount_into dev --bind /dev
mount_into dev/pts --bind /dev/pts
mount_into var/cache/apt/archives --bind "$cache/apt-archives"
if [ -n "$shared" ]; then
  # Read-only: a test that wrote into the shared data set would fail here.
  mount_into src/shared --bind "$shared"
  mount -o remount,bind,ro "$rootfs/src/shared"
  echo "fresh-root: $shared mounted read-only as the clone's ../shared"
fi

# Runs a command line in the root, in the clone, as a new user's login would.
in_root() {
  chroot "$rootfs" /usr/bin/env -i HOME=/root TERM=dumb \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    /bin/bash -c "cd /src/strahl && $1"
}

# README command N, verbatim: the first command line after "# N." in README.md.
readme_command() {
  awk -v n="$1" '$0 ~ "^# " n "\\." { found = 1; next } found && !/^#/ && NF { print; exit }' "$rootfs/src/strahl/README.md"
}
command1="$(readme_command 1)"
[ -n "$command1" ] || fail "README.md has no command after a '# 1.' line"
command2="$(readme_command 2)"
[ -n "$command2" ] || fail "README.md has no command after a '# 2.' line"

step command1 "README command 1: $command1" in_root "$command1"
check_outputs() {
  local f ok=0
  for f in out/default.exr out/default.png; do
    if [ -s "$rootfs/src/strahl/$f" ]; then echo "$f: $(stat -c %s "$rootfs/src/strahl/$f") bytes"
    else echo "$f: missing or empty"; ok=1; fi
  done
  return $ok
}
step outputs "outputs out/default.exr and out/default.png" check_outputs
if ((run_command2)); then
  step command2 "README command 2: $command2" in_root "$command2"
  # The stages' times and counts (the whole output is printed only on failure).
  grep -E '^(sanitize: (build|ctest) took|fuzz: built|fuzz: [0-9]+ targets)|tests passed, [0-9]+ tests? failed' "$logs/command2.log" || true
  tail -n 1 "$logs/command2.log"
else
  step test-quick "scripts/test.sh --quick" in_root "./scripts/test.sh --quick"
  tail -n 1 "$logs/test-quick.log"
fi
echo "fresh-root: passed"
