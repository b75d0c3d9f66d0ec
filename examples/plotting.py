"""Shared by the examples: write a matplotlib figure to a PNG and say where."""
import os


def save_figure(fig, png, axes=(), legend_size=None):
    """Grids and legends on `axes`, a tight layout, then the PNG (its folder made if needed)."""
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=legend_size)
    fig.tight_layout()
    os.makedirs(os.path.dirname(png) or ".", exist_ok=True)
    fig.savefig(png, dpi=110)
    print(f"PNG: {png}")
