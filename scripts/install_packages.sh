#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs Debian packages for one of the project's scripts, through sudo unless run as root;
# apt's output goes to stderr so that the caller's standard output stays its own.
#   scripts/install_packages.sh CALLER PACKAGE...
set -euo pipefail
caller=$1
shift
[ $# -gt 0 ] || exit 0
echo "$caller: installing $*" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq >&2
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$@" >&2
