#!/usr/bin/env bash
# The Debian packages some tests use (tools/system-packages.tsv), installed once before pytest starts, by `.ci/run`
# and by `make test`, never by a test: two test workers running apt at once race for its lock.
#
#   tools/system_packages.sh            install what is missing where this process may (root, with apt-get);
#                                       elsewhere say which tests will skip and why, and succeed
#   tools/system_packages.sh --require  the same, but fail where a package is missing and cannot be installed (CI)
set -euo pipefail
TABLE="$(dirname "$0")/system-packages.tsv"

require=0
[ "${1:-}" = "--require" ] && require=1

packages=()
uses=()
while IFS=$'\t' read -r command package used_by; do
  case "$command" in ''|'#'*) continue ;; esac
  command -v "$command" >/dev/null 2>&1 && continue
  packages+=("$package")
  uses+=("$used_by")
done < "$TABLE"
[ ${#packages[@]} -eq 0 ] && exit 0

if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "system packages: installing ${packages[*]}"
  export DEBIAN_FRONTEND=noninteractive
  # Another apt on the machine (a developer's make test beside CI's) is waited for, not raced.
  apt-get -o DPkg::Lock::Timeout=300 update -qq
  apt-get -o DPkg::Lock::Timeout=300 install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
  exit 0
fi

for index in "${!packages[@]}"; do
  echo "system packages: ${packages[$index]} is missing, so these tests will skip: ${uses[$index]}"
done
echo "system packages: install them as root with tools/system_packages.sh"
[ "$require" = 0 ]
