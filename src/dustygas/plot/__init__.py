"""Figures: the house style and saving a figure together with the numbers behind it.

Plotting never uses :mod:`matplotlib.pyplot` (no global figure state, no GUI backend): figures
are :class:`matplotlib.figure.Figure` objects rendered with Agg. Typical use::

    from dustygas.plot import Column, house_style, new_figure, save_figure

    with house_style():
        fig, ax = new_figure()
        ax.loglog(tau, -v_r, label="dust")
        ax.set_xlabel(r"$\\tau_s$")
        save_figure(fig, out / "fig3_5.png", [Column("tau_s", tau, "1", "stopping time")])
"""

from .style import Column, HOUSE_STYLE, house_style, new_figure, read_table, save_figure

__all__ = ["Column", "HOUSE_STYLE", "house_style", "new_figure", "save_figure", "read_table"]
