"""Figures shared by the CLI, the REST routes and the pages (matplotlib, Agg backend).

Every function returns a matplotlib Figure; callers save it as PNG or SVG.
"""

from __future__ import annotations

import numpy as np


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def steady_profile_figure(profile, title: str = ""):
    """Elevation profile with the carry and return tensions along it (Harrison 2008, Fig. 1).

    ``profile`` is the steady profile table (``s_m``, ``strand``, ``elevation_m``,
    ``tension_kn``, ``sag_pct``). Distances are along the conveyor from the tail [m]: the
    return strand is drawn at the position it passes over.
    """
    plt = _plt()
    s = np.asarray(profile["s_m"], dtype=float)
    strand = np.asarray(profile["strand"])
    z = np.asarray(profile["elevation_m"], dtype=float)
    t = np.asarray(profile["tension_kn"], dtype=float)
    carry = strand == "carry"
    ret = strand == "return"
    length = float(s[carry].max()) if carry.any() else float(s.max())
    s_head_end = float(s[strand == "head"].max()) if (strand == "head").any() else length
    x_carry = s[carry]
    x_ret = length - (s[ret] - s_head_end)
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(9, 6),
                                   gridspec_kw={"height_ratios": [1, 2]})
    ax1.plot(np.concatenate(([0.0], x_carry)), np.concatenate(([0.0], z[carry])), color="0.3")
    ax1.fill_between(np.concatenate(([0.0], x_carry)), np.concatenate(([0.0], z[carry])),
                     min(0.0, float(z.min())), color="0.85")
    ax1.set_ylabel("elevation [m]")
    ax1.grid(alpha=0.3)
    if title:
        ax1.set_title(title)
    ax2.plot(x_carry, t[carry], label="carry", color="tab:red")
    ax2.plot(x_ret, t[ret], label="return", color="tab:blue")
    ax2.set_xlabel("distance from the tail along the conveyor [m]")
    ax2.set_ylabel("belt tension [kN]")
    ax2.set_ylim(bottom=0.0)
    ax2.grid(alpha=0.3)
    ax2.legend(loc="best")
    fig.tight_layout()
    return fig
