#!/usr/bin/env python3
"""Which Mitsuba 3 scenes of a folder render with kasha, unchanged, and the first error of the rest.

Issue 35's acceptance check. For every `*.xml` directly in the folder (the scenes; `include/` and
other subfolders hold their parts), run

    kasha render SCENE --spp SPP --threads T -q -o OUT/NAME.exr [-D NAME=VALUE ...] [-a COMMON]

with `-D` only for a `$name` the scene uses without a `<default>` (Mitsuba's documentation scenes
expect `-D spp=...` for a few of them), and `-a COMMON` (mitsuba-data's common/ folder, Mitsuba's
own `-a` option) only for a scene that, with its includes, has no `<path>` element to find the shared
meshes and textures there; and report "renders" or kasha's one-line error. The table goes to stdout
in Markdown, and with --json to a file.

    python3 bench/mitsuba_scenes/survey.py --kasha build/kasha \
        --scenes /path/to/mitsuba-data/docs/scenes --out /tmp/mitsuba_survey

The scenes are not part of kasha: fetch github.com/mitsuba-renderer/mitsuba-data and point
--scenes at its docs/scenes folder (its `common/` folder beside docs/ is where the scenes' <path>
elements look).
"""

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor


def parameters_without_default(scene_path):
    """The $names the scene file uses that none of its <default> elements defines."""
    with open(scene_path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    text = re.sub(r"<!--.*?-->", "", text, flags=re.S)
    used = set(re.findall(r"\$([A-Za-z_][A-Za-z0-9_]*)", text))
    defined = set(re.findall(r"<default\s+name=\"([^\"]+)\"", text))
    return sorted(used - defined)


def declares_search_path(scene_path):
    """Whether the scene or a file it includes has a <path> element."""
    with open(scene_path, encoding="utf-8", errors="replace") as f:
        text = re.sub(r"<!--.*?-->", "", f.read(), flags=re.S)
    if re.search(r"<path\b", text):
        return True
    for included in re.findall(r"<include\s+filename=\"([^\"]+)\"", text):
        path = os.path.join(os.path.dirname(scene_path), included)
        if os.path.isfile(path) and declares_search_path(path):
            return True
    return False


def survey_one(args, scene_path):
    name = os.path.splitext(os.path.basename(scene_path))[0]
    values = {"spp": str(args.spp)}
    defines = []
    for parameter in parameters_without_default(scene_path):
        defines += ["-D", "%s=%s" % (parameter, values.get(parameter, "1"))]
    common = os.path.normpath(os.path.join(os.path.abspath(args.scenes), "..", "..", "common"))
    if not declares_search_path(scene_path) and os.path.isdir(common):
        defines += ["-a", common]
    output = os.path.join(args.out, name + ".exr")
    command = [args.kasha, "render", scene_path, "--spp", str(args.spp), "--threads",
               str(args.threads), "-q", "-o", output] + defines
    start = time.time()
    try:
        run = subprocess.run(command, capture_output=True, text=True, timeout=args.timeout)
        seconds = time.time() - start
        if run.returncode == 0:
            return {"scene": name, "result": "renders", "seconds": round(seconds, 1),
                    "defines": defines}
        lines = [l for l in run.stderr.splitlines() if l.startswith("kasha: error:")]
        first = lines[0] if lines else (run.stderr.strip().splitlines() or ["exit %d" % run.returncode])[-1]
        if len(lines) != 1 or run.returncode < 0:
            first += "  [NOT ONE ERROR LINE: exit %d, %d error lines]" % (run.returncode, len(lines))
        first = first.replace(os.path.dirname(scene_path) + "/", "")
        # mitsuba-data's own files (common/...) named from its root, not from this machine's
        root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(scene_path))))
        first = first.replace(root + "/", os.path.basename(root) + "/")
        return {"scene": name, "result": first, "seconds": round(seconds, 1), "defines": defines}
    except subprocess.TimeoutExpired:
        return {"scene": name, "result": "TIMEOUT after %d s" % args.timeout, "defines": defines}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kasha", default="build/kasha")
    parser.add_argument("--scenes", required=True, help="folder of Mitsuba 3 scenes")
    parser.add_argument("--out", default="/tmp/mitsuba_survey", help="folder for the renders")
    parser.add_argument("--spp", type=int, default=4)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=int, default=600)
    parser.add_argument("--json", help="also write the results here")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    scenes = sorted(glob.glob(os.path.join(args.scenes, "*.xml")))
    if not scenes:
        sys.exit("survey: no *.xml in " + args.scenes)
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda s: survey_one(args, s), scenes))
    renders = sum(r["result"] == "renders" for r in results)
    outside = sum("outside kasha's scope" in r["result"] for r in results)
    print("# Mitsuba 3's documentation scenes in kasha\n")
    print("Made by `python3 bench/mitsuba_scenes/survey.py --scenes mitsuba-data/docs/scenes --spp %d` "
          "(mitsuba-data from github.com/mitsuba-renderer/mitsuba-data; docs/mitsuba-import.md). "
          "Each scene is rendered unchanged, with `-D` only for a parameter it has no default for, and "
          "`-a common` (Mitsuba's option) only for a scene without a `<path>` to mitsuba-data's shared files.\n" % args.spp)
    print("%d of %d scenes render; %d are outside kasha's scope; the first error of each other scene "
          "names what kasha lacks.\n" % (renders, len(results), outside))
    print("| scene | result |\n|---|---|")
    for r in results:
        shown = [os.path.basename(d) if d.endswith("/common") else d for d in r["defines"]]
        extra = " (" + " ".join(shown) + ")" if shown else ""
        result = r["result"].replace("kasha: error: ", "").replace("|", "\\|")
        print("| %s%s | %s |" % (r["scene"], extra, result))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
