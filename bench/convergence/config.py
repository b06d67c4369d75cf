"""Reading and checking a convergence-report configuration (see README.md in this directory).

A configuration is a JSON file; every problem is reported as `FILE: /json/pointer: reason`.
"""
import json
import os


class ConfigError(Exception):
    pass


def _fail(path, pointer, reason):
    raise ConfigError(f"{path}: {pointer}: {reason}")


def _number(path, pointer, value, positive=True):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or (positive and not value > 0):
        _fail(path, pointer, f"expected a {'positive ' if positive else ''}number, got {json.dumps(value)}")
    return value


def _string(path, pointer, value):
    if not isinstance(value, str) or not value:
        _fail(path, pointer, f"expected a non-empty string, got {json.dumps(value)}")
    return value


def _only(path, pointer, obj, allowed, required=()):
    if not isinstance(obj, dict):
        _fail(path, pointer, f"expected an object, got {json.dumps(obj)}")
    for key in obj:
        if key not in allowed:
            _fail(path, f"{pointer}/{key}", "unknown field")
    for key in required:
        if key not in obj:
            _fail(path, f"{pointer}/{key}", "missing required field")


def _args(path, pointer, value):
    if not isinstance(value, list) or not all(isinstance(a, str) for a in value):
        _fail(path, pointer, "expected a list of strings (extra kasha render arguments)")
    return value


def _configuration(path, pointer, c):
    _only(path, pointer, c, ("label", "integrator", "args"), ("label", "integrator"))
    return {"label": _string(path, pointer + "/label", c["label"]),
            "integrator": _string(path, pointer + "/integrator", c["integrator"]),
            "args": _args(path, pointer + "/args", c.get("args", []))}


def _crop(path, pointer, crop):
    if (not isinstance(crop, list) or len(crop) != 4 or
            not all(isinstance(v, (int, float)) and not isinstance(v, bool) and 0 <= v <= 1 for v in crop) or
            not (crop[0] < crop[2] and crop[1] < crop[3])):
        _fail(path, pointer, "expected [x0, y0, x1, y1], fractions of the image with x0 < x1, y0 < y1")
    return crop


def _comparisons(path, pointer, value, labels):
    """A scene's comparisons: [{"combination": label, "parts": [label, ...]}], labels among the scene's."""
    if not isinstance(value, list):
        _fail(path, pointer, "expected a list of {\"combination\": label, \"parts\": [labels]}")
    out = []
    for i, c in enumerate(value):
        p = f"{pointer}/{i}"
        _only(path, p, c, ("combination", "parts"), ("combination", "parts"))
        if not isinstance(c["parts"], list) or not c["parts"]:
            _fail(path, p + "/parts", "expected a non-empty list of configuration labels")
        for q, label in [("/combination", c["combination"])] + [(f"/parts/{j}", l) for j, l in enumerate(c["parts"])]:
            if _string(path, p + q, label) not in labels:
                _fail(path, p + q, f"no configuration labelled {json.dumps(label)} in this scene")
        out.append({"combination": c["combination"], "parts": list(c["parts"])})
    return out


def _scene_reference(path, pointer, r, default):
    """A scene's reference: the report's, with the scene's own integrator, arguments and time if given."""
    _only(path, pointer, r, ("integrator", "args", "time"))
    out = dict(default)
    if "integrator" in r:
        out["integrator"] = _string(path, pointer + "/integrator", r["integrator"])
        out["args"] = []
    if "args" in r:
        out["args"] = _args(path, pointer + "/args", r["args"])
    if "time" in r:
        out["time"] = _number(path, pointer + "/time", r["time"])
    return out


