"""Figures of the studies: matplotlib without a display, saved as PNG and PDF."""


def panels(count, width=4.2, height=3.6, **options):
    """A figure with `count` panels side by side: (figure, list of axes)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    figure, axes = plt.subplots(1, count, figsize=(width * count, height), **options)
    return figure, list(np.atleast_1d(axes))


def save(figure, path_stem, legend_axis=None):
    """Save as path_stem.png and path_stem.pdf, then close."""
    import matplotlib.pyplot as plt
    if legend_axis is not None:
        legend_axis.legend(frameon=False)
    figure.tight_layout()
    for suffix in (".png", ".pdf"):
        figure.savefig(str(path_stem) + suffix, dpi=150)
    plt.close(figure)
