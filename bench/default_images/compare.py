#!/usr/bin/env python3
"""Default images of two kasha binaries: bit-identical, or equal within 4 sigma per 8x8 block.

Issue 32's acceptance check (README.md beside this file). For every scene and integrator:

1. Render once with both binaries at the scene's own seed. If the EXRs' pixels (R, G, B and
   XYZ.X/Y/Z, compared byte for byte) are equal: "identical".
2. Otherwise render K seeds with each binary (the reference seeds B+1..B+K, the candidate seeds
   B+K+1..B+2K, so that the two samples are independent whether or not the candidate draws its
   random numbers as the reference does) and test each 8x8 block of each XYZ channel with Welch's
   t statistic on the K block means of each side:
       z = (mean_cand - mean_ref) / sqrt(var_cand/K + var_ref/K + (rtol * max|mean|)^2)
   A block is "beyond 4 sigma" when any of its channels has |z| > 4. Its probability under the
   null (same estimator) is taken from Student's t with Welch's degrees of freedom per channel,
   combined over the channels with Sidak's bound 1 - prod(1 - p_c) (never below the truth for
   two-sided tests of correlated Gaussian statistics). The pair is DIFFERENT when
     (A) the observed number of blocks beyond 4 sigma is improbably large for a Poisson count
         with the expected number as its mean (P(N >= observed) < alpha), or
     (B) one block alone is improbable after a Bonferroni correction (its Sidak-combined
         p-value at its own |z| < alpha / blocks tested), which also catches a block that is
         noise-free on both sides (e.g. directly seen emitters) but differs by more than 4 rtol,
   and when an image has non-finite pixels or the two images differ in size.

Only Python 3 and numpy are needed: the OpenEXR reader (scanline, NONE/ZIPS/ZIP, HALF/FLOAT/UINT)
and Student's t tail (the regularized incomplete beta function) are implemented here.
"""

import argparse
import glob
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import zlib
from concurrent.futures import ThreadPoolExecutor

import numpy as np

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
FALLBACK_INTEGRATORS = ["pt", "lt", "bdpt", "bdpt-shared", "bdpt-independent", "bdpt-mollified", "ppm", "vcm",
                        "vc", "bpm"]
PIXEL_CHANNELS = ["R", "G", "B", "XYZ.X", "XYZ.Y", "XYZ.Z"]
XYZ = ["XYZ.X", "XYZ.Y", "XYZ.Z"]
BLOCK = 8
THRESHOLD = 4.0
FAILING = {"DIFFERENT", "NON-FINITE", "REFUSED BY ONE", "REFUSED DIFFERENTLY", "ERROR"}


# ---------------------------------------------------------------------------------------------
# OpenEXR (single-part scanline files, as kasha writes them)