def load(path, quick=False):
    """The configuration as a dict; with quick=True, the `quick` block's reductions applied."""
    try:
        with open(path) as f:
            cfg = json.load(f)
    except OSError as e:
        raise ConfigError(f"{path}: cannot open: {e.strerror}")
    except json.JSONDecodeError as e:
        raise ConfigError(f"{path}: malformed JSON: {e}")
    _only(path, "", cfg, ("description", "output", "work", "threads", "seeds", "budget", "reference",
                          "configurations", "scenes", "quick"),
          ("output", "work", "seeds", "budget", "reference", "configurations", "scenes"))
    base = os.path.dirname(os.path.abspath(path))
    out = {"path": path, "description": cfg.get("description", ""),
           "output": os.path.normpath(os.path.join(base, _string(path, "/output", cfg["output"]))),
           "work": os.path.normpath(os.path.join(base, _string(path, "/work", cfg["work"]))),
           "threads": int(_number(path, "/threads", cfg.get("threads", 0), positive=False))}
    seeds = cfg["seeds"]
    if not isinstance(seeds, list) or len(seeds) < 2 or not all(isinstance(s, int) and s >= 0 for s in seeds):
        _fail(path, "/seeds", "expected a list of at least two non-negative integers (a standard deviation needs two)")
    out["seeds"] = seeds

    b = cfg["budget"]
    _only(path, "/budget", b, ("kind", "values"), ("kind", "values"))
    if b["kind"] not in ("time", "spp"):
        _fail(path, "/budget/kind", f"expected \"time\" (seconds, --time) or \"spp\" (--spp), got {json.dumps(b['kind'])}")
    if not isinstance(b["values"], list) or not b["values"]:
        _fail(path, "/budget/values", "expected a non-empty list of budgets")
    values = [_number(path, f"/budget/values/{i}", v) for i, v in enumerate(b["values"])]
    if b["kind"] == "spp" and not all(isinstance(v, int) for v in values):
        _fail(path, "/budget/values", "samples per pixel must be integers")
    out["budget"] = {"kind": b["kind"], "values": sorted(values)}

    r = cfg["reference"]
    _only(path, "/reference", r, ("integrator", "args", "time", "seed"), ("integrator", "time"))
    out["reference"] = {"integrator": _string(path, "/reference/integrator", r["integrator"]),
                        "args": _args(path, "/reference/args", r.get("args", [])),
                        "time": _number(path, "/reference/time", r["time"]),
                        "seed": int(_number(path, "/reference/seed", r.get("seed", 1000003), positive=False))}

    if not isinstance(cfg["configurations"], list) or not cfg["configurations"]:
        _fail(path, "/configurations", "expected a non-empty list")
    out["configurations"] = [_configuration(path, f"/configurations/{i}", c) for i, c in enumerate(cfg["configurations"])]
    labels = [c["label"] for c in out["configurations"]]
    for i, label in enumerate(labels):
        if labels.index(label) != i:
            _fail(path, f"/configurations/{i}/label", f"duplicate label {json.dumps(label)}")

    if not isinstance(cfg["scenes"], list) or not cfg["scenes"]:
        _fail(path, "/scenes", "expected a non-empty list")
    out["scenes"] = []
    for i, s in enumerate(cfg["scenes"]):
        p = f"/scenes/{i}"
        _only(path, p, s, ("scene", "name", "note", "crop", "resolution_scale", "configurations", "reference",
                           "comparisons"), ("scene", "crop"))
        scene = os.path.normpath(os.path.join(base, _string(path, p + "/scene", s["scene"])))
        if not os.path.isfile(scene):
            _fail(path, p + "/scene", f"no such file: {scene}")
        only = s.get("configurations", labels)
        for j, label in enumerate(only):
            if label not in labels:
                _fail(path, f"{p}/configurations/{j}", f"no configuration labelled {json.dumps(label)}")
        out["scenes"].append({"scene": scene,
                              "name": s.get("name", os.path.splitext(os.path.basename(scene))[0]),
                              "note": s.get("note", ""),
                              "crop": _crop(path, p + "/crop", s["crop"]),
                              "resolution_scale": _number(path, p + "/resolution_scale", s.get("resolution_scale", 1.0)),
                              "reference": _scene_reference(path, p + "/reference", s.get("reference", {}),
                                                            out["reference"]),
                              "configurations": [c for c in out["configurations"] if c["label"] in only],
                              "comparisons": _comparisons(path, p + "/comparisons", s.get("comparisons", []), only)})

    q = cfg.get("quick", {})
    _only(path, "/quick", q, ("budget_scale", "reference_scale", "resolution_scale", "seeds"))
    out["quick"] = quick
    if quick:
        bs = out["quick_budget_scale"] = _number(path, "/quick/budget_scale", q.get("budget_scale", 1.0))
        kind = out["budget"]["kind"]
        out["budget"]["values"] = [max(1, round(v * bs)) if kind == "spp" else v * bs for v in out["budget"]["values"]]
        ref_scale = _number(path, "/quick/reference_scale", q.get("reference_scale", 1.0))
        out["reference"]["time"] *= ref_scale
        rs = _number(path, "/quick/resolution_scale", q.get("resolution_scale", 1.0))
        for s in out["scenes"]:
            s["resolution_scale"] *= rs
            s["reference"]["time"] *= ref_scale
        n = q.get("seeds", len(seeds))
        if not isinstance(n, int) or n < 2:
            _fail(path, "/quick/seeds", "expected an integer >= 2")
        out["seeds"] = seeds[:n]
    return out
