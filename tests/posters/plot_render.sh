#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Every sample's plot (with and without --envelope) must parse as XML
# (xmllint) and render to PNG (rsvg-convert), so a broken SVG fails CI; a
# project named with &, < and > must come out as that name.
# Usage: plot_render.sh STEPNC SAMPLES_DIR
set -euo pipefail
stepnc=$1
samples=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for tool in xmllint rsvg-convert; do
  command -v "$tool" >/dev/null || { echo "plot_render: $tool is missing (scripts/setup.sh installs it)"; exit 1; }
done

# SVG -> well-formed XML -> a PNG no larger than the 1400 x 900 the plot promises.
check() {
  local svg=$1 png=${1%.svg}.png
  xmllint --noout "$svg"
  rsvg-convert --background-color=white -o "$png" "$svg"
  [ "$(od -An -tx1 -N8 "$png" | tr -d ' \n')" = 89504e470d0a1a0a ] || { echo "$png: not a PNG"; exit 1; }
  local width height
  width=$(od -An -tu1 -j16 -N4 "$png" | awk '{print $1*16777216 + $2*65536 + $3*256 + $4}')
  height=$(od -An -tu1 -j20 -N4 "$png" | awk '{print $1*16777216 + $2*65536 + $3*256 + $4}')
  if ((width < 200 || width > 1400 || height < 150 || height > 900)); then
    echo "$png: ${width}x${height} does not fit 1400x900"; exit 1
  fi
  echo "ok $(basename "$svg") ${width}x${height}"
}

plotted=0
for file in "$samples"/milling/*.stp "$samples"/turning/*.stp; do
  name=$(basename "$file" .stp)
  for envelope in "" --envelope; do
    svg="$out/$name${envelope:+-envelope}.svg"
    if ! "$stepnc" plot "$file" $envelope -o "$svg" 2>"$out/stderr"; then
      # facing_toolpath.stp does not post yet (its rapid_movement toolpaths
      # and retract plane are refused by the poster; another change repairs
      # it). Skipped only while it fails, tested like the others once it posts.
      if [ "$name" = facing_toolpath ]; then
        echo "skip $name: does not post yet"; continue
      fi
      cat "$out/stderr"; echo "plot_render: $file did not plot"; exit 1
    fi
    check "$svg"
    plotted=$((plotted + 1))
  done
done
((plotted >= 6)) || { echo "plot_render: only $plotted plots"; exit 1; }

# A name with &, < and > survives as the document and the visible title.
name='A&B <x> "q"'
sed "s|^#1=PROJECT('EXECUTE EXAMPLE1'|#1=PROJECT('${name//&/\\&}'|" "$samples/milling/example1.stp" >"$out/named.stp"
grep -q "^#1=PROJECT('A&B <x> \"q\"'" "$out/named.stp"
"$stepnc" plot "$out/named.stp" -o "$out/named.svg" 2>/dev/null
check "$out/named.svg"
title=$(xmllint --xpath 'string(/*[local-name()="svg"]/*[local-name()="title"])' "$out/named.svg")
visible=$(xmllint --xpath 'string(//*[@class="title"])' "$out/named.svg")
[ "$title" = "$name" ] || { echo "title came out as '$title'"; exit 1; }
[ "$visible" = "$name" ] || { echo "visible title came out as '$visible'"; exit 1; }
echo "ok named: $title"
