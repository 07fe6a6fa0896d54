#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Runs docs/tutorial.md as a reader would, in an empty directory.

    run_tutorial.py TUTORIAL.md WORK_DIR STEPNC_PREFIX

Blocks whose info string names a file (```cpp file=pocket.cpp) are written
to that file; ```sh blocks are run in order with bash -e, with STEPNC_PREFIX
set and its bin/ first on PATH (```sh install blocks, which install stepnc
itself, are skipped: the test suite's fresh install prefix stands in). Then
the files the tutorial promises are checked.
"""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree


def blocks(text):
    for match in re.finditer(r"^```([^\n]*)\n(.*?)^```$", text, re.S | re.M):
        yield match.group(1).split(), match.group(2)


def fail(message):
    print(f"run_tutorial: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    tutorial, work, prefix = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = dict(os.environ, STEPNC_PREFIX=prefix, PATH=f"{prefix}/bin:{os.environ['PATH']}")
    env.pop("CMAKE_PREFIX_PATH", None)
    ran = 0
    with open(tutorial, encoding="utf-8") as file:
        text = file.read()
    for info, body in blocks(text):
        files = [word[len("file="):] for word in info if word.startswith("file=")]
        if files:
            with open(os.path.join(work, files[0]), "w", encoding="utf-8") as out:
                out.write(body)
        elif info == ["sh"]:
            print(f"$ {body}", end="", flush=True)
            done = subprocess.run(["bash", "-e", "-c", body], cwd=work, env=env)
            if done.returncode != 0:
                fail(f"this block exited {done.returncode}:\n{body}")
            ran += 1
    if ran < 4:
        fail(f"only {ran} sh blocks ran")

    def read(name):
        path = os.path.join(work, name)
        if not os.path.isfile(path):
            fail(f"the tutorial did not make {name}")
        with open(path, encoding="utf-8") as file:
            return file.read()

    stp = read("pocket.stp")
    for entity in ("CLOSED_POCKET(", "RECTANGULAR_CLOSED_PROFILE(", "BOTTOM_AND_SIDE_FINISH_MILLING("):
        if entity not in stp:
            fail(f"pocket.stp has no {entity}")
    ngc = read("pocket.ngc")
    for word in ("S9000 M3", "F1200", "M2"):
        if word not in ngc:
            fail(f"pocket.ngc has no {word!r}, as the tutorial says it has")
    if '"WS FINISH POCKET"' not in read("pocket.json"):
        fail("pocket.json does not trace the finishing workingstep")
    svg = ElementTree.fromstring(read("pocket.svg"))
    if not svg.tag.endswith("svg"):
        fail("pocket.svg is not an SVG document")
    print(f"run_tutorial: {ran} sh blocks ran; pocket.stp, pocket.ngc, pocket.json, pocket.svg as described")


main()
