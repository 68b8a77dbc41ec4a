#!/usr/bin/env python3
# %% [markdown]
# # Fitting models to a measured BRDF with shadelab
#
# A notebook-style script (cells marked `# %%`; run it cell by cell in Jupyter, VS Code or Spyder, or whole with
# Debian's Python: `PYTHONPATH=build/release/python/site /usr/bin/python3 examples/fit_measured.py`). No measured
# data set ships offline, so it makes one: `shadelab measure` writes a model of known parameters in the MERL 100
# layout (a virtual gonioreflectometer, docs/models/measured.md). It then reads the file back, fits three models
# to it under a metric (docs/fitting.md), prints what each recovers and how far it stays, and plots the lobes in
# the plane of incidence with matplotlib when it is installed (`apt-get install python3-matplotlib`); without
# it, it prints them as a table.

# %%
import argparse
import math
import os
import shutil
import subprocess
import tempfile

import numpy as np

import shadelab

parser = argparse.ArgumentParser(description="fit models to a synthetic measured BRDF and plot the lobes")
parser.add_argument("--shadelab", default=os.environ.get("SHADELAB_EXE") or shutil.which("shadelab") or
                    "build/release/tools/shadelab/shadelab", help="the shadelab command (for `measure`)")
parser.add_argument("--metric", default="cube-root", help="cosine-l2, cube-root or log")
parser.add_argument("--out", default="fit_lobes.png", help="picture to write when matplotlib is installed")
args = parser.parse_args()

# %% [markdown]
# ## 1. A "measured" material of known parameters
# A coloured rough plastic: GGX with alpha 0.15, F0 0.04, a red diffuse base. Measuring it writes 35 MB.

# %%
truth = {"alpha": 0.15, "f0": 0.04, "kd": [0.6, 0.15, 0.1]}
tmp = tempfile.mkdtemp(prefix="shadelab-fit-")
merl = os.path.join(tmp, "plastic.binary")
subprocess.run([args.shadelab, "measure", "ggx", "--param", "alpha=0.15", "--param", "f0=0.04",
                "--param", "kd=0.6,0.15,0.1", "--out", merl], check=True)
data = shadelab.merl_data(merl, theta_d_stride=6, phi_d_stride=12)
print(f"{data['values'].shape[0]} measured configurations read back from {os.path.basename(merl)}")

# %% [markdown]
# ## 2. Fit three models: one that can represent it, two that cannot

# %%
fits = {}
for model in ("ggx", "ward", "cook-torrance"):
    r = shadelab.fit(model, data["wi"], data["wo"], data["values"], data["weight"], metric=args.metric, starts=2)
    fits[model] = r
    shown = {k: (tuple(round(x, 4) for x in v) if isinstance(v, tuple) else round(v, 4))
             for k, v in r["params"].items() if k in r["fitted"]}
    print(f"{model:<14} residual {r['residual']:.3g} ({r['metric']})  {shown}")
assert abs(fits["ggx"]["params"]["alpha"] - truth["alpha"]) < 1e-3 * truth["alpha"], fits["ggx"]["params"]
assert fits["ward"]["residual"] > 10 * fits["ggx"]["residual"]

# %% [markdown]
# ## 3. The lobes in the plane of incidence, light at 30 degrees

# %%
theta_i = math.radians(30.0)
wi = np.array([math.sin(theta_i), 0.0, math.cos(theta_i)])
angles = np.radians(np.linspace(-89, 89, 179))
wo = np.stack([np.sin(angles), np.zeros_like(angles), np.cos(angles)], axis=1)
lum = np.array([0.2126, 0.7152, 0.0722])
curves = {"measured (ggx truth)": shadelab.Brdf("ggx", **truth).eval(wi, wo) @ lum}
for model, r in fits.items():
    curves[model] = shadelab.Brdf(model, **dict(r["assignments"])).eval(wi, wo) @ lum

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, y in curves.items():
        ax.plot(np.degrees(angles), y, label=name)
    ax.set_xlabel("viewing angle (degrees; the mirror direction at -30)")
    ax.set_ylabel("f_r (1/sr, luminance)")
    ax.set_yscale("log")
    ax.legend()
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")
except ImportError:
    print("viewing angle  " + "  ".join(f"{n[:14]:>14}" for n in curves))
    for k in range(0, len(angles), 10):
        print(f"{math.degrees(angles[k]):+12.0f}  " + "  ".join(f"{y[k]:14.4g}" for y in curves.values()))
shutil.rmtree(tmp)
