#!/usr/bin/python3
"""Holds scenes/scene.schema.json against the scene parser (ctest scenes.schema).

Every scene file the repo ships validates against the schema (jsonschema, draft 2020-12), and each case the parser
refuses is refused by the schema too: both sides are asked, so a rule added to one and not the other fails here.

usage: check_scene_schema.py SHADELAB_CLI
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import jsonschema

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPHERE = [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]

# (what is wrong, material, the JSON pointer the parser's message names)
REFUSED = [
    ("measured without a file", {"model": "measured"}, "/materials/m"),
    ("measured with an empty file", {"model": "measured", "params": {"file": ""}}, "/materials/m/params/file"),
    ("measured with a number as its file", {"model": "measured", "params": {"file": 3}}, "/materials/m/params/file"),
    ("a material with neither model nor emission", {}, "/materials/m"),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cli", help="the shadelab executable")
    args = ap.parse_args()
    with open(os.path.join(ROOT, "scenes", "scene.schema.json")) as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    failures = 0

    shipped = [os.path.join(ROOT, "scenes", n) for n in sorted(os.listdir(os.path.join(ROOT, "scenes")))
               if n.endswith(".json") and n != "scene.schema.json"]
    shipped += [os.path.join(ROOT, "tests", "scale-out", "scene.json"), os.path.join(ROOT, "bench", "cycles_scene.json")]
    for path in shipped:
        with open(path) as f:
            errors = list(validator.iter_errors(json.load(f)))
        for e in errors:
            print("%s: /%s: %s" % (os.path.relpath(path, ROOT), "/".join(map(str, e.absolute_path)), e.message))
        failures += len(errors)
    print("%d shipped scenes validate" % len(shipped))

    # A measured material with a file is valid (the parser's side needs the file: tests/CliMeasured).
    ok = {"materials": {"m": {"model": "measured", "params": {"file": "tables/gold.binary"}}}, "shapes": SPHERE}
    if list(validator.iter_errors(ok)):
        print("a measured material with a file does not validate")
        failures += 1

    with tempfile.TemporaryDirectory() as tmp:
        for what, material, pointer in REFUSED:
            scene = {"materials": {"m": material}, "shapes": SPHERE}
            schema_refuses = bool(list(validator.iter_errors(scene)))
            path = os.path.join(tmp, "scene.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            r = subprocess.run([args.cli, "render", path, "--out", os.path.join(tmp, "out.exr"), "--spp", "1"],
                               capture_output=True, text=True, timeout=60)
            parser_refuses = r.returncode == 2 and (pointer + ":") in r.stderr
            print("%s: schema %s, parser %s (exit %d: %s)" % (what, "refuses" if schema_refuses else "ACCEPTS",
                  "refuses" if parser_refuses else "DOES NOT REFUSE", r.returncode, r.stderr.strip()))
            failures += (not schema_refuses) + (not parser_refuses)
    if failures:
        print("FAILED: %d" % failures)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