def read_exr(path):
    """{channel name: float64 array (height, width)} of a single-part scanline OpenEXR."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError(f"{path}: not an OpenEXR file")
    version = struct.unpack_from("<I", data, 4)[0]
    if version & 0x200 or version & 0x800 or version & 0x1000:
        raise ValueError(f"{path}: tiled, deep or multi-part OpenEXR is not supported")
    pos = 8
    header = {}
    while True:
        end = data.index(b"\0", pos)
        name = data[pos:end].decode()
        pos = end + 1
        if not name:
            break
        end = data.index(b"\0", pos)
        atype = data[pos:end].decode()
        size = struct.unpack_from("<i", data, end + 1)[0]
        header[name] = (atype, data[end + 5:end + 5 + size])
        pos = end + 5 + size
    channels = []  # (name, pixel type), in the file's (alphabetical) order
    raw = header["channels"][1]
    p = 0
    while raw[p] != 0:
        end = raw.index(b"\0", p)
        name = raw[p:end].decode()
        ptype, _, xs, ys = struct.unpack_from("<iB3xii", raw, end + 1)
        if xs != 1 or ys != 1:
            raise ValueError(f"{path}: subsampled channel {name}")
        channels.append((name, ptype))
        p = end + 1 + 16
    compression = header["compression"][1][0]
    lines_per_chunk = {0: 1, 2: 1, 3: 16}.get(compression)
    if lines_per_chunk is None:
        raise ValueError(f"{path}: compression {compression} is not supported (NONE, ZIPS, ZIP only)")
    xmin, ymin, xmax, ymax = struct.unpack("<iiii", header["dataWindow"][1])
    width, height = xmax - xmin + 1, ymax - ymin + 1
    nchunks = (height + lines_per_chunk - 1) // lines_per_chunk
    offsets = struct.unpack_from(f"<{nchunks}Q", data, pos)
    sizes = {0: 4, 1: 2, 2: 4}  # UINT, HALF, FLOAT
    dtypes = {0: "<u4", 1: "<f2", 2: "<f4"}
    out = {name: np.empty((height, width), dtype=dtypes[t]) for name, t in channels}
    for off in offsets:
        y, n = struct.unpack_from("<ii", data, off)
        chunk = data[off + 8:off + 8 + n]
        lines = min(lines_per_chunk, ymax + 1 - y)
        expected = lines * width * sum(sizes[t] for _, t in channels)
        if n < expected:  # compressed (stored raw when compression would not shrink it)
            t = np.frombuffer(zlib.decompress(chunk), dtype=np.uint8).astype(np.int64)
            t = np.cumsum(np.concatenate([t[:1], t[1:] - 128])) & 0xFF  # undo the predictor
            t = t.astype(np.uint8)
            half = (len(t) + 1) // 2
            chunk = np.empty_like(t)
            chunk[0::2], chunk[1::2] = t[:half], t[half:]
            chunk = chunk.tobytes()
        if len(chunk) != expected:
            raise ValueError(f"{path}: chunk at line {y} has {len(chunk)} bytes, expected {expected}")
        q = 0
        for line in range(lines):
            for name, t in channels:
                nbytes = width * sizes[t]
                out[name][y - ymin + line] = np.frombuffer(chunk, dtype=dtypes[t], count=width, offset=q)
                q += nbytes
    return out


# ---------------------------------------------------------------------------------------------
# Statistics

def betainc_reg(a, b, x):
    """Regularized incomplete beta I_x(a, b), elementwise (continued fraction, Numerical Recipes)."""
    a, b, x = np.broadcast_arrays(np.asarray(a, float), np.asarray(b, float), np.asarray(x, float))
    result = np.zeros(a.shape)
    result[x >= 1] = 1.0
    inside = (x > 0) & (x < 1)
    if not inside.any():
        return result
    a, b, x = a[inside], b[inside], x[inside]
    lg = np.vectorize(math.lgamma, otypes=[float])
    front = np.exp(lg(a + b) - lg(a) - lg(b) + a * np.log(x) + b * np.log1p(-x))
    swap = x >= (a + 1) / (a + b + 2)
    aa_, bb_, xx_ = np.where(swap, b, a), np.where(swap, a, b), np.where(swap, 1 - x, x)

    def cf(a, b, x):
        tiny = 1e-300
        qab, qap, qam = a + b, a + 1, a - 1
        c = np.ones_like(x)
        d = 1 - qab * x / qap
        d = 1 / np.where(np.abs(d) < tiny, tiny, d)
        h = d.copy()
        for m in range(1, 1000):
            m2 = 2 * m
            for num in (m * (b - m) * x / ((qam + m2) * (a + m2)), -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))):
                d = 1 + num * d
                d = 1 / np.where(np.abs(d) < tiny, tiny, d)
                c = 1 + num / c
                c = np.where(np.abs(c) < tiny, tiny, c)
                delta = d * c
                h = h * delta
            if np.all(np.abs(delta - 1) < 1e-15):
                break
        return h

    value = front * cf(aa_, bb_, xx_) / aa_
    result[inside] = np.where(swap, 1 - value, value)
    return result


def t_two_sided(t, df):
    """P(|T| > |t|) for Student's t with (real, possibly infinite) df, elementwise."""
    t, df = np.broadcast_arrays(np.abs(np.asarray(t, float)), np.asarray(df, float))
    out = np.empty(t.shape)
    big = ~np.isfinite(df) | (df > 1e7)
    out[big] = np.vectorize(math.erfc, otypes=[float])(t[big] / math.sqrt(2)) if big.any() else []
    small = ~big
    out[small] = betainc_reg(df[small] / 2, 0.5, df[small] / (df[small] + t[small] ** 2))
    out[np.isinf(t)] = 0.0
    return out


def poisson_sf(observed, mean):
    """P(N >= observed) for N ~ Poisson(mean)."""
    if observed <= 0:
        return 1.0
    if mean <= 0:
        return 0.0
    term = lambda k: math.exp(-mean + k * math.log(mean) - math.lgamma(k + 1))
    if observed <= mean:
        return max(0.0, 1.0 - sum(term(k) for k in range(observed)))
    total, k = 0.0, observed
    while True:
        x = term(k)
        total += x
        if x < total * 1e-17 or k > observed + 100000:
            return total
        k += 1


