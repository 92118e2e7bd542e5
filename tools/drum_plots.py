"""Plots of tools/drum.py's results (matplotlib; --plots DIR): the dynamic
angle against Fr (Mellmann's 2001 ranges shaded) and against the rolling
friction, and each case's last cross-section with its regime."""
import math
import os


def plot(results, v, where, regime):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found: no plots")
        return
    os.makedirs(where, exist_ok=True)
    for backend in sorted({k[0] for k, _ in results}):
        rs = [(k, m) for k, m in results if k[0] == backend]
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        for mu_r in sorted({k[2] for k, _ in rs}):
            pts = sorted((k[1], m["angle"]) for k, m in rs if k[2] == mu_r and m["angle"] == m["angle"])
            if pts:
                ax[0].semilogx([p[0] for p in pts], [p[1] for p in pts], "o-", label="rolling_friction %g" % mu_r)
        for lo, hi, name in ((1e-4, 1e-2, "rolling"), (1e-3, 1e-1, "cascading"), (1e-1, 1, "cataracting")):
            ax[0].axvspan(lo, hi, alpha=0.08)
            ax[0].text(math.sqrt(lo * hi), 0.02, name, ha="center", fontsize=7, transform=ax[0].get_xaxis_transform())
        ax[0].axvline(1.0, color="k", lw=0.5)
        ax[0].set_xlabel("Fr = omega^2 R / g")
        ax[0].set_ylabel("dynamic angle of repose [deg]")
        ax[0].legend(fontsize=7)
        ax[0].set_title("angle against Fr (shaded: Mellmann 2001 ranges)", fontsize=8)
        fr0 = [k for k, _ in rs if k[2] > 0]
        frs = sorted({k[1] for k in fr0})
        for fr in frs:
            pts = sorted((k[2], m["angle"]) for k, m in rs if k[1] == fr)
            ax[1].plot([p[0] for p in pts], [p[1] for p in pts], "o-", label="Fr %g" % fr)
        ax[1].set_xlabel("rolling_friction")
        ax[1].set_ylabel("dynamic angle of repose [deg]")
        ax[1].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(where, "drum_angle_%s.png" % backend), dpi=120)
        plt.close(fig)
        cols = 5
        rows = (len(rs) + cols - 1) // cols
        fig, axs = plt.subplots(rows, cols, figsize=(3 * cols, 3 * rows), squeeze=False)
        for a, ((_, fr, mu_r), m) in zip(axs.flat, rs):
            a.add_patch(plt.Circle((0, 0), v["R"], fill=False, color="k", lw=0.8))
            a.scatter([p[0] for p in m["last"]], [p[1] for p in m["last"]], s=0.3, color="tab:blue")
            a.set_title("Fr %g, rolling %g: %s" % (fr, mu_r, regime(m)), fontsize=7)
        for a in axs.flat:
            a.set_aspect("equal")
            a.set_xlim(-1.05 * v["R"], 1.05 * v["R"])
            a.set_ylim(-1.05 * v["R"], 1.05 * v["R"])
            a.axis("off")
        fig.tight_layout()
        fig.savefig(os.path.join(where, "drum_sections_%s.png" % backend), dpi=120)
        plt.close(fig)
