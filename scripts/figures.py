"""Saving figures atomically: a plot is written under a temporary name beside its target and renamed when complete,
so that a plotting run that is stopped leaves the previous complete PNG, or none, never a truncated one."""

import os


def save_figure(fig, path, **options):
    """fig.savefig(path, **options), through path + ".part" and an atomic rename."""
    part = f"{path}.part"
    fmt = os.path.splitext(path)[1].lstrip(".") or "png"
    try:
        fig.savefig(part, format=fmt, **options)
        os.replace(part, path)
    except BaseException:
        if os.path.exists(part):
            os.remove(part)
        raise
