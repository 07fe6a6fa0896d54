#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Compiles every EXPRESS file below DIR with expressc, each file on its own,
# and prints a Markdown table row per file: the file, expressc's exit code,
# and how many warnings and errors it printed. For published schema sets
# fetched by hand (expressc/README.md, "Published schemas"); nothing is
# downloaded here.
#
#   scripts/compile_schemas.sh build/release/expressc/expressc DIR
set -euo pipefail
if [[ $# -ne 2 ]]; then
  echo "usage: $0 EXPRESSC DIR" >&2
  exit 2
fi
expressc=$1
dir=$2
echo "| file | exit code | warnings | errors |"
echo "| --- | --- | --- | --- |"
while IFS= read -r -d '' file; do
  status=0
  output=$("$expressc" --summary "$file" 2>&1) || status=$?
  warnings=$(grep -c ': warning: ' <<<"$output" || true)
  errors=$(grep -c ': error: ' <<<"$output" || true)
  echo "| ${file#"$dir"/} | $status | $warnings | $errors |"
done < <(find "$dir" -name '*.exp' -print0 | sort -z)
