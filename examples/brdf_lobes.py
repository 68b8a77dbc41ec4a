#!/usr/bin/env python3
# %% [markdown]
# # BRDF lobes with shadelab
#
# A notebook-style script (cells marked `# %%`, so Jupyter, VS Code or Spyder run it cell by cell; or
# run it whole with Debian's Python: `PYTHONPATH=build/release/python/site /usr/bin/python3
# examples/brdf_lobes.py`). It evaluates a few models of the registry on a whole array of directions at
# once, prints their directional albedo, and plots their lobes with matplotlib when it is installed
# (`apt-get install python3-matplotlib`); without it, it draws the lobes as text.

# %%
import argparse
import math

import numpy as np

import shadelab

parser = argparse.ArgumentParser(description="plot BRDF lobes in the plane of incidence")
parser.add_argument("--theta-in", type=float, default=45.0, help="viewing angle from the normal, degrees")
parser.add_argument("--out", default="lobes.png", help="picture to write when matplotlib is installed")
args = parser.parse_args()

# %% [markdown]
# Every model of the registry, with its formula and parameters:

# %%
for m in shadelab.models():
    params = ", ".join(f"{p['name']}={p['default_text']}" for p in m["params"])
    print(f"{m['name']:<26} f_r = {m['summary']}\n{'':<26} {params}")

# %% [markdown]
# Models to compare: specular lobes of similar width, and Lambert for scale.

# %%
brdfs = {
    "lambert": shadelab.Brdf("lambert", kd=1),
    "phong-modified n=50": shadelab.Brdf("phong-modified", kd=0, ks=1, n=50),
    "blinn-phong-modified n=200": shadelab.Brdf("blinn-phong-modified", kd=0, ks=1, n=200),
    "cook-torrance m=0.2 F0=1": shadelab.Brdf("cook-torrance", kd=0, ks=1, m=0.2, f0=1),
    "ward alpha=0.15": shadelab.Brdf("ward", kd=0, ks=1, alpha=0.15),
}

# %% [markdown]
# The lobe: f_r(wi, wo) cos(theta_i) for wi swept through the plane of incidence, wo fixed at theta_in on
# the other side of the normal. One `eval` call per model evaluates all 721 directions in C++.

# %%
theta_o = math.radians(args.theta_in)
wo = np.array([math.sin(theta_o), 0.0, math.cos(theta_o)])
angles = np.radians(np.linspace(-90.0, 90.0, 721))  # theta_i, signed: negative on the mirror side
wi = np.stack([np.sin(angles), np.zeros_like(angles), np.cos(angles)], axis=1)
wi[:, 2] = np.maximum(wi[:, 2], 1e-9)  # the horizon itself: a direction just above it
lobes = {name: f.eval(wi, wo)[:, 1] * wi[:, 2] for name, f in brdfs.items()}
for name, lobe in lobes.items():
    peak = np.degrees(angles[np.argmax(lobe)])
    print(f"{name:<28} peak f cos = {lobe.max():9.4f} at theta_i = {peak:6.2f} deg (mirror: {-args.theta_in:.1f})")

# %% [markdown]
# Directional albedo (energy reflected per unit received, by adaptive quadrature in C++): the zoo's
# normalizations keep it at 1 at normal incidence; Cook-Torrance and Ward lose or gain energy at grazing.

# %%
thetas = [0, 30, 60, 80]
print(f"{'albedo at theta_o =':<28}" + "".join(f"{t:>9}" for t in thetas))
for name, f in brdfs.items():
    print(f"{name:<28}" + "".join(f"{a:9.4f}" for a in f.albedo(thetas)[:, 1]))

# %% [markdown]
# The picture: polar plots of the lobes (the normal points up), when matplotlib is there.

# %%
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None

if plt is not None:
    fig, ax = plt.subplots(subplot_kw={"projection": "polar"}, figsize=(7, 4.5))
    ax.set_theta_zero_location("N")
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    for name, lobe in lobes.items():
        ax.plot(-angles, lobe / lobe.max(), label=name)  # matplotlib's angles grow anticlockwise
    ax.plot([-theta_o, -theta_o], [0, 1], "k--", lw=0.8, label="viewer")
    ax.set_thetagrids(range(-90, 91, 30), labels=[f"{abs(a)}" for a in range(-90, 91, 30)])
    ax.set_title(f"f_r cos(theta_i), viewer at {args.theta_in:g} deg (each lobe scaled to its peak)", fontsize=10)
    ax.legend(loc="center left", fontsize=8, bbox_to_anchor=(1.0, 0.5))
    fig.savefig(args.out, dpi=120, bbox_inches="tight")
    print(f"wrote {args.out}")
else:
    print("matplotlib is not installed: the lobes as text (each scaled to its peak)")
    for name, lobe in lobes.items():
        row = lobe[::24] / lobe.max()
        print(f"{name:<28} " + "".join(" .:-=+*#%@"[min(9, int(v * 9.999))] for v in row))