def block_means(img):
    """(blocks_y, blocks_x) mean of each 8x8 block (partial blocks at the edges: their pixels)."""
    h, w = img.shape
    by, bx = -(-h // BLOCK), -(-w // BLOCK)
    padded = np.zeros((by * BLOCK, bx * BLOCK))
    count = np.zeros_like(padded)
    padded[:h, :w], count[:h, :w] = img, 1
    s = padded.reshape(by, BLOCK, bx, BLOCK).sum(axis=(1, 3))
    n = count.reshape(by, BLOCK, bx, BLOCK).sum(axis=(1, 3))
    return s / n


def block_test(ref_images, cand_images, alpha, rtol):
    """Welch test per 8x8 block and XYZ channel over the seeds. ref/cand_images: lists of
    {channel: array}. Returns a dict of the decision and its numbers."""
    k_ref, k_cand = len(ref_images), len(cand_images)
    # (seeds, channels, blocks)
    r = np.stack([np.stack([block_means(im[c].astype(np.float64)).ravel() for c in XYZ]) for im in ref_images])
    c = np.stack([np.stack([block_means(im[ch].astype(np.float64)).ravel() for ch in XYZ]) for im in cand_images])
    mr, mc = r.mean(0), c.mean(0)
    vr, vc = r.var(0, ddof=1), c.var(0, ddof=1)
    sr, sc = vr / k_ref, vc / k_cand
    skip = np.all(r == 0, axis=0) & np.all(c == 0, axis=0)        # zero on both sides in every seed
    scale = rtol * np.maximum(np.abs(mr), np.abs(mc))
    se = np.sqrt(sr + sc + scale ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, (mc - mr) / se, 0.0)
        df = np.where(sr + sc > 0, (sr + sc) ** 2 / (sr ** 2 / (k_ref - 1) + sc ** 2 / (k_cand - 1)), np.inf)
    noiseless = (sr + sc == 0) & ~skip                           # both sides the same in every seed
    z = np.where(skip, 0.0, z)
    # Null probabilities: beyond 4 sigma (for the expected count) and beyond the observed |z|.
    p4 = np.where(skip | noiseless, 0.0, t_two_sided(np.full(z.shape, THRESHOLD), df))
    pz = np.where(skip, 1.0, t_two_sided(z, df))
    pz = np.where(noiseless, np.where(np.abs(z) > THRESHOLD, 0.0, 1.0), pz)
    tested = ~np.all(skip, axis=0)                               # blocks with a channel tested
    beyond = np.any((np.abs(z) > THRESHOLD) & ~skip, axis=0)
    p_block4 = 1 - np.prod(1 - p4, axis=0)                       # Sidak over X, Y, Z
    p_block = 1 - np.prod(1 - pz, axis=0)
    n_tested = int(tested.sum())
    observed = int(beyond.sum())
    expected = float(p_block4[tested].sum())
    p_count = poisson_sf(observed, expected)
    p_min = float(p_block[tested].min()) if n_tested else 1.0
    worst = int(np.argmin(np.where(tested, p_block, 2.0))) if n_tested else 0
    fail_count = p_count < alpha
    fail_block = n_tested > 0 and p_min < alpha / n_tested
    # Sensitivity: 4 sigma of a block relative to its mean (Y), the median over the blocks tested.
    y_tested = ~skip[1] & (np.maximum(np.abs(mr[1]), np.abs(mc[1])) > 0)
    resolution = float(np.median(THRESHOLD * se[1][y_tested] / np.maximum(np.abs(mr[1]), np.abs(mc[1]))[y_tested])) \
        if y_tested.any() else 0.0
    # (C) The whole image's mean per channel: one Welch test per channel on K numbers per side,
    # free of the blocks' correlations; catches a small bias spread over the image.
    ir = np.stack([[im[ch].astype(np.float64).mean() for ch in XYZ] for im in ref_images])
    ic = np.stack([[im[ch].astype(np.float64).mean() for ch in XYZ] for im in cand_images])
    isr, isc = ir.var(0, ddof=1) / k_ref, ic.var(0, ddof=1) / k_cand
    ise = np.sqrt(isr + isc + (rtol * np.maximum(np.abs(ir.mean(0)), np.abs(ic.mean(0)))) ** 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        iz = np.where(ise > 0, (ic.mean(0) - ir.mean(0)) / ise, 0.0)
        idf = np.where(isr + isc > 0, (isr + isc) ** 2 / (isr ** 2 / (k_ref - 1) + isc ** 2 / (k_cand - 1)), np.inf)
    ip = np.where(isr + isc > 0, t_two_sided(iz, idf), np.where(np.abs(iz) > THRESHOLD, 0.0, 1.0))
    p_image = float(1 - np.prod(1 - ip))
    rel_image = (ic.mean(0) - ir.mean(0)) / np.where(ir.mean(0) != 0, np.abs(ir.mean(0)), 1.0)
    fail_image = p_image < alpha
    finite_df = df[~skip & np.isfinite(df)]
    return {
        "blocks_tested": n_tested,
        "blocks_skipped": int((~tested).sum()),
        "beyond_observed": observed,
        "beyond_expected": expected,
        "p_count": p_count,
        "min_block_p": p_min,
        "worst_block": worst,
        "max_abs_z": float(np.abs(z[:, tested]).max()) if n_tested else 0.0,
        "df_median": float(np.median(finite_df)) if finite_df.size else float("inf"),
        "block_resolution": resolution,
        # Noise shape: the candidate's variance over the reference's per block (Y), the median;
        # near 1 when both run the same estimator with different random numbers.
        "variance_ratio": float(np.median(vc[1][y_tested & (vr[1] > 0)] / vr[1][y_tested & (vr[1] > 0)]))
        if (y_tested & (vr[1] > 0)).any() else float("nan"),
        "image_z": [float(v) for v in iz],
        "image_relative_difference": [float(v) for v in rel_image],
        "p_image": p_image,
        "fail_count": bool(fail_count),
        "fail_block": bool(fail_block),
        "fail_image": bool(fail_image),
        "equal": not (fail_count or fail_block or fail_image),
    }


# ---------------------------------------------------------------------------------------------
# Rendering

class Render:
    def __init__(self, binary, scene, integrator, seed, spp, threads, path, extra):
        self.cmd = [binary, "render", scene, "--integrator", integrator, "--threads", str(threads), "-q",
                    "--no-png", "-o", path] + extra
        if spp > 0:
            self.cmd += ["--spp", str(spp)]
        if seed is not None:
            self.cmd += ["--seed", str(seed)]
        self.path = path

    def run(self):
        os.makedirs(os.path.dirname(self.path), exist_ok=True)
        p = subprocess.run(self.cmd, capture_output=True, text=True)
        self.rc, self.stderr = p.returncode, p.stderr
        self.refused = p.returncode != 0 and "kasha: error:" in p.stderr
        return self

    def error_line(self, prefix):
        lines = [l for l in self.stderr.splitlines() if "kasha: error:" in l]
        text = lines[0] if lines else self.stderr.strip()
        return text.replace(os.path.dirname(self.path), prefix)

    def load(self):
        img = read_exr(self.path)
        missing = [c for c in PIXEL_CHANNELS if c not in img]
        if missing:
            raise ValueError(f"{self.path}: no channel {', '.join(missing)}")
        return img


def integrator_names(binary):
    try:
        text = subprocess.run([binary, "render", "--help"], capture_output=True, text=True, timeout=60).stdout
    except (OSError, subprocess.TimeoutExpired):
        return []
    m = re.search(r"Integrator:([^\n]*)", text)
    if not m:
        return []
    return [part.split()[0] for part in m.group(1).split("|") if part.split()]


def compare_pair(args, scene, integrator, pool):
    name = os.path.splitext(os.path.basename(scene))[0]
    base = os.path.join(args.out, "renders", name, integrator)
    run = lambda binary, side, seed, tag: Render(binary, scene, integrator, seed, args.spp, args.threads,
                                                 os.path.join(base, side, f"{tag}.exr"), args.extra)
    row = {"scene": name, "integrator": integrator}
    try:
        return _compare_pair(args, row, run, pool)
    finally:
        if not args.keep_images:
            shutil.rmtree(base, ignore_errors=True)


def _compare_pair(args, row, run, pool):
    ref, cand = pool.map(Render.run, [run(args.reference, "ref", None, "default"),
                                      run(args.candidate, "cand", None, "default")])
    if ref.rc != 0 or cand.rc != 0:
        if ref.refused and cand.refused:
            r, c = ref.error_line("OUT"), cand.error_line("OUT")
            if r == c:
                return dict(row, status="refused by both", detail=r)
            return dict(row, status="REFUSED DIFFERENTLY", detail=f"reference: {r} / candidate: {c}")
        if (ref.refused and cand.rc == 0) or (cand.refused and ref.rc == 0):
            who, r = ("reference", ref) if ref.refused else ("candidate", cand)
            return dict(row, status="REFUSED BY ONE", detail=f"{who}: {r.error_line('OUT')}")
        bad = ref if ref.rc != 0 else cand
        side = "reference" if bad is ref else "candidate"
        return dict(row, status="ERROR", detail=f"{side} exit {bad.rc}: {bad.error_line('OUT')[-300:]}")
    a, b = ref.load(), cand.load()
    for side, img in (("reference", a), ("candidate", b)):
        bad = [c for c in PIXEL_CHANNELS if not np.all(np.isfinite(img[c]))]
        if bad:
            return dict(row, status="NON-FINITE", detail=f"{side} (default seed): channels {', '.join(bad)}")
    if a["XYZ.X"].shape != b["XYZ.X"].shape:
        return dict(row, status="DIFFERENT", detail=f"image sizes {a['XYZ.X'].shape} vs {b['XYZ.X'].shape}")
    identical = all(a[c].tobytes() == b[c].tobytes() for c in PIXEL_CHANNELS)
    if identical and not args.force_statistical:
        return dict(row, status="identical", detail="R, G, B, XYZ bit-identical at the scene's seed")
    # Step 2: K independent seeds per side.
    k = args.seeds
    jobs = [run(args.reference, "ref", args.seed_base + i, f"seed{args.seed_base + i}") for i in range(1, k + 1)]
    jobs += [run(args.candidate, "cand", args.seed_base + k + i, f"seed{args.seed_base + k + i}") for i in range(1, k + 1)]
    done = list(pool.map(Render.run, jobs))
    for r in done:
        if r.rc != 0:
            return dict(row, status="ERROR", detail=f"{' '.join(r.cmd[2:])}: exit {r.rc}: {r.error_line('OUT')[-300:]}")
    images = [r.load() for r in done]
    for r, img in zip(done, images):
        bad = [c for c in PIXEL_CHANNELS if not np.all(np.isfinite(img[c]))]
        if bad:
            return dict(row, status="NON-FINITE", detail=f"{os.path.basename(r.path)} ({'reference' if r in done[:k] else 'candidate'}): {', '.join(bad)}")
        if img["XYZ.X"].shape != a["XYZ.X"].shape:
            return dict(row, status="DIFFERENT", detail="image sizes differ between seeds")
    t = block_test(images[:k], images[k:], args.alpha, args.rtol)
    why = []
    if t["fail_count"]:
        why.append(f"count P={t['p_count']:.2g} < {args.alpha:g}")
    if t["fail_block"]:
        why.append(f"block {t['worst_block']} P={t['min_block_p']:.2g} < {args.alpha:g}/{t['blocks_tested']}")
    if t["fail_image"]:
        why.append(f"image mean P={t['p_image']:.2g} < {args.alpha:g}")
    iz = "/".join(f"{v:+.1f}" for v in t["image_z"])
    rel = "/".join(f"{100 * v:+.2f}" for v in t["image_relative_difference"])
    detail = (f"{t['blocks_tested']} blocks tested ({t['blocks_skipped']} zero), beyond 4σ: {t['beyond_observed']} observed"
              f" vs {t['beyond_expected']:.2f} expected (P={t['p_count']:.2g}); max |z| {t['max_abs_z']:.2f},"
              f" min block P {t['min_block_p']:.2g}; 4σ = {100 * t['block_resolution']:.1f}% of a block (median);"
              f" variance cand/ref {t['variance_ratio']:.2f} (median);"
              f" image mean XYZ z {iz} ({rel}%, P={t['p_image']:.2g})")
    first = "" if identical or not args.force_statistical else " [default seed not identical]"
    if t["equal"]:
        return dict(row, status="statistically equal", detail=detail + first, stats=t)
    return dict(row, status="DIFFERENT", detail="; ".join(why) + ": " + detail + first, stats=t)


# ---------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference", required=True, help="kasha binary of the reference commit")
    ap.add_argument("--candidate", required=True, help="kasha binary to check")
    ap.add_argument("--scenes", nargs="+", help="scene files (default: every scenes/*.json of this repository)")
    ap.add_argument("--integrators", help="comma-separated (default: every name that either binary's "
                                          "`kasha render --help` lists)")
    ap.add_argument("--spp", type=int, default=4, help="samples per pixel of every render (0: the scene's own; default 4)")
    ap.add_argument("--seeds", type=int, default=8, help="seeds per binary when the images are not identical (>= 8; default 8)")
    ap.add_argument("--seed-base", type=int, default=1000, help="reference seeds B+1..B+K, candidate seeds B+K+1..B+2K (default 1000)")
    ap.add_argument("--threads", type=int, default=1, help="--threads of every render (default 1)")
    ap.add_argument("--jobs", type=int, default=1, help="renders run at once (default 1)")
    ap.add_argument("--alpha", type=float, default=1e-4, help="false-alarm probability of each rule per scene and integrator (default 1e-4)")
    ap.add_argument("--rtol", type=float, default=1e-5, help="relative noise floor of a block mean, for float rounding (default 1e-5)")
    ap.add_argument("--force-statistical", action="store_true", help="run the statistical test even where the images are identical")
    ap.add_argument("--out", default="default_images_out", help="directory of the results (results.md, results.json) and renders")
    ap.add_argument("--keep-images", action="store_true", help="keep the EXRs under OUT/renders")
    ap.add_argument("--extra", nargs=argparse.REMAINDER, default=[], help="further `kasha render` options for both binaries (last)")
    args = ap.parse_args()
    if args.seeds < 8:
        ap.error("--seeds must be at least 8 (Student's t tails at fewer seeds are too heavy for a useful test)")
    args.reference, args.candidate = os.path.abspath(args.reference), os.path.abspath(args.candidate)
    args.out = os.path.abspath(args.out)
    scenes = args.scenes or sorted(glob.glob(os.path.join(REPO, "scenes", "*.json")))
    if args.integrators:
        integrators = [s for s in args.integrators.split(",") if s]
    else:
        integrators = []
        for name in integrator_names(args.reference) + integrator_names(args.candidate):
            if name not in integrators:
                integrators.append(name)
        integrators = integrators or FALLBACK_INTEGRATORS
    os.makedirs(args.out, exist_ok=True)
    print(f"reference {args.reference}\ncandidate {args.candidate}\n{len(scenes)} scenes x {len(integrators)} integrators, "
          f"{args.spp or 'scene'} spp, {args.seeds} seeds, alpha {args.alpha:g}", flush=True)
    rows = []
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for scene in scenes:
            for integrator in integrators:
                try:
                    row = compare_pair(args, os.path.abspath(scene), integrator, pool)
                except Exception as e:  # an unreadable image, a missing binary
                    row = {"scene": os.path.splitext(os.path.basename(scene))[0], "integrator": integrator, "status": "ERROR", "detail": str(e)}
                rows.append(row)
                print(f"{row['scene']:<28} {row['integrator']:<17} {row['status']:<20} {row['detail']}", flush=True)
    failed = [r for r in rows if r["status"] in FAILING]
    counts = {}
    for r in rows:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    summary = ", ".join(f"{v} {k}" for k, v in counts.items())
    print(f"\n{summary}\n{'FAIL' if failed else 'PASS'}")
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write(f"# Default images: {os.path.basename(args.candidate)} vs {os.path.basename(args.reference)}\n\n")
        f.write(f"- reference: `{args.reference}`\n- candidate: `{args.candidate}`\n")
        f.write(f"- {args.spp or 'the scene'} spp, {args.seeds} seeds per binary where not identical, alpha {args.alpha:g}, "
                f"rtol {args.rtol:g}{', statistical test forced' if args.force_statistical else ''}"
                f"{', extra options ' + ' '.join(args.extra) if args.extra else ''}\n")
        f.write(f"- {summary}: **{'FAIL' if failed else 'PASS'}**\n\n")
        f.write("| scene | integrator | result | detail |\n|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['scene']} | {r['integrator']} | {r['status']} | {r['detail'].replace('|', '/')} |\n")
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump({"reference": args.reference, "candidate": args.candidate, "spp": args.spp, "seeds": args.seeds,
                   "alpha": args.alpha, "rtol": args.rtol, "force_statistical": args.force_statistical,
                   "extra": args.extra, "rows": rows}, f, indent=1)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
