#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Puts `SPDX-License-Identifier: Apache-2.0` at the top of the project's own
# source files (after a #! line), in the comment syntax of each kind of file.
# Safe to run again: files that carry it are left alone.
#
#   scripts/spdx.sh            every tracked source file
#   scripts/spdx.sh FILE...    only these
#   scripts/spdx.sh --check    list files without it; exit 1 if there are any
#
# generated/ is expressc output and is not stamped (see README, "Licence"):
# the emitter puts no licence on bindings, since a user's own schemas'
# bindings are the user's.
set -euo pipefail
cd "$(dirname "$0")/.."

check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
if (($#)); then
  files=("$@")
else
  mapfile -t files < <(git ls-files -- ':!generated/' ':!tests/*/fuzz/corpus/*' |
    grep -E '(\.(h|cpp|cc|cmake|sh|g4|in|py)|CMakeLists\.txt)$')
fi

tag='SPDX-License-Identifier: Apache-2.0'
missing=0
for file in "${files[@]}"; do
  head -n 3 "$file" | grep -q "$tag" && continue
  missing=1
  if ((check)); then echo "$file"; continue; fi
  case "$file" in
    *.h|*.cpp|*.cc|*.g4|*.h.in) line="// $tag" ;;
    *) line="# $tag" ;;
  esac
  if head -n 1 "$file" | grep -q '^#!'; then
    sed -i "1a $line" "$file"
  else
    sed -i "1i $line" "$file"
  fi
done
if ((check && missing)); then exit 1; fi
exit 0
