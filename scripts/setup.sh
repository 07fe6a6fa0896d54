#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the Debian packages stepnc builds and tests with. Safe to run again:
# it asks apt only for what is missing, so a ready machine costs no network.
set -euo pipefail

packages=(
  g++ cmake ninja-build ccache        # toolchain; ccache keeps CI rebuilds short
  antlr4 libantlr4-runtime-dev        # expressc's parser generator and runtime (expressc only)
  libfmt-dev                          # formatting in every room
  libpolyclipping-dev                 # Clipper: polygon offsets and Booleans (machining room)
  catch2                              # unit tests (v2, header-only)
  libcli11-dev                        # command-line parsing for expressc and stepnc
  nlohmann-json3-dev                  # JSON model dump and its tests
  libsqlite3-dev                      # every store: the knowledge case base, the control run journal
  python3                             # benchmark input generator, the tutorial test runner
  clang libclang-rt-14-dev            # libFuzzer and sanitizers for the reader
  linuxcnc-uspace                     # LinuxCNC's rs274 interpreter checks posted programs
  libxml2-utils librsvg2-bin          # xmllint and rsvg-convert check that every plot is valid SVG
  doxygen                             # the API reference of the public headers (doxygen target, tested)
  pkgconf                             # pkg-config, to test the installed stepnc.pc
  help2man                            # man pages of stepnc and expressc, from their --help
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
