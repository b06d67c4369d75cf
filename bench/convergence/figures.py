"""The report's figures: error against time (log-log, one line per configuration, error bars over
seeds) and the images with false-colour error crops side by side."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.colors as mcolors  # noqa: E402
import matplotlib.image as mimage  # noqa: E402
import matplotlib.patches as mpatches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402


def read_pfm(path):
    """A greyscale Portable Float Map ("Pf", as written by kasha metrics --error-map), top row first."""
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    if parts[0] != b"Pf" or len(parts) < 4:
        raise ValueError(f"{path}: not a greyscale PFM")
    w, h = (int(v) for v in parts[1].split())
    scale = float(parts[2])
    values = np.frombuffer(parts[3], dtype="<f4" if scale < 0 else ">f4", count=w * h)
    return values.reshape(h, w)[::-1]


def quantize_png(path):
    """Rewrites the PNG at `path` with a palette of 256 colours: the committed figures stay a
    quarter of their size, with no difference a reader sees."""
    from PIL import Image
    with Image.open(path) as im:
        rgb = im.convert("RGB")
    rgb.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(path, optimize=True)


def convergence_plot(summary, budget_kind, title, path):
    """relMSE and RMSE against mean render time, log-log; error bars: standard deviation over seeds."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    # Ten colours, then the same ten dashed with square markers: every line stays distinguishable.
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (label, rows) in enumerate(summary.items()):
        t = [r["seconds_mean"] for r in rows]
        style = {"color": colours[i % len(colours)], "marker": "os^"[i // len(colours) % 3],
                 "linestyle": ("-", "--", ":")[i // len(colours) % 3]}
        for ax, key in zip(axes, ("relmse", "rmse")):
            ax.errorbar(t, [r[key + "_mean"] for r in rows], yerr=[r[key + "_std"] for r in rows],
                        capsize=3, label=label, **style)
    for ax, name in zip(axes, ("relMSE", "RMSE (XYZ)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set_xlabel("render time (s)" + (", equal time" if budget_kind == "time" else ", equal samples"))
        ax.set_ylabel(name)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    quantize_png(path)


def _crop(img, crop):
    h, w = img.shape[:2]
    x0, y0, x1, y1 = int(crop[0] * w), int(crop[1] * h), max(int(crop[0] * w) + 1, int(crop[2] * w)), \
        max(int(crop[1] * h) + 1, int(crop[3] * h))
    return img[y0:y1, x0:x1]


def crops_figure(reference_png, columns, crop, title, path):
    """Top: the reference (crop outlined) and each configuration's image crop; bottom: each one's
    per-pixel relative squared error on one shared logarithmic colour scale.
    columns: [(label, png path, pfm error-map path, relMSE)]."""
    ref = mimage.imread(reference_png)
    errors = [read_pfm(c[2]) for c in columns]
    positive = np.concatenate([_crop(e, crop).ravel() for e in errors])
    positive = positive[positive > 0]
    vmax = float(np.percentile(positive, 99)) if positive.size else 1.0
    norm = mcolors.LogNorm(vmin=max(vmax * 1e-4, 1e-12), vmax=max(vmax, 1e-11))
    n = len(columns) + 1
    fig, axes = plt.subplots(2, n, figsize=(2.2 * n, 4.6), squeeze=False)
    h, w = ref.shape[:2]
    axes[0][0].imshow(ref)
    axes[0][0].add_patch(mpatches.Rectangle((crop[0] * w, crop[1] * h), (crop[2] - crop[0]) * w,
                                            (crop[3] - crop[1]) * h, fill=False, edgecolor="white", lw=1))
    axes[0][0].set_title("reference", fontsize=8)
    axes[1][0].imshow(_crop(ref, crop))
    axes[1][0].set_title("reference crop", fontsize=8)
    im = None
    for i, ((label, png, _, relmse), err) in enumerate(zip(columns, errors), start=1):
        axes[0][i].imshow(_crop(mimage.imread(png), crop))
        axes[0][i].set_title(label, fontsize=8)
        im = axes[1][i].imshow(np.maximum(_crop(err, crop), norm.vmin), cmap="inferno", norm=norm)
        axes[1][i].set_title(f"relMSE {relmse:.3g}", fontsize=8)
    for ax in axes.ravel():
        ax.set_xticks([])
        ax.set_yticks([])
    if im is not None:
        fig.colorbar(im, ax=axes[1].tolist(), fraction=0.02, pad=0.01, label="relative squared error")
    fig.suptitle(title, fontsize=9)
    fig.savefig(path, dpi=80, bbox_inches="tight")
    plt.close(fig)
    quantize_png(path)
